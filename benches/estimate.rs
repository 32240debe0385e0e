//! What the live error estimate costs: a run of each method, 30° release, with and without
//! its shadow at N/2, frames made at 60 per time unit and handed to the `()` sink (the
//! logging's own cost is `benches/logging.rs`'s).
//!
//! `cargo bench --bench estimate`; the figures in `docs/measurements.md` and the README come
//! from it.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::run::pipeline;
use rope::run::{RunConfig, RunPlan};
use std::sync::atomic::AtomicBool;

/// (segments, duration): the default size for 3 time units, and a fine one for less.
const SIZES: [(usize, f64); 2] = [(100, 3.0), (1000, 0.3)];

fn plan(method: MethodKind, segments: usize, duration: f64, error_estimate: bool) -> RunPlan {
    RunConfig {
        method,
        scene: Scene::Release { angle_deg: 30.0 },
        segments,
        duration,
        error_estimate,
        ..RunConfig::default()
    }
    .validate()
    .expect("a valid run")
}

fn estimate_cost(c: &mut Criterion) {
    let stop = AtomicBool::new(false);
    for (segments, duration) in SIZES {
        let mut group = c.benchmark_group(format!("run_N{segments}_t{duration}"));
        group.sample_size(10);
        for method in MethodKind::ALL {
            for (label, on) in [("without_estimate", false), ("with_estimate", true)] {
                let plan = plan(method, segments, duration, on);
                group.bench_function(BenchmarkId::new(label, method), |b| {
                    b.iter(|| pipeline::run(&plan, &mut (), &stop, &|_| {}).expect("runs"))
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, estimate_cost);
criterion_main!(benches);
