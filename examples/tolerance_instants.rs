//! What `rope run --tolerance EPS` chooses from each release angle, judged at every instant:
//! the chosen run's tip against a committed reference at every 1/3 000 of a time unit
//! (`tolerance_check::JUDGE_RATE`) and, beside it, at its frames alone (60 a unit), with what
//! its live estimate (watched at every step the run shares with its shadow) said, and so the
//! exit status the run would end with.
//!
//! `cargo run --release --example tolerance_instants -- [EPS,EPS…] [ANGLE,ANGLE…]`: by default
//! the fourteen runs of issue 61, 20° to 80° at 1e-3 and 1e-4, to t = 3, against
//! `assets/tolerance-check/references.csv`. Prints a Markdown table.

use rope::model::Scene;
use rope::plan::pilot;
use rope::study::read_reference::read_all;
use rope::study::tip_reference::{ConvergedTip, LOG_RATE};
use rope::study::tolerance_check::{Cell, JUDGE_RATE, measure};
use rope::study::trajectory::{Trajectory, frame_times};
use std::path::PathBuf;
use std::time::Instant;

const DURATION: f64 = 3.0;

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
    let scenes: Vec<Scene> = angles
        .iter()
        .map(|&angle_deg| Scene::Release { angle_deg })
        .collect();
    let path = PathBuf::from("assets/tolerance-check/references.csv");
    let read = read_all(&[path], &scenes, DURATION)?;
    println!(
        "| angle | EPS | choice (from) | worst / EPS at every 1/{JUDGE_RATE} | at the frames ({LOG_RATE} a unit) | live estimate's first-order bound / EPS | at the nominal order | exit | verdict | CPU s, pilots + run |\n|---|---|---|---|---|---|---|---|---|---|"
    );
    for &eps in &tolerances {
        for scene in &scenes {
            let Some(reference) = read.iter().find(|r| r.scene == *scene) else {
                println!("| {scene} | {eps:.0e} | no reference | | | | | | | |");
                continue;
            };
            let started = Instant::now();
            let (choice, pilots) = pilot::choose(eps, scene, DURATION, u64::MAX)?;
            let pilot_seconds = started.elapsed().as_secs_f64();
            let (m, n, dt) = (choice.method, choice.segments, choice.dt);
            let Some(chosen) = measure(m, scene, n, dt, DURATION, true, reference) else {
                println!("| {scene} | {eps:.0e} | {m} N = {n} diverged | | | | | | | |");
                continue;
            };
            let kept = Trajectory::keep(scene, m, n, dt, DURATION)?;
            let at_frames = frame_times(DURATION, LOG_RATE)
                .into_iter()
                .map(|t| (kept.trajectory.at(t) - reference.tip_at(t)).norm())
                .fold(0.0, f64::max);
            let cell = Cell {
                scene: *scene,
                tolerance: eps,
                skipped: None,
                chosen: Some(chosen),
                pilot_seconds,
                basis: Some(pilots.basis),
                cheapest: None,
            };
            let estimate = chosen.estimate.unwrap_or(f64::NAN);
            // The displayed estimate divides by 2^p − 1 where the bound divides by 2 − 1.
            let nominal = estimate / (2f64.powi(m.descriptor().order_in_h as i32) - 1.0);
            println!(
                "| {} | {eps:.0e} | {m} N = {n}, k = {dt:.2e} ({}) | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {pilot_seconds:.2} + {:.2} |",
                scene,
                pilots.basis.label(),
                chosen.worst / eps,
                at_frames / eps,
                estimate / eps,
                nominal / eps,
                if estimate > eps { 4 } else { 0 },
                cell.verdict().map_or("–", |v| v.label()),
                chosen.seconds,
            );
        }
    }
    Ok(())
}
