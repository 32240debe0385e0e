//! Whether the rods' tip error through the whip is a matter of *when*: the chain (the
//! reference method) at N, 2N, 4N, … to t = 3, each level's whip instant (its tip's largest
//! speed) and peak speed, and between successive levels the largest gap of the tip compared
//! at every 1/1000 of a time unit: over the whole run, and within [`NEAR`] of the finer
//! level's whip, raw and with the coarser level shifted in time so that the two whips
//! coincide. If the shifted gap near the whip is far below the raw one, the levels differ
//! mostly in when the whip comes, and a reference could be extrapolated on its instant.
//!
//! `cargo run --release --example whip_timing -- 30,0 200 1600 [GRADING]` (GRADING given and
//! not 1: rods graded towards the free end, s_i = 1 − (1 − i/N)^GRADING,
//! [`Trajectory::compute_graded`]).

use rayon::prelude::*;
use rope::model::Scene;
use rope::study::trajectory::{Trajectory, frame_times};

const DURATION: f64 = 3.0;
const COMPARE_RATE: f64 = 1000.0;
/// How near the whip (in time) its gaps are compared.
const NEAR: f64 = 0.05;

/// The instant of the tip's largest speed, and that speed (from successive kept tips).
fn whip(path: &Trajectory) -> (f64, f64) {
    let dt = path.dt();
    let last = (DURATION / dt).round() as usize;
    path.tips()[..=last]
        .windows(2)
        .enumerate()
        .map(|(i, w)| ((i as f64 + 0.5) * dt, (w[1] - w[0]).norm() / dt))
        .fold((0.0, 0.0), |best, x| if x.1 > best.1 { x } else { best })
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (angles, coarsest, finest, grading) = match args.as_slice() {
        [a, c, f] => (a, c, f, 1.0),
        [a, c, f, g] => (a, c, f, g.parse()?),
        _ => anyhow::bail!("usage: whip_timing ANGLES COARSEST_N FINEST_N [GRADING]"),
    };
    let (coarsest, finest): (usize, usize) = (coarsest.parse()?, finest.parse()?);
    let mut levels = vec![coarsest];
    while levels.last().is_some_and(|&n| 2 * n <= finest) {
        levels.push(2 * levels[levels.len() - 1]);
    }
    let frames = frame_times(DURATION, COMPARE_RATE);
    println!(
        "angle_deg,segments,whip_t,whip_speed,gap_from_half,gap_near_whip,gap_near_whip_aligned"
    );
    for angle in angles.split(',') {
        let angle_deg: f64 = angle.parse()?;
        let scene = Scene::Release { angle_deg };
        let runs: Vec<Trajectory> = levels
            .par_iter()
            .map(|&n| Trajectory::compute_graded(&scene, n, DURATION, grading))
            .collect::<anyhow::Result<_>>()?;
        let whips: Vec<(f64, f64)> = runs.iter().map(whip).collect();
        for (i, &n) in levels.iter().enumerate() {
            let (when, speed) = whips[i];
            let gaps = if i == 0 {
                String::from(",,")
            } else {
                let shift = whips[i - 1].0 - when;
                let near: Vec<f64> = frames
                    .iter()
                    .copied()
                    .filter(|&t| (t - when).abs() <= NEAR)
                    .collect();
                let gap = |shift: f64| {
                    near.iter()
                        .map(|&t| (runs[i].at(t) - runs[i - 1].at(t + shift)).norm())
                        .fold(0.0, f64::max)
                };
                let raw = runs[i].largest_gap(&runs[i - 1], &frames);
                format!("{raw:.3e},{:.3e},{:.3e}", gap(0.0), gap(shift))
            };
            println!("{angle_deg},{n},{when:.5},{speed:.3},{gaps}");
        }
    }
    Ok(())
}
