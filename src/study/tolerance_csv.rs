//! `rope study --tolerance-check`'s cells as a table a program can read
//! (`tolerance_check.csv`): one row per scene and EPS, what `--tolerance` chose and how it
//! did at every instant, beside the grid's cheapest run that holds EPS. Empty fields where
//! the cell was skipped (its reason in `skipped`) or the grid had none.

use super::tolerance_check::{Cell, Measured};
use crate::methods::MethodKind;

/// A CSV row: one cell.
#[derive(serde::Serialize)]
struct Row<'a> {
    scene: String,
    tolerance: f64,
    method: Option<&'a str>,
    segments: Option<usize>,
    dt: Option<f64>,
    /// What the choice rests on ([`crate::plan::pilot::Basis::label`]).
    basis: Option<&'a str>,
    /// The chosen run's largest tip error at every instant.
    worst: Option<f64>,
    held: Option<bool>,
    /// The largest bound of its live estimate (at first order, or a mode's at its pilots'
    /// order), at every step it shares with its shadow: what its exit status reads.
    estimate_bound: Option<f64>,
    verdict: Option<&'a str>,
    pilot_seconds: Option<f64>,
    run_seconds: Option<f64>,
    cheapest_method: Option<&'a str>,
    cheapest_segments: Option<usize>,
    cheapest_dt: Option<f64>,
    cheapest_worst: Option<f64>,
    cheapest_seconds: Option<f64>,
    /// The choice's CPU, pilots included, over the cheapest's.
    cpu_ratio: Option<f64>,
    skipped: Option<&'a str>,
}

/// Writes one row per cell to `path`.
pub fn write(cells: &[Cell], path: &std::path::Path) -> anyhow::Result<()> {
    let mut out = csv::Writer::from_path(path)?;
    for c in cells {
        let chosen = c.chosen.as_ref();
        let cheapest = c.cheapest.as_ref();
        let name = |m: Option<&Measured>| m.map(|m| MethodKind::name(m.method));
        out.serialize(Row {
            scene: c.scene.to_string(),
            tolerance: c.tolerance,
            method: name(chosen),
            segments: chosen.map(|m| m.segments),
            dt: chosen.map(|m| m.dt),
            basis: c.basis.map(crate::plan::pilot::Basis::label),
            worst: chosen.map(|m| m.worst),
            held: c.held(),
            estimate_bound: chosen.and_then(|m| m.estimate),
            verdict: c.verdict().map(|v| v.label()),
            pilot_seconds: chosen.map(|_| c.pilot_seconds),
            run_seconds: chosen.map(|m| m.seconds),
            cheapest_method: name(cheapest),
            cheapest_segments: cheapest.map(|m| m.segments),
            cheapest_dt: cheapest.map(|m| m.dt),
            cheapest_worst: cheapest.map(|m| m.worst),
            cheapest_seconds: cheapest.map(|m| m.seconds),
            cpu_ratio: c.cpu_ratio(),
            skipped: c.skipped.as_deref(),
        })?;
    }
    out.flush()?;
    Ok(())
}
