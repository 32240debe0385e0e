//! `rope study --estimate-check`: the live error estimate (Richardson against the shadow at
//! N/2, `run::estimate`) checked against the truth. Each method at each N, from each scene,
//! runs with its shadow to t = 3; at every logged frame its estimate is compared with the
//! distance of its tip from a fine reference's (the reference method at N = 1600, its tip kept
//! at every step and interpolated to the frame's time). The same data fit each method's
//! error model over all the scenes, with its safety factor measured.

use super::progress::{Progress, Stopped};
pub use super::trajectory::Trajectory;
use crate::error::Diverged;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::plan::error_model::ErrorModel;
use crate::run::estimate::TipBound;
use crate::run::simulate::{self, Options};
use rayon::prelude::*;

/// The estimate is judged where the true error is above this (below it, round-off and the
/// reference's own error are the same size as what is measured).
pub const RESOLVED: f64 = 1e-7;

/// The estimate should be within this factor of the truth, either way.
pub const FACTOR: f64 = 3.0;

/// Frames per time unit at which the estimate is compared.
pub const LOG_RATE: f64 = 60.0;

/// What to check.
#[derive(Clone, Debug)]
pub struct CheckSpec {
    pub methods: Vec<MethodKind>,
    pub segments: Vec<usize>,
    pub scenes: Vec<Scene>,
    pub duration: f64,
    /// N of the reference ([`MethodKind::REFERENCE`] at its default step).
    pub reference_segments: usize,
}

impl Default for CheckSpec {
    /// The grid: every method at N = 25 … 200, the releases at 0°, 30°, 60° and 90°
    /// and modes 1 and 2 (tip amplitude 0.05), to t = 3 against N = 1600.
    fn default() -> Self {
        let release = |angle_deg| Scene::Release { angle_deg };
        let mode = |number| Scene::Mode {
            number,
            amplitude: 0.05,
        };
        Self {
            methods: MethodKind::ALL.to_vec(),
            segments: vec![25, 50, 100, 200],
            scenes: vec![
                release(0.0),
                release(30.0),
                release(60.0),
                release(90.0),
                mode(1),
                mode(2),
            ],
            duration: 3.0,
            reference_segments: 1600,
        }
    }
}

/// One frame's estimate and the truth.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Sample {
    pub time: f64,
    pub estimate: f64,
    pub truth: f64,
}

/// One method at one N from one scene.
#[derive(Clone, Debug)]
pub struct Cell {
    pub method: MethodKind,
    pub scene: Scene,
    pub segments: usize,
    pub dt: f64,
    pub samples: Vec<Sample>,
    /// Why the method could not start from the scene, if it could not.
    pub refused: Option<String>,
    pub diverged: Option<Diverged>,
    /// Why the shadow stopped before the run, if it did.
    pub lost: Option<Diverged>,
}

/// What a cell's samples say of the estimate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Verdict {
    /// Frames whose true error is above [`RESOLVED`].
    pub judged: usize,
    /// Of those, the frames whose estimate is within [`FACTOR`] of the truth.
    pub within: usize,
    /// The smallest and largest estimate / truth over the judged frames.
    pub lowest: f64,
    pub highest: f64,
    /// The first judged frame outside the factor, if any.
    pub first_out: Option<f64>,
    /// The largest true error at any frame.
    pub max_truth: f64,
}

impl Cell {
    /// How the estimate fared against the truth.
    pub fn verdict(&self) -> Verdict {
        let mut v = Verdict {
            lowest: f64::INFINITY,
            highest: 0.0,
            ..Verdict::default()
        };
        for s in &self.samples {
            v.max_truth = v.max_truth.max(s.truth);
            if s.truth <= RESOLVED {
                continue;
            }
            v.judged += 1;
            let ratio = s.estimate / s.truth;
            v.lowest = v.lowest.min(ratio);
            v.highest = v.highest.max(ratio);
            if (1.0 / FACTOR..=FACTOR).contains(&ratio) {
                v.within += 1;
            } else if v.first_out.is_none() {
                v.first_out = Some(s.time);
            }
        }
        v
    }
}

/// Runs one cell against `reference`.
pub fn run_cell(
    method: MethodKind,
    scene: Scene,
    segments: usize,
    duration: f64,
    reference: &Trajectory,
) -> Cell {
    let dt = method.default_dt(segments);
    let mut cell = Cell {
        method,
        scene,
        segments,
        dt,
        samples: Vec::new(),
        refused: None,
        diverged: None,
        lost: None,
    };
    let options = Options {
        duration,
        log_rate: LOG_RATE,
        frame_grid: None,
    };
    let samples = &mut cell.samples;
    let run = simulate::run_shadowed(
        method,
        &scene,
        segments,
        dt,
        TipBound::FirstOrder,
        &options,
        |frame| {
            if let Some(e) = frame.error_estimate {
                samples.push(Sample {
                    time: frame.time,
                    estimate: e.tip,
                    truth: (frame.tip() - reference.at(frame.time)).norm(),
                });
            }
        },
    );
    cell.refused = run.refused;
    cell.diverged = run.diverged;
    cell.lost = run.lost;
    cell
}

/// The whole check: a reference per scene, then every cell, in parallel. `progress` counts
/// each reference and each cell, and may stop the check before the next run ([`Stopped`]).
pub fn check(spec: &CheckSpec, progress: &impl Progress) -> anyhow::Result<Vec<Cell>> {
    let references = spec
        .scenes
        .par_iter()
        .map(|scene| {
            progress.check()?;
            let r = Trajectory::compute_by(
                MethodKind::REFERENCE,
                scene,
                spec.reference_segments,
                spec.duration,
                progress,
            );
            progress.done();
            r
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let cells: Vec<(MethodKind, usize, usize)> = spec
        .methods
        .iter()
        .flat_map(|&m| {
            (0..spec.scenes.len()).flat_map(move |s| spec.segments.iter().map(move |&n| (m, s, n)))
        })
        .collect();
    Ok(cells
        .into_par_iter()
        .map(|(method, s, n)| {
            progress.check()?;
            let cell = run_cell(method, spec.scenes[s], n, spec.duration, &references[s]);
            progress.done();
            Ok(cell)
        })
        .collect::<Result<Vec<_>, Stopped>>()?)
}

/// Each method's error model over all the scenes: C h^p fitted to the largest true tip error
/// of each N over every scene and frame, with its safety factor (the largest measured error
/// over the model's prediction). A method with fewer than two N measured has none.
pub fn fit_models(cells: &[Cell]) -> Vec<(MethodKind, ErrorModel)> {
    let mut methods: Vec<MethodKind> = cells.iter().map(|c| c.method).collect();
    methods.dedup();
    methods
        .into_iter()
        .filter_map(|method| {
            let mut worst: Vec<(usize, f64)> = Vec::new();
            for c in cells
                .iter()
                .filter(|c| c.method == method && c.diverged.is_none())
            {
                let truth = c.verdict().max_truth;
                match worst.iter_mut().find(|(n, _)| *n == c.segments) {
                    Some((_, e)) => *e = e.max(truth),
                    None => worst.push((c.segments, truth)),
                }
            }
            Some((method, ErrorModel::fit(worst)?))
        })
        .collect()
}

/// A CSV row: one frame of one cell.
#[derive(serde::Serialize)]
struct CsvRow<'a> {
    method: &'a str,
    scene: String,
    segments: usize,
    dt: f64,
    time: f64,
    estimate: f64,
    truth: f64,
}

/// Writes every frame of every cell to `path`.
pub fn write_csv(cells: &[Cell], path: &std::path::Path) -> anyhow::Result<()> {
    let mut out = csv::Writer::from_path(path)?;
    for c in cells {
        for s in &c.samples {
            out.serialize(CsvRow {
                method: c.method.name(),
                scene: c.scene.to_string(),
                segments: c.segments,
                dt: c.dt,
                time: s.time,
                estimate: s.estimate,
                truth: s.truth,
            })?;
        }
    }
    out.flush()?;
    Ok(())
}

/// The check as Markdown: a table per method of every cell's verdict, the cells that missed
/// and when, and the error models fitted over all the scenes.
pub fn markdown(spec: &CheckSpec, cells: &[Cell], command: &str) -> String {
    let mut text = format!(
        "# The live error estimate against the truth\n\n`{command}`\n\n\
         Each method at its default step runs with its shadow at N/2 (twice the step) to \
         t = {}; at every frame the shadow shares ({LOG_RATE} per time unit) the estimate \
         |x_N − x_(N/2)| / (2^p − 1) of the tip error is compared with the tip's distance from \
         the {} method at N = {} (its tip at every step, interpolated to the frame's time). \
         Frames whose true error is at most {RESOLVED:.0e} are not judged.\n\n",
        spec.duration,
        MethodKind::REFERENCE,
        spec.reference_segments
    );
    let (judged, within) = cells
        .iter()
        .map(Cell::verdict)
        .fold((0, 0), |(j, w), v| (j + v.judged, w + v.within));
    text += &format!(
        "**Overall: {within} of {judged} judged frames ({:.1} %) have the estimate within a factor {FACTOR} of the truth.**\n\n",
        100.0 * within as f64 / judged.max(1) as f64
    );
    for &method in &spec.methods {
        text += &format!(
            "## {method}\n\n| scene | N | k | judged frames | within ×{FACTOR} | estimate / truth, lowest … highest | first frame outside | largest true error | notes |\n|---|---|---|---|---|---|---|---|---|\n"
        );
        for c in cells.iter().filter(|c| c.method == method) {
            let v = c.verdict();
            let notes = [
                c.refused.as_ref().map(|r| format!("not run: {r}")),
                c.diverged
                    .as_ref()
                    .map(|d| format!("diverged at t = {:.2}", d.time)),
                c.lost
                    .as_ref()
                    .map(|d| format!("shadow lost at t = {:.2}", d.time)),
            ]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join("; ");
            let range = if v.judged > 0 {
                format!("{:.2} … {:.2}", v.lowest, v.highest)
            } else {
                "–".to_owned()
            };
            text += &format!(
                "| {} | {} | {:.0e} | {} | {} | {range} | {} | {:.1e} | {notes} |\n",
                c.scene,
                c.segments,
                c.dt,
                v.judged,
                if v.judged > 0 {
                    format!("{:.0} %", 100.0 * v.within as f64 / v.judged as f64)
                } else {
                    "–".to_owned()
                },
                v.first_out
                    .map_or("–".to_owned(), |t| format!("t = {t:.2}")),
                v.max_truth
            );
        }
        text += "\n";
    }
    text += &format!(
        "## Error models over all the scenes\n\nFor `--tolerance`: each method's largest true tip error to t = {} over every scene above, at each N, fitted as C h^p; the safety factor is the largest measured error over the fit's prediction.\n\n| method | C | p | safety factor |\n|---|---|---|---|\n",
        spec.duration
    );
    for (method, model) in fit_models(cells) {
        text += &format!(
            "| {method} | {:.3} | {:.2} | {:.2} |\n",
            model.constant, model.order, model.safety
        );
    }
    text
}
