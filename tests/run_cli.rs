//! `rope run` as a user meets it: the real binary, headless, its recording read back with
//! Rerun's own decoder.

mod common;

use common::cli::{ROPE, Recording, Scratch, rope, signal_and_wait, start, summary};
use std::process::Command;
use std::time::{Duration, Instant};

#[test]
fn saved_recording_has_every_entity_one_strip_per_segment_and_one_frame_per_log_interval() {
    let dir = Scratch::new("save");
    let (rrd, json) = (dir.path("run.rrd"), dir.path("summary.json"));
    let out = rope(&[
        "run",
        "--segments",
        "50",
        "--duration",
        "1",
        "--log-rate",
        "30",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rec = Recording::read(&rrd);
    for entity in [
        "rope/segments",
        "rope/support",
        "rope/tip",
        "rope/trail",
        "tension/profile",
        "energy/kinetic",
        "energy/potential",
        "energy/total",
        "energy/deviation",
        "support/tension",
        "tip/speed",
        "tip/acceleration",
        "parameters",
    ] {
        assert!(
            rec.has(entity),
            "missing {entity}; have {:?}",
            rec.chunks.keys()
        );
    }
    let frames = 31; // duration × log-rate + 1
    assert_eq!(rec.temporal_rows("rope/segments"), frames);
    assert_eq!(rec.temporal_rows("energy/total"), frames);
    let strips = rerun::LineStrips2D::descriptor_strips().component;
    let colors = rerun::LineStrips2D::descriptor_colors().component;
    for chunk in &rec.chunks["rope/segments"] {
        for (s, c) in chunk
            .iter_component::<rerun::components::LineStrip2D>(strips)
            .zip(chunk.iter_component::<rerun::components::Color>(colors))
        {
            assert_eq!(s.len(), 50, "one strip per segment");
            assert_eq!(c.len(), 50, "one colour per segment");
        }
    }
    let s = summary(&json);
    for field in [
        "method",
        "scene",
        "segments",
        "dt",
        "angle_deg",
        "duration",
        "steps",
        "status",
        "diverged",
        "wall_seconds",
        "cpu_seconds",
        "ns_per_segment_step",
        "frames_logged",
        "energy",
        "tip",
        "support_tension",
        "tip_samples",
        "period",
    ] {
        assert!(s.get(field).is_some(), "summary lacks {field}");
    }
    for field in [
        "reference",
        "final",
        "max_abs_deviation",
        "max_rel_deviation",
    ] {
        assert!(
            s["energy"].get(field).is_some(),
            "summary.energy lacks {field}"
        );
    }
    assert_eq!(s["status"], "ok");
    assert_eq!(s["frames_logged"], frames);
    assert_eq!(s["tip_samples"].as_array().unwrap().len(), frames);
    assert!(s["diverged"].is_null() && s["period"].is_null());
}

#[test]
fn the_viewer_reads_the_deviation_as_a_logarithm_and_names_the_run() {
    let dir = Scratch::new("viewer-reads");
    let rrd = dir.path("v.rrd");
    let out = rope(&[
        "run",
        "--method",
        "chain",
        "--segments",
        "20",
        "--duration",
        "1",
        "--save",
        rrd.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let rec = Recording::read(&rrd);
    let deviation = rec.scalars("energy/deviation");
    let log = rec.scalars("log10/energy_deviation");
    assert_eq!(deviation.len(), log.len());
    assert!(deviation.len() > 30);
    for (d, l) in deviation.iter().zip(&log) {
        // The floor is round-off of a double; an exact zero (at the reference step) sits on it.
        let expected = d.abs().log10().max(-16.0);
        assert!(
            (l - expected).abs() < 1e-12,
            "{d}: log {l}, expected {expected}"
        );
    }
    assert!(rec.scalars("log10/error/tip_estimate").len() > 5);
    let captions = rec.point_labels("rope/caption");
    assert_eq!(captions.len(), 1, "{captions:?}");
    assert!(
        captions[0].contains("chain") && captions[0].contains("N = 20"),
        "{captions:?}"
    );
}

#[test]
fn mode_scene_summary_measures_the_period() {
    let dir = Scratch::new("mode");
    let json = dir.path("summary.json");
    let out = rope(&[
        "run",
        "--scene",
        "mode",
        "--method",
        "chain",
        "--duration",
        "11",
        "--save",
        dir.path("m.rrd").to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = summary(&json);
    let period = s["period"].as_f64().expect("a period");
    let bernoulli = std::f64::consts::TAU / rope::model::bessel::mode_frequency(1);
    assert!(
        (period / bernoulli - 1.0).abs() < 0.01,
        "period {period}, Bernoulli {bernoulli}"
    );
    // The theory beside the measurement: ω₁ = j₀,₁ / 2 = 2.404826 / 2, and the difference.
    let theory = s["period_theory"].as_f64().expect("the Bessel period");
    assert!(
        (theory - std::f64::consts::TAU / 1.202413).abs() < 1e-5,
        "{theory}"
    );
    let said = String::from_utf8_lossy(&out.stderr);
    let expected = format!("{:+.2} %", 100.0 * (period - theory) / theory);
    assert!(
        said.contains("Bernoulli") && said.contains(&expected),
        "{said}"
    );
}

#[test]
fn a_mode_run_shorter_than_its_period_says_how_long_to_run() {
    let dir = Scratch::new("mode-short");
    let json = dir.path("summary.json");
    let out = rope(&[
        "run",
        "--scene",
        "mode",
        "--mode-number",
        "1",
        "--duration",
        "3",
        "--save",
        dir.path("m.rrd").to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    assert!(summary(&json)["period"].is_null());
    let said = String::from_utf8_lossy(&out.stderr);
    // Three zero crossings of the tip take 1.25 periods of 5.2255: 6.53.
    assert!(
        said.contains("period not measured") && said.contains("--duration 7 or more"),
        "{said}"
    );
}

#[test]
fn a_release_summary_checks_the_free_fall_of_the_tip() {
    let dir = Scratch::new("free-fall");
    let json = dir.path("summary.json");
    let out = rope(&[
        "run",
        "--method",
        "midpoint",
        "--angle",
        "0",
        "--duration",
        "1",
        "--save",
        dir.path("f.rrd").to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let s = summary(&json);
    // From the horizontal the tip falls as a body, y = t²/2, until the bend arrives.
    let (gap, until) = (
        s["free_fall"]["max_gap"].as_f64().unwrap(),
        s["free_fall"]["until"].as_f64().unwrap(),
    );
    assert!(gap < 1e-12 && until > 0.7, "gap {gap} until {until}");
    let tips = s["tip_samples"].as_array().unwrap();
    let worst = tips
        .iter()
        .map(|t| (t[0].as_f64().unwrap(), t[2].as_f64().unwrap()))
        .filter(|&(t, _)| t <= until)
        .map(|(t, y)| (y - t * t / 2.0).abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "{worst}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("free fall of the tip"));
}

#[test]
fn choices_the_program_makes_are_said_before_and_after() {
    let dir = Scratch::new("choices");
    let rrd = dir.path("c.rrd");
    // A step past the chain's limit runs, and the user is told what the limit means.
    let out = rope(&[
        "run",
        "--method",
        "chain",
        "--dt",
        "0.01",
        "--duration",
        "0.2",
        "--save",
        rrd.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("times the chain method's estimated stability limit")
            && said.contains("substeps"),
        "{said}"
    );
    // A seed run longer than the scheme lasts is warned of before, and it suggests a method
    // that lasts; after the run, the energy's stray names the method that keeps it.
    let out = rope(&["run", "--duration", "1e6", "--save", rrd.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(3));
    let said = String::from_utf8_lossy(&out.stderr);
    let warning = said.find("will most likely stop early").expect(&said);
    let diverged = said.find("DIVERGED").expect(&said);
    assert!(warning < diverged, "{said}");
    assert!(
        said.contains("--method chain or rattle or midpoint"),
        "{said}"
    );
    assert!(
        said.contains("the midpoint method keeps it exactly"),
        "{said}"
    );
}

#[test]
fn a_port_in_use_is_reported_once_with_a_free_one_to_try() {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = listener.local_addr().unwrap().port();
    let out = rope(&[
        "run",
        "--serve-grpc",
        &port.to_string(),
        "--duration",
        "0.1",
    ]);
    assert!(!out.status.success());
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(said.matches("os error").count(), 1, "{said}");
    assert!(
        said.contains(&format!("--serve-grpc 127.0.0.1:{}", port + 1)),
        "{said}"
    );
}

#[test]
fn stdout_carries_a_decodable_recording() {
    let out = rope(&[
        "run",
        "--segments",
        "20",
        "--duration",
        "0.5",
        "--log-rate",
        "10",
        "--stdout",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        Recording::decode(&out.stdout).temporal_rows("rope/segments"),
        6
    );
}

#[test]
fn diverging_run_exits_non_zero_says_when_and_keeps_its_frames() {
    let dir = Scratch::new("diverge");
    let (rrd, json) = (dir.path("d.rrd"), dir.path("d.json"));
    let out = rope(&[
        "run",
        "--dt",
        "8e-3",
        "--allow-unstable",
        "--duration",
        "3",
        "--log-rate",
        "20",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let code = out.status.code().expect("exited");
    assert!(code != 0 && code != 2, "exit code {code}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("diverged at step"), "{stderr}");
    let s = summary(&json);
    assert_eq!(s["status"], "diverged");
    let frames = s["frames_logged"].as_u64().unwrap() as usize;
    assert!(frames >= 5, "only {frames} frames before divergence");
    assert_eq!(Recording::read(&rrd).temporal_rows("rope/segments"), frames);
    assert!(s["diverged"]["time"].as_f64().unwrap() < 3.0);
}

#[test]
fn a_diverged_runs_summary_describes_its_last_trusted_state() {
    // The report's scheme past its stability limit diverges within the first time unit,
    // before the bend reaches the tip: the tip of the last trusted state must still be
    // falling freely (docs/physics.md), inside the string's reach, with a finite pull at the
    // support, and labelled as that state.
    let dir = Scratch::new("trusted");
    let json = dir.path("d.json");
    let out = rope(&[
        "run",
        "--dt",
        "0.01",
        "--allow-unstable",
        "--save",
        dir.path("d.rrd").to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    let s = summary(&json);
    assert_eq!(s["status"], "diverged");
    let diverged_at = s["diverged"]["time"].as_f64().unwrap();
    let trusted = s["trusted"]["time"].as_f64().unwrap();
    assert!(
        trusted > 0.0 && trusted < diverged_at && diverged_at < 1.2,
        "trusted t = {trusted}, diverged at t = {diverged_at}"
    );
    let (x, y) = (
        s["tip"]["x"].as_f64().unwrap(),
        s["tip"]["y"].as_f64().unwrap(),
    );
    let reach = x.hypot(y);
    assert!(reach > 0.5 && reach <= 1.0 + 1e-9, "tip at ({x}, {y})");
    let phi0 = 30f64.to_radians();
    let across = -phi0.sin() * x + phi0.cos() * y;
    let fallen = phi0.cos() * trusted * trusted / 2.0;
    assert!(
        (across - fallen).abs() < 0.02,
        "the tip moved {across} across its line, free fall says {fallen}"
    );
    let tension = s["support_tension"].as_f64().unwrap();
    assert!(tension > 0.0 && tension < 3.0, "F_0 = {tension}");
    let (reference, last) = (
        s["energy"]["reference"].as_f64().unwrap(),
        s["energy"]["final"].as_f64().unwrap(),
    );
    assert!(
        (last - reference).abs() < 0.05,
        "E = {last} against E_ref = {reference}"
    );
    let said = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains(&format!("last trusted state (t = {trusted:.4}")),
        "{said}"
    );
}

#[test]
fn messages_point_the_way_a_newcomer_can_follow() {
    // Too many frames for a coarse step names the log rate that would do (the user set
    // neither), a file not named .rrd gets a warning, and an energy of zero prints as 0.
    let out = rope(&[
        "run",
        "--segments",
        "5",
        "--dt",
        "0.1",
        "--save",
        "/nonexistent/x.rrd",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(said.contains("use --log-rate 10 or less"), "{said}");
    let dir = Scratch::new("newcomer");
    let txt = dir.path("out.txt");
    let out = rope(&[
        "run",
        "--method",
        "chain",
        "--angle",
        "0",
        "--duration",
        "0.05",
        "--save",
        txt.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let said = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
    assert!(
        said.contains("warning: --save") && said.contains(".rrd"),
        "{said}"
    );
    assert!(
        said.contains("E_ref = 0.000000") && !said.contains("-0.000000"),
        "{said}"
    );
    assert!(Recording::read(&txt).temporal_rows("rope/segments") > 0);
    // Several scenes: each run's lines once, with its details.
    let out = rope(&[
        "run",
        "--angle",
        "30,60",
        "--duration",
        "0.05",
        "--save",
        dir.path("two.rrd").to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let said = String::from_utf8_lossy(&out.stderr);
    for angle in ["30°", "60°"] {
        let line = format!("release at {angle}, N = 100");
        assert_eq!(said.matches(&line).count(), 1, "{angle}: {said}");
    }
    assert_eq!(said.matches("  energy: E_ref").count(), 2, "{said}");
}

fn interrupt_mid_run(signal: &str) {
    let dir = Scratch::new(&format!("signal-{signal}"));
    let (rrd, json) = (dir.path("i.rrd"), dir.path("i.json"));
    let mut child = start(&[
        "run",
        "--realtime",
        "--duration",
        "60",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    std::thread::sleep(Duration::from_millis(1500));
    let (status, took) = signal_and_wait(&mut child, signal, Duration::from_secs(5));
    assert!(took < Duration::from_secs(2), "took {took:?} to stop");
    assert_eq!(status.code(), Some(130));
    let s = summary(&json);
    assert_eq!(s["status"], "interrupted");
    let frames = s["frames_logged"].as_u64().unwrap() as usize;
    assert!(
        frames >= 30,
        "{frames} frames in 1.5 s of realtime at 60 per second"
    );
    assert_eq!(Recording::read(&rrd).temporal_rows("rope/segments"), frames);
}

#[test]
fn sigint_mid_run_stops_within_a_second_and_leaves_a_complete_recording() {
    interrupt_mid_run("-INT");
}

#[test]
fn sigterm_mid_run_behaves_like_sigint() {
    interrupt_mid_run("-TERM");
}

#[test]
fn bad_inputs_exit_2_naming_the_parameter() {
    let cases: [(&[&str], &str); 18] = [
        (&["--segments", "0"][..], "segments"),
        // No step taken measures nothing (it printed an E_ref "after step 10" and a cost).
        (&["--duration", "0"][..], "duration = 0"),
        // A size is read in any case; a bad one names the flag.
        (&["--max-memory", "1KB"][..], "max-memory"),
        // Advice that works: a step longer than a frame interval names a rate and a step.
        (
            &["--method", "midpoint", "--dt", "10"][..],
            "--log-rate 0.1 or less",
        ),
        (&["--dt", "-1"][..], "dt"),
        (&["--dt", "-1e-3"][..], "dt"),
        (&["--angle", "-1e-3"][..], "angle"),
        (&["--dt", "0.05"][..], "dt"),
        (&["--angle", "120"][..], "angle"),
        (&["--angle", "0"][..], "angle"),
        (&["--duration", "-2"][..], "duration"),
        (&["--log-rate", "0"][..], "log-rate"),
        (
            &["--scene", "mode", "--mode-number", "9"][..],
            "mode-number",
        ),
        (&["--scene", "mode", "--amplitude", "NaN"][..], "amplitude"),
        (&["--segments", "-3"][..], "segments"),
        // A flag of the other scene is refused, not ignored.
        (&["--scene", "mode", "--angle", "45"][..], "--angle"),
        (&["--amplitude", "0.1"][..], "--amplitude"),
        (&["--mode-number", "2"][..], "--mode-number"),
    ];
    assert_each_exits_2_naming(&["run", "--save", "/nonexistent/never-written.rrd"], &cases);
}

/// Runs `prefix` followed by each case's flags: each must exit 2 and name its parameter.
fn assert_each_exits_2_naming(prefix: &[&str], cases: &[(&[&str], &str)]) {
    for &(args, named) in cases {
        let mut full = prefix.to_vec();
        full.extend_from_slice(args);
        let out = rope(&full);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(named),
            "{args:?} should name {named}: {stderr}"
        );
    }
}

#[test]
fn spawning_without_a_viewer_says_how_to_install_one() {
    let empty = Scratch::new("nopath");
    let out = Command::new(ROPE)
        .args(["run", "--duration", "0.1"])
        .env("PATH", &empty.0)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("pip install rerun-sdk==0.36.3") && stderr.contains("--save"),
        "{stderr}"
    );
}

#[test]
fn tolerance_flag_prints_its_choice_and_runs_it() {
    let dir = Scratch::new("tolerance");
    let json = dir.path("t.json");
    let out = rope(&[
        "run",
        "--tolerance",
        "1e-2",
        "--duration",
        "1",
        "--save",
        dir.path("t.rrd").to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // The method the rule picks, its pilots flown (every limit is far off at this tolerance).
    let scene = rope::model::Scene::Release { angle_deg: 30.0 };
    let (rule, _) = rope::plan::tolerance::choose(1e-2, &scene, 1.0, u64::MAX).unwrap();
    assert!(
        stderr.contains(&format!("tolerance 1e-2: chose the {} method", rule.method)),
        "{stderr}"
    );
    let s = summary(&json);
    assert_eq!(s["method"], rule.method.name());
    // The run says whether the live estimate kept to it.
    assert_eq!(s["tolerance"], 1e-2);
    assert!(s["tolerance_met"].is_boolean(), "{s}");
    let clash = rope(&[
        "run",
        "--tolerance",
        "1e-4",
        "--segments",
        "50",
        "--save",
        "/nonexistent/x.rrd",
    ]);
    assert_eq!(clash.status.code(), Some(2));
}

#[test]
fn study_saves_its_chart_data_into_a_recording_and_reports_progress() {
    let dir = Scratch::new("study-save");
    let rrd = dir.path("study.rrd");
    let out = rope(&[
        "study",
        "--segments",
        "10,20",
        "--dts",
        "1e-2,3e-2",
        "--reference-segments",
        "40",
        "--out",
        dir.path("charts").to_str().unwrap(),
        "--save",
        rrd.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let runs = 2 * 2 * rope::methods::MethodKind::STUDIED.len();
    assert!(
        stderr.contains(&format!("{runs}/{runs} runs done")),
        "progress lines off a terminal: {stderr}"
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("Convergence in h"));
    let rec = Recording::read(&rrd);
    for entity in [
        "study/findings",
        "study/work_precision/seed",
        "study/work_precision/chain",
        "study/stability/seed",
        "study/stability/chain",
    ] {
        assert!(
            rec.has(entity),
            "missing {entity}; have {:?}",
            rec.chunks.keys()
        );
    }
    assert!(dir.path("charts").join("study.csv").exists());
}

#[test]
fn study_rejects_bad_grids_with_exit_2() {
    let cases: [(&[&str], &str); 10] = [
        (&["--dts", "0"][..], "dts"),
        (&["--segments", "1"][..], "segments"),
        (&["--duration", "0"][..], "duration"),
        (&["--reference-segments", "41"][..], "reference-segments"),
        (&["--angle", "30,60"][..], "angle"),
        // A reference no finer than the runs would measure errors below its own resolution.
        (
            &["--segments", "16", "--reference-segments", "8"][..],
            "reference-segments = 8",
        ),
        (
            &["--segments", "16", "--reference-segments", "16"][..],
            "--reference-segments 18",
        ),
        // A value given twice would run twice.
        (
            &["--segments", "16,8,16"][..],
            "segments: 16 is given twice",
        ),
        (&["--dts", "1e-3,1e-3"][..], "dts: 0.001 is given twice"),
        // Every run refused (the seed cannot start from the horizontal): nothing to measure;
        // such a study once wrote its files and then spun for ever drawing an empty chart.
        (
            &[
                "--methods",
                "seed",
                "--angle",
                "0",
                "--segments",
                "16",
                "--dts",
                "1e-3",
            ][..],
            "methods",
        ),
    ];
    assert_each_exits_2_naming(&["study", "--out", "/nonexistent/never"], &cases);
}

/// `rope run --duration 0.5 --connect` to a port on this machine, with `more` flags.
fn run_connected_to(port: u16, more: &[&str]) -> std::process::Output {
    let url = format!("rerun+http://127.0.0.1:{port}/proxy");
    let mut args = vec!["run", "--duration", "0.5", "--connect", &url];
    args.extend_from_slice(more);
    rope(&args)
}

#[test]
fn a_refused_connection_is_reported_at_once_before_anything_runs() {
    // A free port on this machine with nothing listening: the connection is refused.
    let port = common::cli::free_port();
    let dir = Scratch::new("refused");
    let json = dir.path("s.json");
    let started = Instant::now();
    let out = run_connected_to(port, &["--summary", json.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // Known at once: no grace to wait out (the bound leaves room for a loaded machine).
    assert!(
        started.elapsed() < Duration::from_secs(3),
        "took {:?}",
        started.elapsed()
    );
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("connect = ") && stderr.contains("no viewer is listening there"),
        "{stderr}"
    );
    assert!(!json.exists(), "nothing ran, so no summary");

    // With a file to keep the run, it goes on without the viewer, and says so.
    let file = dir.path("kept.rrd");
    let out = run_connected_to(port, &["--save", file.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains("the connection was refused") && stderr.contains("goes on"),
        "{stderr}"
    );
    assert_eq!(Recording::read(&file).temporal_rows("rope/tip"), 31);
}

#[test]
fn a_viewer_that_takes_nothing_costs_the_recording_not_the_summary() {
    // Something that takes the connection (the kernel completes it for a listening socket)
    // but never reads: a viewer that takes none of the data.
    let silent = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = silent.local_addr().unwrap().port();
    let dir = Scratch::new("noviewer");
    let json = dir.path("s.json");
    let started = Instant::now();
    let out = run_connected_to(port, &["--summary", json.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        started.elapsed() < Duration::from_secs(20),
        "took {:?}",
        started.elapsed()
    );
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    // Always this reason, never the recording's own flush timeout (which waits longer).
    assert!(
        stderr.contains(&format!(
            "the recording is incomplete: the viewer at rerun+http://127.0.0.1:{port}/proxy did not take the data within"
        )),
        "{stderr}"
    );
    let s = summary(&json);
    assert_eq!(s["status"], "ok");
    assert_eq!(s["frames_logged"], 31);
    assert!(s["recording_error"].is_string());
    drop(silent);
}

#[test]
fn a_long_run_study_charts_the_energy_and_leaves_out_what_cannot_start() {
    let dir = Scratch::new("long-run");
    let out = rope(&[
        "study",
        "--long-run",
        "3",
        "--methods",
        "seed,rattle",
        "--angle",
        "0,30",
        "--out",
        dir.path("long").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let table = std::fs::read_to_string(dir.path("long/long_run.md")).unwrap();
    for row in [
        "| rattle | release at 0°",
        "| rattle | release at 30°",
        "| seed | release at 30°",
    ] {
        assert!(table.contains(row), "{row} missing from {table}");
    }
    assert!(
        table.contains("Left out: seed from the release at 0°"),
        "{table}"
    );
    for file in ["long_run.csv", "long_run.svg", "long_run.png"] {
        assert!(dir.path("long").join(file).exists(), "{file} not written");
    }
    let endless = rope(&["study", "--long-run", "1e300"]);
    assert_eq!(endless.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&endless.stderr).contains("--yes to run them anyway"));
    let bad = rope(&["study", "--long-run", "-1"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("long-run = -1"));
}

#[test]
fn a_long_run_at_chosen_steps_has_a_row_and_a_line_for_each_step() {
    let dir = Scratch::new("long-run-steps");
    let out = rope(&[
        "study",
        "--long-run",
        "2",
        "--methods",
        "rattle",
        "--dts",
        "1e-3,5e-4",
        "--out",
        dir.path("steps").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let table = std::fs::read_to_string(dir.path("steps/long_run.md")).unwrap();
    for row in [
        "| rattle | release at 30° | 1.000e-3 | 2.0 |",
        "| rattle | release at 30° | 5.000e-4 | 2.0 |",
    ] {
        assert!(table.contains(row), "{row} missing from {table}");
    }
    let csv = std::fs::read_to_string(dir.path("steps/long_run.csv")).unwrap();
    let steps: std::collections::BTreeSet<&str> = csv
        .lines()
        .skip(1)
        .map(|line| line.split(',').nth(2).unwrap_or(""))
        .collect();
    assert_eq!(steps.into_iter().collect::<Vec<_>>(), ["0.0005", "0.001"]);
    let bad = rope(&["study", "--long-run", "2", "--dts", "0"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("dts"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
}

#[test]
fn a_blow_up_study_maps_the_seed_schemes_lifetime() {
    let dir = Scratch::new("blow-up");
    let out = rope(&[
        "study",
        "--blow-up",
        "2",
        "--out",
        dir.path("b").to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let table = std::fs::read_to_string(dir.path("b/blow_up.md")).unwrap();
    for n in rope::study::blow_up::SEGMENTS {
        assert!(
            table.contains(&format!("\n| {n} | ")),
            "N = {n} missing from {table}"
        );
    }
    for file in ["blow_up.csv", "divergence_map.svg", "divergence_map.png"] {
        assert!(dir.path("b").join(file).exists(), "{file} not written");
    }
    let bad = rope(&["study", "--blow-up", "inf"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("blow-up = inf"));
    let endless = rope(&["study", "--blow-up", "1e300"]);
    assert_eq!(endless.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&endless.stderr).contains("blow-up: the 30 runs"));
    let horizontal = rope(&["study", "--blow-up", "2", "--angle", "0"]);
    assert_eq!(
        horizontal.status.code(),
        Some(2),
        "the seed cannot start from 0°"
    );
}

/// `rope run FLAGS --log-rate RATE`, saved into `dir` with its summary: its exit status, the
/// summary and what it said on stderr.
fn at_log_rate(
    dir: &Scratch,
    flags: &[&str],
    rate: &str,
) -> (Option<i32>, serde_json::Value, String) {
    let (rrd, json) = (
        dir.path(&format!("{rate}.rrd")),
        dir.path(&format!("{rate}.json")),
    );
    let mut args = vec!["run", "--log-rate", rate, "--save", rrd.to_str().unwrap()];
    args.extend_from_slice(&["--summary", json.to_str().unwrap()]);
    args.extend_from_slice(flags);
    let out = rope(&args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code(), summary(&json), stderr)
}

/// `--tolerance` from 30° at 1e-4 to t = 3 (where 60 frames a unit once read 8.8e-5 of a whip
/// whose peak is 2.35e-4, and said the tolerance held), at 10, 60 and 600 frames a unit: the
/// same method, N, k and predicted error, the same estimate and the same verdict and exit
/// status whatever the frames. 600 is above the chosen step's rate: the frames fall on the
/// steps, and the run is not refused.
#[test]
fn tolerance_choice_and_verdict_do_not_depend_on_the_frames() {
    let dir = Scratch::new("tolerance-frames");
    let flags = ["--angle", "30", "--tolerance", "1e-4", "--duration", "3"];
    let run = |rate: &str| {
        let (status, summary, stderr) = at_log_rate(&dir, &flags, rate);
        assert!(matches!(status, Some(0 | 4)), "--log-rate {rate}: {stderr}");
        (status, summary, stderr)
    };
    // "chose the … method, N = …, k = …; predicted tip error at most …".
    let chose = |stderr: &str| {
        let from = stderr.find("chose the").expect("the choice announced");
        let to = from + stderr[from..].find(", predicted cost").expect("its cost");
        stderr[from..to].to_owned()
    };
    let (status, first, said) = run("60");
    let same = [
        "method",
        "segments",
        "dt",
        "tolerance_met",
        "tolerance_bound",
        "tolerance_exceeded_at",
    ];
    for rate in ["10", "600"] {
        let (other_status, other, stderr) = run(rate);
        assert_eq!(status, other_status, "--log-rate {rate}: {stderr}");
        assert_eq!(chose(&said), chose(&stderr), "--log-rate {rate}");
        for key in same {
            assert_eq!(
                first[key], other[key],
                "{key} at --log-rate {rate}: {other}"
            );
        }
        // The estimate is watched at every step it shares with its shadow, frames or none.
        let tip = |s: &serde_json::Value| s["error_estimate"]["max_tip"].as_f64().unwrap();
        assert_eq!(tip(&first), tip(&other), "--log-rate {rate}");
    }
}

/// The summary's fields that sample the frames and are named so (or are the run's timing).
const AT_THE_FRAMES: [&str; 6] = [
    "frames_logged",
    "tip_samples",
    "max_shape_at_frames",
    "wall_seconds",
    "cpu_seconds",
    "ns_per_segment_step",
];

/// `summary` without the fields of [`AT_THE_FRAMES`], at any depth.
fn without_the_frames(summary: &serde_json::Value) -> serde_json::Value {
    match summary {
        serde_json::Value::Object(fields) => fields
            .iter()
            .filter(|(key, _)| !AT_THE_FRAMES.contains(&key.as_str()))
            .map(|(key, value)| (key.clone(), without_the_frames(value)))
            .collect(),
        serde_json::Value::Array(items) => items.iter().map(without_the_frames).collect(),
        other => other.clone(),
    }
}

/// The summary's text without what names the frames: the notice that the frames fall on the
/// steps, the timing line (which counts them) and the shape estimate "at the frames".
fn text_without_the_frames(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter(|line| !line.starts_with("rope: --log-rate") && !line.contains(" s wall, "))
        .map(
            |line| match (line.find("; shape "), line.ends_with(" at the frames")) {
                (Some(from), true) => line[..from].to_owned(),
                _ => line.to_owned(),
            },
        )
        .collect()
}

/// The README's release, fold and shake (and a mode, for its period) at 30, 60 and 1 000
/// frames a unit: every figure of the summary, in the JSON and in the text, is the same to the
/// last digit, but those named for the frames they sample. The fold's quoted figures are read
/// at every step, the free fall, the period and the shake's swing and balance on a fine grid
/// of 1e-3 (read from the frames, the fold's pull averaged about a fall of 0.75 read −3.93 % at
/// 60 frames a unit and −2.73 % at 1 000). 1 000 is above the release's default step's rate:
/// the frames then fall on every step, and the run is not refused.
#[test]
fn no_summary_figure_depends_on_the_frames_unless_named_for_them() {
    let dir = Scratch::new("summary-frames");
    let scenes: [&[&str]; 4] = [
        &[],
        &["--scene", "fold", "--gap", "0.02", "--segments", "200"],
        &[
            "--scene",
            "shake",
            "--amplitude",
            "0.03",
            "--frequency",
            "2",
            "--duration",
            "12",
        ],
        &["--scene", "mode", "--duration", "7"],
    ];
    for flags in scenes {
        let at = |rate: &str| {
            let (status, summary, stderr) = at_log_rate(&dir, flags, rate);
            assert_eq!(status, Some(0), "{flags:?} at --log-rate {rate}: {stderr}");
            (
                without_the_frames(&summary),
                text_without_the_frames(&stderr),
            )
        };
        let (json, text) = at("60");
        let quoted = ["theory", "free_fall", "shake", "period"];
        assert!(
            quoted.iter().any(|key| !json[key].is_null()),
            "{flags:?}: no figure of the scene's physics in {json}"
        );
        for rate in ["30", "1000"] {
            let (other_json, other_text) = at(rate);
            assert_eq!(other_json, json, "{flags:?} at --log-rate {rate}");
            assert_eq!(other_text, text, "{flags:?} at --log-rate {rate}");
        }
    }
}
