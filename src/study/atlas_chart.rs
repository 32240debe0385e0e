//! The chart of the release atlas: the rods' error constant (worst tip error over its window,
//! times N) against N, one line per release angle, beside the chain's one law: where a release
//! needs fewer segments than the horizontal's whip asks of every scene.

use super::charts::{Drawn, SANS, legend, render_chart};
use crate::methods::MethodKind;
use crate::plan::atlas::Atlas;
use crate::plan::error_model::law;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// The tightest tolerance an atlas serves: past a row's trusted bounds, the chart draws those a
/// reference could judge it by (its own error at most a tenth of it), which the law reads for
/// it ([`Atlas::rows_serving`]).
const JUDGED: f64 = 1e-4;

/// `{name}.svg` and `.png` into `dir`: the atlas of `rods` ("the rods'", "the graded
/// rods'"), named so in the caption.
pub fn write(dir: &Path, name: &str, rods: &str, atlas: &Atlas) -> anyhow::Result<()> {
    render_chart!(dir, name, draw, atlas, rods)
}

/// The colour of the `i`-th of `count` angles: red at the horizontal to blue at the vertical.
fn angle_colour(i: usize, count: usize) -> RGBColor {
    let f = i as f64 / (count.max(2) - 1) as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * f) as u8;
    RGBColor(mix(210.0, 30.0), mix(40.0, 90.0), mix(30.0, 210.0))
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, atlas: &Atlas, rods: &str) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let rows: Vec<(f64, Vec<(usize, f64)>)> = atlas
        .rows()
        .filter(|(_, points)| points.iter().any(|&(_, e)| e > 1e-9))
        .collect();
    // Past each row's trusted bounds, those its reference could still judge 1e-4 by.
    let judged: Vec<Vec<(usize, f64)>> = rows
        .iter()
        .map(|(angle, trusted)| {
            let serving = atlas.rows_serving(JUDGED).find(|(a, _)| a == angle);
            let past = serving.map_or(Vec::new(), |(_, bounds)| bounds);
            past.into_iter()
                .skip(trusted.len().saturating_sub(1))
                .collect()
        })
        .collect();
    let law = law(MethodKind::Chain);
    let finest = rows
        .iter()
        .flat_map(|(_, points)| points.iter().map(|&(n, _)| n))
        .chain(judged.iter().flatten().map(|&(n, _)| n))
        .max()
        .unwrap_or(566);
    let (lo, hi) = (10.0, 1.4 * finest as f64);
    // Every angle's largest bound times the envelope's margin: an unmeasured angle's bound.
    let envelope: Vec<(f64, f64)> = atlas
        .envelope()
        .map(|(n, bound)| (n as f64, bound * n as f64))
        .collect();
    // Room above the largest constant, the envelope's and the law's line (to t = 3 they stay
    // below 0.6).
    let top = rows
        .iter()
        .flat_map(|(_, points)| points.iter().map(|&(n, e)| e * n as f64))
        .chain(envelope.iter().map(|&(_, c)| c))
        .fold(0.6, |top: f64, c| top.max(1.15 * c));
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!(
                "The release atlas: {rods} worst tip error to t = {}, times N, from each release angle",
                atlas.window
            ),
            (SANS, 20),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((lo..hi).log_scale(), 0.0..top)?;
    chart
        .configure_mesh()
        .x_desc("N (segments)")
        .y_desc("worst tip error × N")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.2}"))
        .label_style((SANS, 13))
        .draw()?;
    let bound = law.constant * law.safety;
    chart
        .draw_series(LineSeries::new(
            [(lo, bound), (hi, bound)],
            BLACK.stroke_width(2),
        ))?
        .label(format!(
            "the chain's one law, {:.3} × {:.2} (every scene, to t = 3)",
            law.constant, law.safety
        ))
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2)));
    for (i, (angle, points)) in rows.iter().enumerate() {
        let colour = angle_colour(i, rows.len());
        let line: Vec<(f64, f64)> = points
            .iter()
            .map(|&(n, e)| (n as f64, e * n as f64))
            .collect();
        chart
            .draw_series(LineSeries::new(line.clone(), colour.stroke_width(2)))?
            .label(format!("{angle}°"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(2)));
        chart.draw_series(line.into_iter().map(|p| Circle::new(p, 3, colour.filled())))?;
        let past: Vec<(f64, f64)> = judged[i]
            .iter()
            .map(|&(n, e)| (n as f64, e * n as f64))
            .collect();
        if past.len() > 1 {
            chart.draw_series(DashedLineSeries::new(
                past.clone(),
                4,
                4,
                colour.stroke_width(1),
            ))?;
            chart.draw_series(past.into_iter().skip(1).map(|p| Circle::new(p, 3, colour)))?;
        }
    }
    if judged.iter().any(|past| past.len() > 1) {
        // A legend entry for the dashed continuations, in the first row's colour.
        let colour = angle_colour(0, rows.len());
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(format!(
                "hollow, dashed: a bound (error + its reference's own) read only for a tolerance ≥ {JUDGED:.0e}, which its reference could judge"
            ))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour.stroke_width(1)));
    }
    let grey = RGBColor(110, 110, 110);
    chart
        .draw_series(DashedLineSeries::new(envelope, 7, 5, grey.stroke_width(3)))?
        .label(format!(
            "every angle's largest bound × {:.2}: an angle between them",
            atlas.envelope_margin
        ))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], grey.stroke_width(3)));
    // Above the lines, which fall below 0.4 past N = 100 at every angle.
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::UpperRight,
        12,
    )
}
