//! A small mode's tip error known before it flies: the linear theory of the rods' small
//! oscillations (`rope::plan::mode_theory`) against the chain itself, and `--tolerance`
//! choosing from it, its run then held against a converged reference at every instant.

use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::committed::{Committed, Source};
use rope::plan::{mode_theory, pilot, tolerance};
use rope::run::estimate::TipBound;
use rope::study::tip_reference::TipReference;
use rope::study::tolerance_check::measure;

fn mode(number: u32, amplitude: f64) -> Scene {
    Scene::Mode { number, amplitude }
}

#[test]
fn the_theory_is_the_chains_own_error_from_a_small_mode() {
    // The chain at its tolerance step against the chain extrapolated from N = 100, 200, 400:
    // its worst tip error at every 1/3000 to t = 3 is the theory's within a tenth and a fifth.
    for (number, amplitude) in [(1, 0.05), (1, 0.1), (2, 0.05), (2, 0.1)] {
        let scene = mode(number, amplitude);
        let reference = TipReference::compute(&scene, 100, 3.0).unwrap();
        for n in [8, 16] {
            let method = MethodKind::Chain;
            let chain = measure(
                method,
                &scene,
                n,
                method.tolerance_dt(n),
                3.0,
                None,
                &reference,
            )
            .unwrap()
            .worst;
            let theory = mode_theory::tip_error(number, amplitude, n, 3.0).unwrap();
            let ratio = chain / theory;
            eprintln!(
                "mode {number}, A = {amplitude}, N = {n}: chain {chain:.3e}, theory {theory:.3e}, {ratio:.3}"
            );
            assert!(
                reference.own_error < 0.05 * chain,
                "reference too coarse: {:.1e}",
                reference.own_error
            );
            assert!(
                (0.9..=1.2).contains(&ratio),
                "mode {number}, A = {amplitude}, N = {n}: {ratio}"
            );
        }
    }
}

#[test]
fn the_theorys_error_falls_at_the_rods_second_order() {
    // The rods converge to the string at O(h²) (their mass and stiffness are the string's to
    // second order, and so is the start sampled at the rods' centres).
    for number in [1, 2] {
        let at = |n| mode_theory::tip_error(number, 0.05, n, 3.0).unwrap();
        let ratio = at(64) / at(128);
        assert!((3.3..=4.3).contains(&ratio), "mode {number}: {ratio}");
    }
}

#[test]
fn past_small_swings_and_low_modes_the_theory_serves_nothing() {
    // Mode 2 at a tip amplitude of 0.2 errs by 1.55 times the theory, mode 3 at 0.05 by 1.4
    // (`cargo run --release --example mode_theory`): there the pilots measure the scene.
    for scene in [
        mode(2, 0.2),
        mode(3, 0.05),
        Scene::Release { angle_deg: 90.0 },
    ] {
        assert!(!mode_theory::serves(&scene, 3.0), "{scene}");
        let models = Committed::look_up(&scene, 3.0, 1e-3);
        assert_ne!(models.source(MethodKind::Chain), Source::Theory, "{scene}");
    }
    assert!(mode_theory::serves(&mode(2, 0.1), 10.0));
    assert!(!mode_theory::serves(&mode(2, 0.1), 10.5));
}

#[test]
fn a_small_mode_is_chosen_by_its_theory_without_pilots_of_its_rods_and_holds() {
    let scene = mode(2, 0.05);
    for eps in [1e-3, 1e-4] {
        let (choice, pilots) = tolerance::choose(eps, &scene, 3.0, u64::MAX).unwrap();
        assert_eq!(pilots.basis, pilot::Basis::Theory, "{eps}: {pilots:?}");
        assert!(mode_theory::of_rods(choice.method));
        for p in pilots
            .flown
            .iter()
            .filter(|p| mode_theory::of_rods(p.method))
        {
            assert!(!p.flew(), "{p:?}");
        }
        // What it predicts is what the theory says at that N, with the pilots' safety.
        let theory = mode_theory::tip_error(2, 0.05, choice.segments, 3.0).unwrap();
        assert!(choice.predicted_error <= eps, "{choice:?}");
        assert!(
            choice.predicted_error >= pilot::SAFETY * theory * 0.99,
            "{choice:?}: {theory:e}"
        );
        // Its live estimate is read at the theory's order.
        let order = Committed::look_up(&scene, 3.0, eps).theory_order.unwrap();
        assert_eq!(
            choice.tip_bound,
            TipBound::Observed {
                order,
                safety: pilot::SAFETY
            }
        );
        // Held at every instant against the chain extrapolated from N = 200, 400, 800, and its
        // verdict true: flagged only where the truth is above EPS/2.
        let reference = TipReference::compute(&scene, 200, 3.0).unwrap();
        let (m, n, dt) = (choice.method, choice.segments, choice.dt);
        let run = measure(m, &scene, n, dt, 3.0, Some(choice.tip_bound), &reference).unwrap();
        eprintln!(
            "mode 2 at {eps}: {m} N = {n}, truth {:.2e}, bound {:?}",
            run.worst, run.estimate
        );
        assert!(run.worst <= eps, "{eps}: truth {:.2e}", run.worst);
        if run.estimate.is_some_and(|bound| bound > eps) {
            assert!(
                run.worst > eps / 2.0,
                "a false alarm below EPS/2: {:.2e}",
                run.worst
            );
        }
    }
}
