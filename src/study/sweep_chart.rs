//! The chart of a sweep of the shaken support's frequency: the free end's largest sideways
//! swing against Ω, and its swing at Ω alone, over the support's amplitude, on a log axis,
//! with the resonances ω_n of linear theory marked and its steady state A/|J₀(2Ω)| drawn
//! beside: where the modes appear one after another. Also the sweep as CSV.

use super::charts::{Drawn, SANS, legend, register_font, render_chart};
use crate::model::bessel;
use crate::model::support::{free_end_swing, steady_response};
use crate::run::shake_figures::SweepPoint;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// `<name>.svg`, `<name>.png` and `<name>.csv` into `dir`, for a sweep of support amplitude
/// `amplitude`.
pub fn write(dir: &Path, name: &str, amplitude: f64, points: &[SweepPoint]) -> anyhow::Result<()> {
    register_font()?;
    let mut csv = String::from("frequency,tip_amplitude,driven_amplitude,steady_state_amplitude\n");
    for p in points {
        let steady = free_end_swing(amplitude, p.frequency);
        csv += &format!("{},{},{},{steady}\n", p.frequency, p.largest, p.driven);
    }
    let path = dir.join(format!("{name}.csv"));
    std::fs::write(&path, csv).map_err(|e| anyhow::anyhow!("writing {}: {e}", path.display()))?;
    render_chart!(dir, name, draw, amplitude, points)
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    amplitude: f64,
    points: &[SweepPoint],
) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let (lo, hi) = SweepPoint::span(points);
    let (lo, hi) = if lo < hi { (lo, hi) } else { (0.0, 5.0) };
    let over_a = |swing: fn(&SweepPoint) -> f64| -> Vec<(f64, f64)> {
        points
            .iter()
            .map(|p| (p.frequency, swing(p) / amplitude))
            .filter(|p| p.1 > 0.0)
            .collect()
    };
    let (ratios, driven) = (over_a(|p| p.largest), over_a(|p| p.driven));
    let top = ratios.iter().map(|p| p.1).fold(10.0, f64::max) * 2.0;
    let bottom = ratios
        .iter()
        .chain(&driven)
        .map(|p| p.1)
        .fold(top, f64::min)
        .min(1.0)
        / 2.0;
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!(
                "Shaken support, A = {amplitude}: the free end's swing against the shaking frequency"
            ),
            (SANS, 20),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(lo..hi, (bottom..top).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("Ω (radians per time unit, g = L = 1)")
        .y_desc("swing of the free end / A")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((SANS, 13))
        .draw()?;
    // The resonances, dashed and named.
    let grey = RGBColor(150, 150, 150);
    let mut first = true;
    for n in 1..=40 {
        let omega = bessel::mode_frequency(n);
        if omega > hi {
            break;
        }
        if omega < lo {
            continue;
        }
        let line = chart.draw_series(DashedLineSeries::new(
            [(omega, bottom), (omega, top)],
            6,
            4,
            grey.stroke_width(1),
        ))?;
        if first {
            line.label("resonances ω_n of linear theory (J₀(2ω) = 0)")
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], grey));
            first = false;
        }
        chart.draw_series(std::iter::once(Text::new(
            format!("ω{n} = {omega:.4}"),
            (omega, top / 1.6),
            (SANS, 13),
        )))?;
    }
    // Linear theory's steady state, for reference.
    let steps = 600;
    let steady: Vec<(f64, f64)> = (0..=steps)
        .map(|i| {
            let omega = lo + (hi - lo) * i as f64 / steps as f64;
            (omega, steady_response(omega, 0.0).abs().clamp(bottom, top))
        })
        .collect();
    let blue = RGBColor(60, 120, 220);
    chart
        .draw_series(LineSeries::new(steady, blue.stroke_width(1)))?
        .label("linear steady state 1/|J₀(2Ω)|")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], blue));
    let red = RGBColor(200, 40, 40);
    chart
        .draw_series(LineSeries::new(ratios.clone(), red.stroke_width(2)))?
        .label("measured: the largest swing over each run")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], red.stroke_width(2)));
    chart.draw_series(ratios.into_iter().map(|p| Circle::new(p, 2, red.filled())))?;
    let green = RGBColor(40, 150, 80);
    chart
        .draw_series(LineSeries::new(driven, green.stroke_width(2)))?
        .label("measured: the swing at Ω alone (its Fourier component over the run)")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], green.stroke_width(2)));
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::LowerRight,
        12,
    )
}
