//! What never changes in a recording of the rope, logged once and static: the "then"
//! rope's styling, the tension colour bar, the tension profile's axes and a shaken
//! support's track.

use super::colour::{SCALE_MAX, hue_shade, tension_colour};
use super::entities::path;
use super::shapes::ROPE_RADIUS;
use crate::model::Support;
use rerun::RecordingStream;

/// The "then" rope's styling: thinner and paler than the live one, its tip labelled
/// with its time.
pub(super) fn log_then_styling(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
    rec.log_static(
        path::THEN_SUPPORT,
        &rerun::Points2D::new([[0.0f32, 0.0]])
            .with_radii([0.02])
            .with_colors([rerun::Color::from_rgb(90, 90, 90)]),
    )?;
    rec.log_static(
        path::THEN_SEGMENTS,
        &rerun::LineStrips2D::update_fields().with_radii([ROPE_RADIUS]),
    )?;
    rec.log_static(
        path::THEN_TIP,
        &rerun::Points2D::update_fields()
            .with_radii([0.015])
            .with_colors([rerun::Color::from_rgb(20, 20, 20)])
            .with_show_labels(true),
    )?;
    rec.log_static(
        path::THEN_TIPS,
        &rerun::Points2D::update_fields()
            .with_radii([0.018])
            .with_show_labels(true),
    )?;
    // Spans the swing, as the live view's colour bar does, so the two views match.
    rec.log_static(
        path::THEN_FRAME,
        &rerun::LineStrips2D::new([[[-1.0f32, 1.12], [1.0, 1.12]]])
            .with_radii([0.002])
            .with_colors([rerun::Color::from_unmultiplied_rgba(160, 160, 160, 140)]),
    )
}

/// A static colour bar below the swing, F from 0 to [`SCALE_MAX`], labelled at its ends:
/// the report's map, or side by side (`hued`) a grey ramp of the shades each method's
/// hue takes. Spanning the swing's width, it also keeps the view's extent steady.
pub(super) fn log_scale(rec: &RecordingStream, hued: bool) -> rerun::RecordingStreamResult<()> {
    let pieces = 25;
    let (x0, width, y) = (-1.0f32, 2.0f32, 1.12f32);
    let strips = (0..pieces).map(|i| {
        let a = x0 + width * i as f32 / pieces as f32;
        let b = x0 + width * (i + 1) as f32 / pieces as f32;
        [[a, y], [b, y]]
    });
    let colors = (0..pieces).map(|i| {
        let f = SCALE_MAX * (i as f64 + 0.5) / pieces as f64;
        if hued {
            hue_shade([200, 200, 200], f)
        } else {
            tension_colour(f)
        }
    });
    let mut labels = vec![String::new(); pieces];
    labels[pieces / 2] = if hued {
        format!("tension: dark F = 0 … light F ≥ {SCALE_MAX} m g, each rope in its method's colour")
    } else {
        format!("tension: red F = 0 … yellow F ≥ {SCALE_MAX} m g")
    };
    rec.log_static(
        path::SCALE,
        &rerun::LineStrips2D::new(strips)
            .with_colors(colors)
            .with_radii([0.02])
            .with_labels(labels),
    )
}

/// Static axes for the tension profile: s from the support (0) to the tip (1) along the
/// bottom, its ticks labelled below it, F drawn upward with guide lines at F = 0.5, 1, 1.5
/// and 2.
pub(super) fn log_profile_axes(rec: &RecordingStream) -> rerun::RecordingStreamResult<()> {
    let grey = rerun::Color::from_unmultiplied_rgba(160, 160, 160, 140);
    let mut strips = vec![[[0.0f32, 0.0], [1.0, 0.0]], [[0.0, 0.0], [0.0, -2.0]]];
    let mut labels = vec![String::new(), String::new()];
    for f in [0.5f32, 1.0, 1.5, 2.0] {
        strips.push([[0.0, -f], [1.0, -f]]);
        labels.push(format!("F = {f}"));
    }
    let mut colors = vec![grey; strips.len()];
    // Unseen lines below the axis and above F = 2 (y points down): the view fits its data,
    // not the labels drawn below and over it, and in a short panel (the live layout's) the
    // s labels and the top F label were cut.
    for y in [PROFILE_MARGIN, -2.0 - PROFILE_MARGIN] {
        strips.push([[0.0, y], [1.0, y]]);
        labels.push(String::new());
        colors.push(rerun::Color::from_unmultiplied_rgba(0, 0, 0, 0));
    }
    rec.log_static(
        path::PROFILE_AXES,
        &rerun::LineStrips2D::new(strips)
            .with_radii([0.002])
            .with_colors(colors)
            .with_labels(labels),
    )?;
    // The s axis's ticks, on it, labelled by their values alone: the view's title names the
    // axis ("s: support 0 … tip 1"), and in a narrow panel longer labels overlapped.
    let ticks = [0.0f32, 0.5, 1.0];
    let points: Vec<[f32; 2]> = ticks.iter().map(|&s| [s, 0.0]).collect();
    let names: Vec<String> = ticks.iter().map(|s| format!("{s}")).collect();
    rec.log_static(
        path::PROFILE_TICKS,
        &rerun::Points2D::new(points)
            .with_radii([0.006])
            .with_colors([grey])
            .with_labels(names)
            .with_show_labels(true),
    )
}

/// How far below the tension profile's s axis, and above its F = 2 line, its view reaches (in
/// string lengths, F in m g): room for the labels in a panel a quarter of the window high.
const PROFILE_MARGIN: f32 = 0.35;

/// A shaken support's track: a line from −A to A through the support's rest position, along
/// which the rope's top end slides, and the support's label saying so (nothing for a fixed
/// support).
pub(super) fn log_support_track(
    rec: &RecordingStream,
    support: Support,
) -> rerun::RecordingStreamResult<()> {
    let Support::Shaken { amplitude, .. } = support else {
        return Ok(());
    };
    let a = amplitude as f32;
    rec.log_static(
        path::SUPPORT_TRACK,
        &rerun::LineStrips2D::new([[[-a, 0.0f32], [a, 0.0]]])
            .with_radii([0.004])
            .with_colors([rerun::Color::from_rgb(90, 90, 90)]),
    )?;
    rec.log_static(
        path::SUPPORT,
        &rerun::Points2D::update_fields()
            .with_radii([0.008])
            .with_labels([format!("support, shaken ±{amplitude}")]),
    )?;
    rec.log_static(
        path::SUPPORT_NOW,
        &rerun::Points2D::update_fields()
            .with_radii([0.02])
            .with_colors([rerun::Color::from_rgb(90, 90, 90)]),
    )
}
