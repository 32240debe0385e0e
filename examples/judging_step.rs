//! How far a run's tip moves when its step is made finer: the run `--tolerance EPS` chooses
//! from each release angle, at its step k and at k/6, compared at every step of k. This bounds
//! the run's error in k, and so what judging it at a step at most k that falls on the
//! reference's rows (`tolerance_check::judging_step`) can change; and how far a cubic through
//! the run's own steps misses its tip between them (against the run at k/6 read at its own
//! steps, every 1/3 000 of a time unit nearest one), which is why the check does not read a
//! run between its steps.
//!
//! `cargo run --release --example judging_step -- [EPS,EPS…] [ANGLE,ANGLE…]`: by default the
//! fourteen runs of issue 61 (20° to 80° at 1e-3 and 1e-4, to t = 3).

use rope::model::Scene;
use rope::plan::pilot;
use rope::study::trajectory::{Trajectory, frame_times};

const DURATION: f64 = 3.0;
const FINER: usize = 6;

fn list(arg: Option<String>, default: &[f64]) -> anyhow::Result<Vec<f64>> {
    match arg {
        None => Ok(default.to_vec()),
        Some(text) => text
            .split(',')
            .map(|v| v.trim().parse().map_err(|e| anyhow::anyhow!("{v:?}: {e}")))
            .collect(),
    }
}

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let tolerances = list(args.next(), &[1e-3, 1e-4])?;
    let angles = list(args.next(), &[20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0])?;
    println!(
        "| angle | EPS | choice | at k against k/{FINER}, at every step of k | a cubic through the steps of k, against k/{FINER} |\n|---|---|---|---|---|"
    );
    for &eps in &tolerances {
        for &angle_deg in &angles {
            let scene = Scene::Release { angle_deg };
            let (choice, _) = pilot::choose(eps, &scene, DURATION, u64::MAX)?;
            let (m, n, dt) = (choice.method, choice.segments, choice.dt);
            let run = Trajectory::keep(&scene, m, n, dt, DURATION)?.trajectory;
            let finer = Trajectory::keep(&scene, m, n, dt / FINER as f64, DURATION)?.trajectory;
            let steps = (DURATION / dt).round() as usize;
            let at_steps = (0..=steps)
                .map(|i| (run.tips()[i] - finer.tips()[FINER * i]).norm())
                .fold(0.0, f64::max);
            // The finer run at its own step nearest each instant: within k/12 of it.
            let between = frame_times(DURATION, 3000.0)
                .into_iter()
                .map(|t| {
                    let j = (t / finer.dt()).round() as usize;
                    (run.at(j as f64 * finer.dt()) - finer.tips()[j]).norm()
                })
                .fold(0.0, f64::max);
            println!(
                "| {angle_deg}° | {eps:.0e} | {m} N = {n}, k = {dt:.2e} | {at_steps:.1e} | {between:.1e} |"
            );
        }
    }
    Ok(())
}
