//! A sweep of the shaken support's frequency in the viewer: the free end's largest swing
//! (red) and its swing at Ω alone (green) against Ω, drawn as curves in a 2D view (Rerun's plots run along a timeline, and a sweep
//! runs along Ω), on a log scale of the support's amplitude, with the resonances of linear
//! theory marked. Redrawn, static, as each run of the sweep ends.

use super::entities::path;
use crate::model::bessel;
use crate::run::shake_figures::SweepPoint;
use rerun::RecordingStream;

/// How tall a decade of swing is drawn, in Ω's units.
const DECADE: f32 = 0.8;

/// The sweep's curves of `points` so far, for a support of `amplitude`, over its guides: a
/// line at each decade of swing / A, and at each resonance ω_n within the frequencies swept.
pub(super) fn log_sweep(
    rec: &RecordingStream,
    amplitude: f64,
    points: &[SweepPoint],
) -> rerun::RecordingStreamResult<()> {
    let height = |swing: f64| -DECADE * (swing / amplitude).max(1e-3).log10() as f32;
    let curve = |swing: fn(&SweepPoint) -> f64| -> Vec<[f32; 2]> {
        points
            .iter()
            .map(|p| [p.frequency as f32, height(swing(p))])
            .collect()
    };
    let (largest, driven) = (curve(|p| p.largest), curve(|p| p.driven));
    let (lo, hi) = SweepPoint::span(points);
    let (lo, hi) = (lo as f32, hi as f32);
    let top = largest.iter().map(|p| p[1]).fold(-2.0 * DECADE, f32::min);
    let grey = rerun::Color::from_unmultiplied_rgba(160, 160, 160, 140);
    rec.log_static(
        path::SWEEP_CURVE,
        &rerun::LineStrips2D::new([largest, driven])
            .with_radii([0.01])
            .with_colors([
                rerun::Color::from_rgb(200, 40, 40),
                rerun::Color::from_rgb(40, 150, 80),
            ])
            .with_labels(["largest swing", "swing at Ω alone"]),
    )?;
    // Decades of swing / A, labelled at the left; the resonances, labelled at the top. The
    // labels are points of their own, where they do not cover the curve.
    let mut strips = Vec::new();
    let mut marks = Vec::new();
    let mut labels = Vec::new();
    let mut decade = 0;
    while -DECADE * decade as f32 >= top - DECADE {
        let y = -DECADE * decade as f32;
        strips.push(vec![[lo, y], [hi, y]]);
        marks.push([lo - 0.35, y]);
        labels.push(format!("{} A", 10u64.pow(decade)));
        decade += 1;
    }
    let ceiling = top - 0.3;
    for n in 1..=40 {
        let omega = bessel::mode_frequency(n) as f32;
        if omega > hi {
            break;
        }
        if omega >= lo {
            strips.push(vec![[omega, 0.1], [omega, ceiling]]);
            marks.push([omega, ceiling - 0.15]);
            labels.push(format!("ω{n} = {omega:.4}"));
        }
    }
    rec.log_static(
        path::SWEEP_GUIDES,
        &rerun::LineStrips2D::new(strips)
            .with_radii([0.004])
            .with_colors([grey]),
    )?;
    rec.log_static(
        path::SWEEP_LABELS,
        &rerun::Points2D::new(marks)
            .with_radii([0.002])
            .with_colors([grey])
            .with_labels(labels)
            .with_show_labels(true),
    )
}
