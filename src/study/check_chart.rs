//! The chart of `rope study --estimate-check`: the live error estimate against the true
//! error, one panel per method, one colour per scene, with the band of a factor 3 around
//! equality.

use super::axes::log_range;
use super::charts::{Drawn, SANS, SIZE, legend};
use super::estimate_check::{Cell, FACTOR, RESOLVED};
use crate::methods::MethodKind;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// One colour per scene, in the order the check lists them.
const SCENE_COLOURS: [RGBColor; 6] = [
    RGBColor(200, 40, 40),
    RGBColor(230, 140, 20),
    RGBColor(40, 150, 60),
    RGBColor(30, 110, 200),
    RGBColor(140, 60, 170),
    RGBColor(90, 90, 90),
];

/// `estimate_check.png`: estimate against truth, log–log. PNG only: a vector file of every
/// frame's point would be megabytes.
pub fn write(dir: &Path, cells: &[Cell]) -> anyhow::Result<()> {
    let png = dir.join("estimate_check.png");
    let root = BitMapBackend::new(&png, (SIZE.0 + 300, SIZE.1)).into_drawing_area();
    draw(&root, cells).map_err(|e| anyhow::anyhow!("drawing {}: {e:?}", png.display()))?;
    root.present()
        .map_err(|e| anyhow::anyhow!("writing {}: {e:?}", png.display()))?;
    Ok(())
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, cells: &[Cell]) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!(
            "Live error estimate against the true tip error (frames with truth > {RESOLVED:.0e}; band: ×{FACTOR})"
        ),
        (SANS, 20),
    )?;
    let mut methods: Vec<MethodKind> = cells.iter().map(|c| c.method).collect();
    methods.dedup();
    let mut scenes = Vec::new();
    for c in cells {
        if !scenes.contains(&c.scene) {
            scenes.push(c.scene);
        }
    }
    let judged = |c: &Cell| {
        c.samples
            .iter()
            .filter(|s| s.truth > RESOLVED && s.estimate > 0.0)
            .map(|s| (s.truth, s.estimate))
            .collect::<Vec<_>>()
    };
    let Range { start: lo, end: hi } =
        log_range(cells.iter().flat_map(judged).flat_map(|(t, e)| [t, e]));
    let panels = root.split_evenly((1, methods.len().max(1)));
    for (panel, &method) in panels.iter().zip(&methods) {
        let mut chart = ChartBuilder::on(panel)
            .caption(method.name(), (SANS, 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d((lo..hi).log_scale(), (lo..hi).log_scale())?;
        chart
            .configure_mesh()
            .x_desc("true tip error")
            .y_desc("estimate")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style((SANS, 12))
            .draw()?;
        for (factor, width) in [(1.0, 2), (FACTOR, 1), (1.0 / FACTOR, 1)] {
            chart.draw_series(LineSeries::new(
                [(lo, lo * factor), (hi, hi * factor)],
                BLACK.mix(0.7).stroke_width(width),
            ))?;
        }
        for (i, scene) in scenes.iter().enumerate() {
            let colour = SCENE_COLOURS[i % SCENE_COLOURS.len()];
            let points: Vec<(f64, f64)> = cells
                .iter()
                .filter(|c| c.method == method && c.scene == *scene)
                .flat_map(judged)
                .collect();
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 2, colour.mix(0.6).filled())),
                )?
                .label(scene.to_string())
                .legend(move |(x, y)| Circle::new((x + 6, y), 4, colour.filled()));
        }
        legend(
            chart.configure_series_labels(),
            SeriesLabelPosition::LowerRight,
            11,
        )?;
    }
    Ok(())
}
