//! Helpers shared by the physics tests: run a method and sample it.
//!
//! The physics they check against is in `docs/physics.md`, "What the tests check".
#![allow(dead_code)]

pub mod cli;

use rope::methods::{Method, MethodKind};
use rope::model::Scene;
use rope::plan::error_model::ErrorModel;
use rope::run::simulate::{self, Frame, Options, Outcome};
use std::ops::ControlFlow;

/// Runs `kind` on `scene` to `duration`, keeping every frame logged at `log_rate`.
pub fn run_frames(
    kind: MethodKind,
    scene: Scene,
    segments: usize,
    dt: f64,
    duration: f64,
    log_rate: f64,
) -> (Outcome, Vec<Frame>) {
    let mut method = kind
        .build(&scene, segments, dt)
        .expect("valid configuration");
    let mut frames = Vec::new();
    let outcome = simulate::run(
        method.as_mut(),
        &Options {
            duration,
            log_rate,
            frame_grid: None,
        },
        None,
        |f| {
            frames.push(f);
            ControlFlow::Continue(())
        },
    );
    (outcome, frames)
}

/// Runs to `duration` without frames and returns the outcome.
pub fn run_to(kind: MethodKind, scene: Scene, segments: usize, dt: f64, duration: f64) -> Outcome {
    let mut method: Box<dyn Method> = kind
        .build(&scene, segments, dt)
        .expect("valid configuration");
    simulate::run_to(method.as_mut(), duration)
}

/// Least-squares slope of log(error) against log(h): the measured order of convergence.
pub fn fitted_order(segments: &[usize], errors: &[f64]) -> f64 {
    let points = segments.iter().copied().zip(errors.iter().copied());
    ErrorModel::fit(points)
        .expect("two segment counts or more")
        .order
}

/// The free-fall residual of `docs/physics.md`: the tip's displacement across the initial line,
/// −sin φ0 · x + cos φ0 · y, minus cos φ0 · t²/2 (its initial value is 0).
pub fn free_fall_residual(angle_deg: f64, frame: &Frame) -> f64 {
    let phi0 = angle_deg.to_radians();
    let tip = frame.tip();
    let across = -phi0.sin() * tip.x + phi0.cos() * tip.y;
    across - phi0.cos() * frame.time * frame.time / 2.0
}

/// The tip at t = 1 of the 30° release, at `segments` and the method's default step.
pub fn tip_at_t1(kind: MethodKind, segments: usize) -> rope::model::Point {
    let thirty = Scene::Release { angle_deg: 30.0 };
    run_to(kind, thirty, segments, kind.default_dt(segments), 1.0).tip
}

/// The tip errors at t = 1 of the 30° release for `segments`, against the second-order
/// Richardson extrapolation from N = 200 and 400.
pub fn tip_errors_against_richardson(kind: MethodKind, segments: &[usize]) -> Vec<f64> {
    let fine = [tip_at_t1(kind, 200), tip_at_t1(kind, 400)];
    let converged = fine[1] + (fine[1] - fine[0]) / 3.0;
    segments
        .iter()
        .map(|&n| (tip_at_t1(kind, n) - converged).norm())
        .collect()
}

/// The largest free-fall residual of the tip until t = 1.2, before the bend reaches it: `kind`
/// released straight at `angle_deg`, N = 100, its default step.
pub fn worst_free_fall_residual(kind: MethodKind, angle_deg: f64) -> f64 {
    let scene = Scene::Release { angle_deg };
    let (outcome, frames) = run_frames(kind, scene, 100, kind.default_dt(100), 1.2, 100.0);
    assert!(outcome.diverged.is_none(), "{:?}", outcome.diverged);
    frames
        .iter()
        .map(|f| free_fall_residual(angle_deg, f).abs())
        .fold(0.0, f64::max)
}

/// Measured angular frequency of the `mode` scene from the tip's zero crossings.
pub fn mode_angular_frequency(kind: MethodKind, number: u32, segments: usize, dt: f64) -> f64 {
    let omega = rope::model::bessel::mode_frequency(number);
    let periods = 3.0;
    let (outcome, frames) = run_frames(
        kind,
        Scene::Mode {
            number,
            amplitude: 0.02,
        },
        segments,
        dt,
        periods * std::f64::consts::TAU / omega + 0.1,
        400.0,
    );
    assert!(outcome.diverged.is_none(), "{:?}", outcome.diverged);
    let period = rope::model::analysis::period_from_zero_crossings(
        frames.iter().map(|f| (f.time, f.tip().x)),
    )
    .expect("at least one full period");
    std::f64::consts::TAU / period
}

/// The hanging string (released at 90°) at `n` segments and the method's default step, after
/// 2 time units: every node on the vertical, the tip at y = 1, F(s) = m g (1 − s) at the
/// middle of each rod (docs/physics.md, statics) and m g at the support, s = 0, in every frame
/// and in the outcome, and the joints closed.
pub fn assert_hanging_string_stays_put(kind: MethodKind, n: usize) {
    let hanging = Scene::Release { angle_deg: 90.0 };
    let (outcome, frames) = run_frames(kind, hanging, n, kind.default_dt(n), 2.0, 10.0);
    assert!(outcome.diverged.is_none());
    let last = frames.last().unwrap();
    for node in &last.nodes {
        assert!(
            node.x.abs() < 1e-12,
            "node moved sideways to x = {}",
            node.x
        );
    }
    assert!(
        (last.tip().y - 1.0).abs() < 1e-12,
        "tip at y = {}",
        last.tip().y
    );
    for (i, &f) in last.tension.iter().enumerate() {
        let below = 1.0 - (i as f64 + 0.5) / n as f64;
        assert!(
            (f - below).abs() < 1e-9,
            "segment {i}: F = {f}, expected {below}"
        );
    }
    assert_holds_its_weight_at_the_support(&outcome, &frames);
    let gap = frames
        .iter()
        .map(|f| {
            f.constraint_residual
                .expect("the method reports its joints")
        })
        .fold(0.0, f64::max);
    assert!(gap < 1e-12, "the joints opened {gap:.1e}");
}

/// The whole string's weight, m g = 1, at the support of a string hanging at rest: in every
/// frame and in the outcome (not the first segment's tension, h/2 or h below it).
pub fn assert_holds_its_weight_at_the_support(outcome: &Outcome, frames: &[Frame]) {
    for f in frames {
        assert!(
            (f.support_tension - 1.0).abs() < 1e-9,
            "F(0) = {} at t = {}",
            f.support_tension,
            f.time
        );
    }
    assert!(
        (outcome.support_tension - 1.0).abs() < 1e-9,
        "F(0) = {} at the end",
        outcome.support_tension
    );
}

/// Modes 1 and 2 at N = 100 and the method's default step swing at Bernoulli's frequencies
/// within 0.2 %.
pub fn assert_bernoulli_frequencies(kind: MethodKind) {
    for number in [1, 2] {
        let exact = rope::model::bessel::mode_frequency(number);
        let w = mode_angular_frequency(kind, number, 100, kind.default_dt(100));
        assert!(
            (w / exact - 1.0).abs() < 0.002,
            "mode {number}: ω = {w}, Bernoulli {exact}"
        );
    }
}

/// The order in k of the tip at t = 0.5 of the 30° release at N = 40, from steps of 1/250 to
/// 1/2000 against Richardson's extrapolation from 1/16000 and 1/32000; and the errors.
pub fn order_in_k(kind: MethodKind) -> (f64, Vec<(usize, f64)>) {
    let thirty = Scene::Release { angle_deg: 30.0 };
    let tip =
        |steps_per_unit: usize| run_to(kind, thirty, 40, 1.0 / steps_per_unit as f64, 0.5).tip;
    let fine = [tip(16_000), tip(32_000)];
    let converged = fine[1] + (fine[1] - fine[0]) / 3.0;
    let errors: Vec<(usize, f64)> = [250, 500, 1000, 2000]
        .iter()
        .map(|&r| (r, (tip(r) - converged).norm()))
        .collect();
    (
        ErrorModel::fit(errors.iter().copied()).unwrap().order,
        errors,
    )
}
