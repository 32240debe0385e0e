//! `rope run` and `rope study` called in-process, as the binary calls them: what a run tells
//! the user is read back as notices, not parsed from stderr, and a run is stopped, looped
//! or refused with no process spawned.

mod common;

use common::cli::{Recording, Scratch, run_args, study_args};
use rope::recording::memory::InMemory;
use rope::service::notices::{Collected, Topic};
use rope::service::{ServiceError, Session, run, study};
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

fn listened() -> (Session, Arc<Collected>) {
    let heard = Arc::new(Collected::default());
    (Session::new(heard.clone(), "rope (a test)"), heard)
}

/// A scratch folder for one test, removed when the test ends, passed or failed.
fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("in-process-{name}"))
}

#[test]
fn a_seed_run_longer_than_its_blow_up_is_warned_before_it_starts() {
    let dir = scratch("blow-up");
    let file = dir.path("seed.rrd");
    let args = run_args(&[
        "--method",
        "seed",
        "--duration",
        "80",
        "--save",
        file.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    // Stopped at once: the warning comes before the run, which then ends interrupted.
    session.stop.store(true, Ordering::SeqCst);
    let outcome = run::run(&args, &session).expect("the run is made");
    assert!(heard.told(Topic::BlowUp), "{:?}", heard.notices());
    assert_eq!(outcome.exit_status, 130);
    // A run that the seed lasts is not warned.
    let short = run_args(&[
        "--method",
        "seed",
        "--duration",
        "5",
        "--save",
        file.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    session.stop.store(true, Ordering::SeqCst);
    run::run(&short, &session).expect("the run is made");
    assert!(!heard.told(Topic::BlowUp), "{:?}", heard.notices());
}

#[test]
fn a_run_stopped_midway_ends_interrupted_with_its_file_whole() {
    let dir = scratch("stopped");
    let file = dir.path("endless.rrd");
    let args = run_args(&[
        "--duration",
        "inf",
        "--method",
        "chain",
        "--save",
        file.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    let stop = Arc::clone(&session.stop);
    let stopper = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(500));
        stop.store(true, Ordering::SeqCst);
    });
    let outcome = run::run(&args, &session).expect("the run is made");
    stopper.join().unwrap();
    assert_eq!(outcome.exit_status, 130);
    assert!(outcome.summary.steps > 0, "{:?}", outcome.summary);
    assert!(heard.told(Topic::Summary));
    // The file holds the recording's footer: Rerun reads it back to its end.
    let bytes = std::fs::read(&file).unwrap();
    assert!(
        bytes.len() > 1000 && bytes.starts_with(b"RRF2"),
        "{} bytes",
        bytes.len()
    );
}

#[test]
fn a_loop_of_two_passes_tells_a_summary_at_each_end() {
    let dir = scratch("loop");
    let file = dir.path("loop.rrd");
    let args = run_args(&[
        "--loop",
        "2",
        "--duration",
        "0.5",
        "--method",
        "chain",
        "--save",
        file.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    let outcome = run::run(&args, &session).expect("the run is made");
    assert_eq!(outcome.exit_status, 0);
    let summaries = heard
        .notices()
        .into_iter()
        .filter(|n| n.topic == Topic::Summary)
        .count();
    assert_eq!(summaries, 2, "{:?}", heard.notices());
}

#[test]
fn input_that_cannot_run_comes_back_as_bad_input_naming_the_flag() {
    let (session, heard) = listened();
    match run::run(&run_args(&["--dt", "-1"]), &session) {
        Err(ServiceError::BadInput(text)) => assert!(text.contains("dt"), "{text}"),
        other => panic!("{other:?}"),
    }
    // Refused before anything is announced or opened.
    assert!(heard.notices().is_empty(), "{:?}", heard.notices());
    // --tolerance serves the fold to its snap, no further, and says what would do.
    let fold = run_args(&["--scene", "fold", "--tolerance", "1e-2"]);
    match run::run(&fold, &session) {
        Err(ServiceError::BadInput(text)) => {
            assert!(
                text.starts_with("duration") && text.contains("--duration"),
                "{text}"
            )
        }
        other => panic!("{other:?}"),
    }
    // A flag of another scene is refused, not ignored.
    match run::run(&run_args(&["--gap", "0.02"]), &session) {
        Err(ServiceError::BadInput(text)) => assert!(text.starts_with("gap"), "{text}"),
        other => panic!("{other:?}"),
    }
    for (flags, named) in [
        (&["--frequency", "2"][..], "frequency"),
        (&["--scene", "fold", "--from", "rest"][..], "from"),
        (&["--scene", "mode", "--sweep", "0.2..5"][..], "sweep"),
    ] {
        match run::run(&run_args(flags), &session) {
            Err(ServiceError::BadInput(text)) => assert!(text.starts_with(named), "{text}"),
            other => panic!("{flags:?}: {other:?}"),
        }
    }
    // A sweep that is not Ω₁..Ω₂[:count] with 0 < Ω₁ < Ω₂ ≤ 20 says what it takes.
    for sweep in [
        "5..0.2", "0..5", "0.2..5:1", "0.2-5", "0.2..30", "a..b", "0.2..5:x",
    ] {
        match run::run(&run_args(&["--scene", "shake", "--sweep", sweep]), &session) {
            Err(ServiceError::BadInput(text)) => {
                assert!(
                    text.starts_with("sweep") && text.contains("0.2..5:120"),
                    "{text}"
                )
            }
            other => panic!("{sweep}: {other:?}"),
        }
    }
}

#[test]
fn a_study_none_of_whose_methods_can_start_is_refused_naming_the_flag() {
    let dir = scratch("refused-study");
    let args = study_args(&[
        "--segments",
        "16",
        "--dts",
        "1e-3",
        "--methods",
        "seed",
        "--angle",
        "0",
        "--out",
        dir.0.to_str().unwrap(),
    ]);
    let (session, _) = listened();
    match study::study(&args, &session) {
        Err(ServiceError::BadInput(text)) => {
            assert!(
                text.starts_with("methods:") && text.contains("cannot start"),
                "{text}"
            )
        }
        other => panic!("{other:?}"),
    }
}

/// `rope run` with `flags` into a recording in memory, which must end well: its outcome and
/// what the recording holds.
fn record_in_memory(flags: &[&str]) -> (run::Outcome, Recording) {
    let mut args = run_args(flags);
    let memory = InMemory::default();
    args.output.memory = Some(memory.clone());
    let (session, _) = listened();
    let outcome = run::run(&args, &session).expect("the run is made");
    assert_eq!(outcome.exit_status, 0);
    let mut recording = Recording::default();
    for msg in memory.messages() {
        recording.add(msg);
    }
    (outcome, recording)
}

#[test]
fn every_frame_of_a_run_reaches_a_destination_in_memory() {
    let (outcome, recording) =
        record_in_memory(&["--method", "chain", "--segments", "20", "--duration", "2"]);
    // 60 frames a time unit from t = 0 to 2, each the rope's segments once.
    assert_eq!(outcome.summary.frames_logged, 121);
    assert_eq!(
        recording.temporal_rows("rope/segments") as u64,
        outcome.summary.frames_logged
    );
}

#[test]
fn a_tolerance_runs_summary_says_what_its_choice_rests_on() {
    let mut args = run_args(&["--tolerance", "1e-2", "--duration", "1"]);
    args.output.memory = Some(InMemory::default());
    let (session, _) = listened();
    let outcome = run::run(&args, &session).expect("the run is made");
    let because = outcome
        .summary
        .method_chosen_because
        .clone()
        .expect("the choice is explained");
    assert!(
        because.contains("chosen by --tolerance 1e-2") && because.contains("rests on the "),
        "{because}"
    );
    assert!(outcome.summary.human().contains(&because));
}

/// What a short chain run saved to `file` tells.
fn told_saving_to(file: &std::path::Path) -> Arc<Collected> {
    let short = "--method chain --segments 8 --duration 0.2 --save";
    let mut flags: Vec<&str> = short.split(' ').collect();
    flags.push(file.to_str().unwrap());
    let (session, heard) = listened();
    run::run(&run_args(&flags), &session).expect("the run is made");
    heard
}

#[test]
fn a_file_not_named_rrd_is_warned_of_and_still_written() {
    let dir = scratch("misnamed");
    let file = dir.path("swing.bin");
    let heard = told_saving_to(&file);
    assert!(heard.told(Topic::FileName), "{:?}", heard.notices());
    assert!(std::fs::read(&file).unwrap().starts_with(b"RRF2"));
    let heard = told_saving_to(&dir.path("swing.rrd"));
    assert!(!heard.told(Topic::FileName), "{:?}", heard.notices());
}

#[test]
fn a_fold_runs_the_midpoint_by_default_and_a_bend_of_too_few_rods_is_warned() {
    let dir = scratch("fold");
    let file = dir.path("fold.rrd");
    let (session, heard) = listened();
    let args = run_args(&[
        "--scene",
        "fold",
        "--segments",
        "40",
        "--duration",
        "1.0",
        "--save",
        file.to_str().unwrap(),
    ]);
    let outcome = run::run(&args, &session).expect("the fold runs");
    assert_eq!(outcome.exit_status, 0);
    assert_eq!(outcome.summary.method.name(), "midpoint");
    // The default gap, 0.04, spans 1.6 rods at N = 40.
    assert!(heard.told(Topic::CoarseBend));
    assert!(heard.told(Topic::LastingDefault));
    // The summary reads the theory where the free end has fallen 0.25 and 0.5.
    let falls: Vec<f64> = outcome.summary.theory.iter().map(|t| t.fall).collect();
    assert_eq!(falls, [0.25, 0.5]);

    let (session, heard) = listened();
    let args = run_args(&[
        "--scene",
        "fold",
        "--duration",
        "0.1",
        "--save",
        file.to_str().unwrap(),
    ]);
    run::run(&args, &session).expect("the fold runs");
    assert!(
        !heard.told(Topic::CoarseBend),
        "four rods across at N = 100"
    );
}

#[test]
fn a_shake_draws_its_support_moving_and_its_balance_and_a_release_sends_neither() {
    let (outcome, shake) = record_in_memory(&[
        "--scene",
        "shake",
        "--segments",
        "20",
        "--duration",
        "2",
        "--amplitude",
        "0.02",
    ]);
    // The support moves in the room, a frame at a time, and the rope hangs from it.
    assert_eq!(
        shake.temporal_rows("rope/support_now") as u64,
        outcome.summary.frames_logged
    );
    let balance = shake.scalars("energy/balance");
    assert_eq!(balance.len() as u64, outcome.summary.frames_logged);
    assert!(balance.iter().all(|b| b.abs() < 1e-12), "{balance:?}");
    assert!(shake.has("theory/tip_sideways/steady_state"));
    let figures = outcome.summary.shake.expect("a shake's figures");
    assert!(figures.relative_error.abs() < 0.05, "{figures:?}");
    let (_, release) = record_in_memory(&["--segments", "20", "--duration", "2"]);
    for entity in [
        "rope/support_now",
        "energy/balance",
        "energy/support_work",
        "theory/tip_sideways/measured",
    ] {
        // (Their styling is static, logged for every recording: no value is sent.)
        assert_eq!(release.temporal_rows(entity), 0, "{entity}");
    }
}

#[test]
fn a_sweep_draws_its_curve_writes_its_chart_beside_the_file_and_finds_the_first_resonance() {
    let dir = scratch("sweep");
    let file = dir.path("s.rrd");
    let args = run_args(&[
        "--scene",
        "shake",
        "--from",
        "rest",
        "--amplitude",
        "1e-3",
        "--sweep",
        "0.9..1.5:13",
        "--duration",
        "40",
        "--segments",
        "20",
        "--save",
        file.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    let outcome = run::run(&args, &session).expect("the sweep is made");
    assert_eq!(outcome.exit_status, 0);
    // The chart and its data beside the recording: a row per frequency.
    let csv = std::fs::read_to_string(dir.path("s-response.csv")).expect("the sweep's CSV");
    assert_eq!(csv.lines().count(), 1 + 13, "{csv}");
    for chart in ["s-response.png", "s-response.svg"] {
        assert!(dir.path(chart).exists(), "{chart}");
    }
    // The tallest peak is the first resonance's, within a grid step (0.05) of ω₁ = 1.2024.
    let rows: Vec<(f64, f64)> = csv
        .lines()
        .skip(1)
        .map(|line| {
            let mut cells = line.split(',').map(|c| c.parse::<f64>().unwrap());
            (cells.next().unwrap(), cells.next().unwrap())
        })
        .collect();
    let tallest = rows
        .iter()
        .copied()
        .fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    assert!((tallest.0 - 1.2024).abs() <= 0.05, "{rows:?}");
    let said = heard
        .notices()
        .into_iter()
        .find(|n| n.topic == Topic::Sweep)
        .expect("the sweep's notice");
    assert!(
        said.text.contains("13 frequencies") && said.text.contains("ω1 = 1.2024: the largest"),
        "{said}"
    );
    // One line per resonance, not a summary per frequency; the summary holds every one.
    assert!(!heard.told(Topic::Summary), "{:?}", heard.notices());
    assert_eq!(outcome.summary.sweep.len(), 13);
    // The viewer's curve has every frequency.
    let recording = Recording::read(&file);
    assert!(recording.has("sweep/curve") && recording.has("sweep/labels"));
}

/// A resonance inside a sweep whose grid is too coarse to show its peak (ω₁ = 1.2024 between
/// Ω = 1, 1.5 and 2) is said as such, with a finer grid to try (it once read "none within
/// the sweep").
#[test]
fn a_resonance_the_sweeps_grid_misses_is_said_with_a_finer_grid() {
    let dir = scratch("sweep-coarse");
    let args = run_args(&[
        "--scene",
        "shake",
        "--from",
        "rest",
        "--amplitude",
        "1e-3",
        "--sweep",
        "1..2:3",
        "--duration",
        "5",
        "--segments",
        "20",
        "--save",
        dir.path("c.rrd").to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    run::run(&args, &session).expect("the sweep is made");
    let said = heard
        .notices()
        .into_iter()
        .find(|n| n.topic == Topic::Sweep)
        .expect("the sweep's notice");
    assert!(
        said.text
            .contains("ω1 = 1.2024: the largest swing shows no peak near it")
            && said
                .text
                .contains("too coarse to place it (--sweep 1.14..1.26:41)"),
        "{said}"
    );
}

/// `rope study`'s list defaults are shown as they are typed (`10,20,50,…`, which `--help`
/// prints) and parse to the studied methods and the grid's segment counts.
#[test]
fn the_studys_list_defaults_are_typed_as_a_user_types_them() {
    let args = study_args(&[]);
    assert_eq!(args.methods, rope::methods::MethodKind::STUDIED);
    assert_eq!(args.segments, [10, 20, 50, 100, 200, 500, 1000]);
}

/// Each way a `--sweep` can be wrong is named: the count, the "..", either frequency, their
/// order, the range and the count's bounds, each in its own words.
#[test]
fn each_sweep_refusal_names_the_part_that_is_wrong() {
    for (typed, wrong) in [
        ("1..2:x", "the count \"x\" is not a whole number"),
        ("1-2", "no \"..\" between the two frequencies"),
        ("a..2", "Ω₁ \"a\" is not a number"),
        ("1..b", "Ω₂ \"b\" is not a number"),
        ("0..2", "Ω₁ = 0 is not above 0"),
        ("3..2", "Ω₁ = 3 is not below Ω₂ = 2"),
        ("1..30", "Ω₂ = 30 is above 20"),
        ("1..2:1", "the count 1 is not from 2 to 2000"),
    ] {
        let args = run_args(&["--scene", "shake", "--sweep", typed]);
        let err = args.plans().expect_err(typed).to_string();
        assert!(
            err.contains(&format!("sweep = {typed}: {wrong};")),
            "{typed}: {err}"
        );
    }
}

/// A fold wider than its theory's small-gap limit warns, in `rope run` and in `rope study`,
/// and a study warns of the bends its grid draws too coarsely, as `rope run` does.
#[test]
fn a_wide_gap_and_a_coarse_bend_are_warned_of_by_run_and_by_study() {
    let dir = scratch("fold-warnings");
    let save = dir.path("w.rrd");
    let args = run_args(&[
        "--scene",
        "fold",
        "--gap",
        "0.3",
        "--segments",
        "20",
        "--duration",
        "0.2",
        "--save",
        save.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    run::run(&args, &session).expect("the fold runs");
    assert!(heard.told(Topic::WideGap), "{:?}", heard.notices());
    let out = dir.path("study");
    let args = study_args(&[
        "--scene",
        "fold",
        "--gap",
        "0.02",
        "--segments",
        "10,20",
        "--methods",
        "midpoint",
        "--dts",
        "1e-2",
        "--duration",
        "0.2",
        "--out",
        out.to_str().unwrap(),
    ]);
    let (session, heard) = listened();
    rope::service::study::study(&args, &session).expect("the study runs");
    assert!(heard.told(Topic::CoarseBend), "{:?}", heard.notices());
    assert!(!heard.told(Topic::WideGap), "{:?}", heard.notices());
}
