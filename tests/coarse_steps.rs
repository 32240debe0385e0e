//! A step asked for far past the step `--tolerance` runs at: the midpoint rule and the RK4
//! chain take it as asked while the rods turn slowly (the midpoint rule in one step, not a
//! pair), still split it where the free end whips, and hold the tip where the converged
//! string is (the cheapest whole small runs: `cargo run --release --example
//! small_run_search`).

use rope::Summary;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::study::tip_reference::{ConvergedTip, TipReference};
use rope::{RunConfig, simulate};

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
const HORIZONTAL: Scene = Scene::Release { angle_deg: 0.0 };
/// Far past either method's tolerance step at these N (1/100 or less at N = 8 and 12).
const COARSE: f64 = 0.1;

fn coarse_run(method: MethodKind, scene: Scene, segments: usize, duration: f64) -> rope::Simulated {
    let config = RunConfig {
        method,
        scene,
        segments,
        dt: Some(COARSE),
        duration,
        log_rate: 10.0,
        error_estimate: false,
        ..RunConfig::default()
    };
    let run = simulate(&config).expect("a valid run");
    assert!(run.summary.diverged.is_none(), "{method} diverged");
    run
}

/// The tip's largest distance from the converged string at t = 0.1, 0.2, …, 1.0.
fn worst_tip_error(run: &rope::Simulated) -> f64 {
    // The chain at N = 50, 100, 200, extrapolated: its own error far below 1e-3 to t = 1.
    let reference = TipReference::compute(&THIRTY, 100, 1.0).expect("the reference");
    assert!(
        reference.own_error < 1e-5,
        "own error {}",
        reference.own_error
    );
    reference.farthest(&run.frames)
}

fn own_steps(summary: &Summary) -> u64 {
    summary.step_statistics.as_ref().expect("midpoint's").steps
}

#[test]
fn the_midpoint_takes_a_coarse_step_whole_while_the_rods_turn_slowly_and_holds_the_tip_to_1e_3() {
    let run = coarse_run(MethodKind::Midpoint, THIRTY, 8, 1.0);
    // From 30° the fastest rod turns below 3 rad a time unit to t = 1: 0.3 rad in a step,
    // where the bound at the tolerance step (0.05 rad) split each step into four or six, and
    // before coarse steps were taken whole, each was a pair of 0.05.
    assert_eq!(own_steps(&run.summary), 10);
    let worst = worst_tip_error(&run);
    assert!(worst < 1e-3, "worst tip error {worst:.3e}");
}

#[test]
fn the_midpoint_still_splits_a_coarse_step_where_the_free_end_whips_and_keeps_its_energy() {
    let run = coarse_run(MethodKind::Midpoint, HORIZONTAL, 8, 3.0);
    let statistics = run.summary.step_statistics.as_ref().expect("midpoint's");
    // The whip turns the end rod at over 15 rad a time unit: half a radian takes under 1/30.
    assert!(statistics.smallest_step < COARSE / 4.0, "{statistics:?}");
    assert!(statistics.steps > 60, "{statistics:?}");
    assert!(statistics.newton_failures == 0, "{statistics:?}");
    let energy = run.summary.energy.max_abs_deviation;
    assert!(energy < 1e-12, "energy strays by {energy:.3e}");
}

#[test]
fn the_chain_at_a_coarse_step_holds_the_tip_to_1e_3_and_stays_stable_through_the_whip() {
    let run = coarse_run(MethodKind::Chain, THIRTY, 12, 1.0);
    let worst = worst_tip_error(&run);
    assert!(worst < 1e-3, "worst tip error {worst:.3e}");
    // Its Courant bound, which keeps RK4 stable, never loosens: from the horizontal through
    // the whip the energy moves by RK4's truncation, not a blow-up's.
    let whip = coarse_run(MethodKind::Chain, HORIZONTAL, 8, 3.0);
    let energy = whip.summary.energy.max_abs_deviation;
    assert!(energy < 1e-3, "energy strays by {energy:.3e}");
}
