//! `rope study`: a grid of runs over methods × segments × time steps, each measured for
//! stability, energy deviation, solution error against a converged reference, and CPU cost.
//!
//! The grid runs in parallel (rayon); each run's cost is its own thread's CPU time.

pub mod charts;
pub mod findings;
pub mod model;
pub mod record;

use crate::chain::Chain;
use crate::geometry::{self, Point};
use crate::method::{MethodKind, Observation};
use crate::scene::Scene;
use crate::simulate::{self, Options};
use rayon::prelude::*;
use std::io::Write as _;
use std::ops::ControlFlow;
use std::path::Path;

/// Points along the string (s = 0, 0.1, …, 1) where shapes are compared.
pub const SHAPE_POINTS: usize = 11;

/// What to run.
#[derive(Clone, Debug)]
pub struct Spec {
    pub scene: Scene,
    pub duration: f64,
    pub methods: Vec<MethodKind>,
    pub segments: Vec<usize>,
    pub dts: Vec<f64>,
}

impl Spec {
    /// The time step actually run for a nominal `dt`: the nearest that divides the duration
    /// into whole steps, so that every run ends exactly at the final time.
    pub fn snap(&self, dt: f64) -> f64 {
        self.duration / (self.duration / dt).round().max(1.0)
    }

    /// The grid's runs, the most expensive first (so the parallel tail is short).
    pub fn cells(&self) -> Vec<(MethodKind, usize, f64)> {
        let mut cells: Vec<_> = self
            .methods
            .iter()
            .flat_map(|&m| {
                self.segments
                    .iter()
                    .flat_map(move |&n| self.dts.iter().map(move |&dt| (m, n, self.snap(dt))))
            })
            .collect();
        let cost = |&(m, n, dt): &(MethodKind, usize, f64)| {
            let per_step = if m == MethodKind::Chain { 4.0 } else { 1.0 };
            per_step * n as f64 / dt
        };
        cells.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
        cells
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
    /// Tip position at the final time against the reference.
    pub tip_error: Option<f64>,
    /// RMS distance of the shape (s = 0, 0.1, …, 1) from the reference's.
    pub shape_error: Option<f64>,
    pub cpu_seconds: f64,
    pub ns_per_segment_step: f64,
    /// Final tip and shape (for the reference and for charts).
    pub tip: Option<Point>,
    pub shape: Option<Vec<Point>>,
}

/// Positions at s = 0, 0.1, …, 1 along the string with segment angles `angles`.
pub fn shape(angles: &[f64]) -> Vec<Point> {
    let mut nodes = Vec::with_capacity(angles.len() + 1);
    geometry::nodes(angles, &mut nodes);
    let n = angles.len();
    (0..SHAPE_POINTS)
        .map(|j| {
            let s = j as f64 / (SHAPE_POINTS - 1) as f64 * n as f64;
            let i = (s.floor() as usize).min(n - 1);
            let frac = s - i as f64;
            nodes[i] + frac * (nodes[i + 1] - nodes[i])
        })
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
        shape_error: None,
        cpu_seconds: 0.0,
        ns_per_segment_step: 0.0,
        tip: None,
        shape: None,
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
    let outcome = simulate::run(
        solver.as_mut(),
        &Options {
            duration,
            log_rate: 0.0,
        },
        None,
        |_| ControlFlow::Continue(()),
    );
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
    row.shape = Some(shape(&obs.angle));
    row
}

/// A converged solution the study trusts, and how far it can be trusted.
#[derive(Clone, Debug)]
pub struct Reference {
    pub tip: Point,
    pub shape: Vec<Point>,
    /// |Richardson correction| in N: the error left by the finest N, estimated.
    pub error_in_h: f64,
    /// Change of the finest run when its time step is halved.
    pub error_in_k: f64,
    pub description: String,
}

impl Reference {
    /// The larger of the two estimates: errors below it are not resolved.
    pub fn error_estimate(&self) -> f64 {
        self.error_in_h.max(self.error_in_k)
    }
}

/// The reference: the chain (second order in h, fourth in k) at `finest` and `finest / 2`
/// segments, extrapolated in N by Richardson (x + (x − x_half) / 3), with the time step
/// checked by halving it at the finest N.
pub fn reference(scene: &Scene, duration: f64, finest: usize) -> anyhow::Result<Reference> {
    let run = |n: usize, dt: f64| -> anyhow::Result<(Point, Vec<Point>)> {
        let row = run_cell(scene, duration, MethodKind::Chain, n, dt);
        match (row.status, row.tip, row.shape) {
            (Status::Ok, Some(tip), Some(shape)) => Ok((tip, shape)),
            (status, ..) => {
                anyhow::bail!("the reference run at N = {n}, k = {dt:e} failed: {status:?}")
            }
        }
    };
    let coarse_n = finest / 2;
    let dt = Chain::default_dt(finest);
    let runs: Vec<_> = [
        (finest, dt),
        (coarse_n, Chain::default_dt(coarse_n)),
        (finest, dt / 2.0),
    ]
    .into_par_iter()
    .map(|(n, dt)| run(n, dt))
    .collect::<anyhow::Result<_>>()?;
    let [(tip_f, shape_f), (tip_c, shape_c), (tip_k, _)]: [(Point, Vec<Point>); 3] = runs
        .try_into()
        .map_err(|_| anyhow::anyhow!("three reference runs expected"))?;
    let extrapolate = |f: Point, c: Point| f + (f - c) / 3.0;
    let tip = extrapolate(tip_f, tip_c);
    let shape: Vec<Point> = shape_f
        .iter()
        .zip(&shape_c)
        .map(|(&f, &c)| extrapolate(f, c))
        .collect();
    Ok(Reference {
        tip,
        shape,
        error_in_h: (tip - tip_f).norm(),
        error_in_k: (tip_k - tip_f).norm(),
        description: format!(
            "chain method, Richardson extrapolation (order 2) from N = {coarse_n} and {finest}, k = {dt:e}"
        ),
    })
}

/// Fills in each row's errors against the reference.
pub fn measure_errors(rows: &mut [Row], reference: &Reference) {
    for row in rows {
        if let (Some(tip), Some(shape)) = (row.tip, &row.shape) {
            row.tip_error = Some((tip - reference.tip).norm());
            let sum: f64 = shape
                .iter()
                .zip(&reference.shape)
                .map(|(a, b)| (a - b).norm_squared())
                .sum();
            row.shape_error = Some((sum / SHAPE_POINTS as f64).sqrt());
        }
    }
}

/// Runs every cell in parallel; `progress` is called after each.
pub fn run_grid(spec: &Spec, progress: impl Fn() + Sync) -> Vec<Row> {
    let mut rows: Vec<Row> = spec
        .cells()
        .into_par_iter()
        .with_max_len(1) // one run per task, so that stealing balances runs of unequal cost
        .map(|(m, n, dt)| {
            let row = run_cell(&spec.scene, spec.duration, m, n, dt);
            progress();
            row
        })
        .collect();
    rows.sort_by(|a, b| {
        (a.method.name(), a.segments)
            .cmp(&(b.method.name(), b.segments))
            .then(a.dt.total_cmp(&b.dt))
    });
    rows
}

/// Writes `study.csv`: one row per run.
pub fn write_csv(rows: &[Row], path: &Path) -> std::io::Result<()> {
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        out,
        "method,segments,dt,status,energy_deviation,tip_error,shape_error,cpu_seconds,ns_per_segment_step,diverged_time,reason"
    )?;
    let opt = |v: Option<f64>| v.map(|x| format!("{x:.6e}")).unwrap_or_default();
    for r in rows {
        let (time, reason) = match &r.status {
            Status::Ok => (String::new(), String::new()),
            Status::Diverged { time, reason } => (format!("{time:.6}"), reason.clone()),
            Status::Refused { reason } => (String::new(), reason.clone()),
        };
        // CSV quoting: the reason is free text.
        let reason = format!("\"{}\"", reason.replace('"', "\"\""));
        writeln!(
            out,
            "{},{},{:e},{},{},{},{},{:.6e},{:.3},{time},{reason}",
            r.method,
            r.segments,
            r.dt,
            r.status.word(),
            opt(r.energy_deviation),
            opt(r.tip_error),
            opt(r.shape_error),
            r.cpu_seconds,
            r.ns_per_segment_step
        )?;
    }
    out.flush()
}

/// Kinetic energy at every step of the first `steps` steps (the report's Fig. 1: the burst
/// with which the seed scheme repairs the initial state's violation of eq. (9)).
pub fn startup_burst(
    scene: &Scene,
    method: MethodKind,
    segments: usize,
    dt: f64,
    steps: u64,
) -> Option<Vec<(f64, f64)>> {
    let mut solver = method.build(scene, segments, dt).ok()?;
    let mut series = Vec::new();
    simulate::run(
        solver.as_mut(),
        &Options {
            duration: steps as f64 * dt,
            log_rate: 1.0 / dt,
        },
        None,
        |f| {
            series.push((f.time, f.energy.kinetic()));
            ControlFlow::Continue(())
        },
    );
    Some(series)
}

/// What a whole study produced.
pub struct Outcome {
    pub rows: Vec<Row>,
    pub reference: Reference,
    pub findings: findings::Findings,
    /// The findings as written to `findings.md`.
    pub markdown: String,
    pub startup: Vec<(MethodKind, Vec<(f64, f64)>)>,
}

/// Runs the reference and the grid, measures every run against the reference, and writes
/// `study.csv`, `findings.md` and the charts into `out`. `command` is the command line to
/// cite in the findings.
pub fn execute(
    spec: &Spec,
    reference_segments: usize,
    out: &Path,
    command: &str,
    progress: impl Fn() + Sync,
) -> anyhow::Result<Outcome> {
    use anyhow::Context as _;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let reference = reference(&spec.scene, spec.duration, reference_segments)?;
    let mut rows = run_grid(spec, progress);
    measure_errors(&mut rows, &reference);
    let csv = out.join("study.csv");
    write_csv(&rows, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let findings = findings::Findings::from_rows(&rows);
    let markdown = findings.markdown(&reference, command);
    let md = out.join("findings.md");
    std::fs::write(&md, &markdown).with_context(|| format!("writing {}", md.display()))?;
    let startup: Vec<_> = spec
        .methods
        .iter()
        .filter_map(|&m| Some((m, startup_burst(&spec.scene, m, 100, 1e-5, 300)?)))
        .collect();
    charts::register_font()?;
    charts::write_all(
        out,
        &rows,
        &startup,
        &scene_title(&spec.scene, spec.duration),
    )?;
    Ok(Outcome {
        rows,
        reference,
        findings,
        markdown,
        startup,
    })
}

/// The scene in words, for chart titles.
pub fn scene_title(scene: &Scene, duration: f64) -> String {
    match scene {
        Scene::Release { angle_deg } => format!("release at {angle_deg}°, t = {duration}"),
        Scene::Mode { number, .. } => format!("mode {number}, t = {duration}"),
    }
}
