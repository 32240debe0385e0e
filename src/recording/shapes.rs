//! The rope's shapes as Rerun entities: the rope and its tip, the tip's trail, the tension
//! profile, the shapes a history keeps, and the shared shapes of methods side by side.
//! `logger.rs` decides when each is sent; this file knows how each is drawn.

use super::colour::{SHADE, hue_shade, shaded_strips, tension_colour};
use super::entities::path;
use crate::model::Point;
use crate::run::Frame;
use rerun::RecordingStream;
use std::collections::VecDeque;

/// Line radius of the rope, in string lengths.
pub(super) const ROPE_RADIUS: f32 = 0.006;
/// How many frames of the tip's path the trail keeps.
pub(super) const TRAIL_FRAMES: usize = 45;

/// A shape of the rope (of each method side by side) the history keeps, not yet sent.
pub(super) struct ThenShape {
    pub(super) time: f64,
    pub(super) step: i64,
    pub(super) frames: Vec<Frame>,
}

/// The "then" tip's label: the time the shape is of.
pub(super) fn then_label(time: f64) -> String {
    format!("then: t = {time:.1}")
}

/// Moves a trail on by `tips`; returns the trail as it stood at each of them when `each`.
pub(super) fn advance_trail(
    trail: &mut VecDeque<[f32; 2]>,
    tips: &[[f32; 2]],
    each: bool,
) -> Vec<Vec<[f32; 2]>> {
    let mut trails = Vec::new();
    for &tip in tips {
        if trail.len() == TRAIL_FRAMES {
            trail.pop_front();
        }
        trail.push_back(tip);
        if each {
            trails.push(trail.iter().copied().collect());
        }
    }
    trails
}

/// The rope of each frame: one 2-point strip per segment, coloured by its tension, at
/// `times` (none: static, one frame).
pub(super) fn send_rope(
    rec: &RecordingStream,
    entity: &str,
    frames: &[&Frame],
    times: Vec<rerun::TimeColumn>,
) -> rerun::RecordingStreamResult<()> {
    let mut strips = Vec::new();
    let mut colours = Vec::new();
    let mut lengths = Vec::with_capacity(frames.len());
    for f in frames {
        lengths.push(f.tension.len());
        strips.extend(f.nodes.windows(2).map(|w| [xy(&w[0]), xy(&w[1])]));
        colours.extend(f.tension.iter().map(|&t| tension_colour(t)));
    }
    rec.send_columns(
        entity,
        times,
        rerun::LineStrips2D::update_fields()
            .with_strips(strips)
            .with_colors(colours)
            .columns(lengths)?,
    )
}

/// A tip per row, at `times` (none: static, one row).
pub(super) fn send_tips(
    rec: &RecordingStream,
    entity: &str,
    tips: Vec<[f32; 2]>,
    times: Vec<rerun::TimeColumn>,
) -> rerun::RecordingStreamResult<()> {
    rec.send_columns(
        entity,
        times,
        rerun::Points2D::update_fields()
            .with_positions(tips)
            .columns_of_unit_batches()?,
    )
}

/// Where a moving support is at each frame, at `times` (none: static, one row); nothing for
/// frames under a fixed support, which the static support point marks.
pub(super) fn send_moving_support(
    rec: &RecordingStream,
    frames: &[&Frame],
    times: Vec<rerun::TimeColumn>,
) -> rerun::RecordingStreamResult<()> {
    if frames.iter().all(|f| f.balance.is_none()) {
        return Ok(());
    }
    let supports: Vec<[f32; 2]> = frames
        .iter()
        .map(|f| f.nodes.first().map_or([0.0, 0.0], xy))
        .collect();
    send_tips(rec, path::SUPPORT_NOW, supports, times)
}

/// A trail per row, at `times` (none: static, one row).
pub(super) fn send_trails(
    rec: &RecordingStream,
    entity: &str,
    trails: Vec<Vec<[f32; 2]>>,
    times: Vec<rerun::TimeColumn>,
) -> rerun::RecordingStreamResult<()> {
    rec.send_columns(
        entity,
        times,
        rerun::LineStrips2D::update_fields()
            .with_strips(trails)
            .columns_of_unit_batches()?,
    )
}

/// F(s) of each frame drawn upward, at `times` (none: static, one frame).
pub(super) fn send_profiles(
    rec: &RecordingStream,
    entity: &str,
    frames: &[&Frame],
    times: Vec<rerun::TimeColumn>,
) -> rerun::RecordingStreamResult<()> {
    let profiles: Vec<Vec<[f32; 2]>> = frames.iter().map(|f| profile(f)).collect();
    rec.send_columns(
        entity,
        times,
        rerun::LineStrips2D::update_fields()
            .with_strips(profiles)
            .columns_of_unit_batches()?,
    )
}

/// The ropes (in [`SHADE`]s of tension), tips and tension profiles of instants of several
/// methods, as rows of three entities: an instant a row.
pub(super) struct SharedShapes {
    pub(super) ropes: Vec<Vec<[f32; 2]>>,
    pub(super) rope_colours: Vec<rerun::Color>,
    pub(super) rope_lengths: Vec<usize>,
    pub(super) tips: Vec<[f32; 2]>,
    pub(super) tip_colours: Vec<rerun::Color>,
    pub(super) profiles: Vec<Vec<[f32; 2]>>,
    pub(super) per_instant: Vec<usize>,
}

impl SharedShapes {
    /// The shapes of `instants`, each frame's colour from `lane_of`; `hued`: each rope in
    /// its method's hue, tension its shade (side by side), else in the report's tension map.
    pub(super) fn of(
        instants: &[Vec<&Frame>],
        lane_of: impl Fn(&Frame) -> (rerun::Color, &'static str),
        hued: bool,
    ) -> Self {
        let mut shapes = Self {
            ropes: Vec::new(),
            rope_colours: Vec::new(),
            rope_lengths: Vec::with_capacity(instants.len()),
            tips: Vec::new(),
            tip_colours: Vec::new(),
            profiles: Vec::new(),
            per_instant: Vec::with_capacity(instants.len()),
        };
        for instant in instants {
            let before = shapes.ropes.len();
            for f in instant {
                let nodes: Vec<[f32; 2]> = f.nodes.iter().map(xy).collect();
                let (colour, _) = lane_of(f);
                let [r, g, b, _] = colour.to_array();
                let (strips, colours) = if hued {
                    shaded_strips(&nodes, &f.tension, SHADE, |t| hue_shade([r, g, b], t))
                } else {
                    shaded_strips(&nodes, &f.tension, SHADE, tension_colour)
                };
                shapes.ropes.extend(strips);
                shapes.rope_colours.extend(colours);
                shapes.tips.push(xy(&f.tip()));
                shapes.tip_colours.push(colour);
                shapes.profiles.push(profile(f));
            }
            shapes.rope_lengths.push(shapes.ropes.len() - before);
            shapes.per_instant.push(instant.len());
        }
        shapes
    }

    /// Sends the ropes, tips and (unless its path is empty) profiles at `times` (none:
    /// static, one instant).
    pub(super) fn send(
        self,
        rec: &RecordingStream,
        [segments, tips, profiles]: [&str; 3],
        times: Vec<rerun::TimeColumn>,
    ) -> rerun::RecordingStreamResult<()> {
        rec.send_columns(
            segments,
            times.clone(),
            rerun::LineStrips2D::update_fields()
                .with_strips(self.ropes)
                .with_colors(self.rope_colours)
                .columns(self.rope_lengths)?,
        )?;
        rec.send_columns(
            tips,
            times.clone(),
            rerun::Points2D::update_fields()
                .with_positions(self.tips)
                .with_colors(self.tip_colours.iter().copied())
                .columns(self.per_instant.iter().copied())?,
        )?;
        if profiles.is_empty() {
            return Ok(());
        }
        rec.send_columns(
            profiles,
            times,
            rerun::LineStrips2D::update_fields()
                .with_strips(self.profiles)
                .with_colors(self.tip_colours)
                .columns(self.per_instant)?,
        )
    }
}

/// F(s) of a frame drawn upward, y = −F (the 2D view's y points down): first the tension at
/// the support, s = 0, then each of the method's tensions where it sits (the rods' at each
/// rod's middle, the seed's a segment below each node: `Frame::tension_first_at`).
pub(super) fn profile(f: &Frame) -> Vec<[f32; 2]> {
    std::iter::once([0.0, -(f.support_tension as f32)])
        .chain(
            f.tension
                .iter()
                .enumerate()
                .map(|(i, &t)| [f.tension_s(i) as f32, -(t as f32)]),
        )
        .collect()
}

/// A point as the viewer takes it.
pub(super) fn xy(p: &Point) -> [f32; 2] {
    [p.x as f32, p.y as f32]
}
