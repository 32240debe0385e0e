//! What `rope run --tolerance EPS` chooses from each release angle, judged at every instant:
//! the chosen run's tip against a committed reference at every 1/3 000 of a time unit
//! (`tolerance_check::JUDGE_RATE`) and, beside it, at its frames alone (60 a unit), with what
//! its live estimate (watched at every step the run shares with its shadow) said, and so the
//! exit status the run would end with.
//!
//! A second table says why the run is judged at `judging_step` and not read between its own
//! steps: how far its tip moves when its step is made finer (the run at k and at k/6, compared
//! at every step of k: its error in k, which bounds what judging it at a step at most k can
//! change), and how far a cubic through its own steps misses its tip between them (against
//! the run at k/6 at its own step nearest each 1/3 000).
//!
//! `cargo run --release --example tolerance_instants -- [EPS,EPS…] [SCENE,SCENE…] [DURATION]
//! [PATH,PATH…]`: by default the fourteen runs of issue 61, 20° to 80° at 1e-3 and 1e-4, to
//! t = 3, against `assets/tolerance-check/references.csv`, or against the least-erring reference
//! of a scene that it and the references files or folders PATH hold, as the check reads them
//! ([`best_read`]). A scene is a release angle (`40`), a mode of the
//! check's (`mode=2`, a tip amplitude of 0.05), a fold by its gap (`fold=0.02`) or a shake from its
//! steady state (`shake=2/1e-3`, frequency and amplitude). Past t = 3 (where those end), and for a
//! fold or a shake, each scene's reference is computed as the tolerance check computes one, of the
//! method the rule would choose there ([`reference_method`]), refined towards an own error of 1e-5
//! by one doubling at most (runs up to N = 6400: minutes a scene; a shake's from N = 128, towards a
//! tenth of the smallest EPS, two doublings at most). Prints the two tables in Markdown.

#[path = "common/args.rs"]
mod args;

use rope::model::{Scene, ShakeStart};
use rope::plan::tolerance;
use rope::study::read_reference::{CheckReference, read_all};
use rope::study::tip_reference::{ConvergedTip, LOG_RATE, TipReference};
use rope::study::tolerance_check::{
    Cell, JUDGE_RATE, REFERENCE_MARGIN, best_read, measure, reference_method,
};
use rope::study::trajectory::{Trajectory, frame_times};
use std::path::PathBuf;
use std::time::Instant;

/// The references file read where it reaches the run's duration.
const REFERENCES: &str = "assets/tolerance-check/references.csv";

/// How far [`REFERENCES`] reach.
const DURATION_READ: f64 = 3.0;

/// How many times finer the step of the run the chosen one is held against in the second table.
const FINER: usize = 6;

/// A scene as the command line names it here: a release angle in degrees (`40`), a mode
/// (`mode=2`), a fold by its gap (`fold=0.02`), or a shake from its steady state by its
/// frequency and amplitude (`shake=2/1e-3`).
fn scene(text: &str) -> anyhow::Result<Scene> {
    let number = |v: &str| {
        v.trim()
            .parse::<f64>()
            .map_err(|e| anyhow::anyhow!("{text:?}: {e}"))
    };
    Ok(match text.trim().split_once('=') {
        None => Scene::Release {
            angle_deg: number(text)?,
        },
        Some(("fold", gap)) => Scene::Fold { gap: number(gap)? },
        // The tolerance check's modes: a tip amplitude of 0.05.
        Some(("mode", n)) => Scene::Mode {
            number: number(n)? as u32,
            amplitude: 0.05,
        },
        Some(("shake", rest)) => {
            let (frequency, amplitude) = rest
                .split_once('/')
                .ok_or_else(|| anyhow::anyhow!("{text:?}: shake=FREQUENCY/AMPLITUDE"))?;
            Scene::Shake {
                frequency: number(frequency)?,
                amplitude: number(amplitude)?,
                start: ShakeStart::Steady,
            }
        }
        Some(_) => {
            anyhow::bail!("{text:?}: an angle, mode=NUMBER, fold=GAP or shake=FREQUENCY/AMPLITUDE")
        }
    })
}

fn main() -> anyhow::Result<()> {
    let mut argv = std::env::args().skip(1);
    let tolerances = args::numbers(argv.next(), &[1e-3, 1e-4])?;
    let scenes: Vec<Scene> = match argv.next() {
        None => [20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0]
            .map(|angle_deg| Scene::Release { angle_deg })
            .to_vec(),
        Some(text) => text.split(',').map(scene).collect::<anyhow::Result<_>>()?,
    };
    let duration = args::number(argv.next(), 3.0)?;
    let mut paths = vec![PathBuf::from(REFERENCES)];
    paths.extend(
        argv.next()
            .iter()
            .flat_map(|p| p.split(','))
            .map(PathBuf::from),
    );
    let smallest = tolerances.iter().copied().fold(f64::INFINITY, f64::min);
    // The committed references are of the check's releases and modes, to t = 3.
    let committed = scenes
        .iter()
        .all(|s| matches!(s, Scene::Release { .. } | Scene::Mode { .. }));
    let references: Vec<CheckReference> = if committed && duration <= DURATION_READ {
        let read = read_all(&paths, &scenes, duration)?;
        scenes
            .iter()
            .filter_map(|scene| best_read(&read, scene).cloned())
            .map(CheckReference::Read)
            .collect()
    } else {
        scenes
            .iter()
            .map(|scene| {
                let method = reference_method(scene, duration);
                // A shake's error is small and falls at second order from few rods: from
                // N = 128 (runs at 64, 128, 256), refined until it can judge the smallest EPS
                // (its own error a tenth of it), twice at most.
                let (from, most, target) = match scene {
                    Scene::Shake { .. } => (128, 512, 1e-5f64.min(smallest * REFERENCE_MARGIN)),
                    _ => (1600, 3200, 1e-5),
                };
                let r = TipReference::refined_by(method, scene, from, most, target, duration, &|| ())?;
                eprintln!(
                    "{scene}: reference of the {method} method, N = {} (order {:.2}), own error {:.1e} at every 1/{JUDGE_RATE}",
                    r.segments, r.order, r.own_error
                );
                Ok(CheckReference::Computed(r))
            })
            .collect::<anyhow::Result<_>>()?
    };
    println!(
        "| angle | EPS | choice (from) | worst / EPS at every instant | at the frames ({LOG_RATE} a unit) | live estimate's bound / EPS | at the nominal order | exit | verdict | CPU s, pilots + run |\n|---|---|---|---|---|---|---|---|---|---|"
    );
    let mut chosen_runs = Vec::new();
    for &eps in &tolerances {
        for scene in &scenes {
            let Some(reference) = references.iter().find(|r| r.scene() == *scene) else {
                println!("| {scene} | {eps:.0e} | no reference | | | | | | | |");
                continue;
            };
            let started = Instant::now();
            let (choice, pilots) = tolerance::choose(eps, scene, duration, u64::MAX)?;
            let pilot_seconds = started.elapsed().as_secs_f64();
            let (m, n, dt) = (choice.method, choice.segments, choice.dt);
            chosen_runs.push((*scene, eps, m, n, dt));
            let Some(chosen) =
                measure(m, scene, n, dt, duration, Some(choice.tip_bound), reference)
            else {
                println!("| {scene} | {eps:.0e} | {m} N = {n} diverged | | | | | | | |");
                continue;
            };
            let kept = Trajectory::keep(scene, m, n, dt, duration)?;
            let at_frames = frame_times(duration, LOG_RATE)
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
            // The displayed estimate divides by 2^p − 1 where the first-order bound divides by
            // 2 − 1 (and a mode's bound at the order its pilots saw, by less).
            let first_order = estimate / choice.tip_bound.of_first_order(2.0);
            let nominal = first_order / (2f64.powi(m.descriptor().order_in_h as i32) - 1.0);
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
    println!(
        "\n| angle | EPS | choice | at k against k/{FINER}, at every step of k | a cubic through the steps of k, against k/{FINER} |\n|---|---|---|---|---|"
    );
    for (scene, eps, m, n, dt) in chosen_runs {
        let run = Trajectory::keep(&scene, m, n, dt, duration)?.trajectory;
        let finer = Trajectory::keep(&scene, m, n, dt / FINER as f64, duration)?.trajectory;
        let steps = (duration / dt).round() as usize;
        let at_steps = (0..=steps)
            .map(|i| (run.tips()[i] - finer.tips()[FINER * i]).norm())
            .fold(0.0, f64::max);
        let between = frame_times(duration, JUDGE_RATE)
            .into_iter()
            .map(|t| {
                let j = (t / finer.dt()).round() as usize;
                (run.at(j as f64 * finer.dt()) - finer.tips()[j]).norm()
            })
            .fold(0.0, f64::max);
        println!(
            "| {scene} | {eps:.0e} | {m} N = {n}, k = {dt:.2e} | {at_steps:.1e} | {between:.1e} |"
        );
    }
    Ok(())
}
