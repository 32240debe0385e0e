//! `--tolerance` with pilot runs: the scene at hand measured at a few coarse N before the
//! choice, its tolerance then held against a fine reference at every frame.

mod common;

use common::cli::{Scratch, rope, summary};
use common::run_frames;
use rope::methods::MethodKind;
use rope::model::{Point, Scene};
use rope::run::pilot;

/// The tip of `reference` frames (sampled finely) at time `t`, by linear interpolation.
fn tip_at(reference: &[(f64, Point)], t: f64) -> Point {
    let i = reference
        .partition_point(|(time, _)| *time <= t)
        .clamp(1, reference.len() - 1);
    let ((t0, a), (t1, b)) = (reference[i - 1], reference[i]);
    a + (b - a) * ((t - t0) / (t1 - t0))
}

/// The largest distance, over a run's summary's tip samples, from the reference's tip.
fn worst_tip_error(samples: &serde_json::Value, reference: &[(f64, Point)]) -> f64 {
    samples
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let (t, x, y) = (
                s[0].as_f64().unwrap(),
                s[1].as_f64().unwrap(),
                s[2].as_f64().unwrap(),
            );
            (Point::new(x, y) - tip_at(reference, t)).norm()
        })
        .fold(0.0, f64::max)
}

/// The tip of `kind` at N and k, sampled 600 times per time unit.
fn tips(kind: MethodKind, scene: Scene, segments: usize, dt: f64) -> Vec<(f64, Point)> {
    let (outcome, frames) = run_frames(kind, scene, segments, dt, 3.0, 600.0);
    assert!(outcome.diverged.is_none());
    frames.iter().map(|f| (f.time, f.tip())).collect()
}

/// Runs `rope run` with `--tolerance` and returns the summary and what it said.
fn tolerance_run(name: &str, flags: &[&str]) -> (serde_json::Value, String) {
    let dir = Scratch::new(name);
    let (rrd, json) = (dir.path("t.rrd"), dir.path("t.json"));
    let mut args = vec!["run", "--duration", "3"];
    args.extend_from_slice(flags);
    args.extend_from_slice(&[
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let out = rope(&args);
    let said = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{said}");
    (summary(&json), said)
}

#[test]
fn a_mode_is_modelled_with_what_it_needs_and_holds_the_tolerance() {
    let (s, said) = tolerance_run("pilot-mode", &["--scene", "mode", "--tolerance", "1e-4"]);
    // The committed models, fitted to the whip of the horizontal release, asked for thousands
    // of segments here; the mode's own pilots ask for tens.
    assert!(said.contains("tolerance pilots"), "{said}");
    let segments = s["segments"].as_u64().unwrap();
    assert!(segments <= 100, "N = {segments}");
    // Against the chain at N = 200 (its error in this mode is a few 1e-7) at every frame.
    let mode = Scene::Mode {
        number: 1,
        amplitude: 0.05,
    };
    let reference = tips(
        MethodKind::Chain,
        mode,
        200,
        MethodKind::Chain.default_dt(200),
    );
    let worst = worst_tip_error(&s["tip_samples"], &reference);
    eprintln!(
        "mode 1, 1e-4: {} at N = {segments}, worst tip error {worst:.2e}",
        s["method"]
    );
    assert!(
        worst <= 1e-4,
        "worst tip error {worst:.2e} at N = {segments}"
    );
}

/// The release from 30° to t = 3: the chain at N and 2N at the step of 2N, extrapolated at
/// the first order that the whip's error has (Richardson), sampled finely. Its own error at
/// the whip: about 7e-4 at N = 200, 1e-4 at N = 400 (the two differ by that much).
fn thirty_degree_reference(segments: usize) -> Vec<(f64, Point)> {
    let thirty = Scene::Release { angle_deg: 30.0 };
    let dt = MethodKind::Chain.default_dt(2 * segments);
    let coarse = tips(MethodKind::Chain, thirty, segments, dt);
    let fine = tips(MethodKind::Chain, thirty, 2 * segments, dt);
    fine.iter()
        .zip(&coarse)
        .map(|((t, f), (_, c))| (*t, f + (f - c)))
        .collect()
}

/// Runs `--tolerance eps` from 30° and checks its worst tip error against `reference`.
fn thirty_degrees_holds(eps: &str, reference: &[(f64, Point)]) {
    let flags = ["--angle", "30", "--tolerance", eps];
    let (s, _) = tolerance_run(&format!("pilot-30-{eps}"), &flags);
    let worst = worst_tip_error(&s["tip_samples"], reference);
    let (method, segments) = (&s["method"], &s["segments"]);
    eprintln!("30°, {eps}: {method} at N = {segments}, worst tip error {worst:.2e}");
    let eps: f64 = eps.parse().unwrap();
    assert!(
        worst <= eps,
        "worst tip error {worst:.2e} with {method} at N = {segments}"
    );
}

#[test]
fn a_release_from_30_degrees_holds_1e_2_against_a_reference_at_every_frame() {
    thirty_degrees_holds("1e-2", &thirty_degree_reference(200));
}

/// A minute of CPU for its reference: `cargo test --release --test pilots -- --ignored
/// --nocapture`.
#[test]
#[ignore]
fn a_release_from_30_degrees_holds_1e_3_against_a_fine_reference_at_every_frame() {
    let fine = thirty_degree_reference(400);
    let coarse = thirty_degree_reference(200);
    let apart = fine
        .iter()
        .map(|(t, p)| (p - tip_at(&coarse, *t)).norm())
        .fold(0.0, f64::max);
    eprintln!("the references from N = 200, 400 and from 400, 800 are {apart:.1e} apart at worst");
    thirty_degrees_holds("1e-3", &fine);
}

#[test]
fn a_method_whose_pilot_diverges_is_ruled_out() {
    // From 30° the seed scheme's shadow at N = 8 blows up at once: no model, not chosen.
    let thirty = Scene::Release { angle_deg: 30.0 };
    let seed = pilot::fly(MethodKind::Seed, &thirty, 3.0);
    assert!(seed.diverged.is_some() && seed.model.is_none(), "{seed:?}");
    let (s, said) = tolerance_run("pilot-ruled", &["--angle", "30", "--tolerance", "1e-3"]);
    assert!(said.contains("seed: ruled out, a pilot diverged"), "{said}");
    assert_ne!(s["method"], "seed");
}
