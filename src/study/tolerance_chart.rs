//! The chart of `rope study --tolerance-check`: for each scene and EPS, the CPU of what
//! `--tolerance` did (pilots included) against the CPU of the grid's cheapest run that holds
//! EPS, log–log, with the lines of equal cost and of 3 times it. Only the cells past 3 times
//! and those not held are named: the table names every cell, and 42 names overlap.

use super::axes::log_range;
use super::charts::{Drawn, SANS, legend, render_chart};
use super::tolerance_check::{CPU_FACTOR, Cell};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// One colour per tolerance, from the loosest.
const EPS_COLOURS: [RGBColor; 3] = [
    RGBColor(40, 150, 60),
    RGBColor(30, 110, 200),
    RGBColor(200, 40, 40),
];

/// `tolerance_check.svg` and `.png` into `dir`.
pub fn write(dir: &Path, cells: &[Cell]) -> anyhow::Result<()> {
    render_chart!(dir, "tolerance_check", draw, cells)
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, cells: &[Cell]) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let points: Vec<(f64, f64, &Cell)> = cells
        .iter()
        .filter_map(|c| {
            let (chosen, cheapest) = (c.chosen?, c.cheapest?);
            Some((cheapest.seconds, chosen.seconds + c.pilot_seconds, c))
        })
        .collect();
    let Range { start: lo, end: hi } = log_range(
        points
            .iter()
            .flat_map(|&(x, y, _)| [x.max(1e-5), y.max(1e-5)]),
    );
    let mut chart = ChartBuilder::on(root)
        .caption(
            "--tolerance's CPU (pilots included) against the grid's cheapest run that holds EPS",
            (SANS, 20),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((lo..hi).log_scale(), (lo..hi).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("grid's cheapest run holding EPS, CPU s")
        .y_desc("--tolerance, CPU s")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((SANS, 13))
        .draw()?;
    chart
        .draw_series(LineSeries::new([(lo, lo), (hi, hi)], BLACK.stroke_width(2)))?
        .label("equal cost")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(
            [(lo, lo * CPU_FACTOR), (hi, hi * CPU_FACTOR)],
            BLACK.mix(0.5),
        ))?
        .label(format!(
            "{CPU_FACTOR} × the cheapest (a cell above it, or not held, is named)"
        ))
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLACK.mix(0.5)));
    let mut tolerances: Vec<f64> = cells.iter().map(|c| c.tolerance).collect();
    tolerances.sort_by(|a, b| b.total_cmp(a));
    tolerances.dedup();
    for (i, eps) in tolerances.iter().enumerate() {
        let colour = EPS_COLOURS[i % EPS_COLOURS.len()];
        let mine: Vec<&(f64, f64, &Cell)> =
            points.iter().filter(|p| p.2.tolerance == *eps).collect();
        chart
            .draw_series(mine.iter().map(|&&(x, y, c)| {
                let held = c.held() == Some(true);
                let style = if held {
                    colour.filled()
                } else {
                    colour.stroke_width(2)
                };
                let name = if y > CPU_FACTOR * x || !held {
                    c.scene.to_string()
                } else {
                    String::new()
                };
                EmptyElement::at((x, y))
                    + Circle::new((0, 0), 6, style)
                    + Text::new(name, (8, -6), (SANS, 11))
            }))?
            .label(format!("EPS = {eps:.0e} (hollow: not held)"))
            .legend(move |(x, y)| Circle::new((x + 8, y), 5, colour.filled()));
    }
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::UpperLeft,
        12,
    )
}
