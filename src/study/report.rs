//! The study's files: `study.csv` (one row per run) and the start-up burst of the report's
//! Fig. 1.

use super::grid::{Row, Status};
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::simulate::{self, Options};
use std::ops::ControlFlow;
use std::path::Path;

/// One line of `study.csv`; the header is the field names.
#[derive(serde::Serialize)]
struct CsvRow {
    method: MethodKind,
    segments: usize,
    dt: String,
    status: &'static str,
    energy_deviation: String,
    tip_error: String,
    shape_error: String,
    cpu_seconds: String,
    ns_per_segment_step: String,
    diverged_time: String,
    reason: String,
}

impl CsvRow {
    fn new(r: &Row) -> Self {
        let opt = |v: Option<f64>| v.map(|x| format!("{x:.6e}")).unwrap_or_default();
        let (diverged_time, reason) = match &r.status {
            Status::Ok => (String::new(), String::new()),
            Status::Diverged { time, reason } => (format!("{time:.6}"), reason.clone()),
            Status::Refused { reason } => (String::new(), reason.clone()),
        };
        Self {
            method: r.method,
            segments: r.segments,
            dt: format!("{:e}", r.dt),
            status: r.status.word(),
            energy_deviation: opt(r.energy_deviation),
            tip_error: opt(r.tip_error),
            shape_error: opt(r.shape_error),
            cpu_seconds: format!("{:.6e}", r.cpu_seconds),
            ns_per_segment_step: format!("{:.3}", r.ns_per_segment_step),
            diverged_time,
            reason,
        }
    }
}

/// Writes `study.csv`: one row per run.
pub fn write_csv(rows: &[Row], path: &Path) -> csv::Result<()> {
    let mut out = csv::Writer::from_path(path)?;
    for row in rows {
        out.serialize(CsvRow::new(row))?;
    }
    out.flush()?;
    Ok(())
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
