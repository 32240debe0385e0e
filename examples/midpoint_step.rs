//! What step `midpoint` needs for its tip. At each N, from 0°, 30° and 80° to t = 3, at every
//! step of the default step k:
//! - its time error: the tip's largest distance from the same N at k/4 (which shares every
//!   instant of k; the run at k/4 errs in k about 16 times less, its own error in k
//!   left in the figure);
//! - that N's own spatial error: the tip's largest distance between N and 2N, both at k/4;
//! - the same time error at the rule's step before (0.8 h at most 1e-3, rounded down to 1, 2
//!   or 5 × 10ⁿ): the tip's change from the rule before is at most the sum of the two.
//!
//! The time error must stay below the spatial error: a step that is not needed for accuracy
//! only costs. `midpoint` is stable at any step: its own steps shrink where a rod turns fast.
//! With K, the default is replaced by max(the limit's step, K).
//!
//! ```text
//! cargo run --release --example midpoint_step [K|default] [N,N,…]
//! ```
//!
//! Prints a Markdown table with the CPU seconds of each run at the default step and at the
//! rule's before (its thread's; the cells run on every core at once).

#[path = "common/tips.rs"]
mod tips;

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::methods::method::round_down_nicely;
use rope::model::Scene;
use tips::{cells, largest, tips};

const DURATION: f64 = 3.0;

/// How many times finer the step of the run that stands for the time-converged one is.
const FINER: u64 = 4;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let candidate: Option<f64> = args
        .get(1)
        .filter(|k| *k != "default")
        .map(|k| k.parse().expect("K, a step, or default"));
    let segments: Vec<usize> =
        args.get(2)
            .map_or(vec![100, 200, 400, 800, 1000, 1600, 3200], |l| {
                l.split(',')
                    .map(|n| n.parse().expect("N, a count"))
                    .collect()
            });
    let d = MethodKind::Midpoint.descriptor();
    let limited = |n: usize| round_down_nicely(d.default_step_fraction * d.stability_limit(n));
    let before = |n: usize| limited(n).max(round_down_nicely((0.8 / n as f64).min(1e-3)));
    let rule = |n: usize| match candidate {
        Some(k) => limited(n).max(k),
        None => d.default_dt(n),
    };
    let rows: Vec<String> = cells(&[0.0, 30.0, 80.0], &segments)
        .par_iter()
        .map(|&(angle, n)| {
            let scene = Scene::Release { angle_deg: angle };
            let k = rule(n);
            let fine_k = k / FINER as f64;
            let (run, cpu) = tips(&scene, n, k, 1, DURATION);
            let (fine, _) = tips(&scene, n, fine_k, FINER, DURATION);
            let (finer_rope, _) = tips(&scene, 2 * n, fine_k, FINER, DURATION);
            let (old, old_cpu) = tips(&scene, n, before(n), 1, DURATION);
            let (old_fine, _) = tips(&scene, n, before(n) / FINER as f64, FINER, DURATION);
            let time_error = largest(&run, &fine);
            let spatial = largest(&fine, &finer_rope);
            let old_error = largest(&old, &old_fine);
            eprintln!("{angle}° N = {n}: time error {time_error:.2e}, spatial {spatial:.2e}");
            format!(
                "| {angle}° | {n} | {:.3e} | 1/{:.0} | {old_error:.2e} | {time_error:.2e} | {spatial:.2e} | {:.2} | {old_cpu:.3} | {cpu:.3} |",
                before(n),
                1.0 / k,
                time_error / spatial,
            )
        })
        .collect();
    println!(
        "| from | N | k before | {} | time error at k before | time error (to k/{FINER}), every step | spatial error (to 2N), every step | time / spatial | CPU s at k before | CPU s |",
        candidate.map_or("the default k".to_owned(), |k| format!(
            "k = max(the limit's, {k:e})"
        ))
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    rows.iter().for_each(|r| println!("{r}"));
}
