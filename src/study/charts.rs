//! The study's charts, each drawn twice, as SVG and as PNG: work–precision, the stability
//! map, and the report's Figs. 1–4.

use super::axes::{linear_range, log_range};
use super::grid::{Row, Status};
use crate::methods::{MethodKind, REPORT};
use crate::run::simulate::REFERENCE_STEP;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// The font every chart uses, shipped so that PNGs render the same on any machine.
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
pub(crate) const SANS: &str = "sans-serif";
pub(crate) const SIZE: (u32, u32) = (1100, 620);

pub(crate) type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A named, coloured line of (x, y) points.
pub(crate) type Series = (String, RGBColor, Vec<(f64, f64)>);

/// What a work–precision panel plots against cost: a label and how to read it off a row.
type Metric = (String, fn(&Row) -> Option<f64>);

/// Registers the shipped font; call once before drawing PNGs.
pub fn register_font() -> anyhow::Result<()> {
    plotters::style::register_font(SANS, FontStyle::Normal, FONT)
        .map_err(|_| anyhow::anyhow!("the shipped font assets/fonts/DejaVuSans.ttf is invalid"))
}

/// Draws `chart` to `<dir>/<name>.svg` and `<dir>/<name>.png`.
macro_rules! render_chart {
    ($dir:expr, $name:expr, $chart:ident, $($arg:expr),*) => {{
        let svg = $dir.join(format!("{}.svg", $name));
        let png = $dir.join(format!("{}.png", $name));
        {
            let root = SVGBackend::new(&svg, $crate::study::charts::SIZE).into_drawing_area();
            $chart(&root, $($arg),*).map_err(|e| anyhow::anyhow!("drawing {}: {e:?}", svg.display()))?;
            root.present().map_err(|e| anyhow::anyhow!("writing {}: {e:?}", svg.display()))?;
        }
        {
            let root = BitMapBackend::new(&png, $crate::study::charts::SIZE).into_drawing_area();
            $chart(&root, $($arg),*).map_err(|e| anyhow::anyhow!("drawing {}: {e:?}", png.display()))?;
            root.present().map_err(|e| anyhow::anyhow!("writing {}: {e:?}", png.display()))?;
        }
        anyhow::Ok(())
    }};
}
pub(crate) use render_chart;

/// Colour of a method's curve for the i-th of `count` segment counts (darker = finer).
pub(crate) fn shade(method: MethodKind, i: usize, count: usize) -> RGBColor {
    let t = if count > 1 {
        i as f64 / (count - 1) as f64
    } else {
        1.0
    };
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * t).round() as u8;
    let (coarse, fine) = method.descriptor().colours;
    RGBColor(
        mix(coarse[0], fine[0]),
        mix(coarse[1], fine[1]),
        mix(coarse[2], fine[2]),
    )
}

/// Draws the legend box every chart uses, at `position` with labels of `size` points.
pub(crate) fn legend<'a, 'b, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    mut labels: plotters::chart::SeriesLabelStyle<'a, 'b, DB, CT>,
    position: SeriesLabelPosition,
    size: u32,
) -> Drawn<DB> {
    labels
        .position(position)
        .label_font((SANS, size))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()
}

/// A tick label: plain for ordinary magnitudes, scientific with three significant digits
/// otherwise (log axes land on values like 9.999999999999998e-5 that should read 1e-4).
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".to_owned()
    } else if (1e-2..1e4).contains(&a) {
        let digits = (3 - a.log10().floor() as i32 - 1).max(0) as usize;
        crate::run::config::trimmed_fixed(*v, digits)
    } else {
        // Three significant digits, trailing zeros dropped: ticks 5e-4 apart near 2e-3 read
        // 1.5e-3, 2e-3, 2.5e-3, not 2e-3 twice.
        crate::run::config::trimmed_scientific(*v, 2)
    }
}

fn segment_counts(rows: &[Row], method: MethodKind) -> Vec<usize> {
    let mut n: Vec<usize> = rows
        .iter()
        .filter(|r| r.method == method)
        .map(|r| r.segments)
        .collect();
    n.sort_unstable();
    n.dedup();
    n
}

/// The runs that no other run beats on both cost and error: the Pareto front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|last| p.1 < last.1) {
            front.push(p);
        }
    }
    front
}

/// Work–precision: tip error and energy deviation against CPU seconds.
fn work_precision<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[Row],
    title: &str,
) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(title, (SANS, 22))?;
    let panels = root.split_evenly((1, 2));
    let ok: Vec<&Row> = rows.iter().filter(|r| r.status == Status::Ok).collect();
    let x_range = log_range(ok.iter().map(|r| r.cpu_seconds));
    let metrics: [Metric; 2] = [
        (
            "tip error at the final time (string lengths)".to_owned(),
            |r| r.tip_error,
        ),
        (format!("energy deviation {}", deviation_axis()), |r| {
            r.energy_deviation
        }),
    ];
    for (panel, (label, metric)) in panels.iter().zip(metrics) {
        work_precision_panel(panel, rows, &ok, x_range.clone(), &label, metric)?;
    }
    Ok(())
}

/// One panel of the work–precision chart: `metric` against CPU seconds, a curve per method
/// and N across k, and the Pareto front of all the runs.
fn work_precision_panel<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    rows: &[Row],
    ok: &[&Row],
    x_range: Range<f64>,
    label: &str,
    metric: fn(&Row) -> Option<f64>,
) -> Drawn<DB> {
    let point = |r: &Row| metric(r).filter(|e| *e > 0.0).map(|e| (r.cpu_seconds, e));
    let y_range = log_range(ok.iter().filter_map(|r| metric(r)));
    let mut chart = ChartBuilder::on(panel)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("CPU seconds (one run, one core)")
        .y_desc(label)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((SANS, 13))
        .draw()?;
    for method in MethodKind::ALL {
        let counts = segment_counts(rows, method);
        for (i, &n) in counts.iter().enumerate() {
            let mut pts: Vec<(f64, f64)> = ok
                .iter()
                .filter(|r| r.method == method && r.segments == n)
                .filter_map(|r| point(r))
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let color = shade(method, i, counts.len());
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
                .label(format!("{method} N = {n}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3))
                });
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
    }
    let all: Vec<(f64, f64)> = ok.iter().filter_map(|r| point(r)).collect();
    let front = pareto_front(&all);
    chart
        .draw_series(LineSeries::new(front.clone(), BLACK.stroke_width(1)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    chart.draw_series(
        front
            .iter()
            .map(|&p| Circle::new(p, 6, BLACK.stroke_width(1))),
    )?;
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::UpperRight,
        11,
    )
}

/// Stability map: N × k, each run marked ok / diverged / refused, the measured boundary and
/// the estimate k = C h / sqrt(F_max); one panel per method.
fn stability<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[Row],
    title: &str,
) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let root = root.titled(title, (SANS, 22))?;
    let methods: Vec<MethodKind> = MethodKind::ALL
        .into_iter()
        .filter(|m| rows.iter().any(|r| r.method == *m))
        .collect();
    let panels = root.split_evenly((1, methods.len().max(1)));
    for (panel, &method) in panels.iter().zip(&methods) {
        stability_panel(panel, rows, method)?;
    }
    Ok(())
}

/// One method's panel of the stability map.
fn stability_panel<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    rows: &[Row],
    method: MethodKind,
) -> Drawn<DB> {
    let x_range = log_range(rows.iter().map(|r| r.segments as f64));
    let y_range = log_range(rows.iter().map(|r| r.dt));
    let mut chart = ChartBuilder::on(panel)
        .caption(format!("{method}"), (SANS, 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("segments N")
        .y_desc("time step k")
        .x_labels(6)
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((SANS, 13))
        .draw()?;
    let mine: Vec<&Row> = rows.iter().filter(|r| r.method == method).collect();
    draw_run_statuses(&mut chart, &mine)?;
    let boundary = measured_boundary(rows, method);
    if boundary.len() >= 2 {
        chart
            .draw_series(LineSeries::new(boundary, BLACK.stroke_width(2)))?
            .label("measured boundary")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(2)));
    }
    let estimate: Vec<(f64, f64)> = segment_counts(rows, method)
        .iter()
        .map(|&n| (n as f64, method.stability_limit(n)))
        .collect();
    chart
        .draw_series(DashedLineSeries::new(estimate, 8, 5, BLUE.stroke_width(2)))?
        .label(method.descriptor().limit_meaning)
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLUE.stroke_width(2)));
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::LowerLeft,
        12,
    )
}

/// Each run of a stability panel, marked as it ended: ok, diverged, refused.
fn draw_run_statuses<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    mine: &[&Row],
) -> Drawn<DB> {
    let at = |r: &Row| (r.segments as f64, r.dt);
    let colour = |status: &Status| {
        let [r, g, b] = status.rgb();
        RGBColor(r, g, b)
    };
    let ok = colour(&Status::Ok);
    let diverged = colour(&Status::Diverged {
        time: 0.0,
        reason: String::new(),
    });
    let refused = colour(&Status::Refused {
        reason: String::new(),
    });
    chart
        .draw_series(
            mine.iter()
                .filter(|r| r.status == Status::Ok)
                .map(|r| Circle::new(at(r), 5, ok.filled())),
        )?
        .label("ok")
        .legend(move |(x, y)| Circle::new((x + 8, y), 5, ok.filled()));
    chart
        .draw_series(
            mine.iter()
                .filter(|r| matches!(r.status, Status::Diverged { .. }))
                .map(|r| Cross::new(at(r), 6, diverged.stroke_width(2))),
        )?
        .label("diverged")
        .legend(move |(x, y)| Cross::new((x + 8, y), 6, diverged.stroke_width(2)));
    chart
        .draw_series(
            mine.iter()
                .filter(|r| matches!(r.status, Status::Refused { .. }))
                .map(|r| TriangleMarker::new(at(r), 6, refused.filled())),
        )?
        .label("refused (cannot start)")
        .legend(move |(x, y)| TriangleMarker::new((x + 8, y), 6, refused.filled()));
    Ok(())
}

/// Per N, the geometric mean of the largest stable k and the smallest diverged k above it.
pub fn measured_boundary(rows: &[Row], method: MethodKind) -> Vec<(f64, f64)> {
    segment_counts(rows, method)
        .into_iter()
        .filter_map(|n| {
            let mine = rows
                .iter()
                .filter(|r| r.method == method && r.segments == n);
            let first_bad = mine
                .clone()
                .filter(|r| matches!(r.status, Status::Diverged { .. }))
                .map(|r| r.dt)
                .fold(f64::MAX, f64::min);
            let last_good = mine
                .filter(|r| r.status == Status::Ok && r.dt < first_bad)
                .map(|r| r.dt)
                .fold(0.0, f64::max);
            (first_bad < f64::MAX && last_good > 0.0)
                .then(|| (n as f64, (first_bad * last_good).sqrt()))
        })
        .collect()
}

/// A simple x–y line chart with one or more named series.
pub(crate) fn lines<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    log: (bool, bool),
    series: &[Series],
) -> Drawn<DB> {
    root.fill(&WHITE)?;
    let xs = series.iter().flat_map(|s| s.2.iter().map(|p| p.0));
    let ys = series.iter().flat_map(|s| s.2.iter().map(|p| p.1));
    let linear = linear_range;
    let (xv, yv): (Vec<f64>, Vec<f64>) = (xs.collect(), ys.collect());
    // A linear axis through zero gets a tick computed as, say, −6e-17: it reads 0. (On a log
    // axis no tick is zero, and 1e-13 must stay 1e-13.)
    let snapped = |range: &Range<f64>| {
        let eps = 1e-9 * (range.end - range.start).abs();
        move |v: &f64| {
            if v.abs() < eps {
                "0".to_owned()
            } else {
                tick(v)
            }
        }
    };
    macro_rules! draw {
        ($x:expr, $y:expr, $x_tick:expr, $y_tick:expr) => {{
            let mut chart = ChartBuilder::on(root)
                .caption(title, (SANS, 20))
                .margin(14)
                .x_label_area_size(45)
                .y_label_area_size(80)
                .build_cartesian_2d($x, $y)?;
            chart
                .configure_mesh()
                .x_desc(x_desc)
                .y_desc(y_desc)
                .x_label_formatter(&$x_tick)
                .y_label_formatter(&$y_tick)
                .label_style((SANS, 13))
                .draw()?;
            for (name, color, pts) in series {
                let color = *color;
                chart
                    .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
                    .label(name.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3))
                    });
                if pts.len() < 40 {
                    chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
                }
            }
            legend(
                chart.configure_series_labels(),
                SeriesLabelPosition::UpperRight,
                12,
            )?;
        }};
    }
    match log {
        (true, true) => draw!(
            log_range(xv.into_iter()).log_scale(),
            log_range(yv.into_iter()).log_scale(),
            tick,
            tick
        ),
        (false, true) => {
            let x = linear(xv);
            let x_tick = snapped(&x);
            draw!(x, log_range(yv.into_iter()).log_scale(), x_tick, tick)
        }
        (true, false) => {
            let y = linear(yv);
            let y_tick = snapped(&y);
            draw!(log_range(xv.into_iter()).log_scale(), y, tick, y_tick)
        }
        (false, false) => {
            let (x, y) = (linear(xv), linear(yv));
            let (x_tick, y_tick) = (snapped(&x), snapped(&y));
            draw!(x, y, x_tick, y_tick)
        }
    }
    Ok(())
}

/// Energy deviation of `method`'s ok runs against N at time step `dt` (Figs. 2–3).
fn deviation_against_n(rows: &[Row], method: MethodKind, dt: f64) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.method == method && r.status == Status::Ok && (r.dt / dt - 1.0).abs() < 1e-9)
        .filter_map(|r| r.energy_deviation.map(|e| (r.segments as f64, e)))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// Energy deviation of `method`'s ok runs against k at `segments` (Fig. 4).
fn deviation_against_k(rows: &[Row], method: MethodKind, segments: usize) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.method == method && r.segments == segments && r.status == Status::Ok)
        .filter_map(|r| r.energy_deviation.map(|e| (r.dt, e)))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// The time step nearest to the report's in the grid, for Figs. 2–3.
fn reports_dt(rows: &[Row]) -> f64 {
    let distance = |k: f64| (k.ln() - REPORT.dt.ln()).abs();
    rows.iter()
        .map(|r| r.dt)
        .min_by(|a, b| distance(*a).total_cmp(&distance(*b)))
        .unwrap_or(REPORT.dt)
}

/// Writes every chart into `dir`. `startup` holds the start-up kinetic energy series
/// (Fig. 1) per method; `scene_title` names the scene in the titles.
pub fn write_all(
    dir: &Path,
    rows: &[Row],
    startup: &[(MethodKind, Vec<(f64, f64)>)],
    scene_title: &str,
) -> anyhow::Result<()> {
    render_chart!(
        dir,
        "work_precision",
        work_precision,
        rows,
        &format!("Work–precision, {scene_title}")
    )?;
    render_chart!(
        dir,
        "stability_map",
        stability,
        rows,
        &format!("Stability map, {scene_title}")
    )?;
    write_startup_burst(dir, startup)?;
    write_energy_against_n(dir, rows)?;
    write_energy_against_k(dir, rows)
}

/// The energy deviation's axis: the report's criterion, against the energy after the
/// start-up burst.
fn deviation_axis() -> String {
    format!("max|E − E_ref|/|E|, E_ref at step {REFERENCE_STEP}")
}

/// A method's colour on the report's figures.
fn colour(method: MethodKind) -> RGBColor {
    shade(method, 1, 1)
}

/// Fig. 1: the kinetic energy of the first steps.
fn write_startup_burst(
    dir: &Path,
    startup: &[(MethodKind, Vec<(f64, f64)>)],
) -> anyhow::Result<()> {
    let series: Vec<_> = startup
        .iter()
        .map(|(m, pts)| (format!("{m}"), colour(*m), pts.clone()))
        .collect();
    let title = format!(
        "Fig. 1: kinetic energy at start-up (N = {}, k = {:e}, first 300 steps)",
        REPORT.segments, REPORT.dt
    );
    render_chart!(
        dir,
        "fig1_startup_burst",
        lines,
        &title,
        "time",
        "kinetic energy (m g L)",
        (false, true),
        &series
    )
}

/// Figs. 2 and 3: energy deviation against N, linear and log–log.
fn write_energy_against_n(dir: &Path, rows: &[Row]) -> anyhow::Result<()> {
    let dt = reports_dt(rows);
    let series: Vec<_> = MethodKind::ALL
        .iter()
        .map(|&m| {
            let label = format!("{m}, k = {dt:e}");
            (label, colour(m), deviation_against_n(rows, m, dt))
        })
        .filter(|s| !s.2.is_empty())
        .collect();
    render_chart!(
        dir,
        "fig2_energy_vs_n_linear",
        lines,
        "Fig. 2: energy deviation against N",
        "segments N",
        &deviation_axis(),
        (false, false),
        &series
    )?;
    render_chart!(
        dir,
        "fig3_energy_vs_n_log",
        lines,
        "Fig. 3: energy deviation against N (log–log)",
        "segments N",
        &deviation_axis(),
        (true, true),
        &series
    )
}

/// Fig. 4: energy deviation against k at the report's N.
fn write_energy_against_k(dir: &Path, rows: &[Row]) -> anyhow::Result<()> {
    let series: Vec<_> = MethodKind::ALL
        .iter()
        .map(|&m| {
            let label = format!("{m}, N = {}", REPORT.segments);
            (
                label,
                colour(m),
                deviation_against_k(rows, m, REPORT.segments),
            )
        })
        .filter(|s| !s.2.is_empty())
        .collect();
    let title = format!(
        "Fig. 4: energy deviation against k (N = {}; missing points diverged)",
        REPORT.segments
    );
    render_chart!(
        dir,
        "fig4_energy_vs_k",
        lines,
        &title,
        "time step k",
        &deviation_axis(),
        (true, true),
        &series
    )
}

#[cfg(test)]
mod tests {
    use super::tick;

    #[test]
    fn ticks_of_a_small_linear_axis_are_distinct() {
        let ticks: Vec<String> = (1..=6).map(|i| tick(&(i as f64 * 5e-4))).collect();
        assert_eq!(ticks, ["5e-4", "1e-3", "1.5e-3", "2e-3", "2.5e-3", "3e-3"]);
    }

    #[test]
    fn ticks_keep_round_values_short() {
        assert_eq!(tick(&1e-13), "1e-13");
        assert_eq!(tick(&0.25), "0.25");
        assert_eq!(tick(&-2e-5), "-2e-5");
    }
}
