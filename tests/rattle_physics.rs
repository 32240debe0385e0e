//! RATTLE on the chain of rods against physics: statics, free fall of the tip, Bernoulli's
//! frequencies, second order in h and in k, joints that stay closed, and an energy error that
//! stays bounded where the RK4 chain drifts.

mod common;

use common::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::run::simulate::Frame;
use rope::study::long_run::Trend;

const RATTLE: MethodKind = MethodKind::Rattle;
const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
const HORIZONTAL: Scene = Scene::Release { angle_deg: 0.0 };

/// The largest joint gap over the frames of a run.
fn widest_gap(frames: &[Frame]) -> f64 {
    frames
        .iter()
        .map(|f| f.constraint_residual.expect("rattle reports its joints"))
        .fold(0.0, f64::max)
}

/// Least-squares slope of the energy against time, over frames from `from` on.
fn energy_trend(frames: &[Frame], from: f64) -> f64 {
    let mut trend = Trend::default();
    for f in frames.iter().filter(|f| f.time >= from) {
        trend.add(f.time, f.energy.total());
    }
    trend.slope()
}

#[test]
fn a_hanging_string_stays_put_with_tension_m_g_times_the_length_below() {
    assert_hanging_string_stays_put(RATTLE, 50);
}

#[test]
fn horizontal_release_tip_falls_with_exactly_g_until_t_1_2() {
    let (outcome, frames) = run_frames(RATTLE, HORIZONTAL, 100, RATTLE.default_dt(100), 1.2, 100.0);
    assert!(outcome.diverged.is_none());
    let worst = frames
        .iter()
        .map(|f| (f.tip().y - f.time * f.time / 2.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-3, "largest |y_tip − t²/2| = {worst}");
    assert!(
        frames.last().unwrap().tip().x < 0.9,
        "the tip is pulled inward"
    );
}

#[test]
fn thirty_degree_release_tip_follows_the_general_free_fall_law() {
    let worst = worst_free_fall_residual(RATTLE, 30.0);
    assert!(worst < 1e-3, "largest residual {worst}");
}

#[test]
fn mode_frequencies_match_bernoulli_within_0_2_percent() {
    assert_bernoulli_frequencies(RATTLE);
}

#[test]
fn tip_position_at_t1_converges_at_second_order_in_h() {
    let segments = [25, 50, 100, 200];
    let errors = tip_errors_against_richardson(RATTLE, &segments);
    let order = fitted_order(&segments, &errors);
    assert!(order >= 1.7, "order {order}, errors {errors:?}");
    // The same rods as the RK4 chain: the same tip, to well within the spatial error.
    let chain = run_to(MethodKind::Chain, THIRTY, 100, 2e-4, 1.0).tip;
    assert!(
        (tip_at_t1(RATTLE, 100) - chain).norm() < 0.05 * errors[2],
        "rattle and chain differ"
    );
}

#[test]
fn tip_position_at_t_half_converges_at_second_order_in_k() {
    let (order, errors) = order_in_k(RATTLE);
    assert!(
        (1.8..2.2).contains(&order),
        "order in k {order}, errors {errors:?}"
    );
}

#[test]
fn energy_stays_bounded_over_100_time_units_where_the_rk4_chain_drifts() {
    let long = |kind: MethodKind| run_frames(kind, THIRTY, 100, kind.default_dt(100), 100.0, 10.0);
    let (rattle, frames) = long(RATTLE);
    let (chain, chain_frames) = long(MethodKind::Chain);
    assert!(rattle.diverged.is_none() && chain.diverged.is_none());
    assert!(
        rattle.max_abs_deviation < 1e-5,
        "rattle's energy strayed {:.3e}",
        rattle.max_abs_deviation
    );
    assert!(
        widest_gap(&frames) < 1e-11,
        "the joints opened {:.1e}",
        widest_gap(&frames)
    );
    // After the first whip (t > 10): the chain loses energy steadily, rattle does not.
    let (drift, trend) = (
        energy_trend(&chain_frames, 10.0),
        energy_trend(&frames, 10.0),
    );
    assert!(drift < -2e-8, "the chain drifts {drift:.3e} per time unit");
    assert!(
        trend.abs() < 0.2 * drift.abs(),
        "rattle's trend {trend:.3e} per time unit against the chain's {drift:.3e}"
    );
}

#[test]
fn a_finer_step_refines_the_whip_too_energy_error_falls_as_k_squared() {
    // From the horizontal the free end whips at t ≈ 1.2–1.5, where the last rods spin fast
    // and the step splits into substeps. Below the default step the substeps shrink with k,
    // so the largest energy error through the whip falls as k², as it does before it.
    let n = 50;
    let default = RATTLE.default_dt(n);
    let errors: Vec<(f64, f64)> = [1.0, 0.5, 0.25]
        .iter()
        .map(|f| {
            let dt = f * default;
            let (outcome, frames) = run_frames(RATTLE, HORIZONTAL, n, dt, 3.0, 60.0);
            assert!(outcome.diverged.is_none());
            assert!(frames.last().is_some_and(|f| f.time > 2.9));
            (dt, outcome.max_abs_deviation)
        })
        .collect();
    for pair in errors.windows(2) {
        let ratio = pair[0].1 / pair[1].1;
        assert!(
            (3.0..5.5).contains(&ratio),
            "halving k from {:e} divided the energy error by {ratio:.2}, not about 4: {errors:?}",
            pair[0].0
        );
    }
}
