//! `rope study --tolerance-check`: `--tolerance EPS` checked against the truth. For each scene
//! and EPS, the run `rope run --tolerance EPS` would make (its pilots, then the chosen method,
//! N and k with its shadow) is measured against a converged reference at every instant, and its
//! CPU, pilots included, set beside the cheapest run of a (method, N, k) grid, each method at
//! its default step and at its tolerance step, that also holds EPS. A scene's reference is
//! computed, or read back from a references file where one can judge the check's smallest EPS.

use super::check_timing::{RETIMED_BELOW, fastest, fastest_side_by_side, timed_run};
use super::progress::{Progress, Stopped};
use super::read_reference::{CheckReference, ReadReference};
pub use super::tip_reference::JUDGE_RATE;
pub use super::tip_reference::LOG_RATE;
use super::tip_reference::{ConvergedTip, TipReference};
use super::trajectory::{Trajectory, frame_times};
use crate::methods::{MethodKind, whole_division};
use crate::model::Scene;
use crate::plan::atlas::ATLAS_ANGLES;
use crate::plan::runs::{self, RunRequest};
use crate::plan::{choice, pilot};
use crate::run::cost::Limits;
use crate::run::estimate::TipBound;
use rayon::prelude::*;

/// A tolerance is checked only where the reference's own error is at most this fraction of it.
pub const REFERENCE_MARGIN: f64 = 0.1;

/// The chosen run's CPU may be at most this many times the grid's cheapest.
pub const CPU_FACTOR: f64 = 3.0;

/// Release angles the check adds to the release atlas's: between its angles and its held-out
/// ones, so that they test the atlas where it measured nothing.
pub const UNSEEN_ANGLES: [f64; 2] = [37.0, 52.0];

/// What to check.
#[derive(Clone, Debug)]
pub struct CheckSpec {
    pub scenes: Vec<Scene>,
    pub tolerances: Vec<f64>,
    pub duration: f64,
    /// The reference: [`MethodKind::REFERENCE`] at N/2, N and 2N, extrapolated, from N = this
    /// ...
    pub reference_segments: usize,
    /// ... N doubled while the reference's own error is above [`REFERENCE_MARGIN`] × the
    /// smallest EPS, up to this N ...
    pub reference_segments_max: usize,
    /// ... and on up to this one where the order the runs show (at least 2) would bring it
    /// there by this N ([`TipReference::could_reach`]): a doubling that cannot reach its
    /// target is not paid for (the horizontal release's first-order whip).
    pub reference_segments_reach: usize,
    /// The grid's segment counts (every startable method at each, at [`grid_steps`]).
    pub grid: Vec<usize>,
    /// Where none of the grid's runs holds the smallest EPS the scene's reference can judge,
    /// the grid goes on at these N, every startable method at each, up to the first N where
    /// a run holds it: a choice past the grid's largest N is then set beside runs as fine.
    pub grid_beyond: Vec<usize>,
}

impl Default for CheckSpec {
    /// The check: the releases at every angle of the release atlas (0°, 10°, …, 90°)
    /// and at two that neither the atlas nor its held-out angles measure (37° and 52°), and
    /// modes 1 and 2 (tip amplitude 0.05); EPS = 1e-2, 1e-3 and 1e-4 (each where the
    /// reference allows), to t = 3, against the reference method extrapolated from N/2, N and
    /// 2N with N from 200 up to 3200 (a whip's reference reaches an own error of 1e-5, what
    /// judges 1e-4, near N = 1600 from 20° to 40°: 6400 rods, up to four minutes a scene),
    /// and to 6400 where that can reach it (from 80° and 52°: runs up to 12 800 rods, about
    /// 20 minutes each), beside a grid up to N = 1131 (the graded rods' atlas's largest N), on
    /// to 3200 where nothing in it holds (the chain's atlas's largest N, from 10°).
    fn default() -> Self {
        let release = |angle_deg| Scene::Release { angle_deg };
        let mode = |number| Scene::Mode {
            number,
            amplitude: 0.05,
        };
        let mut scenes: Vec<Scene> = ATLAS_ANGLES.map(release).to_vec();
        scenes.extend(UNSEEN_ANGLES.map(release));
        scenes.extend([mode(1), mode(2)]);
        Self {
            scenes,
            tolerances: vec![1e-2, 1e-3, 1e-4],
            duration: 3.0,
            reference_segments: 200,
            reference_segments_max: 3200,
            reference_segments_reach: 6400,
            grid: vec![16, 25, 32, 50, 64, 100, 141, 200, 283, 400, 566, 800, 1131],
            grid_beyond: vec![1600, 2263, 3200],
        }
    }
}

impl CheckSpec {
    /// The check at its two unseen angles alone ([`UNSEEN_ANGLES`]): where a change to
    /// how the atlas serves an angle it did not measure shows, in about half an hour (the
    /// reference from 52° is the check's slowest).
    pub fn unseen() -> Self {
        Self {
            scenes: UNSEEN_ANGLES
                .map(|angle_deg| Scene::Release { angle_deg })
                .to_vec(),
            ..Self::default()
        }
    }

    /// The check at its two small modes alone (modes 1 and 2, tip amplitude 0.05):
    /// where a change to the linear theory, which chooses for them, shows, in seconds with their
    /// references read.
    pub fn modes() -> Self {
        let full = Self::default();
        Self {
            scenes: full
                .scenes
                .iter()
                .copied()
                .filter(|scene| matches!(scene, Scene::Mode { .. }))
                .collect(),
            ..full
        }
    }

    /// The small check CI runs: the release from 30° and mode 1 at EPS = 1e-2, against the
    /// reference method extrapolated from N = 400, 800 and 1600 (from N = 200, 400 and 800 the
    /// release's own error at every instant is 1.0e-3, too coarse to judge 1e-2).
    pub fn quick() -> Self {
        Self {
            scenes: vec![
                Scene::Release { angle_deg: 30.0 },
                Scene::Mode {
                    number: 1,
                    amplitude: 0.05,
                },
            ],
            tolerances: vec![1e-2],
            duration: 3.0,
            reference_segments: 800,
            reference_segments_max: 800,
            reference_segments_reach: 800,
            grid: vec![16, 25, 32, 50, 64, 100],
            grid_beyond: Vec::new(),
        }
    }
}

/// The steps the grid runs `method` at with N = `segments`: its default step, and its
/// tolerance step where that is another (what `--tolerance` would run it at).
pub fn grid_steps(method: MethodKind, segments: usize) -> Vec<f64> {
    let d = method.descriptor();
    let (default, tolerance) = (d.default_dt(segments), d.tolerance_dt(segments));
    if tolerance == default {
        vec![default]
    } else {
        vec![default, tolerance]
    }
}

/// One run measured against the reference.
#[derive(Clone, Copy, Debug)]
pub struct Measured {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    /// The largest distance of the tip from the reference's at every instant, whatever the
    /// frames: at every row of a references file (1/[`JUDGE_RATE`] of a time unit), or at
    /// every step of the run against a computed reference ([`measure`]).
    pub worst: f64,
    /// For a run with its shadow: the largest bound its live tip estimate makes (its
    /// [`TipBound`]), at
    /// every step the two share (what the run's verdict reads).
    pub estimate: Option<f64>,
    /// Wall seconds of one thread (the fastest of a few timings, for a run of milliseconds:
    /// [`fastest`]).
    pub seconds: f64,
}

/// What `--tolerance EPS` did in one scene, and the grid's cheapest run that holds EPS.
#[derive(Clone, Debug)]
pub struct Cell {
    pub scene: Scene,
    pub tolerance: f64,
    /// Why EPS was not checked (the reference not fine enough, or the rule refused it).
    pub skipped: Option<String>,
    /// The chosen run, measured; its `seconds` are the run's with its shadow.
    pub chosen: Option<Measured>,
    /// Seconds the choice took: the pilots, and the rule (timed as runs are, [`fastest`]; where
    /// it, the chosen run and the grid's cheapest each take milliseconds, the three timed again
    /// side by side, [`fastest_side_by_side`]).
    pub pilot_seconds: f64,
    /// What the choice rests on: a pilot that held, the pilots' model or the committed one.
    pub basis: Option<pilot::Basis>,
    /// The grid's cheapest run that holds EPS (its seconds timed again beside the choice's
    /// where all are of milliseconds: [`Cell::pilot_seconds`]).
    pub cheapest: Option<Measured>,
}

impl Cell {
    /// Whether the chosen run held EPS at every instant.
    pub fn held(&self) -> Option<bool> {
        self.chosen.map(|c| c.worst <= self.tolerance)
    }

    /// What the chosen run's live estimate said of EPS against the truth, both at every
    /// instant.
    pub fn verdict(&self) -> Option<EstimateVerdict> {
        let chosen = self.chosen?;
        let said = chosen.estimate? > self.tolerance;
        let (eps, truth) = (self.tolerance, chosen.worst);
        Some(match (truth > eps, said) {
            (true, true) => EstimateVerdict::MissSaid,
            (true, false) => EstimateVerdict::MissSilent,
            (false, true) if truth > eps / 2.0 => EstimateVerdict::FalseAlarmNear,
            (false, true) => EstimateVerdict::FalseAlarm,
            (false, false) => EstimateVerdict::HeldSaid,
        })
    }

    /// The chosen run's CPU, pilots included, over the grid's cheapest.
    pub fn cpu_ratio(&self) -> Option<f64> {
        let (chosen, cheapest) = (self.chosen?, self.cheapest?);
        Some((chosen.seconds + self.pilot_seconds) / cheapest.seconds)
    }
}

/// What a run's verdict (its exit status: 4 where its live estimate passed EPS) said, against
/// the truth at every instant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EstimateVerdict {
    /// EPS held, and the run said so.
    HeldSaid,
    /// EPS missed, and the run said so.
    MissSaid,
    /// EPS missed, and the run said it held: a verdict that lied.
    MissSilent,
    /// EPS held, the run said it did not, and the truth was above EPS/2: allowed.
    FalseAlarmNear,
    /// EPS held within EPS/2, and the run said it did not: a verdict that lied.
    FalseAlarm,
}

impl EstimateVerdict {
    /// A few words for the table.
    pub fn label(self) -> &'static str {
        match self {
            Self::HeldSaid => "held, said",
            Self::MissSaid => "missed, said",
            Self::MissSilent => "**missed, silent**",
            Self::FalseAlarmNear => "false alarm above EPS/2",
            Self::FalseAlarm => "**false alarm**",
        }
    }
}

/// Runs `method` at N = `segments` and step `dt` from `scene`, its shadow with it bounding the
/// tip's error as `shadow` says if there is one, and measures it against `reference` at every
/// instant: at every one of its own steps, or, against a reference known only at its rows
/// ([`ConvergedTip::rows_only`], every 1/[`JUDGE_RATE`]), at every row, the run kept at
/// [`judging_step`] (a cubic through the run's own steps misses a whip's tip by up to 2.9e-4 from
/// 20°, the graded rods at N = 370, more than the tolerances it would judge). `None` if it could
/// not start or diverged. Its seconds are those of the run `rope run` makes, frames at
/// [`LOG_RATE`]; its tip is kept in a second run, untimed.
pub fn measure(
    method: MethodKind,
    scene: &Scene,
    segments: usize,
    dt: f64,
    duration: f64,
    shadow: Option<TipBound>,
    reference: &impl ConvergedTip,
) -> Option<Measured> {
    let run_at = (method, segments, dt);
    let (seconds, run) = fastest(|| timed_run(scene, run_at, duration, shadow));
    let (stopped, estimate) = run?;
    if stopped {
        return None;
    }
    // At every row of a reference known only there, the run kept at a step on them; else at
    // every one of the run's own steps.
    let (step, times) = match reference.rows_only() {
        true => (judging_step(dt), frame_times(duration, JUDGE_RATE)),
        false => (dt, frame_times(duration, 1.0 / dt)),
    };
    let kept = Trajectory::keep(scene, method, segments, step, duration).ok()?;
    let worst = times
        .into_iter()
        .map(|t| (kept.trajectory.at(t) - reference.tip_at(t)).norm())
        .fold(0.0, f64::max);
    Some(Measured {
        method,
        segments,
        dt,
        worst,
        estimate,
        seconds,
    })
}

/// Where a choice's planning (`request`), its run (its shadow bounding as `shadow` says; none
/// where it was `rehearsed`, flown as the pilot that held) and the grid's cheapest run each
/// took under [`RETIMED_BELOW`], times the three again side by side
/// ([`fastest_side_by_side`]) and keeps those timings: a ratio of milliseconds read from
/// timings made minutes apart moves with the machine.
fn retime_side_by_side(
    cell: &mut Cell,
    request: &RunRequest,
    shadow: Option<TipBound>,
    rehearsed: bool,
    duration: f64,
) {
    let (Some(chosen), Some(cheapest)) = (cell.chosen, cell.cheapest) else {
        return;
    };
    let parts = [cell.pilot_seconds, chosen.seconds, cheapest.seconds];
    if parts.iter().any(|&seconds| seconds >= RETIMED_BELOW) {
        return;
    }
    let scene = cell.scene;
    let run =
        |m: Measured, shadow| timed_run(&scene, (m.method, m.segments, m.dt), duration, shadow);
    let mut plan = || {
        std::hint::black_box(runs::plan_scene(request, scene, |_| {}).is_ok());
    };
    let mut chosen_run = || {
        if !rehearsed {
            std::hint::black_box(run(chosen, shadow));
        }
    };
    let mut cheapest_run = || {
        std::hint::black_box(run(cheapest, None));
    };
    let [planning, chosen_seconds, cheapest_seconds] =
        fastest_side_by_side([&mut plan, &mut chosen_run, &mut cheapest_run]);
    cell.pilot_seconds = planning;
    if let (Some(measured), false) = (cell.chosen.as_mut(), rehearsed) {
        measured.seconds = chosen_seconds;
    }
    if let Some(measured) = cell.cheapest.as_mut() {
        measured.seconds = cheapest_seconds;
    }
}

/// What `rope run --tolerance EPS --duration D --log-rate LOG_RATE` asks of a scene, within
/// any memory.
fn request(eps: f64, duration: f64) -> RunRequest {
    RunRequest {
        method: MethodKind::Chain, // the choice's, with a tolerance
        others: Vec::new(),
        segments: 100,
        dt: None,
        duration,
        log_rate: LOG_RATE,
        log_rate_asked: true,
        realtime: None,
        allow_unstable: false,
        limits: Limits {
            max_memory: Some(u64::MAX),
            yes: true,
        },
        error_estimate: true,
        tolerance: Some(eps),
    }
}

/// The step a run of step `dt` is judged at: the largest at most `dt` that puts a step on
/// every 1/[`JUDGE_RATE`], where the reference has its rows, so that the run's tip is read at
/// its own steps and nowhere between. The same method at N with a step at most `dt` differs
/// from the run at `dt` by its error in k alone, which `--tolerance`'s steps keep far below
/// its error in h to t = 3: against the run at k/6, within 6.0e-6 from 20° to 80° (the
/// second table of `cargo run --release --example tolerance_instants`). Not always past it:
/// from 45° to t = 5 the graded rods at N = 400 differ by 5.1e-4, so a reference that can be
/// read at any instant (computed, not read) judges a run at its own steps instead.
pub fn judging_step(dt: f64) -> f64 {
    whole_division(1.0 / JUDGE_RATE, dt)
}

/// The method the check's reference of `scene` to `duration` is made of: a scene's own method
/// where it has one (a fold's or a shake's, [`MethodKind::scene_default`]: the one the rule
/// chooses there), else the graded rods where the rule may choose them (a release from 20°
/// up: their tip converges faster through the whip, and their end rods do not spin on), else
/// [`MethodKind::REFERENCE`].
pub fn reference_method(scene: &Scene, duration: f64) -> MethodKind {
    if let Some((method, _)) = MethodKind::scene_default(scene.name()) {
        return method;
    }
    match (MethodKind::Graded.descriptor().plannable)(scene, duration) {
        true => MethodKind::Graded,
        false => MethodKind::REFERENCE,
    }
}

/// The whole check's outcome.
#[derive(Clone, Debug)]
pub struct Checked {
    /// A cell per scene and tolerance.
    pub cells: Vec<Cell>,
    /// Each scene's reference, as [`CheckSpec::scenes`] lists them.
    pub references: Vec<CheckReference>,
}

impl CheckSpec {
    /// The smallest EPS the check asks.
    pub fn smallest_tolerance(&self) -> f64 {
        self.tolerances
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
    }
}

/// Of the references in `read` of `scene`, the one whose own error (at every row) is least:
/// the check takes it instead of computing one, whatever its own error. A file given holds the
/// finest reference its maker could afford (the committed graded ones come from runs up to
/// N = 12 800, past the check's own 6 400, and from 70° and 80° they still err by 2.1e-5 and
/// 1.5e-5 at every 1/3 000; from 50° and 60°, from runs to 25 600, by 4.5e-6 and 8.4e-6):
/// computing one again would cost up to 20 minutes a scene to reach no finer. A tolerance it
/// cannot judge is skipped, and the table says why.
pub fn best_read<'a>(read: &'a [ReadReference], scene: &Scene) -> Option<&'a ReadReference> {
    read.iter()
        .filter(|r| r.scene == *scene)
        .min_by(|a, b| a.own_error.total_cmp(&b.own_error))
}

/// The whole check: a reference per scene (read from `read` where it has one, [`best_read`], else
/// computed, the scenes' in parallel), then each scene's grid and each tolerance's choice one run
/// at a time, so that their wall seconds are one thread's. `progress` counts each reference and
/// each run, and may stop the check before the next ([`Stopped`]).
pub fn check(
    spec: &CheckSpec,
    read: &[ReadReference],
    progress: &impl Progress,
) -> anyhow::Result<Checked> {
    let mut cells = Vec::new();
    let smallest = spec.smallest_tolerance();
    // The references first, the scenes' in parallel: no CPU is measured while they run.
    let references = spec
        .scenes
        .par_iter()
        .map(|scene| {
            if let Some(read) = best_read(read, scene) {
                progress.done();
                return Ok(CheckReference::Read(read.clone()));
            }
            progress.check()?;
            let target = REFERENCE_MARGIN * smallest;
            let reference = TipReference::refined_by(
                reference_method(scene, spec.duration),
                scene,
                spec.reference_segments,
                spec.reference_segments_max,
                target,
                spec.duration,
                progress,
            )?
            .refined_where_reachable(
                target,
                spec.reference_segments_reach,
                progress,
            )?;
            progress.done();
            Ok(CheckReference::Computed(reference))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    for reference in &references {
        let scene = &reference.scene();
        // `method`'s runs at N = `n`, one at each of its grid steps (those that finished).
        let runs_at = |method: MethodKind, n: usize| -> Result<Vec<Measured>, Stopped> {
            grid_steps(method, n)
                .into_iter()
                .map(|dt| {
                    progress.check()?;
                    let run = measure(method, scene, n, dt, spec.duration, None, reference);
                    progress.done();
                    Ok(run)
                })
                .filter_map(Result::transpose)
                .collect()
        };
        // Each method up the grid until a run holds the smallest EPS and none at that N costs
        // less than the cheapest that holds: a finer run costs more than every run at a
        // coarser N, but at its default step it may cost less than a coarser one at its
        // (finer) tolerance step.
        let mut grid: Vec<Measured> = Vec::new();
        for method in choice::startable(scene, spec.duration) {
            let mut cheapest_holding = f64::INFINITY;
            for &n in &spec.grid {
                let runs = runs_at(method, n)?;
                let seconds = |held: bool| {
                    runs.iter()
                        .filter(|r| !held || r.worst <= smallest)
                        .map(|r| r.seconds)
                        .fold(f64::INFINITY, f64::min)
                };
                cheapest_holding = cheapest_holding.min(seconds(true));
                let cheapest_here = seconds(false);
                grid.extend(runs);
                if cheapest_holding.is_finite() && cheapest_here >= cheapest_holding {
                    break;
                }
            }
        }
        // The smallest EPS the reference can judge; where no run holds it, on past the grid.
        let judged = spec
            .tolerances
            .iter()
            .copied()
            .filter(|&eps| reference.own_error() <= REFERENCE_MARGIN * eps)
            .fold(f64::INFINITY, f64::min);
        for &n in &spec.grid_beyond {
            if grid.iter().any(|r| r.worst <= judged) {
                break;
            }
            for method in choice::startable(scene, spec.duration) {
                grid.extend(runs_at(method, n)?);
            }
        }
        for &eps in &spec.tolerances {
            let mut cell = Cell {
                scene: *scene,
                tolerance: eps,
                skipped: None,
                chosen: None,
                pilot_seconds: 0.0,
                basis: None,
                cheapest: grid
                    .iter()
                    .filter(|r| r.worst <= eps)
                    .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
                    .copied(),
            };
            if reference.own_error() > REFERENCE_MARGIN * eps {
                cell.skipped = Some(format!(
                    "the reference's own error {:.1e} is above {REFERENCE_MARGIN} × EPS",
                    reference.own_error()
                ));
                cells.push(cell);
                continue;
            }
            progress.check()?;
            // Planned as `rope run --tolerance EPS` plans it, frames at [`LOG_RATE`]: its
            // pilots may fly as the run, and the one that holds is then not flown again.
            let request = request(eps, spec.duration);
            let (seconds, planned) = fastest(|| runs::plan_scene(&request, *scene, |_| {}));
            match planned.map(|p| (p.choice.zip(p.pilots), p.rehearsal.is_some())) {
                Ok((Some((choice, flown)), rehearsed)) => {
                    cell.pilot_seconds = seconds;
                    cell.basis = Some(flown.basis);
                    let (m, n, dt) = (choice.method, choice.segments, choice.dt);
                    let bound = Some(choice.tip_bound);
                    cell.chosen = measure(m, scene, n, dt, spec.duration, bound, reference);
                    if let (Some(chosen), true) = (&mut cell.chosen, rehearsed) {
                        // The run was the pilot that held: its CPU is in the pilots'.
                        chosen.seconds = 0.0;
                    }
                    retime_side_by_side(&mut cell, &request, bound, rehearsed, spec.duration);
                }
                // (A request with a tolerance is always planned by it.)
                Ok((None, _)) => cell.skipped = Some("no choice was made".to_owned()),
                Err(err) => cell.skipped = Some(err.to_string()),
            }
            progress.done();
            cells.push(cell);
        }
    }
    Ok(Checked { cells, references })
}
