//! Inputs that ask for the impossible: refused before anything of their size is allocated,
//! with the parameter named and what would fit; and no input, however extreme, crashes the
//! parser or the validation (a property test over wide ranges, the non-finite values and the
//! extremes).

mod common;

use clap::Parser as _;
use common::cli::{Scratch, rope};
use proptest::prelude::*;
use rope::cli::{Cli, Command};
use rope::run::cost;

/// Every parameter an error of `rope run` may name first.
const RUN_PARAMETERS: [&str; 11] = [
    "segments",
    "dt",
    "duration",
    "log-rate",
    "tolerance",
    "loop",
    "realtime",
    "angle",
    "mode-number",
    "amplitude",
    "max-memory",
];

/// Every parameter an error of `rope study` may name first.
const STUDY_PARAMETERS: [&str; 7] = [
    "angle",
    "mode-number",
    "amplitude",
    "duration",
    "dts",
    "segments",
    "reference-segments",
];

#[test]
fn each_impossible_run_exits_2_naming_the_parameter_and_what_would_fit() {
    let dir = Scratch::new("limits");
    let rrd = dir.path("x.rrd");
    let rrd = rrd.to_str().unwrap();
    let cases: [(&[&str], &str, &str); 6] = [
        (
            &["--tolerance", "1e-12"],
            "tolerance = 1e-12",
            "the tightest reachable is",
        ),
        (
            &["--segments", "100000000"],
            "segments = 100000000",
            "segments fit",
        ),
        (&["--duration", "1e300"], "duration = 1e300", "--yes"),
        (
            &["--summary", "/dev/null/s.json"],
            "summary = /dev/null/s.json",
            "cannot write there",
        ),
        (
            &["--segments", "20000", "--max-memory", "100MB"],
            "segments = 20000",
            "(--max-memory)",
        ),
        (
            &["--segments", "50000", "--duration", "1000"],
            "duration = 1e3",
            "time units fit in a day",
        ),
    ];
    for (flags, named, says) in cases {
        let mut args = vec!["run", "--save", rrd];
        args.extend_from_slice(flags);
        let out = rope(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flags:?}: {stderr}");
        assert!(
            stderr.contains(named) && stderr.contains(says),
            "{flags:?}: {stderr}"
        );
    }
}

#[test]
fn a_save_path_where_nothing_can_be_written_is_refused_before_the_run() {
    let out = rope(&["run", "--save", "/dev/null/x.rrd"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("save = /dev/null/x.rrd"), "{stderr}");
    assert!(!stderr.contains("steps to t ="), "nothing ran: {stderr}");
}

#[test]
fn a_study_that_cannot_run_or_write_is_refused_before_it_starts() {
    let dir = Scratch::new("limits-study");
    let out_dir = dir.path("out");
    let out_dir = out_dir.to_str().unwrap();
    let cases: [(&[&str], &str); 3] = [
        (
            &[
                "--out",
                "/dev/null/study",
                "--segments",
                "10",
                "--dts",
                "1e-2",
            ],
            "out = /dev/null/study",
        ),
        (
            &[
                "--out",
                out_dir,
                "--save",
                "/dev/null/s.rrd",
                "--segments",
                "10",
                "--dts",
                "1e-2",
            ],
            "save = /dev/null/s.rrd",
        ),
        (
            &["--out", out_dir, "--segments", "100000", "--dts", "1e-7"],
            "segments: the study is predicted to take",
        ),
    ];
    for (flags, named) in cases {
        let mut args = vec!["study"];
        args.extend_from_slice(flags);
        let out = rope(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flags:?}: {stderr}");
        assert!(stderr.contains(named), "{flags:?}: {stderr}");
    }
}

/// A number as a user might type it: ordinary, extreme, or not a number at all.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| x.to_string()),
        (-1e3..1e3f64).prop_map(|x| x.to_string()),
        (1e-9..1e-1f64).prop_map(|x| format!("{x:e}")),
        prop::sample::select(vec![
            "inf", "-inf", "NaN", "0", "-0", "1e308", "5e-324", "x"
        ])
        .prop_map(str::to_owned),
    ]
}

/// A count as a user might type it, up to the largest the platform has.
fn count() -> impl Strategy<Value = String> {
    prop_oneof![
        (0..20_000u64).prop_map(|n| n.to_string()),
        any::<u64>().prop_map(|n| n.to_string()),
        prop::sample::select(vec!["18446744073709551615", "-1", "1e3", ""]).prop_map(str::to_owned),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn every_run_input_validates_or_is_refused_naming_a_parameter(
        segments in count(),
        dt in proptest::option::of(number()),
        duration in number(),
        angle in number(),
        log_rate in number(),
        realtime in proptest::option::of(number()),
        tolerance in proptest::option::of(number()),
        method in proptest::option::of(prop::sample::select(vec!["seed", "chain"])),
        mode in proptest::option::of((0..6u32, number())),
        repeat in proptest::option::of(proptest::option::of(count())),
    ) {
        let mut args: Vec<String> = ["rope", "run", "--segments", &segments, "--duration", &duration,
            "--log-rate", &log_rate].iter().map(|s| s.to_string()).collect();
        let mut flag = |name: &str, value: Option<&String>| {
            args.push(format!("--{name}"));
            if let Some(value) = value { args.push(value.clone()); }
        };
        if let Some(dt) = &dt { flag("dt", Some(dt)); }
        if let Some(speed) = &realtime { flag("realtime", Some(speed)); }
        if let Some(eps) = &tolerance { flag("tolerance", Some(eps)); }
        if let Some(m) = method { flag("method", Some(&m.to_owned())); }
        // Each scene with its own flags (a flag of the other scene is refused: its own test).
        match &mode {
            Some((number, amplitude)) => {
                flag("scene", Some(&"mode".to_owned()));
                flag("mode-number", Some(&number.to_string()));
                flag("amplitude", Some(amplitude));
            }
            None => flag("angle", Some(&angle)),
        }
        if let Some(passes) = &repeat { flag("loop", passes.as_ref()); }
        let Ok(cli) = Cli::try_parse_from(&args) else {
            return Ok(()); // the parser's own refusal: exit 2, naming the flag
        };
        let Command::Run(run) = cli.command else { unreachable!("a run") };
        match run.plans() {
            Ok(plans) => {
                let limits = run.limits.limits();
                for planned in plans {
                    prop_assert!(planned.plan.cost.bytes <= limits.memory());
                    if planned.plan.duration.is_finite() {
                        prop_assert!(planned.plan.cost.seconds <= cost::LONG_SECONDS);
                    }
                }
            }
            Err(err) => {
                let text = err.to_string();
                prop_assert!(
                    RUN_PARAMETERS.iter().any(|p| text.starts_with(p)),
                    "{args:?}: {text}"
                );
            }
        }
    }

    #[test]
    fn every_study_input_validates_or_is_refused_naming_a_parameter(
        segments in prop::collection::vec(count(), 1..4),
        dts in prop::collection::vec(number(), 1..4),
        duration in number(),
        angle in number(),
        reference in proptest::option::of(count()),
    ) {
        let mut args: Vec<String> = ["rope", "study", "--segments", &segments.join(","), "--dts",
            &dts.join(","), "--duration", &duration, "--angle", &angle]
            .iter().map(|s| s.to_string()).collect();
        if let Some(reference) = reference {
            args.push("--reference-segments".to_owned());
            args.push(reference);
        }
        let Ok(cli) = Cli::try_parse_from(&args) else { return Ok(()) };
        let Command::Study(study) = cli.command else { unreachable!("a study") };
        if let Err(err) = study.plan() {
            let text = err.to_string();
            prop_assert!(
                STUDY_PARAMETERS.iter().any(|p| text.starts_with(p)),
                "{args:?}: {text}"
            );
        }
    }
}
