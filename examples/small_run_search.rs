//! The cheapest whole small run for a tip tolerance: from 30° to t = 1, frames at 10 a time
//! unit, every method at N = 6 … 48 and k from 0.1 down, its tip at t = 0.1, 0.2, …, 1.0
//! held against a converged reference (the chain at N = 200, 400, 800 extrapolated). For each
//! tolerance and method, the run of least CPU that keeps within it, `rope::simulate` timed as
//! a program embedding rope calls it (no live estimate; the fastest of repeated runs).
//!
//! `cargo run --release --example small_run_search -- [EPS,EPS…]` (by default 1e-3 and 1e-4;
//! about a minute). `cargo bench --bench small_run` keeps the two runs the issue named.

#[path = "common/args.rs"]
mod args;

use rope::methods::MethodKind;
use rope::model::Scene;
use rope::study::tip_reference::{ConvergedTip, TipReference};
use rope::{RunConfig, simulate};
use std::time::Instant;

const SCENE: Scene = Scene::Release { angle_deg: 30.0 };

/// The fastest of `repeats` runs of `config`, in seconds, and its worst tip error at the
/// frames after t = 0.
fn measure(config: &RunConfig, reference: &TipReference, repeats: usize) -> Option<(f64, f64)> {
    let run = simulate(config).ok()?;
    if run.summary.diverged.is_some() {
        return None;
    }
    let worst = reference.farthest(&run.frames);
    let fastest = (0..repeats)
        .map(|_| {
            let started = Instant::now();
            let _ = std::hint::black_box(simulate(config));
            started.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min);
    Some((fastest, worst))
}

fn main() -> anyhow::Result<()> {
    let tolerances = args::numbers(std::env::args().nth(1), &[1e-3, 1e-4])?;
    let reference = TipReference::compute(&SCENE, 400, 1.0)?;
    eprintln!(
        "reference: the chain at N = 200, 400, 800, order {:.2}, own error {:.1e}",
        reference.order, reference.own_error
    );
    let steps = [
        0.1, 0.05, 0.04, 0.025, 0.02, 0.0125, 0.01, 0.005, 0.0025, 0.001,
    ];
    let segments = [6, 8, 10, 12, 14, 16, 18, 20, 24, 25, 28, 32, 40, 48];
    println!("| EPS | method | N | k | worst tip error at t = 0.1 … 1 | µs of CPU, whole run |");
    println!("|---|---|---|---|---|---|");
    for &eps in &tolerances {
        for method in MethodKind::ALL {
            let mut best: Option<(f64, usize, f64, f64)> = None;
            for &n in &segments {
                for &dt in &steps {
                    let config = RunConfig {
                        method,
                        scene: SCENE,
                        segments: n,
                        dt: Some(dt),
                        duration: 1.0,
                        log_rate: 10.0,
                        error_estimate: false,
                        allow_unstable: true,
                        ..RunConfig::default()
                    };
                    // A cheap first look, then a careful timing of a candidate that holds.
                    let Some((rough, worst)) = measure(&config, &reference, 3) else {
                        continue;
                    };
                    if worst > eps || best.is_some_and(|b| rough > 2.0 * b.0) {
                        continue;
                    }
                    let Some((seconds, _)) = measure(&config, &reference, 200) else {
                        continue;
                    };
                    if best.is_none_or(|b| seconds < b.0) {
                        best = Some((seconds, n, dt, worst));
                    }
                }
            }
            match best {
                Some((seconds, n, dt, worst)) => println!(
                    "| {eps:e} | {method} | {n} | {dt} | {worst:.2e} | {:.1} |",
                    seconds * 1e6
                ),
                None => println!("| {eps:e} | {method} | none within N ≤ 48 | | | |"),
            }
        }
    }
    Ok(())
}
