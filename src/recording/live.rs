//! How a recording keeps a run for viewers of a run that never ends: a live picture that
//! replaces itself, and a history that grows slowly enough for a week.
//!
//! A viewer keeps every temporal row it is sent, and Rerun's web viewer stops (it traps)
//! when what it keeps passes about 2.3 GiB; data logged as *static* replaces what was there
//! before. So a run that never ends (`--duration inf`, `--loop`) or that is served
//! (`--serve-grpc`, `--web`) sends its viewers two streams of one recording:
//!
//! * **the live picture** ([`LivePicture`]): the rope, its tension colours, the tip and its
//!   trail, the tension profile and the caption, static, at every frame (at most
//!   [`LIVE_PER_SECOND`] a second of wall time). A browser page kept it for an hour with its
//!   memory flat; a native viewer on a software renderer rose in 32 MiB steps within 20
//!   minutes, its renderer's staging buffers, which Rerun never gives back; the rest grew
//!   16 MB in an hour, mostly its store keeping the history (docs/measurements.md, "A page
//!   left open").
//! * **the history** ([`Keeping::History`]): the time series at
//!   [`HistoryRates::series_per_unit`] rows per time unit and the rope's shape at
//!   [`HistoryRates::shapes_per_unit`], on the timelines, under `then/` so that scrubbing
//!   shows the rope *then* beside the live one.
//!
//! A finite run to a file or a spawned viewer keeps every frame ([`Keeping::Everything`]);
//! so does the `--save` file of a run whose viewers get the two streams.

use std::time::{Duration, Instant};

/// What a recording keeps on its timelines.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Keeping {
    /// Every frame's rope, tip, trail and profile, and every frame's time series.
    Everything,
    /// The history a user scrubs beside a live picture.
    History(HistoryRates),
}

/// How fast the history grows, per time unit of the run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HistoryRates {
    /// Rows of the time series kept per time unit (per method side by side).
    pub series_per_unit: f64,
    /// Shapes of the rope kept per time unit, for the "then" rope.
    pub shapes_per_unit: f64,
}

impl HistoryRates {
    /// The rope's shape is kept at this fraction of the series' rate: a shape of 100
    /// segments costs about as much as three rows of every series.
    pub const SHAPES_PER_ROW: f64 = 1.0 / 3.0;

    /// The default: 0.75 rows per time unit (3 every 4 time units) and a shape every 4 time
    /// units, which a browser page holds for more than a week of a run of one method at
    /// realtime, and more than 3 days of three side by side (the budget the run prints, from
    /// the growth measured in a browser: docs/measurements.md, "A page left open").
    pub const DEFAULT: Self = Self::at(0.75);

    /// Rates for `series_per_unit` rows per time unit (`--history-rate`).
    pub const fn at(series_per_unit: f64) -> Self {
        Self {
            series_per_unit,
            shapes_per_unit: series_per_unit * Self::SHAPES_PER_ROW,
        }
    }

    /// Every how many frames at `log_rate` a row of series is kept.
    pub fn series_stride(&self, log_rate: f64) -> u64 {
        (log_rate / self.series_per_unit).round().max(1.0) as u64
    }

    /// Time units between kept shapes.
    pub fn shape_interval(&self) -> f64 {
        1.0 / self.shapes_per_unit
    }
}

/// At most this many live pictures a second of wall time. A page reads every message its
/// endpoint sends as it comes, and ingests them as fast as it draws: a page drawing a few
/// frames a second (software rendering) fell behind 60 pictures a second, the backlog
/// growing in its memory; and a run going faster than the clock would flood its viewers
/// with pictures they never draw.
pub const LIVE_PER_SECOND: f64 = 20.0;

/// The caption's time is updated at most this often (a second of wall time).
const CAPTION_EVERY: Duration = Duration::from_secs(1);

/// The live picture's recording stream, and when it was last drawn.
pub struct LivePicture {
    pub rec: rerun::RecordingStream,
    last: Option<Instant>,
    caption: Option<Instant>,
}

impl LivePicture {
    pub fn new(rec: rerun::RecordingStream) -> Self {
        Self {
            rec,
            last: None,
            caption: None,
        }
    }

    /// Whether the caption's time is due for an update (and, if it is, that it is made now).
    pub fn caption_due(&mut self) -> bool {
        let now = Instant::now();
        if self
            .caption
            .is_some_and(|c| now.duration_since(c) < CAPTION_EVERY)
        {
            return false;
        }
        self.caption = Some(now);
        true
    }

    /// The caption is due at once (a new run's headline).
    pub fn caption_now(&mut self) {
        self.caption = None;
    }

    /// Whether a picture is due now (and, if it is, that one is drawn now).
    pub fn due(&mut self) -> bool {
        let gap = Duration::from_secs_f64(1.0 / LIVE_PER_SECOND);
        let now = Instant::now();
        match self.last {
            Some(last) if now.duration_since(last) < gap => false,
            _ => {
                self.last = Some(now);
                true
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_history_keeps_three_rows_every_four_time_units_and_a_shape_every_four() {
        let rates = HistoryRates::DEFAULT;
        assert_eq!(rates.series_stride(60.0), 80);
        assert!((rates.shape_interval() - 4.0).abs() < 1e-12);
        assert_eq!(HistoryRates::at(100.0).series_stride(60.0), 1);
    }
}
