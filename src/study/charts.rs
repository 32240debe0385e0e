//! The study's charts, each drawn twice, as SVG and as PNG: work–precision, the stability
//! map, and the report's Figs. 1–4.

use super::axes::{linear_range, log_range};
use super::grid::{Row, Status};
use crate::methods::{MethodKind, REPORT};
use crate::run::simulate::REFERENCE_STEP;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
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
    let metrics: [(Metric, [f64; 3]); 2] = [
        (
            (
                "largest tip error over the frames (string lengths)".to_owned(),
                |r| r.tip_error,
            ),
            TIP_TARGETS,
        ),
        (
            (format!("energy deviation {}", deviation_axis()), |r| {
                r.energy_deviation
            }),
            [1e-4, 1e-6, 1e-8],
        ),
    ];
    for (panel, ((label, metric), targets)) in panels.iter().zip(metrics) {
        work_precision_panel(panel, &ok, x_range.clone(), &label, metric, targets)?;
    }
    Ok(())
}

/// The tip errors at which the work–precision chart marks the cheapest run that holds each.
pub const TIP_TARGETS: [f64; 3] = [1e-3, 1e-4, 1e-5];

/// The cheapest of `runs` (cost, error, method) whose error is at most `target`.
pub fn cheapest_holding(
    runs: &[(f64, f64, MethodKind)],
    target: f64,
) -> Option<(f64, f64, MethodKind)> {
    runs.iter()
        .copied()
        .filter(|&(_, e, _)| e <= target)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// One panel of the work–precision chart, made to answer "which method is cheapest for
/// this error?": every run a faint dot in its method's colour; each method's front (the
/// runs no other run of that method beats on both cost and error) a line, the legend one
/// entry per method; and at each of `targets` a dashed line with the cheapest run that
/// holds it ringed and named.
fn work_precision_panel<DB: DrawingBackend>(
    panel: &DrawingArea<DB, Shift>,
    ok: &[&Row],
    x_range: Range<f64>,
    label: &str,
    metric: fn(&Row) -> Option<f64>,
    targets: [f64; 3],
) -> Drawn<DB> {
    let runs: Vec<(f64, f64, MethodKind)> = ok
        .iter()
        .filter_map(|r| {
            let e = metric(r).filter(|e| *e > 0.0)?;
            Some((r.cpu_seconds, e, r.method))
        })
        .collect();
    let y_range = log_range(runs.iter().map(|r| r.1));
    let (x_lo, x_hi) = (x_range.start, x_range.end);
    let mut chart = ChartBuilder::on(panel)
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.clone().log_scale())?;
    chart
        .configure_mesh()
        .x_desc("CPU seconds (one run, one core)")
        .y_desc(label)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((SANS, 13))
        .draw()?;
    for method in MethodKind::ALL {
        let mine: Vec<(f64, f64)> = runs
            .iter()
            .filter(|r| r.2 == method)
            .map(|r| (r.0, r.1))
            .collect();
        if mine.is_empty() {
            continue;
        }
        let color = colour(method);
        chart.draw_series(
            mine.iter()
                .map(|&p| Circle::new(p, 2, color.mix(0.3).filled())),
        )?;
        let front = pareto_front(&mine);
        chart
            .draw_series(LineSeries::new(front.clone(), color.stroke_width(3)))?
            .label(format!(
                "{method}: its cheapest front ({} runs)",
                mine.len()
            ))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3))
            });
        chart.draw_series(front.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
    }
    let mut marked = false;
    for target in targets {
        if !y_range.contains(&target) {
            continue;
        }
        chart.draw_series(DashedLineSeries::new(
            [(x_lo, target), (x_hi, target)],
            6,
            4,
            BLACK.mix(0.5).stroke_width(1),
        ))?;
        let Some((cost, error, method)) = cheapest_holding(&runs, target) else {
            continue;
        };
        let color = colour(method);
        let ring = chart.draw_series(std::iter::once(Circle::new(
            (cost, error),
            9,
            BLACK.stroke_width(2),
        )))?;
        if !marked {
            ring.label("cheapest run that holds the dashed target")
                .legend(|(x, y)| Circle::new((x + 9, y), 6, BLACK.stroke_width(2)));
            marked = true;
        }
        // Just above the dashed line, to the right of the ringed run.
        let style = (SANS, 14)
            .into_font()
            .color(&color)
            .pos(Pos::new(HPos::Left, VPos::Bottom));
        chart.draw_series(std::iter::once(Text::new(
            format!("≤ {target:.0e}: {method}, {}", cost_text(cost)),
            (cost * 1.3, target),
            style,
        )))?;
    }
    legend(
        chart.configure_series_labels(),
        SeriesLabelPosition::UpperRight,
        12,
    )
}

/// CPU seconds as a label beside a marked run.
fn cost_text(seconds: f64) -> String {
    if seconds >= 0.1 {
        format!("{seconds:.2} s")
    } else {
        format!("{seconds:.1e} s")
    }
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
    use super::*;

    fn row(method: MethodKind, segments: usize, dt: f64, cpu: f64, tip: f64) -> Row {
        Row {
            method,
            segments,
            dt,
            status: Status::Ok,
            energy_deviation: Some(tip * 0.1),
            tip_error: Some(tip),
            final_tip_error: Some(tip),
            shape_error: Some(tip),
            cpu_seconds: cpu,
            ns_per_segment_step: 1.0,
            tip: None,
            shape: None,
            frame_tips: Vec::new(),
        }
    }

    /// Every chart of a study is drawn for no data, one run, and runs all alike: none may
    /// fail or hang (an empty one once computed ticks for ever).
    #[test]
    fn every_chart_draws_no_data_one_point_and_equal_values() {
        register_font().unwrap();
        let dir = std::env::temp_dir().join(format!("rope-charts-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let one = [row(MethodKind::Chain, 16, 1e-3, 0.01, 1e-4)];
        let alike = [
            row(MethodKind::Chain, 16, 1e-3, 0.01, 1e-4),
            row(MethodKind::Seed, 16, 1e-3, 0.01, 1e-4),
            row(MethodKind::Seed, 32, 1e-3, 0.01, 1e-4),
        ];
        let burst = [(MethodKind::Chain, vec![(0.0, 0.5), (0.001, 0.5)])];
        for (rows, startup) in [
            (&[][..], &[][..]),
            (&one[..], &burst[..]),
            (&alike[..], &[][..]),
        ] {
            write_all(&dir, rows, startup, "a test").unwrap();
            assert!(dir.join("work_precision.png").exists());
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn the_cheapest_run_holding_a_target_is_marked_and_none_when_none_holds() {
        let runs = [
            (1.0, 1e-3, MethodKind::Seed),
            (0.5, 5e-4, MethodKind::Chain),
            (0.1, 2e-3, MethodKind::Rattle),
        ];
        assert_eq!(
            cheapest_holding(&runs, 1e-3).map(|r| r.2),
            Some(MethodKind::Chain)
        );
        assert_eq!(
            cheapest_holding(&runs, 1e-2).map(|r| r.2),
            Some(MethodKind::Rattle)
        );
        assert!(cheapest_holding(&runs, 1e-5).is_none());
        assert!(cheapest_holding(&[], 1.0).is_none());
    }

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
