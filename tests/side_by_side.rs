//! `rope run --method A,B,…`: several methods side by side in one recording, in lockstep on
//! the same frame times, their strings compared, a failing one stopping alone.

mod common;

use common::cli::{Recording, Scratch, rope, summary};

#[test]
fn two_methods_share_one_recording_with_a_rope_and_a_plot_line_each() {
    let dir = Scratch::new("side-two");
    let (rrd, json) = (dir.path("two.rrd"), dir.path("two.json"));
    let out = rope(&[
        "run",
        "--method",
        "seed,chain,rattle",
        "--duration",
        "1",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{said}");
    let rec = Recording::read(&rrd);
    // Every rope on the same frame times: t = 0, 1/30, …, 1 (side by side, 30 frames per
    // time unit unless --log-rate says otherwise).
    // The methods' ropes, tips and profiles share their entities, an instant a row: every
    // row has a tip per method, in its colour.
    let rows = rec.point_methods_by_row("rope/tips");
    assert_eq!(rows.len(), 31);
    for (i, (t, names)) in rows.iter().enumerate() {
        assert!((t - i as f64 / 30.0).abs() < 1e-9, "a row at {t}");
        assert_eq!(names, &["seed", "chain", "rattle"], "at {t}");
    }
    assert_eq!(rec.sim_times("rope/segments").len(), 31);
    assert_eq!(rec.sim_times("tension/profiles").len(), 31);
    // One energy line per method, 10 points per time unit side by side (t = 0, 0.1, …, 1).
    for method in ["seed", "chain", "rattle"] {
        assert_eq!(
            rec.scalars(&format!("log10/energy_deviation/{method}"))
                .len(),
            11
        );
    }
    // The most accurate (chain, by the registry) is what the others are measured from. Rattle
    // is the same chain of rods, so it differs only by its time error; the seed scheme is a
    // first-order finite-difference string, so it differs by its spatial error, far more.
    assert!(rec.scalars("disagreement/chain").is_empty());
    let worst = |m: &str| {
        rec.scalars(&format!("disagreement/{m}"))
            .into_iter()
            .fold(0.0, f64::max)
    };
    assert!(worst("rattle") < 1e-4, "rattle {}", worst("rattle"));
    assert!(
        worst("seed") > 10.0 * worst("rattle"),
        "seed {}",
        worst("seed")
    );
    let s = summary(&json);
    let methods = s["methods"].as_array().expect("a section per method");
    let names: Vec<&str> = methods
        .iter()
        .map(|m| m["method"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["seed", "chain", "rattle"]);
    assert_eq!(s["method"], "seed"); // today's fields: the first method's
    assert!(methods[1]["disagreement"].is_null());
    let rattle = methods[2]["disagreement"].as_f64().unwrap();
    assert!((rattle - worst("rattle")).abs() <= 1e-12 * worst("rattle").max(1e-300));
    assert!(
        said.contains("largest distance from chain's string"),
        "{said}"
    );
    every_rope_is_drawn_whole_in_shades(&rec, &s);
}

/// Side by side a rope is drawn in shades of tension, a strip per run of one shade: the
/// strips of each method's rope must still join end to end from the support through every
/// node to the tip, a colour each, and be fewer than the segments.
fn every_rope_is_drawn_whole_in_shades(rec: &Recording, s: &serde_json::Value) {
    let segments = s["segments"].as_u64().unwrap() as usize;
    let strips = rerun::LineStrips2D::descriptor_strips().component;
    let colors = rerun::LineStrips2D::descriptor_colors().component;
    let mut rows = 0;
    for chunk in rec.chunks["rope/segments"]
        .iter()
        .filter(|c| !c.is_static())
    {
        for (row, colours) in chunk
            .iter_component::<rerun::components::LineStrip2D>(strips)
            .zip(chunk.iter_component::<rerun::components::Color>(colors))
        {
            rows += 1;
            assert_eq!(row.len(), colours.len(), "a colour per strip");
            // Split the row into ropes: a rope starts at the support.
            let mut ropes: Vec<Vec<&rerun::components::LineStrip2D>> = Vec::new();
            for strip in row.iter() {
                if strip.0[0].0 == [0.0, 0.0] {
                    ropes.push(Vec::new());
                }
                ropes
                    .last_mut()
                    .expect("a rope starts at the support")
                    .push(strip);
            }
            assert_eq!(ropes.len(), 3, "a rope per method");
            for rope in ropes {
                assert!(rope.len() < segments, "{} strips", rope.len());
                let drawn: usize = rope.iter().map(|strip| strip.0.len() - 1).sum();
                assert_eq!(drawn, segments, "every segment drawn once");
                for pair in rope.windows(2) {
                    assert_eq!(pair[0].0.last(), pair[1].0.first(), "strips join");
                }
            }
        }
    }
    assert_eq!(rows, 31);
}

#[test]
fn a_method_that_diverges_stops_alone_and_the_other_finishes() {
    let dir = Scratch::new("side-diverge");
    let (rrd, json) = (dir.path("d.rrd"), dir.path("d.json"));
    // 0.012 comes down to 1/120 on the frames' grid: past the seed scheme's limit (5.7e-3 at
    // N = 100), where it blows up; the chain takes substeps and goes on.
    let out = rope(&[
        "run",
        "--method",
        "seed,chain",
        "--dt",
        "0.012",
        "--allow-unstable",
        "--duration",
        "3",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{said}");
    let s = summary(&json);
    let methods = s["methods"].as_array().unwrap();
    assert_eq!(methods[0]["status"], "diverged");
    assert_eq!(methods[1]["status"], "ok");
    let diverged_at = methods[0]["diverged"]["time"].as_f64().unwrap();
    assert!(diverged_at < 3.0);
    assert!(
        (methods[1]["steps"].as_f64().unwrap() * methods[1]["dt"].as_f64().unwrap() - 3.0).abs()
            < 1e-9
    );
    let rec = Recording::read(&rrd);
    // The seed's tip (and its rope and profile) leave the instants after its last trusted
    // frame; the chain's go on to the end.
    let rows = rec.point_methods_by_row("rope/tips");
    let seed_last = rows
        .iter()
        .filter(|(_, names)| names.iter().any(|n| n == "seed"))
        .map(|(t, _)| *t)
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(seed_last < diverged_at, "a seed frame at {seed_last}");
    assert!(
        seed_last > diverged_at - 0.1,
        "the seed's last frame at {seed_last}"
    );
    for (t, names) in &rows {
        let expected: &[&str] = if *t <= seed_last {
            &["seed", "chain"]
        } else {
            &["chain"]
        };
        assert_eq!(names, expected, "at {t}");
    }
    assert!((rows.last().unwrap().0 - 3.0).abs() < 1e-9);
    let events = rec.log_texts("events");
    assert!(
        events.iter().any(|e| e.starts_with("seed diverged at t =")),
        "{events:?}"
    );
    // The seed's plot lines break where it stopped (a loop would start it again later);
    // the chain's do not.
    for entity in ["log10/energy_deviation/seed", "energy/total/seed"] {
        let cleared = rec.cleared_at(entity);
        assert_eq!(cleared.len(), 1, "{entity}: {cleared:?}");
        assert!(
            (cleared[0] - diverged_at).abs() < 1e-6,
            "{entity}: {cleared:?}"
        );
    }
    assert!(rec.cleared_at("energy/total/chain").is_empty());
    assert!(
        said.contains("seed, release at 30°") && said.contains("DIVERGED"),
        "{said}"
    );
}

#[test]
fn bad_method_lists_are_refused_naming_the_flag() {
    for (list, angle, named) in [
        ("seed,pendulum", "30", "--method"),
        ("chain,chain", "30", "method: chain is named twice"),
        ("chain,seed", "0", "method = seed"),
    ] {
        let out = rope(&[
            "run",
            "--method",
            list,
            "--angle",
            angle,
            "--save",
            "/nonexistent/never.rrd",
        ]);
        let said = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{list}: {said}");
        assert!(said.contains(named), "{list} should name {named}: {said}");
    }
}

#[test]
fn the_same_flags_give_the_same_steps_wherever_the_recording_goes() {
    use clap::Parser as _;
    use rope::cli::{Cli, Command};
    let plans = |extra: &[&str]| {
        let mut args = vec!["rope", "run", "--method", "seed,chain", "--angle", "60"];
        args.extend_from_slice(&["--duration", "60"]);
        args.extend_from_slice(extra);
        match Cli::try_parse_from(&args).unwrap().command {
            Command::Run(run) => run.plans().unwrap(),
            Command::Study(_) => unreachable!(),
        }
    };
    let steps = |extra: &[&str]| -> Vec<(f64, f64)> {
        plans(extra)[0]
            .lanes()
            .iter()
            .map(|p| (p.dt, p.log_rate))
            .collect()
    };
    // A viewer of a served run gets a live picture and a slow history whatever the frame
    // rate, so the destination no longer sets the frames, nor the steps brought onto them.
    let file = steps(&["--save", "x.rrd"]);
    assert_eq!(steps(&["--web"]), file);
    assert_eq!(steps(&["--serve-grpc", "127.0.0.1:9876"]), file);
    assert_eq!(steps(&["--stdout"]), file);
    assert_eq!(file.len(), 2);
    assert!(file.iter().all(|&(_, rate)| rate == 30.0));
    // --log-rate sets the frames, and no step: the frames follow the steps.
    for rate in ["25", "10", "7"] {
        let fewer = steps(&["--web", "--log-rate", rate]);
        let dts: Vec<f64> = fewer.iter().map(|&(dt, _)| dt).collect();
        let file_dts: Vec<f64> = file.iter().map(|&(dt, _)| dt).collect();
        assert_eq!(dts, file_dts, "--log-rate {rate}");
        assert!(fewer.iter().all(|&(_, r)| r.to_string() == rate));
    }
}

/// The example: at --log-rate 10 (a served page's rate until the frames followed
/// the steps) the seed ran at 2.000e-3 and survived; with a file, at 1.852e-3 and
/// diverged. Any frame rate now gives one show: the same steps, the same end.
#[test]
fn the_frame_rate_changes_neither_the_steps_nor_when_a_method_diverges() {
    let dir = Scratch::new("side-rate");
    let run = |rate: &str| {
        let json = dir.path(&format!("rate-{rate}.json"));
        let rrd = dir.path(&format!("rate-{rate}.rrd"));
        let out = rope(&[
            "run",
            "--save",
            rrd.to_str().unwrap(),
            "--method",
            "seed,chain",
            "--angle",
            "60",
            "--duration",
            "60",
            "--log-rate",
            rate,
            "--summary",
            json.to_str().unwrap(),
        ]);
        let said = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), summary(&json), said)
    };
    let (code_30, at_30, said_30) = run("30");
    let (code_10, at_10, said_10) = run("10");
    assert_eq!(code_30, code_10, "{said_30}\n{said_10}");
    let methods = |s: &serde_json::Value| s["methods"].as_array().unwrap().clone();
    for (a, b) in methods(&at_30).iter().zip(&methods(&at_10)) {
        assert_eq!(a["dt"], b["dt"], "{}", a["method"]);
        assert_eq!(a["steps"], b["steps"], "{}", a["method"]);
        assert_eq!(a["status"], b["status"], "{}", a["method"]);
        assert_eq!(a["diverged"], b["diverged"], "{}", a["method"]);
        // Three times the frames at three times the rate (the shared instants: t = 0 and
        // every 1/30 or 1/10 up to the end).
        let frames = |s: &serde_json::Value| s["frames_logged"].as_f64().unwrap();
        assert!(frames(a) > 2.5 * frames(b), "{} {}", frames(a), frames(b));
    }
    // More frames than shared instants are refused, naming the flag and what works.
    let out = rope(&["run", "--method", "seed,chain", "--log-rate", "60"]);
    let said = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{said}");
    assert!(
        said.contains("log-rate = 60") && said.contains("--log-rate 30 or less"),
        "{said}"
    );
}

/// The CPU seconds of the process's children that have ended (`/proc/self/stat`'s cutime and
/// cstime, in the kernel's 100 ticks a second).
fn children_cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap()
        .split_whitespace()
        .collect();
    // After the command's name: state is field 3, so cutime (16) and cstime (17) are 13, 14.
    let ticks: f64 = fields[13].parse::<f64>().unwrap() + fields[14].parse::<f64>().unwrap();
    ticks / 100.0
}

/// Four methods on threads of their own, more threads than this machine's cores: each
/// method's figure is its thread's CPU time, so together they are no more than the CPU the
/// whole process used (a figure of busy wall time counted the time a thread stood waiting
/// for a core: 11.9 s of figures in a run that used 6.84 s of CPU).
#[test]
fn each_method_reports_its_own_cpu_time_and_they_sum_within_the_process() {
    let dir = Scratch::new("side-cpu");
    let (rrd, json) = (dir.path("cpu.rrd"), dir.path("cpu.json"));
    let before = children_cpu_seconds();
    let out = rope(&[
        "run",
        "--method",
        "seed,chain,rattle,midpoint",
        "--duration",
        "6",
        "--save",
        rrd.to_str().unwrap(),
        "--summary",
        json.to_str().unwrap(),
    ]);
    // Other tests' children may end meanwhile: that only adds to the process's side.
    let process = children_cpu_seconds() - before;
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s = summary(&json);
    let mut threads = 0.0;
    for m in s["methods"].as_array().unwrap() {
        let cpu = m["cpu_seconds"].as_f64().unwrap();
        let per = m["ns_per_segment_step"].as_f64().unwrap();
        let segment_steps = m["segments"].as_f64().unwrap() * m["steps"].as_f64().unwrap();
        assert!(cpu > 0.0, "{}", m["method"]);
        assert!((per * 1e-9 * segment_steps - cpu).abs() <= 1e-9 * cpu.max(1.0));
        threads += cpu;
    }
    assert!(
        threads <= process + 0.02,
        "the methods' CPU {threads:.3} s against the process's {process:.3} s"
    );
}
