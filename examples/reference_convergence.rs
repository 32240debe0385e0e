//! How the rods' tip converges in N through the whip, release by release: the chain (the
//! reference method) at N, 2N, 4N, … to t = 3 at its default step, compared at every 1/1000
//! of a time unit. For each level it prints the largest change of the tip when N is doubled,
//! the order that the changes show, and the own error of the reference extrapolated from the
//! last three levels (the largest change of the extrapolation when it is made one level
//! finer). This is the measurement that says what a converged reference costs.
//!
//! `cargo run --release --example reference_convergence -- 30,52 200 3200 [RATE [GRADING
//! [DURATION]]]` (angles in degrees, the coarsest N, the finest N, the frames a time unit
//! compared, 1000 unless given: the tolerance check's 60 misses the whip's peaks between its
//! frames; rods graded towards the free end, s_i = 1 − (1 − i/N)^GRADING, where GRADING is
//! given and not 1: `Chain::graded`; the time run, 3 unless given; and a folder where, given,
//! each release's reference from its three finest levels is written as
//! `release-ANGLE.csv`: its tip and own error at every compared instant, as the tolerance
//! check's `references.csv` gives them).
//!
//! `RAYON_NUM_THREADS=1 … -- ANGLE 1600 12800 3000 1.5 3
//! assets/reference-convergence/graded-references` made the committed graded references at
//! N = 6 400 (3 000 instants a unit hold a run's every frame and every 1/1000; about 1 200 s
//! of CPU a release; `docs/measurements.md`).

use anyhow::Context as _;
use rayon::prelude::*;
use rope::model::{Point, Scene};
use rope::study::tip_reference::{extrapolate, write_reference_csv};
use rope::study::trajectory::{Trajectory, frame_times};
use std::time::Instant;

/// Frames per time unit at which the levels are compared unless told: fine enough to judge
/// between frames.
const COMPARE_RATE: f64 = 1000.0;
/// The time run unless told: the tolerance check's.
const DURATION: f64 = 3.0;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (angles, coarsest, finest, rate, grading, duration, out) = match args.as_slice() {
        [a, c, f] => (a, c, f, COMPARE_RATE, 1.0, DURATION, None),
        [a, c, f, r] => (a, c, f, r.parse()?, 1.0, DURATION, None),
        [a, c, f, r, g] => (a, c, f, r.parse()?, g.parse()?, DURATION, None),
        [a, c, f, r, g, d] => (a, c, f, r.parse()?, g.parse()?, d.parse()?, None),
        [a, c, f, r, g, d, o] => (a, c, f, r.parse()?, g.parse()?, d.parse()?, Some(o)),
        _ => anyhow::bail!(
            "usage: reference_convergence ANGLES COARSEST_N FINEST_N [RATE [GRADING [DURATION [OUT_DIR]]]]"
        ),
    };
    if let Some(out) = out {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create {out}"))?;
    }
    let angles: Vec<f64> = angles
        .split(',')
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let (coarsest, finest): (usize, usize) = (coarsest.parse()?, finest.parse()?);
    let mut levels = vec![coarsest];
    while levels.last().is_some_and(|&n| 2 * n <= finest) {
        levels.push(2 * levels[levels.len() - 1]);
    }
    let frames = frame_times(duration, rate);
    println!("angle_deg,segments,wall_s,change_from_half,order,own_error");
    for angle_deg in angles {
        let scene = Scene::Release { angle_deg };
        let runs: Vec<(Trajectory, f64)> = levels
            .par_iter()
            .map(|&n| {
                let started = Instant::now(); // wall time: the levels run in parallel
                let path = Trajectory::compute_graded(&scene, n, duration, grading)?;
                Ok((path, started.elapsed().as_secs_f64()))
            })
            .collect::<anyhow::Result<_>>()?;
        // The order the three finest levels show: their reference's.
        let mut finest_order = None;
        for (i, &n) in levels.iter().enumerate() {
            let change = (i >= 1).then(|| runs[i].0.largest_gap(&runs[i - 1].0, &frames));
            let previous = (i >= 2).then(|| runs[i - 1].0.largest_gap(&runs[i - 2].0, &frames));
            let order = change
                .zip(previous)
                .map(|(c, p)| (p / c).log2().clamp(1.0, 2.0));
            // The own error of the extrapolation from this level and the one below, measured
            // as the change from the extrapolation one level coarser.
            let own = order.map(|p| {
                frames
                    .iter()
                    .map(|&t| own_error_at(&runs[i].0, &runs[i - 1].0, &runs[i - 2].0, p, t))
                    .fold(0.0, f64::max)
            });
            finest_order = order;
            let show = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:.3e}"));
            println!(
                "{angle_deg},{n},{:.1},{},{},{}",
                runs[i].1,
                show(change),
                order.map_or(String::new(), |p| format!("{p:.2}")),
                show(own)
            );
        }
        if let (Some(out), Some(order), [.., half, coarse, fine]) =
            (out, finest_order, runs.as_slice())
        {
            let path = std::path::Path::new(out).join(format!("release-{angle_deg}.csv"));
            let rows = frames.iter().map(|&t| {
                let tip = extrapolated(&fine.0, &coarse.0, order, t);
                let own = own_error_at(&fine.0, &coarse.0, &half.0, order, t);
                (scene, t, tip, own)
            });
            write_reference_csv(&path, rows)
                .with_context(|| format!("cannot write {}", path.display()))?;
        }
    }
    Ok(())
}

/// The tip at `t` extrapolated at `order` from `fine` and the level at half its N, `coarse`.
fn extrapolated(fine: &Trajectory, coarse: &Trajectory, order: f64, t: f64) -> Point {
    extrapolate(fine.at(t), coarse.at(t), order)
}

/// The own error at `t` of the extrapolation from `fine` and `coarse`: its change from the
/// extrapolation one level coarser, from `coarse` and `half`.
fn own_error_at(
    fine: &Trajectory,
    coarse: &Trajectory,
    half: &Trajectory,
    order: f64,
    t: f64,
) -> f64 {
    (extrapolated(fine, coarse, order, t) - extrapolated(coarse, half, order, t)).norm()
}
