//! `--tolerance` beyond releases and modes: the fold over its fall, to the snap, and the
//! shaken string, each modelled from its own pilots (no committed model was measured on
//! them) and held at every step of the chosen run.

mod common;

use common::cli::{rope, run_judged, tip_samples};
use rope::methods::MethodKind;
use rope::model::{Scene, ShakeStart, fold};
use rope::study::tip_reference::TipReference;

/// Runs `rope run` with `flags` (one string, split at spaces), a frame at every step
/// (`--log-rate` far above any step's rate is brought down to one), and returns the summary
/// and what it said.
fn run_every_step(name: &str, flags: &str) -> (serde_json::Value, String) {
    let mut args = vec!["run", "--log-rate", "1000000"];
    args.extend(flags.split_whitespace());
    run_judged(name, &args)
}

/// As [`run_every_step`], for a scene `--tolerance` serves from its own method's pilots
/// alone: asserts that they flew and that the scene's own method was chosen.
fn served_by_midpoints_pilots(name: &str, flags: &str) -> serde_json::Value {
    let (s, said) = run_every_step(name, flags);
    assert!(said.contains("tolerance pilots"), "{said}");
    assert_eq!(s["method"], "midpoint", "{said}");
    s
}

#[test]
fn a_steady_shake_is_served_by_its_own_pilots_and_holds_against_linear_theory() {
    // Ω = 2, A = 1e-3 from its steady state to t = 10: the free end swings A / |J₀(4)| = 2.5e-3
    // sideways, and linear theory's A sin Ωt / J₀(2Ω) is exact but for terms of the swing's
    // cube, some 1e-8 here: the rods' own error is what the tip shows against it.
    let eps = 1e-4;
    let s = served_by_midpoints_pilots(
        "shake-tolerance",
        "--scene shake --frequency 2 --amplitude 1e-3 --duration 10 --tolerance 1e-4",
    );
    let scene = Scene::Shake {
        amplitude: 1e-3,
        frequency: 2.0,
        start: ShakeStart::Steady,
    };
    let samples = tip_samples(&s);
    assert!(samples.len() > 1000, "{} frames", samples.len());
    let worst = samples
        .iter()
        .map(|&(t, tip)| (tip.x - scene.sideways_prediction(t).unwrap().1).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "shake at 1e-4: N = {}, k = {}, worst sideways error {worst:.2e} at {} frames",
        s["segments"],
        s["dt"],
        samples.len()
    );
    assert!(worst <= eps, "worst {worst:.2e} at N = {}", s["segments"]);
}

#[test]
fn the_fold_is_served_to_its_snap_and_holds_against_a_converged_reference() {
    // A gap of 0.1: the arm runs out at t = 1.1564; the pilots fly from sixteen rods across
    // the gap (N = 160, 320, 640).
    let gap = 0.1;
    let duration = 1.15;
    assert!(duration < fold::snap_time(gap));
    let eps = 1e-3;
    let s = served_by_midpoints_pilots(
        "fold-tolerance",
        "--scene fold --gap 0.1 --duration 1.15 --tolerance 1e-3",
    );
    let scene = Scene::Fold { gap };
    // The fold's own method at N = 640, 1 280 and 2 560, extrapolated in N.
    let reference = TipReference::compute_by(MethodKind::Midpoint, &scene, 1280, duration).unwrap();
    eprintln!(
        "fold reference: order {:.2}, own error {:.1e}",
        reference.order, reference.own_error
    );
    assert!(reference.own_error <= eps / 10.0, "{}", reference.own_error);
    let samples = tip_samples(&s);
    let worst = samples
        .iter()
        .map(|&(t, tip)| (tip - reference.at(t)).norm())
        .fold(0.0, f64::max);
    eprintln!(
        "fold at 1e-3: N = {}, k = {}, worst tip error {worst:.2e} at {} frames",
        s["segments"],
        s["dt"],
        samples.len()
    );
    assert!(worst <= eps, "worst {worst:.2e} at N = {}", s["segments"]);
}

/// What `rope run FLAGS --save /dev/null` said, refused as bad input (exit 2).
fn refused(flags: &str) -> String {
    let mut args = vec!["run", "--save", "/dev/null"];
    args.extend(flags.split_whitespace());
    let out = rope(&args);
    let said = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{said}");
    said
}

#[test]
fn the_fold_past_its_snap_is_refused_naming_the_duration_that_would_work() {
    // The default gap, 0.04: its arm runs out at t = 1.1876.
    let said = refused("--scene fold --tolerance 1e-3");
    assert!(
        said.contains("duration = 3")
            && said.contains("t = 1.1876")
            && said.contains("--duration 1.18"),
        "{said}"
    );
}

#[test]
fn a_fold_too_narrow_for_its_pilots_is_refused_before_one_flies() {
    // Sixteen rods across a gap of 1e-9 are 1.6e10 rods: refused at once, naming the gap.
    let said = refused("--scene fold --gap 1e-9 --duration 0.01 --tolerance 1e-3");
    assert!(
        said.contains("gap = 1e-9") && said.contains("1.60e10") && said.contains("--gap"),
        "{said}"
    );
}

#[test]
fn a_folds_first_pilot_is_told_before_it_flies_and_a_refused_fold_tells_nothing() {
    // Sixteen rods across a gap of 0.1: the fold's own method at N = 160, to t = 0.5.
    let scene = Scene::Fold { gap: 0.1 };
    let told = std::cell::Cell::new(None);
    let (choice, _) =
        rope::plan::tolerance::choose_telling(1e-3, &scene, 0.5, u64::MAX, &|_| None, |first| {
            assert!(told.replace(Some(first)).is_none(), "told twice");
        })
        .unwrap();
    let first = told.get().expect("the first pilot is told");
    assert_eq!(
        (first.method, first.segments, first.duration),
        (MethodKind::Midpoint, 160, 0.5)
    );
    assert!(
        first.seconds > 0.0 && first.seconds.is_finite(),
        "{first:?}"
    );
    assert_eq!(choice.method, MethodKind::Midpoint);
    // Past the snap the request is refused before a pilot is told of, or flies.
    let snap = fold::snap_time(0.1);
    let refused = rope::plan::tolerance::choose_telling(
        1e-3,
        &scene,
        snap + 0.1,
        u64::MAX,
        &|_| None,
        |_| panic!("a refused fold told of a pilot"),
    );
    assert!(refused.is_err());
}
