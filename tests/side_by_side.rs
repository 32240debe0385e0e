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
    let times = rec.sim_times("rope/segments/chain");
    assert_eq!(times.len(), 31);
    for method in ["seed", "rattle"] {
        let theirs = rec.sim_times(&format!("rope/segments/{method}"));
        assert_eq!(theirs.len(), times.len(), "{method}");
        for (a, b) in theirs.iter().zip(&times) {
            assert!(
                (a - b).abs() < 1e-9,
                "{method}: a frame at {a}, chain's at {b}"
            );
        }
    }
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
    // The seed's rope is cleared where it diverged, after its last trusted frame.
    let cleared = rec.cleared_at("rope/segments/seed");
    assert_eq!(cleared.len(), 1);
    assert!(
        (cleared[0] - diverged_at).abs() < 1e-9,
        "cleared at {cleared:?}"
    );
    let seed_frames: Vec<f64> = rec
        .sim_times("rope/segments/seed")
        .into_iter()
        .filter(|t| (t - cleared[0]).abs() > 1e-9)
        .collect();
    let seed_last = seed_frames.last().copied().unwrap();
    assert!(seed_last < diverged_at, "a seed frame at {seed_last}");
    assert!((rec.sim_times("rope/segments/chain").last().unwrap() - 3.0).abs() < 1e-9);
    let events = rec.log_texts("events");
    assert!(
        events.iter().any(|e| e.starts_with("seed diverged at t =")),
        "{events:?}"
    );
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
