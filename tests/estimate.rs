//! The live error estimate as scenarios: against the truth (a fine reference, at a size that
//! runs in seconds), in the recording and the summary, and `--tolerance` kept or reported
//! broken. Also the committed error models against what the check measures, and the
//! tolerance rule they drive.

mod common;

use common::cli::{Recording, Scratch, rope, summary};
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::plan::choice;
use rope::plan::error_model::law;
use rope::run::{RunConfig, Verdict, pipeline};
use rope::study::estimate_check::{self, Cell, FACTOR, Trajectory};
use std::sync::atomic::AtomicBool;

const THIRTY: Scene = Scene::Release { angle_deg: 30.0 };
const MODE_2: Scene = Scene::Mode {
    number: 2,
    amplitude: 0.05,
};

/// The reference of these tests: the N = 1600 is the study's; N = 400 is within a few
/// per cent of it at N = 50 and runs in about a second.
const REFERENCE_SEGMENTS: usize = 400;
const DURATION: f64 = 3.0;

fn cells(scene: Scene, segments: usize) -> Vec<Cell> {
    let reference = Trajectory::compute(&scene, REFERENCE_SEGMENTS, DURATION).unwrap();
    // The methods the rule may choose from the scene (the graded rods from a release at 20° and
    // above).
    choice::startable(&scene, DURATION)
        .map(|m| estimate_check::run_cell(m, scene, segments, DURATION, &reference))
        .collect()
}

#[test]
fn the_estimate_is_within_a_factor_three_of_the_truth_at_nine_frames_in_ten() {
    // Measured on the full grid: 94 % of all frames, 96–100 % for these cells; the misses are
    // where the error passes near zero, and after the whip.
    for scene in [THIRTY, MODE_2] {
        for cell in cells(scene, 50) {
            let v = cell.verdict();
            assert!(v.judged > 100, "{} from the {scene}: {v:?}", cell.method);
            assert!(
                v.within as f64 >= 0.9 * v.judged as f64,
                "{} from the {scene}: {} of {} frames within ×{FACTOR}",
                cell.method,
                v.within,
                v.judged
            );
        }
    }
}

#[test]
fn the_committed_error_models_bound_the_worst_error_and_are_not_far_above_it() {
    // Each model was fitted by `rope study --estimate-check` over six scenes; here the 30°
    // release to t = 3, through its whip.
    for cell in cells(THIRTY, 50) {
        let worst = cell.verdict().max_truth;
        let bound = law(cell.method).bound(cell.segments);
        assert!(
            worst <= bound && bound <= 3.0 * worst,
            "{}: worst tip error {worst:.2e}, model's bound {bound:.2e}",
            cell.method
        );
    }
}

#[test]
fn the_tolerance_rule_keeps_its_tolerance_through_the_whip_and_a_tighter_one_costs_more() {
    let reference = Trajectory::compute(&THIRTY, REFERENCE_SEGMENTS, DURATION).unwrap();
    let mut choices = Vec::new();
    for eps in [3e-2, 1e-2] {
        let choice = choice::by_committed(eps, DURATION, &THIRTY, |_, _, _| true).unwrap();
        let cell =
            estimate_check::run_cell(choice.method, THIRTY, choice.segments, DURATION, &reference);
        let worst = cell.verdict().max_truth;
        assert!(
            worst <= eps,
            "tolerance {eps}: {choice:?} reached {worst:.2e}"
        );
        choices.push(choice);
    }
    assert!(
        choices[0].predicted_seconds < choices[1].predicted_seconds,
        "{choices:?}"
    );
    // From the horizontal only the chain methods can start.
    let horizontal = Scene::Release { angle_deg: 0.0 };
    let from_horizontal =
        choice::by_committed(1e-2, DURATION, &horizontal, |_, _, _| true).unwrap();
    assert_ne!(from_horizontal.method, MethodKind::Seed);
}

/// Runs `segments` of the chain from 30° to t = 2 with `tolerance`, returning the summary
/// and how many frames said the tolerance was passed.
fn run_with_tolerance(segments: usize, tolerance: f64) -> (rope::run::Summary, usize) {
    let plan = RunConfig {
        method: MethodKind::Chain,
        segments,
        duration: 2.0,
        tolerance: Some(tolerance),
        ..RunConfig::default()
    }
    .validate()
    .unwrap();
    let (mut tx, rx) = crossbeam_channel::unbounded();
    let summary = pipeline::run(&plan, &mut tx, &AtomicBool::new(false), &|_| {}).unwrap();
    drop(tx);
    let said = rx.iter().filter(|f| f.tolerance_exceeded.is_some()).count();
    (summary, said)
}

#[test]
fn a_run_whose_estimate_passes_its_tolerance_says_so_once_and_when() {
    let (broken, said) = run_with_tolerance(20, 1e-5);
    assert_eq!(broken.tolerance_met, Some(false));
    // A script sees it: the run ended, with a status of its own.
    assert_eq!(broken.verdict(), Verdict::ToleranceMissed);
    assert_eq!(broken.verdict().exit_status(), 4);
    let when = broken.tolerance_exceeded_at.expect("the time it passed");
    assert!(when > 0.0 && when < 2.0, "{when}");
    assert_eq!(said, 1);
    let estimate = broken.error_estimate.expect("an estimate");
    assert!(estimate.max_tip > 1e-5 && estimate.lost.is_none());

    let (kept, said) = run_with_tolerance(20, 1.0);
    assert_eq!(
        (kept.tolerance_met, kept.tolerance_exceeded_at, said),
        (Some(true), None, 0)
    );
    assert_eq!(kept.verdict(), Verdict::Ok);
}

#[test]
fn a_run_interrupted_before_its_end_does_not_say_its_tolerance_was_met() {
    let plan = RunConfig {
        method: MethodKind::Chain,
        segments: 20,
        duration: 2.0,
        tolerance: Some(1.0),
        ..RunConfig::default()
    }
    .validate()
    .unwrap();
    // Stopped as the frame at t = 0.5 comes: the estimate held 1.0 to there, and so it did
    // to the end uninterrupted (above).
    let stop = AtomicBool::new(false);
    let stop_at_half = |frame: &rope::run::Frame| {
        if frame.time >= 0.5 {
            stop.store(true, std::sync::atomic::Ordering::SeqCst);
        }
    };
    let (mut tx, _rx) = crossbeam_channel::unbounded();
    let summary = pipeline::run(&plan, &mut tx, &stop, &stop_at_half).unwrap();
    assert_eq!(summary.status, rope::run::summary::Status::Interrupted);
    let reached = summary.steps as f64 * summary.dt;
    assert!((0.5..2.0).contains(&reached), "{reached}");
    assert_eq!(summary.tolerance_met, None);
    assert_eq!(summary.verdict(), Verdict::Interrupted);
    let text = summary.human();
    assert!(
        text.contains("tolerance 1.0e0: unknown, the run was interrupted at t = "),
        "{text}"
    );
}

#[test]
fn the_recording_and_the_summary_carry_the_estimate_unless_it_is_turned_off() {
    let dir = Scratch::new("estimate");
    for (flag, carried) in [(None, true), (Some("--no-error-estimate"), false)] {
        let (rrd, json) = (dir.path("e.rrd"), dir.path("e.json"));
        let mut args = vec![
            "run",
            "--method",
            "chain",
            "--segments",
            "40",
            "--duration",
            "0.5",
            "--save",
            rrd.to_str().unwrap(),
            "--summary",
            json.to_str().unwrap(),
        ];
        args.extend(flag);
        let out = rope(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let recording = Recording::read(&rrd);
        let s = summary(&json);
        for entity in ["error/tip_estimate", "error/shape_estimate"] {
            assert_eq!(
                recording.temporal_rows(entity) > 0,
                carried,
                "{flag:?}: {entity}"
            );
        }
        assert_eq!(s["error_estimate"].is_object(), carried, "{flag:?}: {s}");
        if carried {
            // Every frame is taken at a step the shadow shares, so every frame has one.
            assert_eq!(
                recording.temporal_rows("error/tip_estimate") as u64,
                s["frames_logged"].as_u64().unwrap()
            );
            let largest = s["error_estimate"]["max_tip"].as_f64().unwrap();
            assert!(largest > 0.0 && largest < 0.1, "{largest}");
        }
    }
}

#[test]
fn a_frame_at_every_step_keeps_every_frame_and_estimates_at_the_steps_the_shadow_shares() {
    let plan = RunConfig {
        method: MethodKind::Chain,
        segments: 40,
        dt: Some(1e-3),
        log_rate: 1000.0,
        duration: 0.1,
        ..RunConfig::default()
    }
    .validate()
    .unwrap();
    let (mut tx, rx) = crossbeam_channel::unbounded();
    pipeline::run(&plan, &mut tx, &AtomicBool::new(false), &|_| {}).unwrap();
    drop(tx);
    let frames: Vec<_> = rx.iter().collect();
    assert_eq!(frames.len(), 101);
    for f in &frames {
        assert_eq!(
            f.error_estimate.is_some(),
            f.step % 2 == 0,
            "step {}",
            f.step
        );
    }
}
