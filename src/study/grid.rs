//! The study's grid: methods × segments × time steps, each cell one run measured for
//! stability, energy deviation and CPU cost (errors against the reference come later).
//! The grid runs in parallel (rayon); each run's cost is its own thread's CPU time.

use super::progress::{Progress, Stopped};
use crate::methods::{MethodKind, Observation};
use crate::model::Scene;
use crate::model::geometry::{self, Point};
use crate::plan::error_model::ErrorModel;
use crate::run::simulate;
use rayon::prelude::*;
use std::ops::ControlFlow;

/// Points along the string (s = 0, 0.1, …, 1) where shapes are compared.
pub const SHAPE_POINTS: usize = 11;

/// Frames per time unit at which a run's tip is measured against the reference, as
/// `rope run` logs them by default: the tip error is the largest over these frames, as
/// `--tolerance` and the live estimate mean it.
pub const FRAMES_PER_UNIT: f64 = 30.0;

/// What to run.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Spec {
    pub scene: Scene,
    pub duration: f64,
    pub methods: Vec<MethodKind>,
    pub segments: Vec<usize>,
    pub dts: Vec<f64>,
}

impl Spec {
    /// The time step actually run for a nominal `dt`: the largest no larger than `dt` that
    /// divides the duration into whole steps, so that every run ends exactly at the final
    /// time and none runs at a coarser step than asked. A `dt` that already divides it (to
    /// round-off) is kept as given, so that charts and tables print the step the user typed
    /// (1e-4, not 9.999999999999999e-5); the run takes the same whole number of steps
    /// either way. [`Spec::moved_dts`] lists the others, for the study to say so.
    pub fn snap(&self, dt: f64) -> f64 {
        let steps = (self.duration / dt * (1.0 - 1e-12)).ceil().max(1.0);
        let snapped = self.duration / steps;
        if (snapped - dt).abs() <= 8.0 * f64::EPSILON * dt {
            dt
        } else {
            snapped
        }
    }

    /// Each nominal step that runs at another ([`Spec::snap`]), with the step it runs at.
    pub fn moved_dts(&self) -> Vec<(f64, f64)> {
        self.dts
            .iter()
            .map(|&dt| (dt, self.snap(dt)))
            .filter(|(dt, run)| dt != run)
            .collect()
    }

    /// The grid's runs in a fixed order, the same on every machine: methods as listed, then
    /// N, then k, as given (shards are cut from it; [`run_cells`] reorders for speed).
    pub fn cells(&self) -> Vec<(MethodKind, usize, f64)> {
        self.methods
            .iter()
            .flat_map(|&m| {
                self.segments
                    .iter()
                    .flat_map(move |&n| self.dts.iter().map(move |&dt| (m, n, self.snap(dt))))
            })
            .collect()
    }
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    Ok,
    /// Blew up at `time`, for `reason`.
    Diverged {
        time: f64,
        reason: String,
    },
    /// The method cannot start from this state (e.g. the seed scheme at the horizontal).
    Refused {
        reason: String,
    },
}

impl Status {
    /// The CSV word for it.
    pub fn word(&self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::Diverged { .. } => "diverged",
            Self::Refused { .. } => "refused",
        }
    }

    /// Its colour on the stability map, in charts and in the recording alike.
    pub fn rgb(&self) -> [u8; 3] {
        match self {
            Self::Ok => [30, 150, 60],
            Self::Diverged { .. } => [210, 40, 40],
            Self::Refused { .. } => [120, 120, 120],
        }
    }
}

/// One run's measurements.
#[derive(Clone, Debug)]
pub struct Row {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    pub status: Status,
    /// max |E − E(step 10)| / |E|, the report's criterion.
    pub energy_deviation: Option<f64>,
    /// The largest distance of the tip from the reference's over the frames
    /// ([`FRAMES_PER_UNIT`] a time unit, each at the step nearest its time).
    pub tip_error: Option<f64>,
    /// The tip's distance from the reference's at the final time alone (errors that cancel
    /// by chance at that instant show here as accuracy; [`Row::tip_error`] does not).
    pub final_tip_error: Option<f64>,
    /// RMS distance of the shape (s = 0, 0.1, …, 1) from the reference's.
    pub shape_error: Option<f64>,
    pub cpu_seconds: f64,
    pub ns_per_segment_step: f64,
    /// Final tip and shape (for the reference and for charts).
    pub tip: Option<Point>,
    pub shape: Option<Vec<Point>>,
    /// The tip at each frame, with the frame's time (to measure [`Row::tip_error`]; not
    /// kept in `study.csv`).
    pub frame_tips: Vec<(f64, Point)>,
}

/// Positions at s = 0, 0.1, …, 1 along the string with segment angles `angles`.
pub fn shape(angles: &[f64]) -> Vec<Point> {
    shape_of(angles, None)
}

/// As [`shape`], for rods of `lengths` where they are given ([`Method::lengths`](crate::methods::Method::lengths)).
pub fn shape_of(angles: &[f64], lengths: Option<&[f64]>) -> Vec<Point> {
    let mut nodes = Vec::with_capacity(angles.len() + 1);
    geometry::nodes_of(angles, lengths, &mut nodes);
    let edges = lengths.map(|l| {
        let mut edges = Vec::with_capacity(l.len() + 1);
        geometry::edges(l.len(), Some(l), &mut edges);
        edges
    });
    let mut along = geometry::Along::new(&nodes, edges.as_deref());
    (0..SHAPE_POINTS)
        .map(|j| along.at(j as f64 / (SHAPE_POINTS - 1) as f64))
        .collect()
}

/// Runs one cell of the grid and measures it (errors are filled in later, against the
/// reference).
pub fn run_cell(scene: &Scene, duration: f64, method: MethodKind, segments: usize, dt: f64) -> Row {
    let mut row = Row {
        method,
        segments,
        dt,
        status: Status::Ok,
        energy_deviation: None,
        tip_error: None,
        final_tip_error: None,
        shape_error: None,
        cpu_seconds: 0.0,
        ns_per_segment_step: 0.0,
        tip: None,
        shape: None,
        frame_tips: Vec::new(),
    };
    let mut solver = match method.build(scene, segments, dt) {
        Ok(solver) => solver,
        Err(err) => {
            row.status = Status::Refused {
                reason: err.to_string(),
            };
            return row;
        }
    };
    let started = cpu_time::ThreadTime::now();
    let mut frame_tips = Vec::with_capacity((duration * FRAMES_PER_UNIT) as usize + 2);
    let options = simulate::Options {
        duration,
        log_rate: FRAMES_PER_UNIT,
        frame_grid: None,
    };
    let outcome = simulate::run(solver.as_mut(), &options, None, |frame| {
        frame_tips.push((frame.time, frame.tip()));
        ControlFlow::Continue(())
    });
    row.cpu_seconds = started.elapsed().as_secs_f64();
    row.ns_per_segment_step =
        row.cpu_seconds * 1e9 / (outcome.steps.max(1) as f64 * segments as f64);
    if let Some(d) = outcome.diverged {
        row.status = Status::Diverged {
            time: d.time,
            reason: d.reason,
        };
        return row;
    }
    row.energy_deviation = Some(outcome.max_rel_deviation());
    let mut obs = Observation::default();
    solver.observe(&mut obs);
    row.tip = Some(outcome.tip);
    row.shape = Some(shape_of(&obs.angle, solver.lengths()));
    row.frame_tips = frame_tips;
    row
}

/// Runs every cell in parallel; `progress` counts each, and may stop the grid before its
/// next run ([`Stopped`]).
pub fn run_grid(spec: &Spec, progress: &impl Progress) -> Result<Vec<Row>, Stopped> {
    run_cells(spec, spec.cells(), progress)
}

/// Runs `cells` of `spec`'s grid in parallel, the most expensive first (so the parallel tail
/// is short); `progress` counts each, and may stop the grid before its next run. The rows
/// come sorted by method, N and k.
pub fn run_cells(
    spec: &Spec,
    mut cells: Vec<(MethodKind, usize, f64)>,
    progress: &impl Progress,
) -> Result<Vec<Row>, Stopped> {
    let cost =
        |&(m, n, dt): &(MethodKind, usize, f64)| m.descriptor().ns_per_segment_step * n as f64 / dt;
    cells.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
    let mut rows = cells
        .into_par_iter()
        .with_max_len(1) // one run per task, so that stealing balances runs of unequal cost
        .map(|(m, n, dt)| {
            progress.check()?;
            let row = run_cell(&spec.scene, spec.duration, m, n, dt);
            progress.done();
            Ok(row)
        })
        .collect::<Result<Vec<Row>, Stopped>>()?;
    sort_rows(&mut rows);
    Ok(rows)
}

/// The rows' order in `study.csv`: by method name, N, then k.
pub fn sort_rows(rows: &mut [Row]) {
    rows.sort_by(|a, b| {
        (a.method.name(), a.segments)
            .cmp(&(b.method.name(), b.segments))
            .then(a.dt.total_cmp(&b.dt))
    });
}

/// Fits C h^p to the tip errors of the `ok` runs of `method` with N ≥ `min_segments`, taking
/// at each N the run with the smallest time step (so that the error is the spatial one).
pub fn fit(rows: &[Row], method: MethodKind, min_segments: usize) -> Option<ErrorModel> {
    let mut segments: Vec<usize> = rows
        .iter()
        .filter(|r| r.method == method && r.segments >= min_segments)
        .map(|r| r.segments)
        .collect();
    segments.sort_unstable();
    segments.dedup();
    ErrorModel::fit(segments.into_iter().filter_map(|n| {
        rows.iter()
            .filter(|r| r.method == method && r.segments == n && r.status == Status::Ok)
            .filter_map(|r| r.tip_error.map(|e| (r.dt, e)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, e)| (n, e))
    }))
}
