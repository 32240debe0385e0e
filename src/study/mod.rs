//! `rope study`: a grid of runs over methods × segments × time steps, each measured for
//! stability, energy deviation, solution error against a converged reference, and CPU cost;
//! then what the rows say, as findings, charts and (optionally) a Rerun recording.
//!
//! * [`grid`]: the cells, one run each, in parallel; [`mod@reference`]: the converged solution,
//!   kept at every step ([`trajectory`]) so that each run is measured at every frame;
//! * [`findings`]: convergence orders, stability limits, the cheapest accurate runs;
//! * [`report`]: `study.csv`; [`charts`]: SVG and PNG; [`record`]: the same into Rerun;
//! * [`shard`]: the grid split over processes or machines (`--shard`, `--reference-only`,
//!   `--merge`);
//! * [`long_run`]: `--long-run T`, the energy error of each method over a long swing;
//! * [`blow_up`]: `--blow-up T`, when the report's scheme blows up and what grows first;
//! * [`long_charts`]: the charts of those two;
//! * [`estimate_check`]: `--estimate-check`, the live error estimate against the truth, and
//!   the error models over all the scenes; [`check_chart`]: its chart;
//! * [`tolerance_check`]: `--tolerance-check`, what `--tolerance` chooses against the truth
//!   and against the cheapest run of a grid; [`tolerance_chart`]: its chart;
//! * [`tip_reference`]: the converged tip those checks and the release atlas judge runs
//!   against, from runs at [`trajectory`]; [`run_cache`]: those runs kept on disk
//!   (`ROPE_RUN_CACHE`), to be read instead of run again; [`read_reference`]: such a tip
//!   read back from a references file (`--references`), instead of computed again.

pub mod atlas_chart;
pub mod axes;
pub mod blow_up;
pub mod charts;
pub mod check_chart;
pub mod check_timing;
pub mod estimate_check;
pub mod findings;
pub mod grid;
pub mod long_charts;
pub mod long_run;
pub mod progress;
pub mod read_reference;
pub mod record;
pub mod reference;
pub mod report;
pub mod run_cache;
pub mod shard;
pub mod sweep_chart;
pub mod tip_reference;
pub mod tolerance_chart;
pub mod tolerance_check;
pub mod tolerance_csv;
pub mod tolerance_table;
pub mod trajectory;

pub use grid::{Row, Spec, Status, fit, run_cell, run_grid, shape};
pub use progress::{Progress, Stopped};
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
    cost_of(spec, &spec.cells(), Some(reference_segments), threads)
}

/// As [`cost`], for some `cells` of the grid, and the reference at `reference_segments` if
/// it is to be computed (not read from a file).
pub fn cost_of(
    spec: &Spec,
    cells: &[(MethodKind, usize, f64)],
    reference_segments: Option<usize>,
    threads: usize,
) -> Cost {
    let reference = reference_segments.map(reference::reference_runs);
    let costs: Vec<Cost> = cells
        .iter()
        .copied()
        .chain(reference.into_iter().flatten())
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
/// cite in the findings. `progress` counts the runs, and may stop the study before its files
/// ([`Stopped`]).
pub fn execute(
    spec: &Spec,
    reference_segments: usize,
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<Outcome> {
    create_dir(out)?;
    let reference = reference(&spec.scene, spec.duration, reference_segments, progress)?;
    execute_with(spec, reference, out, command, progress)
}

/// As [`execute`], against a reference already computed (`--reference FILE`).
pub fn execute_with(
    spec: &Spec,
    reference: Reference,
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<Outcome> {
    create_dir(out)?;
    let mut rows = run_grid(spec, progress)?;
    measure_errors(&mut rows, &reference);
    finish(spec, reference, rows, out, command)
}

/// Computes the reference alone and writes it to `out/reference.json`, for shards to share
/// (`--reference FILE`). Returns the file's path. `progress` may stop it before the file
/// ([`Stopped`]).
pub fn execute_reference_only(
    spec: &Spec,
    reference_segments: usize,
    out: &Path,
    progress: &impl Progress,
) -> anyhow::Result<std::path::PathBuf> {
    create_dir(out)?;
    let file = reference_file(spec, reference_segments, progress)?;
    let path = out.join(shard::REFERENCE);
    write(&path, &serde_json::to_string_pretty(&file)?)?;
    Ok(path)
}

/// The reference of `spec` at `reference_segments`, computed, as a file holds it.
fn reference_file(
    spec: &Spec,
    reference_segments: usize,
    progress: &impl Progress,
) -> anyhow::Result<shard::ReferenceFile> {
    let r = reference(&spec.scene, spec.duration, reference_segments, progress)?;
    Ok(shard::ReferenceFile::new(
        spec.scene,
        spec.duration,
        reference_segments,
        &r,
    ))
}

/// Runs one shard's cells of the grid, measured against `reference` (computed here when
/// none is given), and writes the partial `study.csv` and its manifest `shard.json` into
/// `out`. Returns the shard's rows.
pub fn execute_shard(
    spec: &Spec,
    shard: shard::Shard,
    reference: Option<shard::ReferenceFile>,
    reference_segments: usize,
    out: &Path,
    progress: &impl Progress,
) -> anyhow::Result<Vec<Row>> {
    use anyhow::Context as _;
    create_dir(out)?;
    let reference = match reference {
        Some(file) => file,
        None => reference_file(spec, reference_segments, progress)?,
    };
    let mut rows = grid::run_cells(spec, shard.cells(spec), progress)?;
    measure_errors(&mut rows, &reference.reference());
    let csv = out.join("study.csv");
    report::write_csv(&rows, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let manifest = shard::Manifest {
        shard,
        spec: spec.clone(),
        reference,
    };
    write(
        &out.join(shard::MANIFEST),
        &serde_json::to_string_pretty(&manifest)?,
    )?;
    Ok(rows)
}

/// Merges the shards in `dirs` (see [`shard::merge`]) and writes the whole study from them
/// into `out`, as [`execute`] would have.
pub fn execute_merge(
    dirs: &[std::path::PathBuf],
    out: &Path,
    command: &str,
) -> anyhow::Result<Outcome> {
    let (spec, reference, rows) = shard::merge(dirs)?;
    create_dir(out)?;
    finish(&spec, reference.reference(), rows, out, command)
}

/// What every whole study ends with: `study.csv`, the findings and the charts from its
/// measured rows.
fn finish(
    spec: &Spec,
    reference: Reference,
    rows: Vec<Row>,
    out: &Path,
    command: &str,
) -> anyhow::Result<Outcome> {
    use anyhow::Context as _;
    let csv = out.join("study.csv");
    report::write_csv(&rows, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let findings = findings::Findings::from_rows(&rows);
    let markdown = findings.markdown(&reference, command);
    write(&out.join("findings.md"), &markdown)?;
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

/// Creates the output directory `out`.
fn create_dir(out: &Path) -> anyhow::Result<()> {
    use anyhow::Context as _;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))
}

/// Writes `text` to `path`.
fn write(path: &Path, text: &str) -> anyhow::Result<()> {
    use anyhow::Context as _;
    std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))
}

/// Makes the long `runs` (method, scene, step; see [`long_run::runs`]) for `duration` time
/// units (in parallel, a core each), and writes `long_run.csv`, `long_run.md` and the chart
/// `long_run.svg`/`.png` into `out`. Returns the Markdown. `progress` counts each time unit
/// simulated, by any run, and may stop the runs before their files ([`Stopped`]).
pub fn execute_long_runs(
    runs: &[(MethodKind, crate::model::Scene, f64)],
    duration: f64,
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<String> {
    use anyhow::Context as _;
    use rayon::prelude::*;
    create_dir(out)?;
    // A method that cannot start from a scene (the seed from the horizontal) is left out,
    // with its reason in the Markdown.
    let mut startable = Vec::new();
    let mut left_out = Vec::new();
    for &(m, s, dt) in runs {
        match m.build(&s, REPORT.segments, dt) {
            Ok(_) => startable.push((m, s, dt)),
            Err(err) => left_out.push(format!(
                "\nLeft out: {m} from the {s} at k = {dt:e}: {err}.\n"
            )),
        }
    }
    for _ in 0..left_out.len() as u64 * duration.ceil() as u64 {
        progress.done();
    }
    let runs = startable
        .par_iter()
        .map(|&(m, s, dt)| long_run::run(m, s, dt, duration, progress))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let csv = out.join("long_run.csv");
    long_run::write_csv(&runs, &csv).with_context(|| format!("writing {}", csv.display()))?;
    let markdown = long_run::markdown(&runs, duration, command) + &left_out.concat();
    write(&out.join("long_run.md"), &markdown)?;
    charts::register_font()?;
    long_charts::write_long_runs(out, &runs)?;
    Ok(markdown)
}

/// The report's method's time to divergence over N × k, and its sawtooth before the blow-up
/// at N = 100 and its default step; writes `blow_up.md`, `blow_up.csv` and the charts
/// `divergence_map` and `sawtooth` into `out`. Returns the Markdown. `progress` counts the
/// runs, and may stop them before their files ([`Stopped`]).
pub fn execute_blow_up(
    scene: &crate::model::Scene,
    duration: f64,
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<String> {
    use anyhow::Context as _;
    create_dir(out)?;
    let lifetimes = blow_up::lifetimes(scene, duration, progress)?;
    progress.check()?;
    let dt = REPORT.method.default_dt(REPORT.segments);
    let saw = blow_up::sawtooth(scene, dt, duration)?;
    let csv_path = out.join("blow_up.csv");
    let mut csv = csv::Writer::from_path(&csv_path)
        .with_context(|| format!("writing {}", csv_path.display()))?;
    for l in &lifetimes {
        csv.serialize(l)?;
    }
    csv.flush()?;
    let markdown = blow_up::markdown(scene, &lifetimes, saw.as_ref(), duration, command);
    write(&out.join("blow_up.md"), &markdown)?;
    charts::register_font()?;
    long_charts::write_blow_up(out, &lifetimes, saw.as_ref())?;
    Ok(markdown)
}

/// The live error estimate of each cell of `spec` against the truth; writes
/// `estimate_check.md`, `estimate_check.csv` and the chart `estimate_check.png` into `out`.
/// Returns the Markdown. `progress` counts each reference and each cell, and may stop the
/// check before its files ([`Stopped`]).
pub fn execute_estimate_check(
    spec: &estimate_check::CheckSpec,
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<String> {
    use anyhow::Context as _;
    create_dir(out)?;
    let cells = estimate_check::check(spec, progress)?;
    let csv = out.join("estimate_check.csv");
    estimate_check::write_csv(&cells, &csv)
        .with_context(|| format!("writing {}", csv.display()))?;
    let markdown = estimate_check::markdown(spec, &cells, command);
    write(&out.join("estimate_check.md"), &markdown)?;
    charts::register_font()?;
    check_chart::write(out, &cells)?;
    Ok(markdown)
}

/// What `--tolerance` chooses in each scene of `spec` (its references read from `read` where
/// they can judge it), against the truth and the grid's cheapest run; writes
/// `tolerance_check.md`, the references' tips (`references.csv`) and the chart
/// `tolerance_check.svg`/`.png` into `out`. Returns the Markdown. `progress` counts each
/// reference, run and choice, and may stop the check before its files ([`Stopped`]).
pub fn execute_tolerance_check(
    spec: &tolerance_check::CheckSpec,
    read: &[read_reference::ReadReference],
    out: &Path,
    command: &str,
    progress: &impl Progress,
) -> anyhow::Result<String> {
    create_dir(out)?;
    use anyhow::Context as _;
    let checked = tolerance_check::check(spec, read, progress)?;
    let csv = out.join("references.csv");
    tip_reference::write_references(&csv, &checked.references, spec.duration)
        .with_context(|| format!("writing {}", csv.display()))?;
    let markdown = tolerance_table::markdown(spec, &checked, command);
    write(&out.join("tolerance_check.md"), &markdown)?;
    let table = out.join("tolerance_check.csv");
    tolerance_csv::write(&checked.cells, &table)
        .with_context(|| format!("writing {}", table.display()))?;
    charts::register_font()?;
    tolerance_chart::write(out, &checked.cells)?;
    Ok(markdown)
}
