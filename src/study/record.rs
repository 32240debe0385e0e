//! Puts a study's chart data into a Rerun recording: the work–precision points, the
//! stability map and the findings, so that a `.rrd` carries the study.

use super::Outcome;
use super::grid::Status;
use crate::methods::MethodKind;

/// Logs the study's points (static: a study has no time axis) under `study/…`.
pub fn log(rec: &rerun::RecordingStream, outcome: &Outcome) -> rerun::RecordingStreamResult<()> {
    rec.log_static(
        "study/findings",
        &rerun::TextDocument::from_markdown(outcome.markdown.as_str()),
    )?;
    for method in MethodKind::ALL {
        let mine: Vec<_> = outcome.rows.iter().filter(|r| r.method == method).collect();
        if mine.is_empty() {
            continue;
        }
        // Runs with a measurable tip error: log10 CPU seconds across, −log10 error up.
        let (points, labels): (Vec<[f32; 2]>, Vec<String>) = mine
            .iter()
            .filter(|r| r.status == Status::Ok)
            .filter_map(|r| {
                let e = r.tip_error.filter(|e| *e > 0.0)?;
                let point = [r.cpu_seconds.max(1e-9).log10() as f32, -(e.log10() as f32)];
                Some((point, format!("N = {}, k = {:e}", r.segments, r.dt)))
            })
            .unzip();
        rec.log_static(
            format!("study/work_precision/{method}"),
            &rerun::Points2D::new(points)
                .with_labels(labels)
                .with_radii([0.04]),
        )?;
        let (points, colors): (Vec<[f32; 2]>, Vec<rerun::Color>) = mine
            .iter()
            .map(|r| {
                let [red, green, blue] = r.status.rgb();
                let color = rerun::Color::from_rgb(red, green, blue);
                (
                    [(r.segments as f64).log10() as f32, -(r.dt.log10() as f32)],
                    color,
                )
            })
            .unzip();
        rec.log_static(
            format!("study/stability/{method}"),
            &rerun::Points2D::new(points)
                .with_colors(colors)
                .with_radii([0.03]),
        )?;
    }
    Ok(())
}
