//! The energy–momentum midpoint rule against physics: statics, free fall of the tip from 0°
//! and 30°, Bernoulli's frequencies, second order in h and in k, an energy kept exactly under
//! any sequence of steps, joints whose velocities stay on the constraints over a long run, and
//! a calm release's longer default step whose time error stays below the rods' own.

mod common;

use common::*;
use rope::methods::MethodKind;
use rope::methods::midpoint::Midpoint;
use rope::methods::{Method, Observation};
use rope::model::Scene;
use rope::model::energy;

const MIDPOINT: MethodKind = MethodKind::Midpoint;
const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
const HORIZONTAL: Scene = Scene::Release { angle_deg: 0.0 };

#[test]
fn a_hanging_string_stays_put_with_tension_m_g_times_the_length_below() {
    assert_hanging_string_stays_put(MIDPOINT, 50);
}

#[test]
fn horizontal_release_tip_falls_with_exactly_g_until_t_0_75() {
    // Before the bend comes near it, the end of a chain of rigid rods released straight from
    // rest falls freely; the midpoint rule is exact for a constant acceleration.
    let (outcome, frames) = run_frames(
        MIDPOINT,
        HORIZONTAL,
        100,
        MIDPOINT.default_dt(100),
        0.75,
        100.0,
    );
    assert!(outcome.diverged.is_none());
    let worst = frames
        .iter()
        .map(|f| (f.tip().y - f.time * f.time / 2.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "largest |y_tip − t²/2| = {worst:.3e}");
}

#[test]
fn thirty_degree_release_tip_follows_the_general_free_fall_law() {
    let worst = worst_free_fall_residual(MIDPOINT, 30.0);
    assert!(worst < 1e-3, "largest residual {worst}");
}

#[test]
fn mode_frequencies_match_bernoulli_within_0_2_percent() {
    assert_bernoulli_frequencies(MIDPOINT);
}

#[test]
fn tip_position_at_t1_converges_at_second_order_in_h_within_2e_5_at_n_100() {
    let segments = [25, 50, 100, 200];
    let errors = tip_errors_against_richardson(MIDPOINT, &segments);
    let order = fitted_order(&segments, &errors);
    println!("tip errors at t = 1 for N = {segments:?}: {errors:?}, order {order:.2}");
    assert!(order >= 1.7, "order {order}, errors {errors:?}");
    assert!(errors[2] < 2e-5, "tip error at N = 100: {:.3e}", errors[2]);
    // The same rods as the RK4 chain: the same tip, to well within the spatial error.
    let chain = run_to(MethodKind::Chain, THIRTY, 100, 2e-4, 1.0).tip;
    assert!(
        (tip_at_t1(MIDPOINT, 100) - chain).norm() < 0.05 * errors[2],
        "midpoint and chain differ"
    );
}

#[test]
fn tip_position_at_t_half_converges_at_second_order_in_k() {
    let (order, errors) = order_in_k(MIDPOINT);
    assert!(
        (1.8..2.2).contains(&order),
        "order in k {order}, errors {errors:?}"
    );
}

/// A fixed-seed generator of step lengths, log-uniform in [1e-5, 2e-4].
fn random_steps(count: usize) -> Vec<f64> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            1e-5 * 20f64.powf(u)
        })
        .collect()
}

#[test]
fn energy_is_kept_exactly_under_a_random_sequence_of_steps() {
    // The scheme's own steps, no projection between them: ΔT = −ΔV whatever each step's
    // length, through the first whip of the horizontal release (t ≈ 1.2–1.5), to Newton's
    // tolerance (1e-11 rad in the turns). It strays by about 6e-12 over these 28 000 steps
    // (their last solve keeps the Jacobian); one solve a step, the scheme kept only by the
    // projection's rescale, strayed by 1e-9 to 2.5e-8, and a Jacobian kept from 1e-2 by 9e-11.
    for scene in [HORIZONTAL, THIRTY] {
        let mut rope = Midpoint::new(&scene, 50, 1e-3).unwrap();
        let start = rope.energy().total();
        let mut time = 0.0;
        let mut worst: f64 = 0.0;
        for dt in random_steps(28_000) {
            rope.step_exactly(dt).expect("Newton converges");
            time += dt;
            worst = worst.max((rope.energy().total() - start).abs());
        }
        eprintln!("{scene}: |E − E₀| at most {worst:.3e} to t = {time:.2}");
        assert!(time > 1.6, "the run reached t = {time}");
        assert!(
            worst < 1e-11,
            "{scene}: |E − E₀| reached {worst:.3e} by t = {time:.2}"
        );
    }
}

#[test]
fn velocities_stay_on_the_constraints_and_the_energy_stays_put_over_a_long_run() {
    // The scheme holds G v = 0 only on average; each pair of its steps is projected onto
    // G v = 0. Then the energy of the method's own velocities (centres and spins) equals the
    // energy of the chain moving with its rates alone (eq. 13, where every centre velocity
    // follows from the rates): at every frame, and the energy stays at its start.
    let n = 50;
    let mut rope = Midpoint::new(&THIRTY, n, MIDPOINT.default_dt(n)).unwrap();
    let start = rope.energy().total();
    let mut seen = Observation::default();
    let (mut worst_split, mut worst_drift, mut worst_gv): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let per_frame = (0.1 / rope.dt()).round() as usize;
    for _ in 0..2_000 {
        for _ in 0..per_frame {
            rope.step().expect("no divergence");
            worst_gv = worst_gv.max(rope.velocity_residual().unwrap());
        }
        rope.observe(&mut seen);
        let own = rope.energy().total();
        let from_rates = energy::energy(&seen.angle, &seen.angular_velocity).total();
        worst_split = worst_split.max((own - from_rates).abs());
        worst_drift = worst_drift.max((own - start).abs());
    }
    assert!(rope.time() > 199.0);
    assert!(
        worst_split < 1e-12,
        "own energy and the rates' differ by {worst_split:.3e}"
    );
    assert!(worst_drift < 1e-12, "|E − E₀| reached {worst_drift:.3e}");
    assert!(
        worst_gv < 0.1,
        "|G v| before a projection reached {worst_gv:.3e}"
    );
    assert!(widest_gap_of(&rope) < 1e-12);
}

fn widest_gap_of(rope: &Midpoint) -> f64 {
    rope.constraint_residual()
        .expect("midpoint reports its joints")
}

#[test]
fn a_calm_releases_longer_default_step_keeps_its_time_error_well_below_the_rods_own() {
    // From 30° the free end whips less than from the horizontal, whose whip sets the rule:
    // the default step is twice the rule's. Its error in time (the tip against the same N at
    // a quarter of the step) must stay a small share of the rods' own error (N against 2N),
    // at every step to t = 3, through the whip.
    let n = 400;
    let k = MIDPOINT.default_step(&THIRTY, n);
    assert_eq!(k, 2.0 * MIDPOINT.default_dt(n));
    let tips = |segments: usize, dt: f64| {
        let (outcome, frames) = run_frames(MIDPOINT, THIRTY, segments, dt, 3.0, 1.0 / k);
        assert!(outcome.diverged.is_none());
        assert_eq!(frames.len(), 1_501, "a frame at every step of k");
        frames.iter().map(|f| f.tip()).collect::<Vec<_>>()
    };
    let largest = |a: &[rope::model::Point], b: &[rope::model::Point]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max)
    };
    let (run, fine, finer_rope) = (tips(n, k), tips(n, k / 4.0), tips(2 * n, k / 4.0));
    let (time, spatial) = (largest(&run, &fine), largest(&fine, &finer_rope));
    eprintln!("N = {n}, k = {k}: time error {time:.2e}, the rods' own {spatial:.2e}");
    assert!(spatial > 1e-4, "the rods' own error {spatial:.2e}");
    assert!(
        time < 0.25 * spatial,
        "time error {time:.2e} against the rods' own {spatial:.2e}"
    );
}
