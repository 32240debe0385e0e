//! The charts of the long studies: `long_run` (the energy error over a long swing) and the
//! report's scheme's blow-up (`divergence_map`, `sawtooth`).

use super::blow_up::{Lifetime, SEGMENTS, Sawtooth};
use super::charts::{Series, lines, render_chart, shade};
use super::long_run::LongRun;
use crate::methods::REPORT;
use plotters::prelude::*;
use std::path::Path;

/// `long_run.svg`/`.png`: |E − E_ref| against t, log–log, one line per long run.
pub fn write_long_runs(dir: &Path, runs: &[LongRun]) -> anyhow::Result<()> {
    let series: Vec<Series> = runs
        .iter()
        .map(|r| {
            let same: Vec<_> = runs.iter().filter(|o| o.method == r.method).collect();
            let i = same.iter().position(|o| std::ptr::eq(*o, r)).unwrap_or(0);
            let mut name = format!("{}, {}", r.method, r.scene);
            if runs.iter().any(|o| o.method == r.method && o.dt != r.dt) {
                name += &format!(", k = {:e}", r.dt);
            }
            if let Some(d) = &r.diverged {
                name += &format!(" (diverged at t = {:.1})", d.time);
            }
            let points = r
                .bins
                .iter()
                .filter(|b| b.max_abs_deviation > 0.0)
                .map(|b| (b.t, b.max_abs_deviation))
                .collect();
            (name, shade(r.method, i, same.len()), points)
        })
        .collect();
    render_chart!(
        dir,
        "long_run",
        lines,
        "Energy error over a long swing (N = 100)",
        "t (time units)",
        "max |E − E_ref| in each bin",
        (true, true),
        &series
    )
}

/// `divergence_map` (time to divergence against k, one line per N, log–log) and `sawtooth`
/// (φ_i minus its smoothed profile along s at instants before the blow-up).
pub fn write_blow_up(
    dir: &Path,
    lifetimes: &[Lifetime],
    saw: Option<&Sawtooth>,
) -> anyhow::Result<()> {
    let counts = SEGMENTS;
    let map: Vec<Series> = counts
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let points = lifetimes
                .iter()
                .filter(|l| l.segments == n)
                .filter_map(|l| Some((l.dt, l.diverged_at?)))
                .collect();
            (
                format!("N = {n}"),
                shade(REPORT.method, i, counts.len()),
                points,
            )
        })
        .collect();
    render_chart!(
        dir,
        "divergence_map",
        lines,
        &format!("When the {} scheme blows up", REPORT.method),
        "time step k",
        "time to divergence",
        (true, true),
        &map
    )?;
    let Some(saw) = saw else {
        return Ok(());
    };
    let count = saw.profiles.len();
    let profiles: Vec<Series> = saw
        .profiles
        .iter()
        .enumerate()
        .map(|(i, (t, profile))| {
            (
                format!("t = {t:.2} ({:.1} before)", saw.diverged_at - t),
                shade(REPORT.method, i, count),
                profile.clone(),
            )
        })
        .collect();
    render_chart!(
        dir,
        "sawtooth",
        lines,
        &format!(
            "{}, N = {}, k = {:e}: the sawtooth before the blow-up at t = {:.2}",
            saw.method, saw.segments, saw.dt, saw.diverged_at
        ),
        "s (along the string, support = 0)",
        "φ_i − (φ_{i−1} + 2φ_i + φ_{i+1})/4 (rad)",
        (false, false),
        &profiles
    )
}
