//! What a release's angle lets `midpoint`'s default step be. The rule for the tip's step
//! (`AccurateStep`) is the horizontal release's, whose free end whips hardest; from further
//! below the horizontal the time error is a smaller share of the spatial error, and the
//! default step in the scene (`Descriptor::default_step`) is up to twice the rule's. At each
//! angle and N, to t = 3, at every step:
//! - the time error at the rule's step k₀ and at the scene's step k: the tip's largest
//!   distance from the same N at a quarter of that step (which shares every instant of it);
//! - that N's own spatial error: the tip's largest distance between N and 2N, both at k₀/4;
//! - the tip's change from the run at k₀, at every instant the two runs share;
//! - each run's CPU seconds (its thread's; the cells run on every core at once).
//!
//! The time error at the scene's step must stay below the spatial error, as the rule's does
//! from the horizontal (at most 0.62 of it): a step not needed for accuracy only costs.
//!
//! ```text
//! cargo run --release --example release_step [ANGLE,ANGLE,…] [N,N,…]
//! ```
//!
//! Prints a Markdown table.

#[path = "common/args.rs"]
mod args;
#[path = "common/tips.rs"]
mod tips;

use rayon::prelude::*;
use rope::methods::MethodKind;
use rope::model::Scene;
use rope::model::geometry::Point;
use tips::{cells, largest, tips};

const DURATION: f64 = 3.0;

/// How many times finer the step of the run that stands for the time-converged one is.
const FINER: u64 = 4;

/// The largest distance between the tips of a run at `k` and one at `k0`, at every instant
/// both reach (each tip list holds every step's).
fn shared(run: &[Point], k: f64, base: &[Point], k0: f64) -> f64 {
    (0..run.len())
        .filter_map(|j| {
            let i = j as f64 * k / k0;
            let at = i.round() as usize;
            ((i - i.round()).abs() < 1e-6 && at < base.len()).then(|| (run[j] - base[at]).norm())
        })
        .fold(0.0, f64::max)
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let angles = args::numbers(
        args.next(),
        &[
            0.0, 1.0, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0, 80.0,
        ],
    )?;
    let segments: Vec<usize> = args::numbers(
        args.next(),
        &[100.0, 200.0, 400.0, 800.0, 1000.0, 1600.0, 3200.0],
    )?
    .into_iter()
    .map(|n| n as usize)
    .collect();
    let d = MethodKind::Midpoint.descriptor();
    let rows: Vec<String> = cells(&angles, &segments)
        .par_iter()
        .map(|&(angle, n)| {
            let scene = Scene::Release { angle_deg: angle };
            let (k0, k) = (d.default_dt(n), d.default_step(&scene, n));
            let finer = FINER as f64;
            let (fine0, _) = tips(&scene, n, k0 / finer, FINER, DURATION);
            let (finer_rope, _) = tips(&scene, 2 * n, k0 / finer, FINER, DURATION);
            let (run0, cpu0) = tips(&scene, n, k0, 1, DURATION);
            let spatial = largest(&fine0, &finer_rope);
            let time0 = largest(&run0, &fine0);
            let (time, change, cpu) = match k == k0 {
                true => (time0, 0.0, cpu0),
                false => {
                    let (run, cpu) = tips(&scene, n, k, 1, DURATION);
                    let (fine, _) = tips(&scene, n, k / finer, FINER, DURATION);
                    (largest(&run, &fine), shared(&run, k, &run0, k0), cpu)
                }
            };
            eprintln!("{angle}° N = {n}: time error {time:.2e}, spatial {spatial:.2e}");
            format!(
                "| {angle}° | {n} | 1/{:.0} | 1/{:.0} | {time0:.2e} | {time:.2e} | {spatial:.2e} | {:.2} | {:.2} | {change:.2e} | {cpu0:.3} | {cpu:.3} |",
                1.0 / k0,
                1.0 / k,
                time0 / spatial,
                time / spatial,
            )
        })
        .collect();
    println!(
        "| from | N | the rule's k₀ | the scene's k | time error at k₀ | time error at k | spatial error (to 2N) | time / spatial at k₀ | time / spatial at k | tip's change from k₀ | CPU s at k₀ | CPU s at k |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    rows.iter().for_each(|r| println!("{r}"));
    Ok(())
}
