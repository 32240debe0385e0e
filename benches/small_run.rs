//! A whole small run's CPU, with the accuracy it reaches: from 30° to t = 1, frames at 10 a
//! time unit, held against a converged reference at t = 0.1, 0.2, …, 1.0. The two runs issue
//! 63 named for 1e-3 and 1e-4 (rattle at N = 12, k = 0.025; midpoint at N = 25, k = 0.05,
//! which since its coarse steps are taken whole keeps 2.4e-4, not 1e-4), and the cheapest
//! that `cargo run --release --example small_run_search` finds for each: midpoint at N = 8,
//! k = 0.1 (1e-3: a step that coarse is taken whole while the rods turn slowly,
//! `Descriptor::is_coarse`) and at N = 14, k = 0.05 (1e-4). Each is timed three ways:
//! `rope::simulate` as a program embedding rope calls it (without the live estimate), the
//! method built and stepped alone, and its steps alone (the floor).
//!
//! `cargo bench --bench small_run`; the accuracy is printed before the timings, and the table
//! in `docs/measurements.md` comes from both. Beside them, what `--tolerance` spends choosing
//! a small mode's run, which costs as much as the run (`small_mode_planning`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::study::tip_reference::{ConvergedTip, TipReference};
use rope::{RunConfig, simulate};
use std::hint::black_box;

/// The scene, the duration and the frame rate of the runs.
const SCENE: Scene = Scene::Release { angle_deg: 30.0 };
const DURATION: f64 = 1.0;
const LOG_RATE: f64 = 10.0;

/// The runs: method, N, k, and the tolerance each is the cheapest run to keep.
const RUNS: [(MethodKind, usize, f64, f64); 4] = [
    (MethodKind::Rattle, 12, 0.025, 1e-3),
    (MethodKind::Midpoint, 25, 0.05, 1e-4),
    (MethodKind::Midpoint, 8, 0.1, 1e-3),
    (MethodKind::Midpoint, 14, 0.05, 1e-4),
];

fn config(method: MethodKind, segments: usize, dt: f64) -> RunConfig {
    RunConfig {
        method,
        scene: SCENE,
        segments,
        dt: Some(dt),
        duration: DURATION,
        log_rate: LOG_RATE,
        error_estimate: false,
        ..RunConfig::default()
    }
}

/// The tip's largest distance from the reference at the frames t = 0.1, …, 1.0, the same
/// rods' own error (at k = 0.001, where the time error is far below it), and the method's own
/// steps and solves.
fn accuracy(reference: &TipReference) {
    for (method, segments, dt, eps) in RUNS {
        let run = simulate(&config(method, segments, dt)).expect("a valid run");
        let worst = reference.farthest(&run.frames);
        let fine = simulate(&config(method, segments, 1e-3)).expect("a valid run");
        let own = match run.summary.step_statistics {
            Some(s) => format!(
                "; {} own steps, {} solves, {:.1e} of kinetic energy restored",
                s.steps, s.solves, s.restored_energy
            ),
            None => String::new(),
        };
        eprintln!(
            "{method} N = {segments}, k = {dt}: worst tip error at t = 0.1 … 1.0 {worst:.2e} ({:.2} of {eps:e}; {} frames{own}); at k = 0.001, {:.2e}",
            worst / eps,
            run.frames.len(),
            reference.farthest(&fine.frames),
        );
    }
}

fn small_runs(c: &mut Criterion) {
    // The chain at N = 200, 400, 800, extrapolated: its own error far below 1e-4 to t = 1.
    let reference = TipReference::compute(&SCENE, 400, DURATION).expect("the reference");
    eprintln!(
        "reference: the chain at N = 200, 400, 800 (order {:.2}), own error {:.1e}",
        reference.order, reference.own_error
    );
    accuracy(&reference);
    let mut group = c.benchmark_group("small_run");
    for (method, segments, dt, _) in RUNS {
        let id = format!("{method}_{segments}");
        let config = config(method, segments, dt);
        group.bench_function(BenchmarkId::new("simulate", &id), |b| {
            b.iter(|| simulate(black_box(&config)).expect("a valid run"))
        });
        let steps = (DURATION / dt).round() as usize;
        group.bench_function(BenchmarkId::new("build_and_step", &id), |b| {
            b.iter(|| {
                let mut run = method.build(&SCENE, segments, dt).expect("valid");
                for _ in 0..steps {
                    run.step().expect("stable");
                }
                black_box(run.time())
            })
        });
        let start = method.build(&SCENE, segments, dt).expect("valid");
        group.bench_function(BenchmarkId::new("steps", &id), |b| {
            b.iter_batched(
                || start.box_clone(),
                |mut run| {
                    for _ in 0..steps {
                        run.step().expect("stable");
                    }
                    black_box(run.time())
                },
                criterion::BatchSize::SmallInput,
            )
        });
    }
    group.finish();
}

/// What `--tolerance` spends choosing before a small mode's run (mode 2, tip amplitude 0.05,
/// to t = 3 at 1e-3; the run it chooses, the chain at N = 33, takes about 2 ms): the linear
/// theory worked out alone (`committed::from_theory`), and the whole choice, the seed's pilot
/// at N = 16 included (`tolerance::choose`).
fn small_mode_planning(c: &mut Criterion) {
    use rope::plan::{committed, tolerance};
    let mode = Scene::Mode {
        number: 2,
        amplitude: 0.05,
    };
    let mut group = c.benchmark_group("small_mode_planning");
    group.bench_function("theory", |b| {
        b.iter(|| committed::from_theory(black_box(&mode), 3.0, 1e-3).expect("served"))
    });
    group.bench_function("choose", |b| {
        b.iter(|| tolerance::choose(1e-3, black_box(&mode), 3.0, u64::MAX).expect("a choice"))
    });
    group.finish();
}

criterion_group!(benches, small_runs, small_mode_planning);
criterion_main!(benches);
