//! The folded chain let go at one end, against Calkin & March's energy-conserving string
//! (`rope::model::fold`): the free end's speed, the support's pull, and the energy through
//! the final snap. The midpoint method at N = 200 with a gap of 0.02 (four rods across it,
//! the fewest the docs ask for).

mod common;

use common::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::model::fold;
use rope::run::Frame;

const FOLD: Scene = Scene::Fold { gap: 0.02 };
const SEGMENTS: usize = 200;

/// The fold's frames at every driver step to `duration`, each with the free end's fall x.
fn fold_frames(duration: f64) -> (rope::run::simulate::Outcome, Vec<(f64, Frame)>) {
    let method = MethodKind::Midpoint;
    let dt = method.default_dt(SEGMENTS);
    let (outcome, frames) = run_frames(method, FOLD, SEGMENTS, dt, duration, 1.0 / dt);
    let start = frames.first().expect("a first frame").tip().y;
    let falls = frames.into_iter().map(|f| (f.tip().y - start, f)).collect();
    (outcome, falls)
}

/// The frames before the snap: while the fall only grows.
fn before_snap(frames: &[(f64, Frame)]) -> Vec<&(f64, Frame)> {
    let mut highest = f64::NEG_INFINITY;
    frames
        .iter()
        .take_while(|(x, _)| {
            let growing = *x >= highest;
            highest = highest.max(*x);
            growing
        })
        .collect()
}

#[test]
fn the_free_end_outruns_gravity_at_the_speed_calkin_and_march_predict() {
    let (outcome, frames) = fold_frames(1.3);
    assert!(outcome.diverged.is_none());
    let falling = before_snap(&frames);
    let worst = |low: f64, high: f64| {
        falling
            .iter()
            .filter(|(x, _)| (low..=high).contains(x))
            .map(|(x, f)| (f.tip_velocity.norm() / fold::speed(*x) - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let (to_075, to_085) = (worst(0.05, 0.75), worst(0.75, 0.85));
    eprintln!(
        "fold speed against Calkin–March: {to_075:.2e} at worst for x in [0.05, 0.75], {to_085:.2e} in [0.75, 0.85]"
    );
    assert!(
        to_075 < 0.01,
        "speed off by {to_075:.2e} for x in [0.05, 0.75]"
    );
    assert!(
        to_085 < 0.02,
        "speed off by {to_085:.2e} for x in [0.75, 0.85]"
    );
    // Faster than a body dropped at the same moment, all the way down.
    for (x, f) in falling.iter().filter(|(x, _)| *x >= 0.05) {
        assert!(f.tip_velocity.norm() > fold::free_fall_speed(*x), "x = {x}");
    }
    // It reaches 0.85 before a body would.
    let at = falling
        .iter()
        .find(|(x, _)| *x >= 0.85)
        .expect("x = 0.85 reached");
    assert!(at.1.time < (2.0f64 * 0.85).sqrt());
}

#[test]
fn the_support_pull_averaged_over_a_window_of_fall_is_the_formula() {
    let (_, frames) = fold_frames(1.3);
    let falling = before_snap(&frames);
    for k in 2..=15 {
        let centre = 0.05 * k as f64;
        let window: Vec<_> = falling
            .iter()
            .filter(|(x, _)| (*x - centre).abs() <= 0.05)
            .collect();
        let (first, last) = (window[0], window[window.len() - 1]);
        let span = last.1.time - first.1.time;
        // The weight less the rate the string gains downward momentum: the support's pull
        // over the window, whatever the instants between rods rounding the bend.
        let pulled = 1.0 - (last.1.momentum.y - first.1.momentum.y) / span;
        // The raw tension at every step, averaged over the same time.
        let raw = window.iter().map(|(_, f)| f.support_tension).sum::<f64>() / window.len() as f64;
        let formula = window
            .iter()
            .map(|(x, _)| fold::support_tension(*x))
            .sum::<f64>()
            / window.len() as f64;
        eprintln!(
            "fold support pull at x = {centre:.2} ± 0.05: from momentum {pulled:.4}, raw tension {raw:.4}, formula {formula:.4}"
        );
        for (what, value) in [("pull from momentum", pulled), ("raw tension", raw)] {
            let off = (value / formula - 1.0).abs();
            assert!(
                off < 0.05,
                "x = {centre:.2}: {what} {value:.4} against {formula:.4}"
            );
        }
    }
}

#[test]
fn the_energy_is_kept_through_the_final_snap() {
    let method = MethodKind::Midpoint;
    let initial = method
        .build(&FOLD, SEGMENTS, method.default_dt(SEGMENTS))
        .expect("the fold starts")
        .energy()
        .total();
    let (outcome, frames) = fold_frames(2.2);
    assert!(outcome.diverged.is_none());
    let statistics = outcome.step_statistics.expect("the midpoint's own steps");
    assert_eq!(statistics.newton_failures, 0);
    // The snap happened: the free end reached the bottom and came back.
    let falling = before_snap(&frames);
    assert!(falling.last().expect("frames").0 > 0.95);
    assert!(falling.len() < frames.len());
    let mut worst: f64 = 0.0;
    for (_, f) in &frames {
        let off = (f.energy.total() - initial).abs();
        assert!(off <= 1e-9, "t = {}: |E − E₀| = {off:.2e}", f.time);
        worst = worst.max(off);
    }
    eprintln!(
        "fold energy to t = 2.2: |E − E₀| ≤ {worst:.2e}, the snap at t = {:.4}, fastest rod {:.0} rad per time unit",
        falling.last().expect("frames").1.time,
        statistics.fastest_rotation
    );
}

/// The summary says the fold fully: the free arm runs out at a fall of 1 − πd/2, the free end
/// falls at least that far, and the snap (the support's largest pull) comes when Calkin &
/// March's string has fallen all the way (t = 1.198), within 1 %, the deepest fall with it.
#[test]
fn the_summary_gives_the_deepest_fall_and_the_snap_when_the_theory_ends() {
    let plan = rope::RunConfig {
        method: MethodKind::Midpoint,
        scene: FOLD,
        segments: SEGMENTS,
        duration: 1.6,
        log_rate: 10.0,
        ..rope::RunConfig::default()
    };
    let run = rope::simulate(&plan).expect("the fold runs");
    let fold = run.summary.fold.expect("a fold's figures");
    let ends = fold::time_to_fall(1.0);
    assert!((fold.arm_limit - (1.0 - std::f64::consts::PI * 0.01)).abs() < 1e-12);
    assert!(
        fold.deepest_fall >= fold.arm_limit && fold.deepest_fall < 1.0,
        "{fold:?}"
    );
    let snap = run.summary.max_support_tension_time;
    for t in [snap, fold.deepest_fall_time] {
        assert!(
            (t / ends - 1.0).abs() < 0.01,
            "{t} against {ends}: {fold:?}"
        );
    }
    assert!(run.summary.human().contains("deepest fall"));
}
