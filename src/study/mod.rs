//! `rope study`: a grid of runs over methods × segments × time steps, each measured for
//! stability, energy deviation, solution error against a converged reference, and CPU cost;
//! then what the rows say, as findings, charts and (optionally) a Rerun recording.
//!
//! * [`grid`]: the cells, one run each, in parallel; [`reference`]: the converged solution;
//! * [`findings`]: convergence orders, stability limits, the cheapest accurate runs;
//! * [`report`]: `study.csv`; [`charts`]: SVG and PNG; [`record`]: the same into Rerun.

pub mod charts;
pub mod findings;
pub mod grid;
pub mod record;
pub mod reference;
pub mod report;

pub use grid::{Row, Spec, Status, fit, run_cell, run_grid, shape};
pub use reference::{Reference, measure_errors, reference};

use crate::methods::{MethodKind, REPORT};
use crate::run::cost::Cost;
use std::path::Path;

/// What a whole study produced.
pub struct Outcome {
    pub rows: Vec<Row>,
    pub reference: Reference,
    pub findings: findings::Findings,
    /// The findings as written to `findings.md`.
    pub markdown: String,
    pub startup: Vec<(MethodKind, Vec<(f64, f64)>)>,
}

/// What the grid of `spec` and a reference at `reference_segments` are predicted to cost:
/// the CPU time of every run added up, and the memory of as many of the largest runs as
/// there are `threads`.
pub fn cost(spec: &Spec, reference_segments: usize, threads: usize) -> Cost {
    let costs: Vec<Cost> = spec
        .cells()
        .into_iter()
        .chain(reference::reference_runs(reference_segments))
        .map(|(m, n, dt)| Cost::of_run(m, n, dt, spec.duration, 0.0))
        .collect();
    let largest = costs.iter().map(|c| c.bytes).max().unwrap_or(0);
    Cost {
        seconds: costs.iter().map(|c| c.seconds).sum(),
        bytes: largest.saturating_mul(threads.max(1) as u64),
    }
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
    report::write_csv(&rows, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let findings = findings::Findings::from_rows(&rows);
    let markdown = findings.markdown(&reference, command);
    let md = out.join("findings.md");
    std::fs::write(&md, &markdown).with_context(|| format!("writing {}", md.display()))?;
    let startup: Vec<_> = spec
        .methods
        .iter()
        .filter_map(|&m| {
            let burst = report::startup_burst(&spec.scene, m, REPORT.segments, REPORT.dt, 300)?;
            Some((m, burst))
        })
        .collect();
    charts::register_font()?;
    charts::write_all(
        out,
        &rows,
        &startup,
        &format!("{}, t = {}", spec.scene, spec.duration),
    )?;
    Ok(Outcome {
        rows,
        reference,
        findings,
        markdown,
        startup,
    })
}
