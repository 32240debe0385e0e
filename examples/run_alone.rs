//! A whole small run, repeated, for counting instructions: `rope::simulate` of METHOD at N
//! rods and step K from 30° to t = 1, frames at 10 a time unit, no live estimate (the runs
//! of `cargo bench --bench small_run`), REPEATS times. Where `steps_alone` counts the steps,
//! this counts all a program embedding rope pays for the run: validation, building, steps,
//! frames.
//!
//! `valgrind --tool=callgrind target/release/examples/run_alone midpoint 8 0.1 2000`
//! (the defaults; prints the tip at t = 1); the instructions a run are the total over REPEATS.

#[path = "common/args.rs"]
mod args;

use anyhow::Context;
use rope::model::Scene;
use rope::{RunConfig, simulate};

fn main() -> anyhow::Result<()> {
    let mut given = std::env::args().skip(1);
    let method = args::method(given.next())?;
    let segments = args::number(given.next(), 8.0)?;
    let dt = args::number(given.next(), 0.1)?;
    let repeats = args::number(given.next(), 2000.0)?;
    anyhow::ensure!(
        segments >= 1.0 && segments.fract() == 0.0 && repeats >= 1.0 && repeats.fract() == 0.0,
        "N and REPEATS are whole numbers, at least 1 (given {segments} and {repeats})"
    );
    let config = RunConfig {
        method,
        scene: Scene::Release { angle_deg: 30.0 },
        segments: segments as usize,
        dt: Some(dt),
        duration: 1.0,
        log_rate: 10.0,
        error_estimate: false,
        ..RunConfig::default()
    };
    let mut last = None;
    for _ in 0..repeats as u64 {
        last = simulate(&config)?.frames.pop();
    }
    let tip = last.context("the run logged no frame")?.tip();
    println!("{method} at N = {segments}, k = {dt}: tip at t = 1 {tip:?}");
    Ok(())
}
