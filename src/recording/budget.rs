//! What a history costs a viewer, worked out before the run: the bytes each time unit adds
//! to what a viewer keeps, and so how long a browser page can stay open before the web
//! viewer's ceiling.
//!
//! The bytes are not modelled but measured: the run's own logger writes a stretch of
//! history (frames shaped like the run's, [`SAMPLE_UNITS`] time units past the
//! [`WARM_UP_UNITS`] in which it sends more often) into memory, and
//! the Arrow data it sends is counted. A viewer holds more than the bytes it is sent (its
//! indices and caches): [`VIEWER_PER_BYTE`] is that ratio, measured in a browser.

use super::live::HistoryRates;
use super::logger::{HISTORY_SEND_UNITS, RopeLogger};
use crate::model::{Energy, Point, SupportNow};
use crate::run::config::trimmed_fixed;
use crate::run::cost::Cost;
use crate::run::estimate::ErrorEstimate;
use crate::run::simulate::Lane;
use crate::run::{Frame, FrameSink, RunPlan};
use nalgebra::Vector2;

/// What Rerun's web viewer can hold before it stops (it traps past about 2.3 GiB of
/// WebAssembly memory, whatever it is asked to keep: rerun-io/rerun#11699, #8173).
pub const WEB_VIEWER_CEILING: f64 = 2.3 * 1024.0 * 1024.0 * 1024.0;

/// What the page holds before the history starts (the viewer itself, its fonts and render
/// buffers, the blueprint, the live picture): the largest WebAssembly memory a page held a
/// minute into a served run in headless Chromium, 760.1 MB (other soaks: 624.1, 628.5 and
/// 658.6 MB; docs/measurements.md, "A page left open").
pub const PAGE_BASELINE: f64 = 760.0e6;

/// How many bytes the web viewer's memory grows by per byte of Arrow data of history it is
/// sent (the Arrow arrays' allocated size, which rounds each small buffer up). Two long soaks
/// of the default page measured it (docs/measurements.md, "A page left open"): 1.8 at the
/// former default of 1.5 rows a time unit (168.1 MB over 46 226 time units, 2.0 kB sent a
/// time unit), and 0.77 at today's 0.75 (302.5 MB over 327 279 time units, 1.2 kB sent). The
/// page grows in steps of 33.6 MB and its allocator keeps room, so neither is exact: 1.2,
/// their geometric middle, predicts each within a factor of 1.6.
pub const VIEWER_PER_BYTE: f64 = 1.2;

/// Time units of history written to measure its bytes.
pub const SAMPLE_UNITS: f64 = 4.0 * HISTORY_SEND_UNITS;

/// Time units of history written, and not counted, before the sample: after a start the
/// history sends sooner (at 2, 4, 8, 16 and 32), so that a page's plots fill soon; from
/// then on it sends every [`HISTORY_SEND_UNITS`], which is what a page left open pays. A
/// sample a whole number of those intervals long, past the warm-up, holds exactly its
/// time units of history, whatever the sends' phase.
pub const WARM_UP_UNITS: f64 = 2.0 * HISTORY_SEND_UNITS;

/// What one time unit of a run's history costs, and how fast the run goes through them.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Arrow bytes of history sent per time unit.
    pub bytes_per_unit: f64,
    /// Time units per second of wall time: `--realtime`'s speed, or what the run's cost
    /// model predicts for one going as fast as it can.
    pub units_per_second: f64,
    /// Whether the speed is `--realtime`'s (else it is predicted).
    pub paced: bool,
}

impl Budget {
    /// The history of runs `lanes` (one plan, or several side by side) at `rates`, measured.
    pub fn measure(lanes: &[RunPlan], rates: HistoryRates) -> Self {
        let bytes_per_unit = history_bytes(lanes, rates).unwrap_or(f64::NAN) / SAMPLE_UNITS;
        let first = lanes.first();
        let paced = first.and_then(|p| p.realtime);
        let units_per_second = paced.unwrap_or_else(|| {
            // Side by side, each method has a thread: the slowest sets the pace.
            let slowest = lanes
                .iter()
                .map(|p| Cost::of_run(p.method, p.segments, p.dt, 1.0, p.log_rate).seconds)
                .fold(0.0, f64::max);
            1.0 / slowest
        });
        Self {
            bytes_per_unit,
            units_per_second,
            paced: paced.is_some(),
        }
    }

    /// Bytes a web viewer's memory grows by per second of wall time.
    pub fn viewer_bytes_per_second(&self) -> f64 {
        self.bytes_per_unit * VIEWER_PER_BYTE * self.units_per_second
    }

    /// Days a browser page can stay open before the web viewer's ceiling.
    pub fn days(&self) -> f64 {
        (WEB_VIEWER_CEILING - PAGE_BASELINE) / self.viewer_bytes_per_second() / 86_400.0
    }

    /// What the budget means, in a sentence (and, under a day, which flags lengthen it).
    pub fn text(&self) -> String {
        let days = self.days();
        let lifetime = if days >= 10.0 {
            format!("about {days:.0} days")
        } else if days >= 2.0 {
            format!("about {days:.1} days")
        } else if days * 24.0 >= 2.0 {
            format!("about {:.0} hours", days * 24.0)
        } else {
            format!("about {:.0} minutes", days * 24.0 * 60.0)
        };
        let pace = if self.paced {
            match trimmed_fixed(self.units_per_second, 3).as_str() {
                "1" => "1 time unit a second (--realtime)".to_owned(),
                speed => format!("{speed} time units a second (--realtime {speed})"),
            }
        } else {
            format!(
                "about {:.0} time units a second (as fast as it runs, predicted)",
                self.units_per_second
            )
        };
        let mut text = format!(
            "a browser page can stay open {lifetime} at this rate: its history adds {:.1} kB per time unit \
             (about {:.1} kB to the page's memory), at {pace}; the live picture adds nothing",
            self.bytes_per_unit / 1e3,
            self.bytes_per_unit * VIEWER_PER_BYTE / 1e3,
        );
        if days < 1.0 {
            text.push_str("; a lower --history-rate, or a slower --realtime, keeps it open longer");
        }
        text
    }
}

/// The Arrow bytes of [`SAMPLE_UNITS`] time units of the history of `lanes`, past its
/// [`WARM_UP_UNITS`].
fn history_bytes(lanes: &[RunPlan], rates: HistoryRates) -> Option<f64> {
    let (rec, storage) = rerun::RecordingStreamBuilder::new("rope-budget")
        .memory()
        .ok()?;
    let mut logger =
        RopeLogger::live(rec.clone(), rerun::RecordingStream::disabled(), rates).ok()?;
    match lanes {
        [one] => logger.begin_run(one).ok()?,
        several => logger.begin_lanes(several).ok()?,
    }
    logger.flush().ok()?;
    storage.take(); // what never changes: it does not grow
    let rate = lanes.first()?.log_rate;
    let warm_up = (WARM_UP_UNITS * rate).round() as u64;
    let last = ((WARM_UP_UNITS + SAMPLE_UNITS) * rate).round() as u64;
    let side_by_side = lanes.len() > 1;
    for j in 0..=last {
        let time = j as f64 / rate;
        let batch: Vec<Frame> = lanes
            .iter()
            .enumerate()
            .map(|(i, p)| sample_frame(p, j, time, side_by_side.then_some(i)))
            .collect();
        logger.frames(&batch).ok()?;
        if j == warm_up {
            // What the warm-up sent is not counted; what it gathered goes with the next send,
            // and is.
            rec.flush_blocking().ok()?;
            storage.take();
        }
    }
    // Through the last send, at the sample's end; not the gathering a flush would send.
    rec.flush_blocking().ok()?;
    Some(arrow_bytes(&storage))
}

/// The Arrow bytes of the messages `storage` holds, taken out of it.
fn arrow_bytes(storage: &rerun::sink::MemorySinkStorage) -> f64 {
    storage
        .take()
        .iter()
        .map(|msg| match msg {
            rerun::log::LogMsg::ArrowMsg(_, arrow) => arrow.batch.get_array_memory_size() as f64,
            _ => 0.0,
        })
        .sum()
}

/// A frame shaped like one of `plan`'s: its N segments hanging in a swinging arc, their
/// tension falling from the support to the tip (so that its shades of tension split the
/// rope as a swinging one's do), and every quantity a frame of the method can carry.
fn sample_frame(plan: &RunPlan, step: u64, time: f64, lane: Option<usize>) -> Frame {
    let n = plan.segments.max(1);
    let swing = 0.8 * time.sin();
    let nodes = (0..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            let angle = swing * (1.0 + s * s);
            Point::new(s * angle.sin(), s * angle.cos())
        })
        .collect::<Vec<Point>>();
    // The scene's theory beside the motion, as its frames would carry it (a fold's plots).
    let theory = plan.scene.theory(&crate::model::theory::Reading {
        time,
        initial_tip: Point::origin(),
        tip: nodes[n],
        tip_velocity: Vector2::new(time.cos(), time.sin()),
        support_tension: 1.0 + 0.2 * time.cos(),
        momentum: Vector2::new(0.5 * time.cos(), 0.5 * time.sin()),
    });
    let tension = (0..n)
        .map(|i| (1.0 + 0.3 * time.cos()) * (1.0 - (i as f64 + 0.5) / n as f64))
        .collect();
    Frame {
        step,
        time,
        nodes,
        edges: None,
        tension,
        tension_first_at: 0.5,
        energy: Energy {
            translational: 0.2 + 0.1 * time.sin(),
            rotational: 1e-3,
            potential: -0.5 - 0.1 * time.sin(),
        },
        energy_deviation: 1e-9 * time.cos(),
        // A moving support's series (its work and the balance) as a shake sends them.
        support: plan.scene.support().moves().then_some(SupportNow {
            position: 1e-3 * time.sin(),
            velocity: 1e-3 * time.cos(),
            acceleration: -1e-3 * time.sin(),
            work: 1e-4 * time.sin(),
        }),
        balance: plan.scene.support().moves().then_some(1e-12 * time.cos()),
        tip_velocity: Vector2::new(time.cos(), time.sin()),
        tip_acceleration: Vector2::new(-time.sin(), time.cos()),
        momentum: Vector2::new(0.5 * time.cos(), 0.5 * time.sin()),
        support_tension: 1.0 + 0.2 * time.cos(),
        theory,
        constraint_residual: Some(1e-13),
        velocity_residual: Some(1e-13),
        error_estimate: plan.error_estimate.then_some(ErrorEstimate {
            tip: 1e-4,
            shape: 1e-4,
        }),
        tolerance_exceeded: None,
        lane: lane.map(|index| Lane {
            index,
            method: plan.method,
            disagreement: (index > 0).then_some(1e-3),
        }),
    }
}
