//! The study's files: `study.csv` (one row per run) and the start-up burst of the report's
//! Fig. 1.

use super::grid::{Row, Status};
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::simulate::{self, Options};
use std::ops::ControlFlow;
use std::path::Path;

/// One line of `study.csv`; the header is the field names.
#[derive(serde::Serialize, serde::Deserialize)]
struct CsvRow {
    method: MethodKind,
    segments: usize,
    dt: String,
    status: String,
    energy_deviation: String,
    tip_error: String,
    final_tip_error: String,
    shape_error: String,
    cpu_seconds: String,
    ns_per_segment_step: String,
    diverged_time: String,
    reason: String,
}

impl CsvRow {
    fn new(r: &Row) -> Self {
        // Shortest round-trip form: a merged study reads back exactly what its shards measured.
        let opt = |v: Option<f64>| v.map(|x| format!("{x:e}")).unwrap_or_default();
        let (diverged_time, reason) = match &r.status {
            Status::Ok => (String::new(), String::new()),
            Status::Diverged { time, reason } => (format!("{time:e}"), reason.clone()),
            Status::Refused { reason } => (String::new(), reason.clone()),
        };
        Self {
            method: r.method,
            segments: r.segments,
            dt: format!("{:e}", r.dt),
            status: r.status.word().to_owned(),
            energy_deviation: opt(r.energy_deviation),
            tip_error: opt(r.tip_error),
            final_tip_error: opt(r.final_tip_error),
            shape_error: opt(r.shape_error),
            cpu_seconds: format!("{:e}", r.cpu_seconds),
            ns_per_segment_step: format!("{:e}", r.ns_per_segment_step),
            diverged_time,
            reason,
        }
    }
}

impl CsvRow {
    /// The row back, as far as the file keeps it (the final tip and shape and the frames'
    /// tips are not kept: they were needed only to measure the errors, which are).
    fn row(self) -> Result<Row, String> {
        let number = |name: &str, text: &str| -> Result<Option<f64>, String> {
            if text.is_empty() {
                return Ok(None);
            }
            text.parse()
                .map(Some)
                .map_err(|_| format!("{name} = {text:?} is not a number"))
        };
        let required =
            |name: &str, text: &str| number(name, text)?.ok_or_else(|| format!("{name} is empty"));
        let status = match self.status.as_str() {
            "ok" => Status::Ok,
            "diverged" => Status::Diverged {
                time: required("diverged_time", &self.diverged_time)?,
                reason: self.reason,
            },
            "refused" => Status::Refused {
                reason: self.reason,
            },
            other => {
                return Err(format!(
                    "status = {other:?} is none of ok, diverged, refused"
                ));
            }
        };
        Ok(Row {
            method: self.method,
            segments: self.segments,
            dt: required("dt", &self.dt)?,
            status,
            energy_deviation: number("energy_deviation", &self.energy_deviation)?,
            tip_error: number("tip_error", &self.tip_error)?,
            final_tip_error: number("final_tip_error", &self.final_tip_error)?,
            shape_error: number("shape_error", &self.shape_error)?,
            cpu_seconds: required("cpu_seconds", &self.cpu_seconds)?,
            ns_per_segment_step: required("ns_per_segment_step", &self.ns_per_segment_step)?,
            tip: None,
            shape: None,
            frame_tips: Vec::new(),
        })
    }
}

/// Reads a `study.csv` back into rows.
pub fn read_csv(path: &Path) -> Result<Vec<Row>, String> {
    let mut reader = csv::Reader::from_path(path).map_err(|e| e.to_string())?;
    reader
        .deserialize::<CsvRow>()
        .enumerate()
        .map(|(i, line)| {
            line.map_err(|e| e.to_string())
                .and_then(CsvRow::row)
                .map_err(|e| format!("row {}: {e}", i + 1))
        })
        .collect()
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
            frame_grid: None,
        },
        None,
        |f| {
            series.push((f.time, f.energy.kinetic()));
            ControlFlow::Continue(())
        },
    );
    Some(series)
}
