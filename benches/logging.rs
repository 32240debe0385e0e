//! What streaming costs: the report's run (N = 100, k = 1e-5, 30°, 1 time unit) with 60
//! frames per time unit saved to an .rrd file, against the same run with logging off.
//!
//! `cargo bench --bench logging`; the overhead figure in `docs/measurements.md` comes from it.

use criterion::{Criterion, criterion_group, criterion_main};
use rope::methods::REPORT;
use rope::model::Scene;
use rope::recording::logger::RopeLogger;
use rope::run::pipeline;
use rope::run::{RunConfig, RunPlan};
use std::sync::atomic::AtomicBool;

fn config() -> RunPlan {
    RunConfig {
        method: REPORT.method,
        scene: Scene::Release { angle_deg: 30.0 },
        segments: REPORT.segments,
        dt: Some(REPORT.dt),
        duration: 1.0,
        error_estimate: false, // its cost is `benches/estimate.rs`'s
        ..RunConfig::default()
    }
    .validate()
    .expect("the report's setting is valid")
}

fn logging_overhead(c: &mut Criterion) {
    let config = config();
    let stop = AtomicBool::new(false);
    let path = std::env::temp_dir().join(format!("rope-bench-{}.rrd", std::process::id()));
    let mut group = c.benchmark_group("report_run_1_time_unit");
    group.sample_size(20);
    group.bench_function("logging_off", |b| {
        b.iter(|| pipeline::run(&config, &mut (), &stop, &|_| {}).expect("runs"))
    });
    group.bench_function("saved_to_rrd", |b| {
        b.iter(|| {
            let rec = rerun::RecordingStreamBuilder::new("rope-bench")
                .save(&path)
                .expect("a writable temp file");
            let mut logger = RopeLogger::new(rec).expect("styling logged");
            pipeline::run(&config, &mut logger, &stop, &|_| {}).expect("runs")
        })
    });
    group.finish();
    let _ = std::fs::remove_file(&path);
}

criterion_group!(benches, logging_overhead);
criterion_main!(benches);
