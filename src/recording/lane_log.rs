//! What the logger keeps for each method's frames (a lane): where its entities go, its
//! colour and name side by side, its trail, and its time series not yet sent.

use super::entities::{HISTORY_LEAVES_OUT, SERIES, SIDE_BY_SIDE};
use super::live::Keeping;
use super::shapes::TRAIL_FRAMES;
use crate::run::{Frame, RunPlan};
use std::collections::VecDeque;

/// Room for the time series of a batch of frames without reallocating.
const BATCH_SERIES_CAPACITY: usize = 32;

/// The time series of one frame, one value per [`SERIES`] entry.
pub(super) type SeriesRow = (f64, i64, [f64; SERIES.len()]);

/// What the logger keeps for one method's frames: where its entities go, its trail, and its
/// time series not yet sent. A run of one method has one, with the plain entity paths.
pub(super) struct LaneLog {
    /// Where the method stands among several side by side; `None` in a run of one method.
    pub(super) index: Option<usize>,
    /// The method's name side by side.
    pub(super) name: &'static str,
    /// The method's colour side by side (its finest shade on the study's charts).
    pub(super) colour: rerun::Color,
    /// What its entity paths end with: "" alone, "/{method}" side by side.
    pub(super) suffix: String,
    pub(super) trail: VecDeque<[f32; 2]>,
    pub(super) series: Vec<SeriesRow>,
    /// Every how many frames a row of time series is kept: 1 alone; side by side, enough to
    /// keep [`SIDE_BY_SIDE_SERIES_RATE`] rows per time unit (the plots redraw their whole
    /// history every frame, and a browser on a small machine could not keep up with more);
    /// for a history, its own rate, if that is lower.
    pub(super) series_stride: u64,
    /// Whether only the series a history keeps are sent.
    pub(super) history: bool,
    /// Frames of this lane seen so far.
    pub(super) frames_seen: u64,
    /// Which series' styling has been logged, bit i for [`SERIES`]`[i]` (bit 63 for the
    /// tolerance's): a series is styled when it is first sent, so that a recording holds no
    /// entity its scene never logs.
    pub(super) styled: u64,
}

/// Rows of time series per time unit each of several methods side by side sends at most.
const SIDE_BY_SIDE_SERIES_RATE: f64 = 10.0;

impl LaneLog {
    /// The one lane of a run of one method (`plan` none before the first run).
    pub(super) fn alone(plan: Option<&RunPlan>, keeping: Keeping) -> Self {
        let stride = match (keeping, plan) {
            (Keeping::History(rates), Some(plan)) => rates.series_stride(plan.log_rate),
            _ => 1,
        };
        Self::new(None, "", [0, 0, 0], stride, keeping)
    }

    /// The lane of the method at `index` among several side by side.
    pub(super) fn of(index: usize, plan: &RunPlan, keeping: Keeping) -> Self {
        let mut stride = (plan.log_rate / SIDE_BY_SIDE_SERIES_RATE).ceil().max(1.0) as u64;
        if let Keeping::History(rates) = keeping {
            stride = stride.max(rates.series_stride(plan.log_rate));
        }
        Self::new(
            Some(index),
            plan.method.name(),
            plan.method.descriptor().colours.1,
            stride,
            keeping,
        )
    }

    pub(super) fn new(
        index: Option<usize>,
        name: &'static str,
        [r, g, b]: [u8; 3],
        series_stride: u64,
        keeping: Keeping,
    ) -> Self {
        Self {
            index,
            name,
            colour: rerun::Color::from_rgb(r, g, b),
            suffix: index.map_or(String::new(), |_| format!("/{name}")),
            trail: VecDeque::with_capacity(TRAIL_FRAMES),
            series: Vec::with_capacity(BATCH_SERIES_CAPACITY),
            series_stride,
            history: keeping != Keeping::Everything,
            frames_seen: 0,
            styled: 0,
        }
    }

    /// `entity`'s path for this lane.
    pub(super) fn at(&self, entity: &str) -> String {
        format!("{entity}{}", self.suffix)
    }

    /// Whether this lane sends the time series of `entity`.
    pub(super) fn sends(&self, entity: &str) -> bool {
        match self.index {
            None => !(self.history && HISTORY_LEAVES_OUT.contains(&entity)),
            Some(_) => SIDE_BY_SIDE.contains(&entity),
        }
    }

    /// Whether `frame` is of this lane.
    pub(super) fn owns(&self, frame: &Frame) -> bool {
        frame.lane.map(|l| l.index) == self.index
    }
}

/// The colour and name of the method `frame` is of, among `lanes` (dark grey and no name
/// if none owns it).
pub(super) fn style_of(lanes: &[LaneLog], frame: &Frame) -> (rerun::Color, &'static str) {
    lanes
        .iter()
        .find(|l| l.owns(frame))
        .map_or((rerun::Color::from_rgb(20, 20, 20), ""), |l| {
            (l.colour, l.name)
        })
}
