//! What step `midpoint` needs for its tip, against the step its stability limit sets. At each
//! N, from 0°, 30° and 80° to t = 3: the tip's largest change, at every 1e-3 of a time unit,
//! between the run at the limit's step (0.4 of the limit, which shrinks as h: the default
//! before `AccurateStep`) and at the default step, against that N's own spatial error (the
//! tip's largest distance from the run at 2N, both at the default step). `midpoint` is stable
//! at any step: its own steps shrink where a rod turns fast, so a step that is not needed for
//! accuracy only costs. With K, the default is replaced by max(the limit's step, K).
//!
//! ```text
//! cargo run --release --example midpoint_step [K|default] [N,N,…]
//! ```
//!
//! Prints a Markdown table and the CPU seconds of each run (its thread's).

use rayon::prelude::*;
use rope::methods::method::round_down_nicely;
use rope::methods::{Method, MethodKind};
use rope::model::Scene;
use rope::model::geometry::Point;
use rope::model::support::tip_in_the_room;
use rope::run::trust::steps_between;

const DURATION: f64 = 3.0;

/// The tip at every instant of the fine grid to [`DURATION`], and the run's CPU seconds.
fn tips(scene: &Scene, n: usize, dt: f64) -> (Vec<Point>, f64) {
    let cpu = cpu_time::ThreadTime::now();
    let mut method = MethodKind::Midpoint
        .build(scene, n, dt)
        .expect("midpoint starts from every release");
    let every = steps_between(dt);
    let total = (DURATION / dt).round() as u64;
    let tip = |m: &dyn Method| tip_in_the_room(m.support(), m.angles(), m.lengths());
    let mut out = vec![tip(method.as_ref())];
    while method.steps() < total {
        method.step().expect("midpoint does not diverge");
        if method.steps().is_multiple_of(every) {
            out.push(tip(method.as_ref()));
        }
    }
    (out, cpu.elapsed().as_secs_f64())
}

/// The largest distance between two runs' tips over the instants both have (the finer run's
/// grid is thinned to the coarser one's: both are every 1e-3 unless a step is longer).
fn largest(a: &[Point], b: &[Point]) -> f64 {
    let (fine, coarse) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let ratio = (fine.len() - 1) / (coarse.len() - 1).max(1);
    coarse
        .iter()
        .enumerate()
        .map(|(i, p)| (fine[i * ratio] - p).norm())
        .fold(0.0, f64::max)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let candidate: Option<f64> = args
        .get(1)
        .filter(|k| *k != "default")
        .map(|k| k.parse().expect("K, a step, or default"));
    let segments: Vec<usize> = args
        .get(2)
        .map_or(vec![25, 50, 100, 200, 400, 800, 1600], |l| {
            l.split(',')
                .map(|n| n.parse().expect("N, a count"))
                .collect()
        });
    let d = MethodKind::Midpoint.descriptor();
    let today = |n: usize| round_down_nicely(d.default_step_fraction * d.stability_limit(n));
    let rule = |n: usize| match candidate {
        Some(k) => today(n).max(k),
        None => d.default_dt(n),
    };
    let cells: Vec<(f64, usize)> = [0.0, 30.0, 80.0]
        .iter()
        .flat_map(|&a| segments.iter().map(move |&n| (a, n)))
        .collect();
    let rows: Vec<String> = cells
        .par_iter()
        .map(|&(angle, n)| {
            let scene = Scene::Release { angle_deg: angle };
            let (old, old_cpu) = tips(&scene, n, today(n));
            let (new, new_cpu) = if rule(n) == today(n) {
                (old.clone(), old_cpu)
            } else {
                tips(&scene, n, rule(n))
            };
            let (fine, _) = tips(&scene, 2 * n, rule(2 * n));
            let change = largest(&old, &new);
            let spatial = largest(&new, &fine);
            eprintln!("{angle}° N = {n}: change {change:.2e}, spatial {spatial:.2e}");
            format!(
                "| {angle}° | {n} | {:.0e} | {:.0e} | {change:.2e} | {spatial:.2e} | {:.2} | {old_cpu:.3} | {new_cpu:.3} |",
                today(n),
                rule(n),
                change / spatial,
                )
        })
        .collect();
    println!(
        "| from | N | the limit's k | {} | tip change | spatial error (to 2N) | change / spatial | CPU s at the limit's k | CPU s |",
        candidate.map_or("the default k".to_owned(), |k| format!(
            "k = max(the limit's, {k:e})"
        ))
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    rows.iter().for_each(|r| println!("{r}"));
}
