//! `rope study --tolerance-check quick`, the small version CI runs: what `--tolerance` chooses
//! in two scenes, held against a converged reference at every frame.

use rope::Scene;
use rope::study::read_reference::{CheckReference, read_all};
use rope::study::tip_reference::{ConvergedTip, LOG_RATE, write_references};
use rope::study::tolerance_check::{CheckSpec, REFERENCE_MARGIN, check};

#[test]
fn the_quick_tolerance_check_holds_eps_against_a_converged_reference_in_each_scene() {
    let spec = CheckSpec::quick();
    let checked = check(&spec, &[], &|| {}).unwrap();
    let cells = &checked.cells;
    let eps = spec.tolerances[0];
    // The reference must be fine enough to judge EPS: the check says so when it is not.
    for r in &checked.references {
        eprintln!(
            "reference from the {}: {:?}, own error {:.1e}",
            r.scene(),
            r.made_of(),
            r.own_error()
        );
        assert!(
            r.own_error() <= REFERENCE_MARGIN * eps,
            "{}: own error {:.1e}",
            r.scene(),
            r.own_error()
        );
    }
    // Each reference starts where its scene does (y down): a release's tip at (cos θ, sin θ),
    // where every run starts too (its own error there is nil), a mode's hanging nearly
    // straight down.
    assert_eq!(checked.references.len(), spec.scenes.len());
    for (scene, tip) in spec.scenes.iter().zip(&checked.references) {
        assert_eq!(tip.scene(), *scene);
        let start = tip.tip_at(0.0);
        if let Scene::Release { angle_deg } = *scene {
            let angle = angle_deg.to_radians();
            assert!((start.x - angle.cos()).abs() < 1e-12 && (start.y - angle.sin()).abs() < 1e-12);
            assert!(tip.own_error_at(0.0) < 1e-12);
        } else {
            assert!((start.y - 1.0).abs() < 1e-2, "{scene}: {start}");
        }
    }
    assert_eq!(cells.len(), spec.scenes.len());
    for cell in cells {
        assert!(cell.skipped.is_none(), "{}: {:?}", cell.scene, cell.skipped);
        let chosen = cell.chosen.expect("a chosen run that finished");
        eprintln!(
            "{}: {} at N = {}, worst tip error {:.1e}",
            cell.scene, chosen.method, chosen.segments, chosen.worst
        );
        assert_eq!(
            cell.held(),
            Some(true),
            "{}: {:.1e}",
            cell.scene,
            chosen.worst
        );
        // The grid has runs that hold EPS too: the comparison of CPU has something to compare.
        let cheapest = cell.cheapest.expect("a grid run that holds EPS");
        assert!(cheapest.worst <= eps);
    }
    // The cells as a program reads them: a row each, the choice and its worst error as measured.
    let path = std::env::temp_dir().join(format!("rope-check-{}.csv", std::process::id()));
    rope::study::tolerance_csv::write(cells, &path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), cells.len(), "{text}");
    for (row, cell) in rows.iter().zip(cells) {
        let chosen = cell.chosen.unwrap();
        assert_eq!(row[column("method")], chosen.method.name(), "{text}");
        assert_eq!(row[column("held")], "true", "{text}");
        let worst: f64 = row[column("worst")].parse().unwrap();
        assert_eq!(worst, chosen.worst, "{text}");
    }
}

/// The committed `assets/tolerance-check/references.csv` (written by the full check): every
/// scene of the check, its tip every 1/3000 to t = 3 (every frame and every 1/1000), held to
/// what the physics of the string says, whatever the extrapolation did.
#[test]
fn the_committed_references_obey_the_physics_of_the_string() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/tolerance-check/references.csv"
    );
    let text = std::fs::read_to_string(path).expect("the committed references");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("scene,t,tip_x,tip_y,own_error"));
    let rows: Vec<(String, [f64; 4])> = lines
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let number = |i: usize| fields[i].parse::<f64>().unwrap();
            (
                fields[0].to_owned(),
                [number(1), number(2), number(3), number(4)],
            )
        })
        .collect();
    let spec = CheckSpec::default();
    let rate = rope::study::tip_reference::REFERENCE_ROWS_RATE;
    let per_scene = 1 + (spec.duration * rate) as usize;
    assert_eq!(rows.len(), spec.scenes.len() * per_scene);
    for (scene, rows) in spec.scenes.iter().zip(rows.chunks(per_scene)) {
        for (j, (name, [t, x, y, own])) in rows.iter().enumerate() {
            assert_eq!(*name, scene.to_string());
            assert!((t - j as f64 / rate).abs() < 1e-12, "{scene}: t = {t}");
            assert!(*own >= 0.0);
            // Inextensible: the tip is never farther from the support than the string is long
            // (an extrapolated point may stray outside by its own error; the file rounds to
            // 1e-9).
            assert!(
                x.hypot(*y) <= 1.0 + own + 1e-9,
                "{scene}: t = {t}, |tip| = {}",
                x.hypot(*y)
            );
            match *scene {
                // Until the bend reaches it, the tip of a release falls freely across its
                // initial line (exact for the rods, and for any extrapolation of them), but for
                // round-off: the file's rounding to 1e-9 (up to 7e-10 across the line), and the
                // rods' own, which grows with N and the steps and which the extrapolation
                // weighs up (from 60°, runs to N = 25 600 extrapolated at order 1.37: 2.1e-9 by
                // t = 0.74, every other reference under 9e-10).
                Scene::Release { .. } if *t <= rope::run::summary::FREE_FALL_UNTIL => {
                    let gap = scene.free_fall_gap(*t, *x, *y).unwrap();
                    assert!(gap < 4e-9, "{scene}: t = {t}, off free fall by {gap:e}");
                }
                // A small mode is a standing wave: its tip swings no wider than it was set.
                Scene::Mode { amplitude, .. } => {
                    assert!(x.abs() <= 1.01 * amplitude, "{scene}: t = {t}, x = {x}");
                }
                _ => {}
            }
        }
    }
}

/// Where no run of the grid holds the smallest EPS the reference judges, the grid goes on past
/// its largest N, every method at each N, and stops at the first N where one holds: mode 2
/// errs by about 0.5/N² on the chain's rods, within 1e-4 from N = 100 but not at 50.
#[test]
fn a_grid_that_holds_nothing_goes_on_past_its_largest_n_until_a_run_holds() {
    use rope::plan::choice::startable;
    use rope::study::tolerance_check::grid_steps;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let scene = Scene::Mode {
        number: 2,
        amplitude: 0.05,
    };
    let spec = CheckSpec {
        scenes: vec![scene],
        tolerances: vec![1e-4],
        grid: vec![16],
        grid_beyond: vec![25, 50, 100, 141, 200],
        ..CheckSpec::quick()
    };
    let ticks = AtomicUsize::new(0);
    let checked = check(&spec, &[], &|| {
        ticks.fetch_add(1, Ordering::Relaxed);
    })
    .unwrap();
    let cheapest = checked.cells[0]
        .cheapest
        .expect("a run past the grid holds 1e-4");
    assert_eq!(cheapest.segments, 100, "{cheapest:?}");
    assert!(cheapest.worst <= 1e-4);
    // The reference, every startable method at each N up to 100 (none past it), the choice.
    let runs: usize = [16, 25, 50, 100]
        .iter()
        .flat_map(|&n| startable(&scene, 3.0).map(move |m| grid_steps(m, n).len()))
        .sum();
    assert_eq!(ticks.load(Ordering::Relaxed), 1 + runs + 1);
}

#[test]
fn a_check_that_reads_its_references_back_judges_every_run_as_the_one_that_computed_them() {
    let spec = CheckSpec {
        scenes: vec![Scene::Mode {
            number: 1,
            amplitude: 0.05,
        }],
        ..CheckSpec::quick()
    };
    let computed = check(&spec, &[], &|| {}).unwrap();
    let path = std::env::temp_dir().join(format!("rope-check-refs-{}.csv", std::process::id()));
    write_references(&path, &computed.references, spec.duration).unwrap();
    let read = read_all(std::slice::from_ref(&path), &spec.scenes, spec.duration);
    std::fs::remove_file(&path).unwrap();
    let read = read.unwrap();
    let again = check(&spec, &read, &|| {}).unwrap();
    let (before, after) = (&computed.references[0], &again.references[0]);
    assert!(matches!(before, CheckReference::Computed(_)));
    assert!(
        matches!(after, CheckReference::Read(_)),
        "{:?}",
        after.made_of()
    );
    // The file keeps the tip to 1e-9 and the own error to two digits, at every frame.
    for k in 0..=(spec.duration * LOG_RATE) as usize {
        let t = k as f64 / LOG_RATE;
        assert!(
            (before.tip_at(t) - after.tip_at(t)).norm() < 1e-9,
            "t = {t}"
        );
    }
    assert!((before.own_error() - after.own_error()).abs() <= 0.05 * before.own_error());
    // The same runs, measured against either, err alike: against the computed reference at
    // every one of their own steps, against the file at every row, kept at a step on the rows
    // (`judging_step`: k = 1/3000 for the seed scheme's k = 1e-2 at N = 16, the choice here),
    // which moves the tip by its error in k alone (3.5 % of the worst error here).
    let (one, two) = (&computed.cells[0], &again.cells[0]);
    let (a, b) = (one.chosen.unwrap(), two.chosen.unwrap());
    assert_eq!((a.method, a.segments, a.dt), (b.method, b.segments, b.dt));
    assert!(
        (a.worst - b.worst).abs() < 0.05 * a.worst,
        "{} against {}",
        a.worst,
        b.worst
    );
}
