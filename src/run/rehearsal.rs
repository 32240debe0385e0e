//! A run made before it was asked for: the `--tolerance` pilot that held its tolerance is the
//! very run the choice then makes (the same method, N, k, frames and shadow), so it is flown
//! once with its frames and summary kept ([`Rehearsal::fly`]), and handed to the sink in place
//! of a second flight ([`Rehearsal::replay`]). Where a held pilot was flown twice, the two
//! flights alone were about 2.6 times the bare run: mode 1 at 1e-3 cost 3.0 times the
//! cheapest run that holds it, its pilots included (`docs/measurements.md`).

use super::config::RunPlan;
use super::pipeline::{self, BATCH_FRAMES, Delivery};
use super::simulate::Frame;
use super::sink::FrameSink;
use super::summary::{Status, Summary};
use crate::error::ConfigError;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Frames times nodes a rehearsal may keep: some 64 MiB of frames (about 32 bytes a node: its
/// position, where it sits, its rod's tension). A pilot whose frames would take more flies bare,
/// and if it holds, it is flown again as the run.
pub const KEPT_NODE_FRAMES: u64 = 1 << 21;

/// A run flown with every frame kept: what a pilot that holds hands over as the run.
#[derive(Clone)]
pub struct Rehearsal {
    /// The run it is: the plan the choice would make ([`RunConfig::validate`]).
    ///
    /// [`RunConfig::validate`]: super::RunConfig::validate
    pub plan: RunPlan,
    pub frames: Vec<Frame>,
    pub summary: Summary,
}

impl std::fmt::Debug for Rehearsal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Rehearsal")
            .field("plan", &self.plan)
            .field("frames", &self.frames.len())
            .field("status", &self.summary.status)
            .finish()
    }
}

impl Rehearsal {
    /// Whether `plan`'s frames fit in [`KEPT_NODE_FRAMES`], so that it may be flown as one.
    pub fn fits(plan: &RunPlan) -> bool {
        let frames = (plan.duration * plan.log_rate).ceil() + 1.0;
        frames * (plan.segments as f64 + 1.0) <= KEPT_NODE_FRAMES as f64
    }

    /// Flies `plan` on this thread, every frame kept ([`pipeline::run_in_memory`]).
    pub fn fly(plan: RunPlan) -> Result<Self, ConfigError> {
        let (frames, summary) = pipeline::run_in_memory(&plan)?;
        Ok(Self {
            plan,
            frames,
            summary,
        })
    }

    /// Hands the kept frames to `sink` as [`pipeline::run`] hands a run's (`progress` hearing
    /// each first; paced to the wall clock where the plan asks it), and returns the summary:
    /// the rehearsal's, its CPU the flight's, with the recording's error if the sink failed. A
    /// `stop` set meanwhile ends the delivery: the summary then says the run was interrupted,
    /// its frames counted up to there.
    pub fn replay<S: FrameSink>(
        &self,
        sink: &mut S,
        stop: &AtomicBool,
        progress: &(dyn Fn(&Frame) + Sync),
    ) -> Summary {
        let started = Instant::now();
        let mut summary = self.summary.clone();
        let batch = match self.plan.realtime {
            Some(_) => 1,
            None => BATCH_FRAMES,
        };
        let mut delivered = 0;
        let mut failed = sink
            .begin_run(&self.plan)
            .err()
            .map(|e| Delivery::Begin(e).to_string());
        for frames in self.frames.chunks(batch) {
            if failed.is_some() || stop.load(Ordering::Relaxed) {
                break;
            }
            for frame in frames {
                progress(frame);
                if let Some(speed) = self.plan.realtime {
                    pipeline::pace(started, frame.time / speed, stop);
                }
            }
            failed = sink
                .frames(frames)
                .err()
                .map(|e| Delivery::Frames(e).to_string());
            delivered += frames.len();
        }
        if let Err(err) = sink.flush() {
            failed = failed.or(Some(Delivery::Flush(err).to_string()));
        }
        sink.end_run(summary.trusted.time, summary.trusted.step);
        if delivered < self.frames.len() && failed.is_none() {
            summary.status = Status::Interrupted;
        }
        summary.frames_logged = delivered as u64;
        summary.recording_error = failed;
        summary.wall_seconds += started.elapsed().as_secs_f64();
        summary
    }
}
