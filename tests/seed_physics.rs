//! The report's scheme (with the derived support sign) against physics that nobody here
//! wrote: statics, the start-up tension, energy conservation, free fall of the tip,
//! convergence, Bernoulli's hanging-string frequencies, and where it fails.

mod common;

use common::*;
use rope::methods::seed::{Seed, SupportSign};
use rope::methods::{Method, MethodKind};
use rope::model::Scene;
use std::f64::consts::FRAC_PI_2;

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };

#[test]
fn hanging_string_stays_put_with_tension_one_minus_s() {
    let n = 100;
    let mut seed = Seed::new(&Scene::Release { angle_deg: 90.0 }, n, 1e-3).unwrap();
    for _ in 0..2000 {
        seed.step().unwrap();
    }
    let mut obs = rope::methods::Observation::default();
    seed.observe(&mut obs);
    let h = 1.0 / n as f64;
    for (i, (&phi, &f)) in obs.angle.iter().zip(&obs.tension).enumerate() {
        assert!(
            (phi - FRAC_PI_2).abs() < 1e-12,
            "segment {i} moved: φ = {phi}"
        );
        // F_i sits at s = (i + 1) h: F_{N−1} = 0 is the free end, and at rest the
        // tension system (3)+(5) is linear in i.
        let s = (i as f64 + 1.0) * h;
        assert!((f - (1.0 - s)).abs() < 1e-9, "F({s}) = {f}, expected 1 − s");
    }
    let (outcome, frames) = run_frames(
        MethodKind::Seed,
        Scene::Release { angle_deg: 90.0 },
        n,
        1e-3,
        2.0,
        10.0,
    );
    assert_holds_its_weight_at_the_support(&outcome, &frames);
}

#[test]
fn first_tension_solve_at_thirty_degrees_is_sin_phi0_times_one_minus_s() {
    let n = 100;
    let seed = Seed::new(&THIRTY, n, 1e-5).unwrap();
    let h = 1.0 / n as f64;
    let sin = 30f64.to_radians().sin();
    for (i, &f) in seed.tension().iter().enumerate() {
        let s = (i as f64 + 0.5) * h;
        assert!(
            (f - sin * (1.0 - s)).abs() <= sin * h,
            "F_{i} = {f}, expected sin φ0 (1 − s) = {}",
            sin * (1.0 - s)
        );
    }
}

#[test]
fn energy_deviation_at_the_reports_setting_stays_below_two_percent() {
    let outcome = run_to(MethodKind::Seed, THIRTY, 100, 1e-5, 1.0);
    assert!(outcome.diverged.is_none());
    let rel = outcome.max_rel_deviation();
    assert!(rel < 0.02, "max relative energy deviation {rel}");
    assert!(
        rel > 0.0,
        "a discretisation that conserves energy exactly is suspicious"
    );
}

#[test]
fn energy_deviation_shrinks_linearly_with_h() {
    let segments = [25, 50, 100, 200];
    let errors: Vec<f64> = segments
        .iter()
        .map(|&n| run_to(MethodKind::Seed, THIRTY, n, 1e-5, 1.0).max_rel_deviation())
        .collect();
    let order = fitted_order(&segments, &errors);
    assert!(
        (0.7..=1.3).contains(&order),
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn tip_falls_freely_across_the_initial_line_until_the_bend_arrives() {
    let mut worst = Vec::new();
    for n in [25, 50, 100] {
        let (_, frames) = run_frames(MethodKind::Seed, THIRTY, n, 1e-5, 1.0, 50.0);
        let w = frames
            .iter()
            .map(|f| free_fall_residual(30.0, f).abs())
            .fold(0.0, f64::max);
        worst.push(w);
    }
    assert!(worst[2] < 1e-2, "deviation at N = 100: {}", worst[2]);
    assert!(
        worst[0] > worst[1] && worst[1] > worst[2],
        "does not shrink with h: {worst:?}"
    );
}

#[test]
fn tip_position_at_t1_converges_at_first_order() {
    // Reference: the rigid-rod chain, an independent discretisation that converges at second
    // order to the same continuum (its N = 400 error is ~1e-6, below the seed's by 1000×).
    let dt = MethodKind::Chain.default_dt(400);
    let reference = run_to(MethodKind::Chain, THIRTY, 400, dt, 1.0).tip;
    let segments = [50, 100, 200, 400, 800];
    let errors: Vec<f64> = segments
        .iter()
        .map(|&n| {
            let tip = run_to(
                MethodKind::Seed,
                THIRTY,
                n,
                MethodKind::Seed.default_dt(n),
                1.0,
            )
            .tip;
            (tip - reference).norm()
        })
        .collect();
    let order = fitted_order(&segments, &errors);
    assert!(
        (0.8..=1.2).contains(&order),
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn printed_support_sign_makes_the_same_run_diverge() {
    let mut seed = Seed::with_support_sign(&THIRTY, 100, 1e-5, SupportSign::Printed).unwrap();
    let outcome = rope::run::simulate::run_to(&mut seed, 1.0);
    let diverged = outcome
        .diverged
        .expect("the printed sign must be detected as divergent");
    assert!(diverged.step > 0 && diverged.time <= 1.0);
    assert!(diverged.time.is_finite() && !diverged.reason.is_empty());
}

#[test]
fn mode_one_oscillates_at_bernoulli_frequency_within_one_percent() {
    let w = mode_angular_frequency(MethodKind::Seed, 1, 100, MethodKind::Seed.default_dt(100));
    assert!((w / 1.2024 - 1.0).abs() < 0.01, "ω1 = {w}");
}

#[test]
fn mode_two_oscillates_at_bernoulli_frequency_within_two_percent() {
    let w = mode_angular_frequency(MethodKind::Seed, 2, 100, MethodKind::Seed.default_dt(100));
    assert!((w / 2.7601 - 1.0).abs() < 0.02, "ω2 = {w}");
}

#[test]
fn time_step_far_past_the_stable_range_is_reported_diverged_with_step_and_time() {
    let outcome = run_to(MethodKind::Seed, THIRTY, 100, 2e-2, 3.0);
    let d = outcome.diverged.expect("k = 2e-2 at N = 100 must diverge");
    assert!(d.step >= 1 && (d.time - d.step as f64 * 2e-2).abs() < 1e-12);
    assert!(
        d.reason.contains("exceeds the estimated limit"),
        "{}",
        d.reason
    );
}

#[test]
fn time_step_well_inside_the_stable_range_does_not_diverge() {
    let dt = 0.5 * MethodKind::Seed.stability_limit(100);
    let outcome = run_to(MethodKind::Seed, THIRTY, 100, dt, 3.0);
    assert!(outcome.diverged.is_none(), "{:?}", outcome.diverged);
}
