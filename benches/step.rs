//! Nanoseconds per segment-step of each method's step, against the bare tridiagonal solve of
//! the same size (the floor the seed scheme's step is measured against).
//!
//! `cargo bench --bench step`; the table in `docs/measurements.md` comes from it.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rope::methods::MethodKind;
use rope::methods::tridiagonal::{self, Workspace};
use rope::model::Scene;
use std::hint::black_box;

const SIZES: [usize; 3] = [100, 1_000, 10_000];

fn bare_solve(c: &mut Criterion) {
    let mut group = c.benchmark_group("bare_tridiagonal_solve");
    for n in SIZES {
        // The seed scheme's system has N − 1 unknowns, diagonal ≈ −2, off-diagonals 1.
        let m = n - 1;
        let lower = vec![1.0; m];
        let upper = vec![1.0; m];
        let diag: Vec<f64> = (0..m).map(|i| -2.0 - 1e-4 * (i % 7) as f64).collect();
        let rhs: Vec<f64> = (0..m).map(|i| -1e-6 * (i % 5) as f64).collect();
        let mut x = vec![0.0; m];
        let mut ws = Workspace::new(m);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                tridiagonal::solve(&lower, &diag, &upper, black_box(&rhs), &mut x, &mut ws);
                black_box(&x);
            })
        });
    }
    group.finish();
}

fn method_step(c: &mut Criterion) {
    for kind in MethodKind::ALL {
        let mut group = c.benchmark_group(format!("{kind}_step"));
        for n in SIZES {
            let scene = Scene::Release { angle_deg: 30.0 };
            let start = kind.build(&scene, n, kind.default_dt(n)).expect("valid");
            let mut method = start.box_clone();
            group.throughput(Throughput::Elements(n as u64));
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| {
                    // Stay within the first two time units of the swing (a restart costs
                    // one copy every ≥ 700 steps).
                    if method.time() > 2.0 {
                        method = start.box_clone();
                    }
                    method.step().expect("stable")
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bare_solve, method_step);
criterion_main!(benches);
