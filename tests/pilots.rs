//! `--tolerance` with pilot runs: the scene at hand measured at a few coarse N before the
//! choice, its tolerance then held against a fine reference at every frame.

mod common;

use common::cli::{run_judged, tip_samples};
use rope::methods::MethodKind;
use rope::model::{Point, Scene};
use rope::plan::error_model::law;
use rope::plan::{atlas, choice, committed, pilot, tolerance};
use rope::run::estimate::TipBound;
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::measure;

/// The largest distance, over a run's summary's tip samples, from the reference's tip.
fn worst_tip_error(summary: &serde_json::Value, reference: impl Fn(f64) -> Point) -> f64 {
    tip_samples(summary)
        .into_iter()
        .map(|(t, tip)| (tip - reference(t)).norm())
        .fold(0.0, f64::max)
}

/// Runs `rope run` with `--tolerance` (to t = 3 unless `flags` give a `--duration`) and returns
/// the summary and what it said (exit 0, or 4 where the live estimate's bound
/// passed EPS: these tests judge the choice themselves).
fn tolerance_run(name: &str, flags: &[&str]) -> (serde_json::Value, String) {
    let mut args = vec!["run"];
    if !flags.contains(&"--duration") {
        args.extend_from_slice(&["--duration", "3"]);
    }
    args.extend_from_slice(flags);
    run_judged(name, &args)
}

#[test]
fn a_mode_is_modelled_with_what_it_needs_and_holds_the_tolerance() {
    let (s, said) = tolerance_run("pilot-mode", &["--scene", "mode", "--tolerance", "1e-4"]);
    // The committed models, fitted to the whip of the horizontal release, asked for thousands
    // of segments here; the mode's linear theory asks for tens (and the seed scheme, which it
    // does not cover, flies a pilot).
    assert!(said.contains("tolerance pilots"), "{said}");
    let segments = s["segments"].as_u64().unwrap();
    assert!(segments <= 100, "N = {segments}");
    // Against the chain at N = 100, 200, 400 extrapolated (its own error a few 1e-8) at every
    // frame.
    let mode = Scene::Mode {
        number: 1,
        amplitude: 0.05,
    };
    let reference = TipReference::compute(&mode, 200, 3.0).unwrap();
    let worst = worst_tip_error(&s, |t| reference.at(t));
    eprintln!(
        "mode 1, 1e-4: {} at N = {segments}, worst tip error {worst:.2e}",
        s["method"]
    );
    assert!(
        worst <= 1e-4,
        "worst tip error {worst:.2e} at N = {segments}"
    );
}

#[test]
fn a_modes_verdict_reads_its_error_at_its_own_order_and_still_bounds_it() {
    // Mode 2 from a tip amplitude of 0.05, the tolerance check's: at first order the live
    // bound read 2.4 and 2.6 times the truth, so runs that held at 0.50 and 0.42 of EPS exited
    // 4. Read at the order the mode theory works out (its pilots', past small swings), the
    // bound is above the truth and flags a run only where the truth is above EPS/2. Judged at
    // every step against the chain at N = 400, 800, 1 600, extrapolated.
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.05,
    };
    let reference = TipReference::compute(&mode, 400, 3.0).unwrap();
    for eps in [1e-3, 1e-4] {
        assert!(reference.own_error <= eps / 10.0, "{}", reference.own_error);
        let (choice, _) = tolerance::choose(eps, &mode, 3.0, u64::MAX).unwrap();
        let TipBound::Observed { order, safety } = choice.tip_bound else {
            panic!("{eps:e}: {:?}", choice.tip_bound);
        };
        assert!(
            (1.0..=2.0).contains(&order) && safety >= pilot::SAFETY,
            "{order} {safety}"
        );
        let (m, n, dt) = (choice.method, choice.segments, choice.dt);
        let run = measure(m, &mode, n, dt, 3.0, Some(choice.tip_bound), &reference).unwrap();
        let bound = run.estimate.unwrap();
        eprintln!(
            "mode 2 at {eps:e}: {m} N = {n}, order {order:.2}: worst tip error {:.2e}, bound {bound:.2e}",
            run.worst
        );
        // It holds, its bound is above the truth, and a flag is never a false alarm below EPS/2.
        assert!(
            run.worst <= eps && run.worst <= bound,
            "{:.2e} {bound:.2e}",
            run.worst
        );
        assert!(
            bound <= eps || run.worst > eps / 2.0,
            "{:.2e} {bound:.2e}",
            run.worst
        );
    }
    // A release keeps the first order: its whip comes past the pilots' N.
    let thirty = Scene::Release { angle_deg: 30.0 };
    let (choice, _) = tolerance::choose(1e-3, &thirty, 3.0, u64::MAX).unwrap();
    assert_eq!(choice.tip_bound, TipBound::FirstOrder);
}

/// The release from 30° to t = 3: the reference method (the chain) at N/2, N and 2N,
/// extrapolated at the order the three show, its own error printed.
fn thirty_degree_reference(segments: usize) -> TipReference {
    let thirty = Scene::Release { angle_deg: 30.0 };
    let reference = TipReference::compute(&thirty, segments, 3.0).unwrap();
    eprintln!(
        "reference from 30° at N = {}, {}, {}: order {:.2}, own error {:.1e}",
        segments / 2,
        segments,
        2 * segments,
        reference.order,
        reference.own_error
    );
    reference
}

/// Runs `--tolerance eps` from 30° and checks its worst tip error against `reference`.
fn thirty_degrees_holds(eps: &str, reference: &TipReference) {
    let flags = ["--angle", "30", "--tolerance", eps];
    let (s, _) = tolerance_run(&format!("pilot-30-{eps}"), &flags);
    let worst = worst_tip_error(&s, |t| reference.at(t));
    let (method, segments) = (&s["method"], &s["segments"]);
    eprintln!("30°, {eps}: {method} at N = {segments}, worst tip error {worst:.2e}");
    let eps: f64 = eps.parse().unwrap();
    assert!(
        worst <= eps,
        "worst tip error {worst:.2e} with {method} at N = {segments}"
    );
}

#[test]
fn a_release_from_30_degrees_holds_1e_2_against_a_reference_at_every_frame() {
    thirty_degrees_holds("1e-2", &thirty_degree_reference(200));
}

/// The release from 30° against the chain at N = 800, 1600, 3200: three minutes of CPU,
/// computed once for the tests that need it.
fn fine_thirty_degree_reference() -> &'static TipReference {
    static FINE: std::sync::OnceLock<TipReference> = std::sync::OnceLock::new();
    FINE.get_or_init(|| thirty_degree_reference(1600))
}

/// `cargo test --release --test pilots -- --ignored --nocapture`.
#[test]
#[ignore]
fn a_release_from_30_degrees_holds_1e_3_against_a_fine_reference_at_every_frame() {
    let fine = fine_thirty_degree_reference();
    // Converged to a tenth of the tolerance at every frame, whips included: a proof, not an
    // estimate.
    assert!(fine.own_error <= 1e-4, "own error {:.1e}", fine.own_error);
    thirty_degrees_holds("1e-3", fine);
}

/// Why `--tolerance 1e-3` from 30° needs the release atlas to find a run near the grid's
/// cheapest (N = 283, within a fifth of EPS): the tip's true error constant falls at large N,
/// and pilots flown higher would not see it. The largest of |x_N − x_{N/2}| over the frames falls at order
/// below 1 from N = 64 to 256, while the true worst error falls at order above 1.3.
/// `cargo test --release --test pilots -- --ignored --nocapture` prints the table.
#[test]
#[ignore]
fn higher_pilots_from_30_degrees_do_not_see_the_error_constant_fall() {
    let fine = fine_thirty_degree_reference();
    let thirty = Scene::Release { angle_deg: 30.0 };
    let options = rope::run::simulate::Options {
        duration: 3.0,
        log_rate: 60.0,
        frame_grid: None,
    };
    let levels = [64, 128, 256];
    let measured: Vec<(f64, f64)> = levels
        .iter()
        .map(|&n| {
            let method = MethodKind::Rattle;
            let dt = method.default_dt(n);
            let mut worst: f64 = 0.0;
            let run = rope::run::simulate::run_shadowed(method, &thirty, n, dt, rope::run::estimate::TipBound::FirstOrder, &options, |f| {
                worst = worst.max((f.tip() - fine.at(f.time)).norm());
            });
            let estimate = run.max_tip.unwrap();
            eprintln!(
                "rattle N = {n}: largest estimate {estimate:.2e}, true worst {worst:.2e} (constant {:.3}), ratio {:.2}",
                worst * n as f64,
                worst / estimate
            );
            (estimate, worst)
        })
        .collect();
    let order = |coarse: f64, fine: f64| (coarse / fine).log2();
    let (first, last) = (measured[0], measured[2]);
    let estimated = order(first.0, last.0) / 2.0;
    let true_order = order(first.1, last.1) / 2.0;
    eprintln!(
        "N = 64 to 256: estimates fall at order {estimated:.2}, the truth at {true_order:.2}"
    );
    assert!(estimated < 1.0, "estimates' order {estimated:.2}");
    assert!(true_order > 1.3, "true order {true_order:.2}");
}

#[test]
fn a_pilot_whose_shadow_fails_flies_on_where_the_estimate_can_start() {
    // From 30° the seed scheme's shadow at N = 8 blows up at once, at the seed's tolerance
    // step: the seed at N = 16 runs, its estimate does not. That rules the shadow out at
    // that level, not the seed: the seed flies the next level, where its estimate (0.12 at
    // N = 32) shows it far dearer at 1e-3 than the rods, so it flies no further and is not
    // chosen.
    let thirty = Scene::Release { angle_deg: 30.0 };
    let (choice, pilots) = tolerance::choose(1e-3, &thirty, 3.0, u64::MAX).unwrap();
    let seed = pilots.flown.iter().find(|p| p.method == MethodKind::Seed);
    let seed = seed.expect("the seed scheme can start from 30°: its pilot flies");
    assert!(seed.diverged.is_none(), "{seed:?}");
    let (level, why) = seed.shadow_lost.first().expect("the shadow at N = 8 fails");
    assert_eq!(*level, 16);
    assert!(why.reason.contains("shadow at N = 8"), "{why:?}");
    assert!(seed.measured.iter().map(|&(n, _)| n).eq([32]), "{seed:?}");
    assert_ne!(choice.method, MethodKind::Seed);
    let (s, said) = tolerance_run("pilot-shadow", &["--angle", "30", "--tolerance", "1e-3"]);
    assert!(!said.contains("seed: ruled out"), "{said}");
    assert!(
        said.contains("seed: ") && said.contains("at N = 32"),
        "{said}"
    );
    assert_ne!(s["method"], "seed");
}

#[test]
fn a_pilot_that_already_holds_is_the_run_chosen_and_the_climb_stops_there() {
    // Mode 1 is smooth: a pilot holds 1e-3 by its own estimate at the first level, and no
    // level above it is flown, by any method.
    let mode = Scene::Mode {
        number: 1,
        amplitude: 0.2,
    };
    let (choice, pilots) = tolerance::choose(1e-3, &mode, 3.0, u64::MAX).unwrap();
    assert_eq!(pilots.basis, pilot::Basis::Held);
    let held: Vec<_> = pilots
        .flown
        .iter()
        .filter(|p| p.held_at.is_some())
        .collect();
    assert_eq!(held.len(), 1, "{pilots:?}");
    assert_eq!(
        (held[0].method, held[0].held_at),
        (choice.method, Some(choice.segments))
    );
    assert!(choice.predicted_error <= 1e-3, "{choice:?}");
    for p in &pilots.flown {
        assert!(
            p.measured.iter().all(|&(n, _)| n <= choice.segments),
            "{p:?}"
        );
    }
}

#[test]
fn a_pilots_bound_is_its_estimate_rescaled_to_the_order_it_observes() {
    let pilot = |measured: Vec<(usize, f64)>| pilot::Pilot {
        method: MethodKind::Chain,
        measured,
        model: None,
        held_at: None,
        diverged: None,
        shadow_lost: Vec::new(),
        measured_by: None,
        seconds: 0.0,
        passed_over: None,
    };
    // One level: no order observed, the lowest taken (a whip's first), so the difference
    // the estimate divided by 2² − 1 is divided by 2¹ − 1 instead.
    let (n, bound) = pilot(vec![(16, 1e-3)]).bound().unwrap();
    assert_eq!(n, 16);
    assert!((bound - 3e-3 * pilot::SAFETY).abs() < 1e-15);
    // Halved from one level to the next: first order observed, the same.
    let (n, bound) = pilot(vec![(16, 2e-3), (32, 1e-3)]).bound().unwrap();
    assert_eq!(n, 32);
    assert!((bound - 3e-3 * pilot::SAFETY).abs() < 1e-15);
    // Quartered: the nominal order, the estimate as it is.
    let (_, bound) = pilot(vec![(16, 4e-3), (32, 1e-3)]).bound().unwrap();
    assert!((bound - 1e-3 * pilot::SAFETY).abs() < 1e-15);
}

#[test]
fn pilots_stop_where_measuring_would_cost_more_than_the_committed_choice() {
    // From 30° at 1e-2 the committed model, the release atlas's, chooses a run of a hundredth
    // of a second. No pilot holds 1e-2, and their first-order model asks for more segments
    // than the atlas's, the tighter: the rods' top level would cost more than that run, so
    // it is never flown and the committed choice is made.
    let thirty = Scene::Release { angle_deg: 30.0 };
    let (choice, pilots) = tolerance::choose(1e-2, &thirty, 3.0, u64::MAX).unwrap();
    let committed = choice::by_committed(1e-2, 3.0, &thirty, |_, _, _| true).unwrap();
    assert_eq!(choice, committed);
    assert_eq!(pilots.basis, pilot::Basis::Atlas);
    let atlas = committed::from_atlas(choice.method, &thirty, 3.0, 1e-2).unwrap();
    assert_eq!(choice.segments, atlas.segments_for(1e-2));
    let top = pilot::LEVELS[pilot::LEVELS.len() - 1];
    for p in &pilots.flown {
        assert!(p.held_at.is_none(), "{p:?}");
        if p.method != MethodKind::Seed {
            assert!(p.measured.iter().all(|&(n, _)| n < top), "{p:?}");
        }
    }
}

#[test]
fn a_pilot_that_cannot_save_what_it_costs_does_not_fly() {
    // Mode 2 at 1e-3 (from a tip amplitude of 0.2, past the mode theory's small swings): the
    // seed scheme's estimate at N = 16 asks thousands of segments at its first order, a run far
    // dearer than the rods' own model asks after their first level. Its next level could save
    // nothing, and does not fly; the rods', which can, do.
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.2,
    };
    let eps = 1e-3;
    let (choice, pilots) = tolerance::choose(eps, &mode, 3.0, u64::MAX).unwrap();
    let of = |m: MethodKind| pilots.flown.iter().find(|p| p.method == m).unwrap();
    let seed = of(MethodKind::Seed);
    assert!(seed.measured.iter().map(|&(n, _)| n).eq([16]), "{seed:?}");
    assert!(seed.fewest(eps, 16) > 10 * choice.segments, "{seed:?}");
    let chain = of(MethodKind::Chain);
    assert!(chain.measured.len() >= 2, "{chain:?}");
    assert_eq!(choice.method, MethodKind::Chain);
}

#[test]
fn a_releases_pilot_that_cannot_hold_where_the_atlas_rules_does_not_fly() {
    // From 10° at 1e-2 the chain's own atlas row asks N = 50, and rules over anything its
    // pilots could model: a pilot could change the choice only by holding at its level, and
    // the row's error at N = 16 and 32 is past EPS. Those pilots cost 9.5 ms, more than the
    // run chosen; they no longer fly, and the choice is the atlas's.
    let eps = 1e-2;
    let ten = Scene::Release { angle_deg: 10.0 };
    let models = committed::Committed::look_up(&ten, 3.0, eps);
    assert_eq!(models.source(MethodKind::Chain), committed::Source::Atlas);
    for level in [16, 32] {
        assert!(models.model(MethodKind::Chain).predict(level) > eps);
        assert!(!models.may_hold(MethodKind::Chain, level, eps));
    }
    let (choice, pilots) = tolerance::choose(eps, &ten, 3.0, u64::MAX).unwrap();
    let chain = pilots.flown.iter().find(|p| p.method == MethodKind::Chain);
    assert!(!chain.unwrap().flew(), "{chain:?}");
    let committed = choice::by_committed(eps, 3.0, &ten, |_, _, _| true).unwrap();
    assert_eq!((choice.method, choice.segments), (MethodKind::Chain, 50));
    assert_eq!(choice, committed);
    // Where the atlas's error at a level is within EPS, though with its margin it asks for
    // more, the pilot may hold there, and flies: from 72° at 3e-3 the graded rods' atlas asks
    // N = 75, and their pilot flies at 64.
    let seventy_two = Scene::Release { angle_deg: 72.0 };
    let models = committed::Committed::look_up(&seventy_two, 3.0, 3e-3);
    assert_eq!(models.source(MethodKind::Graded), committed::Source::Atlas);
    assert!(models.model(MethodKind::Graded).segments_for(3e-3) > 64);
    assert!(models.may_hold(MethodKind::Graded, 64, 3e-3));
    let (_, pilots) = tolerance::choose(3e-3, &seventy_two, 3.0, u64::MAX).unwrap();
    let graded = pilots.flown.iter().find(|p| p.method == MethodKind::Graded);
    assert!(
        graded.unwrap().measured.iter().any(|&(n, _)| n == 64),
        "{graded:?}"
    );
    // The one law, the worst of six scenes, rules no pilot out: from 90°, hanging still, the
    // seed's pilot holds at N = 16 where its law reads 0.2.
    let ninety = Scene::Release { angle_deg: 90.0 };
    let models = committed::Committed::look_up(&ninety, 3.0, eps);
    assert!(law(MethodKind::Seed).predict(16) > 10.0 * eps);
    assert!(models.may_hold(MethodKind::Seed, 16, eps));
    let (choice, pilots) = tolerance::choose(eps, &ninety, 3.0, u64::MAX).unwrap();
    assert_eq!(pilots.basis, pilot::Basis::Held);
    assert_eq!((choice.method, choice.segments), (MethodKind::Seed, 16));
}

#[test]
fn methods_of_one_discretization_fly_one_pilot_the_cheapest() {
    // The chain, rattle and midpoint are the same rods: at their tolerance steps their tip
    // errors are the rods' own, so only the cheapest of them, the chain, flies; the others
    // say whose pilots stand for theirs.
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.2,
    };
    let (_, pilots) = tolerance::choose(1e-3, &mode, 3.0, u64::MAX).unwrap();
    let of = |m: MethodKind| pilots.flown.iter().find(|p| p.method == m).unwrap();
    assert!(of(MethodKind::Chain).flew() && of(MethodKind::Chain).measured_by.is_none());
    for m in [MethodKind::Rattle, MethodKind::Midpoint] {
        assert_eq!(of(m).measured_by, Some(MethodKind::Chain), "{:?}", of(m));
        assert!(!of(m).flew(), "{:?}", of(m));
    }
    // The seed scheme's finite differences are a discretization of their own: it flies.
    assert!(of(MethodKind::Seed).flew() && of(MethodKind::Seed).measured_by.is_none());
    let (_, said) = tolerance_run("pilot-rods", &["--angle", "30", "--tolerance", "1e-2"]);
    assert!(
        said.contains("rattle: not flown: its rods are the chain's"),
        "{said}"
    );
    // From 30° at 1e-2 the release atlas rules the chain's choice and puts its error at
    // N = 16 and 32 past EPS: its pilots could change the choice only by holding, and do not
    // fly, and the announcement says so.
    assert!(
        said.contains(
            "chain: not flown: the release atlas puts its error at N = 16 and 32 past the tolerance"
        ),
        "{said}"
    );
}

#[test]
fn a_scene_its_pilots_show_cheaper_is_run_from_their_model_and_holds() {
    // In mode 2 the pilots' estimates fall faster than first order: their own model asks for
    // tens of segments at 1e-3 where the committed models (fitted to the horizontal release's
    // whip) ask for hundreds. (From a tip amplitude of 0.15, past the mode theory's small
    // swings, which would otherwise choose before any pilot of the rods flies.)
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.15,
    };
    let (choice, pilots) = tolerance::choose(1e-3, &mode, 3.0, u64::MAX).unwrap();
    let committed = choice::by_committed(1e-3, 3.0, &mode, |_, _, _| true).unwrap();
    assert_eq!(pilots.basis, pilot::Basis::OwnModel, "{pilots:?}");
    assert!(
        choice.segments * 4 < committed.segments,
        "{choice:?} {committed:?}"
    );
    // Held at every frame against the chain at N = 200, 400, 800 extrapolated: its distance
    // from the reference plus the reference's own error bounds its distance from the truth.
    let reference = TipReference::compute(&mode, 200, 3.0).unwrap();
    assert!(
        reference.own_error <= 1e-4,
        "own error {:.1e}",
        reference.own_error
    );
    let flags = [
        "--scene",
        "mode",
        "--mode-number",
        "2",
        "--amplitude",
        "0.15",
        "--tolerance",
        "1e-3",
    ];
    let (s, _) = tolerance_run("pilot-mode-2", &flags);
    assert_eq!(s["segments"].as_u64(), Some(choice.segments as u64));
    let worst = worst_tip_error(&s, |t| reference.at(t)) + reference.own_error;
    eprintln!(
        "mode 2, 1e-3: N = {}, worst tip error at most {worst:.2e}",
        choice.segments
    );
    assert!(
        worst <= 1e-3,
        "worst tip error {worst:.2e} at N = {}",
        choice.segments
    );
}

/// Within the committed window a release's pilots may not ask fewer rods than the committed
/// model that covers the run: a release's error constant goes on growing past their N ≤ 64.
/// From 80° at 1e-4 the chain's pilots fit about 0.14/N (×1.9 for scatter and safety) and once
/// asked N = 2 639, which erred by 1.15e-4 at every instant against the committed reference
/// (0.30/N; `cargo run --release --example tolerance_instants -- 1e-4 80`); the chain's law,
/// measured up to large N, asks more, and its run held at 0.66 of EPS.
#[test]
fn within_the_committed_window_a_releases_pilots_never_ask_fewer_rods_than_the_committed_model() {
    let scene = Scene::Release { angle_deg: 80.0 };
    let (choice, pilots) = tolerance::choose(1e-4, &scene, 3.0, u64::MAX).unwrap();
    let models = committed::Committed::look_up(&scene, 3.0, 1e-4);
    assert!(models.floors_pilots && models.covers(choice.method));
    let own = pilots
        .flown
        .iter()
        .find(|p| p.method == choice.method)
        .and_then(|p| p.model)
        .expect("the chosen method's pilots have a model");
    let committed = models.model(choice.method);
    assert!(
        own.segments_for(1e-4) < committed.segments_for(1e-4),
        "the pilots' own model no longer asks fewer: the test tests nothing"
    );
    assert_eq!(
        pilots.basis,
        pilot::Basis::CommittedOverPilots,
        "{pilots:?}"
    );
    assert!(
        choice.segments >= committed.segments_for(1e-4),
        "N = {} below the committed model's {}",
        choice.segments,
        committed.segments_for(1e-4)
    );
    // A mode's error settles within the pilots' N: there their model still rules.
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.05,
    };
    assert!(!committed::Committed::look_up(&mode, 3.0, 1e-4).floors_pilots);
}

/// Past the windows the committed models were measured over (t = 3, and t = 5 for the graded
/// rods' longer atlas) the pilots rule: from 45° to t = 5 the law fitted to t ≤ 3 once asked
/// N = 491 where the pilots measured about 0.93/N, and the run missed 1e-3 after t = 4.88.
/// The choice now asks at least what the pilots' own model asks, and within its window the
/// committed model may still be the tighter.
#[test]
fn past_the_committed_window_the_pilots_measured_figure_rules() {
    let scene = Scene::Release { angle_deg: 45.0 };
    let (choice, pilots) = tolerance::choose(1e-3, &scene, 6.0, u64::MAX).unwrap();
    assert!(
        matches!(pilots.basis, pilot::Basis::OwnModel | pilot::Basis::Held),
        "{:?}",
        pilots.basis
    );
    let own = pilots
        .flown
        .iter()
        .find(|p| {
            p.method == choice.method
                || p.method.descriptor().discretization == choice.method.descriptor().discretization
                    && p.model.is_some()
        })
        .and_then(|p| p.model)
        .expect("the chosen rods' pilots have a model");
    assert!(
        choice.segments >= own.segments_for(1e-3),
        "N = {} below the pilots' {}",
        choice.segments,
        own.segments_for(1e-3)
    );
    // The test is of a run past every window; were one to grow past 6, it would test nothing.
    const { assert!(6.0 > atlas::LONGER_WINDOW && 6.0 > committed::LAW_UNTIL) };
}

/// From t = 3 to 5 the chain's one law, fitted to t ≤ 3, does not cover the run, and the
/// graded rods' atlas to t = 5 does: from 45° to t = 5 at 1e-3 it chooses the graded rods, at
/// no more segments than the pilots' own model would ask of them (it measured the whips after
/// t = 3 up to N = 1131, which the pilots see only to N = 64).
#[test]
fn from_45_degrees_to_t_5_the_graded_rods_longer_atlas_covers_the_run_and_the_law_does_not() {
    let scene = Scene::Release { angle_deg: 45.0 };
    let models = committed::Committed::look_up(&scene, 5.0, 1e-3);
    assert!(!models.covers(MethodKind::Chain));
    assert!(models.covers(MethodKind::Graded));
    assert_eq!(models.source(MethodKind::Graded), committed::Source::Atlas);
    // The committed choice alone is made of the models that cover the run: the chain's law,
    // whose run would be predicted the cheaper, is not among them.
    let committed = choice::by_committed(1e-3, 5.0, &scene, |_, _, _| true).unwrap();
    assert_eq!(committed.method, MethodKind::Graded, "{committed:?}");
    let law = law(MethodKind::Chain);
    let by_law = choice::by_model(MethodKind::Chain, &law, 1e-3, 16, 5.0);
    assert!(
        by_law.predicted_seconds < committed.predicted_seconds,
        "{committed:?}"
    );
    graded_rods_from_their_atlas(1e-3, &scene, 5.0);
    // To t = 3 the shorter atlas serves: its window is the shortest that covers the run.
    let shorter = atlas::Atlas::of(MethodKind::Graded, 3.0).unwrap();
    assert_eq!(shorter.window, atlas::WINDOW);
    let longer = atlas::Atlas::of(MethodKind::Graded, 5.0).unwrap();
    assert_eq!(longer.window, atlas::LONGER_WINDOW);
    assert!(atlas::Atlas::of(MethodKind::Chain, 5.0).is_none());
}

#[test]
fn from_30_degrees_at_1e_4_the_graded_rods_are_chosen_from_their_atlas_for_a_fraction_of_the_chain()
{
    // The chain's atlas does not reach 1e-4 (its references err by 2e-5 and more), so the
    // chain falls back on its one law, fitted to the horizontal release's whip: thousands of
    // rods. The graded rods resolve the whip, and their atlas, against graded references that
    // err by a few 1e-6 from 20° to 30°, reaches 1e-4 there.
    let thirty = Scene::Release { angle_deg: 30.0 };
    let (choice, pilots) = tolerance::choose(1e-4, &thirty, 3.0, u64::MAX).unwrap();
    assert_eq!(choice.method, MethodKind::Graded, "{choice:?}");
    assert_eq!(pilots.basis, pilot::Basis::Atlas);
    let law = law(MethodKind::Chain);
    let by_law = choice::by_model(MethodKind::Chain, &law, 1e-4, 16, 3.0);
    assert!(
        choice.predicted_seconds < 0.25 * by_law.predicted_seconds,
        "{choice:?} against the chain's law: {by_law:?}"
    );
    // Not from the horizontal, whose graded end rods spin on after the whip: no atlas there.
    let horizontal = Scene::Release { angle_deg: 0.0 };
    assert!(committed::from_atlas(MethodKind::Graded, &horizontal, 3.0, 1e-2).is_none());
}

/// From 37°, which no atlas measured, the graded atlas bounds the error by the larger of the
/// 30° and 40° rows times its margin. With the 30° row ending at N = 800 (its reference,
/// from runs up to N = 6 400, erred by 2.1e-6, not a tenth of the rods' 1.8e-5 at N = 1 131)
/// the choice fell to the chain at N = 4 901 by its one law (43 s); with that reference
/// doubled (runs up to 12 800) both rows reach N = 1 131, and the graded rods are chosen
/// within it.
#[test]
fn from_37_degrees_at_1e_4_the_graded_atlas_reaches_far_enough_to_choose_the_graded_rods() {
    let between = Scene::Release { angle_deg: 37.0 };
    graded_rods_from_their_atlas(1e-4, &between, 3.0);
}

/// An atlas serves a tolerance only where a reference could judge it (its own error at most a
/// tenth of EPS). Measured at every 1/3 000, the committed references from 70° and 80° err by
/// 2.1e-5 and 1.5e-5, and that from 10° (the chain's whip at N = 3 200, extrapolated) by
/// 2.8e-4: no atlas serves 1e-4 there, and the choice rests on a law or on the pilots. (At 60
/// frames a unit the references looked fine enough, and the atlas's choices there missed 1e-4
/// by up to 1.5 times between the frames.) From 20° to 60° the graded rods' atlas serves it:
/// at 20°, 30°, …, 60° their own rows, from 50° and 60° against references refined to
/// N = 25 600 (4.5e-6 and 8.4e-6; before, those erred by 1.6e-5 and 1.4e-5 and served no more
/// than 70°'s); between them the neighbours' law, from rows measured on to N = 2 263 against
/// references that can judge 1e-4 there.
#[test]
fn at_1e_4_an_atlas_serves_only_where_its_reference_can_judge_at_every_instant() {
    for angle_deg in [10.0, 70.0, 80.0] {
        let scene = Scene::Release { angle_deg };
        for method in [MethodKind::Chain, MethodKind::Graded] {
            let model = committed::from_atlas(method, &scene, 3.0, 1e-4);
            assert!(model.is_none(), "{angle_deg}°, {method}: {model:?}");
        }
        let (_, pilots) = tolerance::choose(1e-4, &scene, 3.0, u64::MAX).unwrap();
        assert_ne!(pilots.basis, pilot::Basis::Atlas, "{angle_deg}°");
    }
    for angle_deg in [20.0, 25.0, 30.0, 37.0, 40.0, 45.0, 50.0, 52.0, 55.0, 60.0] {
        let scene = Scene::Release { angle_deg };
        graded_rods_from_their_atlas(1e-4, &scene, 3.0);
    }
}

/// The graded rods may be chosen from 20° to t = 3, but past t = 3 only from 40°: below it
/// their end rods come out of a second whip, near t = 4.8, spinning (a step to t = 5 from 30°
/// costs 13 times its price to t = 3), which the cost model does not see. From 30° to t = 5 the
/// pilots then fly the chain, not the graded rods.
#[test]
fn past_t_3_the_graded_rods_are_chosen_only_from_40_degrees() {
    use rope::methods::graded::{SPIN_FREE_FROM, SPIN_FREE_LONGER_FROM};
    let graded = |angle_deg: f64, duration: f64| {
        let scene = Scene::Release { angle_deg };
        choice::startable(&scene, duration).any(|m| m == MethodKind::Graded)
    };
    assert!(graded(SPIN_FREE_FROM, 3.0) && graded(30.0, 3.0));
    assert!(!graded(30.0, 5.0) && !graded(39.0, 3.5));
    assert!(graded(SPIN_FREE_LONGER_FROM, 5.0) && graded(60.0, 5.0));
    assert!(!graded(10.0, 3.0) && !graded(10.0, 5.0));
    let thirty = Scene::Release { angle_deg: 30.0 };
    let (_, pilots) = tolerance::choose(1e-2, &thirty, 5.0, u64::MAX).unwrap();
    assert!(pilots.flown.iter().all(|p| p.method != MethodKind::Graded));
    assert!(pilots.flown.iter().any(|p| p.method == MethodKind::Chain));
}

/// What `--tolerance eps` chooses for `scene` to `duration`, asserted to be the graded rods,
/// from their atlas, within the N it measured.
fn graded_rods_from_their_atlas(eps: f64, scene: &Scene, duration: f64) -> choice::Choice {
    let (choice, pilots) = tolerance::choose(eps, scene, duration, u64::MAX).unwrap();
    assert_eq!(choice.method, MethodKind::Graded, "{choice:?}");
    assert_eq!(pilots.basis, pilot::Basis::Atlas);
    let graded_atlas = atlas::Atlas::of(MethodKind::Graded, duration).unwrap();
    let largest = graded_atlas
        .rows()
        .flat_map(|(_, row)| row.into_iter().map(|(n, _)| n))
        .chain(graded_atlas.envelope().map(|(n, _)| n));
    assert!(choice.segments <= largest.max().unwrap(), "{choice:?}");
    choice
}

/// The release from `angle_deg` to `duration` of the graded rods at N = 800, 1600, 3200,
/// extrapolated (and from 1600, 3200, 6400 if its own error is above `own`), its own error
/// printed and asserted to be at most `own`.
fn graded_reference(angle_deg: f64, duration: f64, own: f64) -> TipReference {
    let scene = Scene::Release { angle_deg };
    let graded = MethodKind::Graded;
    let reference =
        TipReference::refined_by(graded, &scene, 1600, 3200, own, duration, &|| ()).unwrap();
    eprintln!(
        "graded reference from {angle_deg}° to t = {duration} at N = {}, {}, {}: order {:.2}, own error {:.1e}",
        reference.segments / 2,
        reference.segments,
        reference.segments * 2,
        reference.order,
        reference.own_error
    );
    assert!(
        reference.own_error <= own,
        "own error {:.1e}",
        reference.own_error
    );
    reference
}

/// The release from 30° against the graded rods: their reference's own error a few 1e-6.
/// `cargo test --release --test pilots -- --ignored --nocapture` (about five minutes of CPU).
#[test]
#[ignore]
fn a_release_from_30_degrees_holds_1e_4_against_the_graded_reference_at_every_frame() {
    thirty_degrees_holds("1e-4", &graded_reference(30.0, 3.0, 1e-5));
}

/// `rope run --angle 45 --tolerance 1e-3 --duration 5`, chosen from the graded rods' atlas to
/// t = 5 (45° is one of its held-out angles), against the graded rods at N = 800, 1600, 3200
/// to t = 5, extrapolated.
/// `cargo test --release --test pilots -- --ignored a_release_from_45_degrees --nocapture`
/// (about five minutes of CPU).
#[test]
#[ignore]
fn a_release_from_45_degrees_over_5_units_holds_1e_3_against_the_graded_reference() {
    over_5_units_holds_1e_3(45.0);
}

/// From 42°, which the atlas to t = 5 did not measure, its envelope asks more than the pilots'
/// model, which chooses the chain (N = 2 028): against the graded reference too, from
/// N = 1600, 3200 and 6400 (from 800, 1600 and 3200 its own error is 1.2e-4).
/// `cargo test --release --test pilots -- --ignored a_release_from_42_degrees --nocapture`
/// (about fifteen minutes of CPU).
#[test]
#[ignore]
fn a_release_from_42_degrees_over_5_units_holds_1e_3_against_the_graded_reference() {
    over_5_units_holds_1e_3(42.0);
}

/// `rope run --angle ANGLE --tolerance 1e-3 --duration 5` against the graded rods at N = 800,
/// 1600, 3200 to t = 5, extrapolated: its worst tip error plus the reference's own holds 1e-3.
fn over_5_units_holds_1e_3(angle_deg: f64) {
    let reference = graded_reference(angle_deg, 5.0, 1e-4);
    let angle = angle_deg.to_string();
    let flags = ["--angle", &angle, "--tolerance", "1e-3", "--duration", "5"];
    let (s, _) = tolerance_run(&format!("pilot-{angle}-5"), &flags);
    let worst = worst_tip_error(&s, |t| reference.at(t));
    let (method, segments) = (&s["method"], &s["segments"]);
    // Against the truth: the error against the reference plus the reference's own.
    let bound = worst + reference.own_error;
    eprintln!(
        "{angle}° to t = 5, 1e-3: {method} at N = {segments}, worst tip error {worst:.2e} against the reference, at most {bound:.2e}"
    );
    assert!(
        bound <= 1e-3,
        "worst tip error at most {bound:.2e} with {method} at N = {segments}"
    );
}
