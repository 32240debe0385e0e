//! The chain of rigid rods against physics: free fall of the tip from the horizontal and at
//! an angle, Bernoulli's frequencies, energy conservation, and second-order convergence.

mod common;

use common::*;
use rope::methods::MethodKind;
use rope::model::Scene;

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
const HORIZONTAL: Scene = Scene::Release { angle_deg: 0.0 };

#[test]
fn horizontal_release_tip_falls_with_exactly_g_until_t_1_2() {
    let (outcome, frames) = run_frames(
        MethodKind::Chain,
        HORIZONTAL,
        100,
        MethodKind::Chain.default_dt(100),
        1.2,
        100.0,
    );
    assert!(outcome.diverged.is_none());
    for f in &frames {
        let fall = f.tip().y - f.time * f.time / 2.0;
        assert!(fall.abs() < 1e-3, "t = {}: y_tip − t²/2 = {fall}", f.time);
    }
    // …while it is pulled inward: the tip's x shrinks.
    assert!(frames.last().unwrap().tip().x < 0.9);
}

#[test]
fn thirty_degree_release_tip_follows_the_general_free_fall_law() {
    let worst = worst_free_fall_residual(MethodKind::Chain, 30.0);
    assert!(worst < 1e-3, "largest residual {worst}");
}

#[test]
fn mode_frequencies_match_bernoulli_within_0_2_percent() {
    for (n, expected) in [(1, 1.2024), (2, 2.7601)] {
        let exact = rope::model::bessel::mode_frequency(n);
        assert!((exact - expected).abs() < 1e-4);
        let w =
            mode_angular_frequency(MethodKind::Chain, n, 100, MethodKind::Chain.default_dt(100));
        assert!(
            (w / exact - 1.0).abs() < 0.002,
            "mode {n}: ω = {w}, Bernoulli {exact}"
        );
    }
}

#[test]
fn energy_drift_over_one_time_unit_is_below_1e_6_at_the_default_step() {
    for scene in [THIRTY, HORIZONTAL] {
        let outcome = run_to(
            MethodKind::Chain,
            scene,
            100,
            MethodKind::Chain.default_dt(100),
            1.0,
        );
        assert!(outcome.diverged.is_none());
        let rel = outcome.max_rel_deviation();
        assert!(rel < 1e-6, "{scene:?}: relative drift {rel}");
    }
}

#[test]
fn energy_never_grows_and_drifts_below_1e_6_over_ten_time_units() {
    let (outcome, frames) = run_frames(
        MethodKind::Chain,
        THIRTY,
        100,
        MethodKind::Chain.default_dt(100),
        10.0,
        20.0,
    );
    assert!(outcome.diverged.is_none());
    // RK4 is not symplectic: it loses a little energy at each fast pass of the tip (O(k⁴)),
    // but it never gains any, so nothing can build up into a blow-up.
    let highest = frames
        .iter()
        .map(|f| f.energy_deviation)
        .fold(f64::MIN, f64::max);
    assert!(highest < 1e-9, "energy rose by {highest:.3e} (relative)");
    assert!(
        outcome.max_rel_deviation() < 1e-6,
        "drift {:.3e}",
        outcome.max_rel_deviation()
    );
}

#[test]
fn tip_position_at_t1_converges_at_second_order() {
    let segments = [25, 50, 100, 200];
    let errors = tip_errors_against_richardson(MethodKind::Chain, &segments);
    let order = fitted_order(&segments, &errors);
    assert!(order >= 1.7, "order {order}, errors {errors:?}");
    assert!(
        errors[2] < 1e-4,
        "N = 100 is {} from the converged tip",
        errors[2]
    );
    // The seed scheme at the same N is about two orders of magnitude further off (the chain
    // at N = 400 is within 1e-6 of the converged tip).
    let fine = tip_at_t1(MethodKind::Chain, 400);
    let seed = tip_at_t1(MethodKind::Seed, 100);
    assert!((seed - fine).norm() > 30.0 * errors[2]);
}

#[test]
fn a_finer_step_refines_the_whips_too_energy_error_falls_as_k_to_the_fourth() {
    // From the horizontal the free end whips again and again in the first ten time units,
    // and the steps split into substeps there. Below the default step the substeps shrink
    // with k, so RK4's energy error falls about as k⁴ (16× per halving) through the whips.
    let n = 20;
    let default = MethodKind::Chain.default_dt(n);
    let errors: Vec<(f64, f64)> = [1.0, 0.5, 0.25]
        .iter()
        .map(|f| {
            let dt = f * default;
            let (outcome, _) = run_frames(MethodKind::Chain, HORIZONTAL, n, dt, 10.0, 60.0);
            assert!(outcome.diverged.is_none());
            (dt, outcome.max_abs_deviation)
        })
        .collect();
    for pair in errors.windows(2) {
        let ratio = pair[0].1 / pair[1].1;
        assert!(
            ratio > 8.0,
            "halving k from {:e} divided the energy error by {ratio:.2}, not about 16: {errors:?}",
            pair[0].0
        );
    }
}

#[test]
fn a_hanging_string_holds_its_whole_weight_at_the_support() {
    let hanging = Scene::Release { angle_deg: 90.0 };
    let n = 50;
    let chain = MethodKind::Chain;
    let (outcome, frames) = run_frames(chain, hanging, n, chain.default_dt(n), 2.0, 10.0);
    assert_holds_its_weight_at_the_support(&outcome, &frames);
}

/// The tip of a chain of rods of `lengths`.
fn tip_of(angles: &[f64], lengths: &[f64]) -> (f64, f64) {
    angles
        .iter()
        .zip(lengths)
        .fold((0.0, 0.0), |(x, y), (&phi, &l)| {
            (x + l * phi.cos(), y + l * phi.sin())
        })
}

/// The rods' lengths of `chain`: its own where graded, else 1/N each.
fn lengths_of(chain: &rope::methods::chain::Chain) -> Vec<f64> {
    use rope::methods::Method;
    let n = chain.segments();
    chain
        .lengths()
        .map_or_else(|| vec![1.0 / n as f64; n], <[f64]>::to_vec)
}

#[test]
fn graded_rods_of_all_but_equal_length_move_as_equal_rods() {
    use rope::methods::Method;
    use rope::methods::chain::Chain;
    let dt = MethodKind::Chain.default_dt(100);
    let mut equal = Chain::new(&THIRTY, 100, dt).unwrap();
    let mut graded = Chain::graded(
        MethodKind::Graded.descriptor(),
        &THIRTY,
        100,
        dt,
        1.0 + 1e-12,
    )
    .unwrap();
    for _ in 0..(1.5 / dt).round() as usize {
        equal.step().unwrap();
        graded.step().unwrap();
    }
    let (a, b) = (
        tip_of(equal.angles(), &lengths_of(&equal)),
        tip_of(graded.angles(), &lengths_of(&graded)),
    );
    assert!(
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
        "{a:?} {b:?}"
    );
}

#[test]
fn graded_rods_fall_freely_keep_the_energy_and_reach_the_same_string() {
    use rope::methods::Method;
    use rope::methods::chain::Chain;
    let n = 200;
    let dt = MethodKind::Chain.default_dt(n);
    let mut graded =
        Chain::graded(MethodKind::Graded.descriptor(), &HORIZONTAL, n, dt, 1.5).unwrap();
    let mut equal = Chain::new(&HORIZONTAL, 2 * n, MethodKind::Chain.default_dt(2 * n)).unwrap();
    let lengths = lengths_of(&graded);
    assert!((lengths.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(lengths[n - 1] < 0.2 * lengths[0]);
    let start = graded.energy().total();
    let mut worst_fall: f64 = 0.0;
    let mut worst_energy: f64 = 0.0;
    for step in 1..=(1.0 / dt).round() as usize {
        graded.step().unwrap();
        let t = step as f64 * dt;
        let (_, y) = tip_of(graded.angles(), &lengths);
        // From the horizontal the tip falls freely until the bend reaches it.
        if t <= 0.75 {
            worst_fall = worst_fall.max((y - t * t / 2.0).abs());
        }
        worst_energy = worst_energy.max((graded.energy().total() - start).abs());
    }
    for _ in 0..(1.0 / equal.dt()).round() as usize {
        equal.step().unwrap();
    }
    let (g, e) = (
        tip_of(graded.angles(), &lengths),
        tip_of(equal.angles(), &lengths_of(&equal)),
    );
    let apart = ((g.0 - e.0).powi(2) + (g.1 - e.1).powi(2)).sqrt();
    eprintln!(
        "graded rods (1.5, N = {n}): free fall to {worst_fall:.1e}, energy to {worst_energy:.1e}, tip {apart:.1e} from 2N equal rods at t = 1"
    );
    assert!(worst_fall < 1e-10, "{worst_fall}");
    assert!(worst_energy < 1e-9, "{worst_energy}");
    assert!(apart < 1e-4, "{apart}");
}
