//! The study's mechanics on tiny grids (rows, statuses, the reference's error estimate,
//! chart files). The error models and the tolerance rule are `tests/estimate.rs`'s. Timings
//! are not tested here (they live in benchmarks).

mod common;

use common::cli::Scratch;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::study::{self, Spec, Status};

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };

#[test]
fn tiny_grid_writes_a_row_per_run_with_statuses_errors_and_every_chart() {
    let spec = Spec {
        scene: THIRTY,
        duration: 0.5,
        methods: MethodKind::ALL.to_vec(),
        segments: vec![10, 50],
        dts: vec![1e-3, 3e-2],
    };
    let scratch = Scratch::new("study-tiny");
    let out = &scratch.0;
    let outcome = study::execute(&spec, 100, out, "test", &|| {}).expect("the study runs");
    assert_eq!(outcome.rows.len(), 2 * 2 * MethodKind::ALL.len());
    // The seed scheme at N = 50 cannot take k = 3e-2 (its limit is about 1.7e-2 there).
    let seed_50_big = outcome
        .rows
        .iter()
        .find(|r| r.method == MethodKind::Seed && r.segments == 50 && r.dt > 1e-2)
        .unwrap();
    assert!(
        matches!(seed_50_big.status, Status::Diverged { .. }),
        "{:?}",
        seed_50_big.status
    );
    for row in outcome.rows.iter().filter(|r| r.status == Status::Ok) {
        assert!(row.tip_error.unwrap() > 0.0 && row.shape_error.unwrap() > 0.0);
        assert!(row.energy_deviation.unwrap().is_finite());
        assert!(row.cpu_seconds > 0.0);
    }
    let estimate = outcome.reference.error_estimate();
    assert!(
        estimate > 0.0 && estimate < 1e-4,
        "reference error estimate {estimate}"
    );
    let csv = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "method,segments,dt,status,energy_deviation,tip_error,final_tip_error,shape_error,cpu_seconds,ns_per_segment_step,diverged_time,reason"
    );
    assert_eq!(lines.count(), outcome.rows.len());
    for chart in [
        "work_precision",
        "stability_map",
        "fig1_startup_burst",
        "fig2_energy_vs_n_linear",
        "fig3_energy_vs_n_log",
        "fig4_energy_vs_k",
    ] {
        for ext in ["svg", "png"] {
            let path = out.join(format!("{chart}.{ext}"));
            let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
            assert!(size > 1000, "{} is missing or empty", path.display());
        }
    }
    assert!(
        std::fs::read_to_string(out.join("findings.md"))
            .unwrap()
            .contains("Convergence in h")
    );
}

/// The study's tip error is the worst over the frames, not the final instant's (where errors
/// can cancel by chance): checked against the truth, an independent run of the chain at
/// N = 400 read at each frame's time, for coarse runs whose error swings as the whip passes.
#[test]
fn a_runs_tip_error_is_its_worst_over_the_frames_against_an_independent_fine_run() {
    let spec = Spec {
        scene: THIRTY,
        duration: 2.0,
        methods: vec![MethodKind::Chain, MethodKind::Midpoint],
        segments: vec![8, 16],
        dts: vec![2e-3],
    };
    let scratch = Scratch::new("study-frames");
    let out = &scratch.0;
    let outcome = study::execute(&spec, 200, out, "test", &|| {}).expect("the study runs");
    let truth = study::trajectory::Trajectory::compute(&THIRTY, 400, spec.duration).unwrap();
    let resolution = outcome.reference.error_estimate() + 1e-4;
    let mut wider = 0;
    for row in &outcome.rows {
        assert_eq!(row.status, Status::Ok, "{row:?}");
        // Every frame, at 30 a time unit: 61 over [0, 2].
        assert_eq!(row.frame_tips.len(), 61, "{:?}", row.method);
        let worst = row
            .frame_tips
            .iter()
            .map(|&(t, tip)| (tip - truth.at(t)).norm())
            .fold(0.0, f64::max);
        let (tip, last) = (row.tip_error.unwrap(), row.final_tip_error.unwrap());
        assert!(
            (tip - worst).abs() <= resolution,
            "{} N = {}: the study's {tip:.3e} against the truth's {worst:.3e}",
            row.method,
            row.segments
        );
        assert!(tip >= last - resolution, "{tip:e} below the final {last:e}");
        if tip > 2.0 * last {
            wider += 1;
        }
    }
    assert!(wider > 0, "no run's worst frame was far from its final one");
    let csv = std::fs::read_to_string(out.join("study.csv")).unwrap();
    assert!(
        csv.lines()
            .next()
            .unwrap()
            .contains(",tip_error,final_tip_error,")
    );
}

#[test]
fn seed_runs_from_the_horizontal_are_refused_and_the_chain_runs() {
    let spec = Spec {
        scene: Scene::Release { angle_deg: 0.0 },
        duration: 0.3,
        methods: MethodKind::ALL.to_vec(),
        segments: vec![10],
        dts: vec![1e-3],
    };
    let rows = study::run_grid(&spec, &|| {}).unwrap();
    let seed = rows.iter().find(|r| r.method == MethodKind::Seed).unwrap();
    assert!(matches!(&seed.status, Status::Refused { reason } if reason.contains("horizontal")));
    let chain = rows.iter().find(|r| r.method == MethodKind::Chain).unwrap();
    assert_eq!(chain.status, Status::Ok);
}

#[test]
fn a_small_grid_says_why_it_fits_no_order_and_prints_steps_as_given() {
    // 0.3 / 1e-4 is 2999.9999999999995 in floating point: the step must still print as 1e-4.
    let spec = Spec {
        scene: THIRTY,
        duration: 0.3,
        methods: vec![MethodKind::Chain, MethodKind::Rattle],
        segments: vec![10, 20],
        dts: vec![1e-3, 1e-4],
    };
    let scratch = Scratch::new("study-small");
    let out = &scratch.0;
    let outcome = study::execute(&spec, 40, out, "test", &|| {}).expect("the study runs");
    let findings = std::fs::read_to_string(out.join("findings.md")).unwrap();
    assert!(
        findings.contains("No fit for chain, rattle") && findings.contains("two or more N ≥ 20"),
        "{findings}"
    );
    let csv = std::fs::read_to_string(out.join("study.csv")).unwrap();
    let steps: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(2).unwrap())
        .collect();
    assert_eq!(steps.len(), outcome.rows.len());
    assert!(
        steps.iter().all(|k| *k == "1e-3" || *k == "1e-4"),
        "{steps:?}"
    );
}
