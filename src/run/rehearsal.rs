//! A run made before it was asked for: the `--tolerance` pilot that held its tolerance is the
//! very run the choice then makes (the same method, N, k, frames and shadow), so it is flown
//! once with its frames and summary kept ([`Rehearsal::fly`]), and handed to the sink in place
//! of a second flight ([`Rehearsal::replay`]). Where a held pilot was flown twice, the two
//! flights alone were about 2.6 times the bare run: mode 1 at 1e-3 cost 3.0 times the
//! cheapest run that holds it, its pilots included (`docs/measurements.md`).

use super::config::RunPlan;
use super::estimate::{Shadow, TipBound};
use super::pipeline::{self, BATCH_FRAMES, Delivery};
use super::simulate::Frame;
use super::sink::FrameSink;
use super::summary::Summary;
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

    /// Flies `plan` on this thread, every frame kept ([`pipeline::run_in_memory`]), as fast as
    /// it can: a run paced to the wall clock (`--realtime`) is paced when it is replayed.
    pub fn fly(plan: RunPlan) -> Result<Self, ConfigError> {
        let unpaced = RunPlan {
            realtime: None,
            ..plan.clone()
        };
        let (frames, summary) = pipeline::run_in_memory(&unpaced)?;
        Ok(Self {
            plan,
            frames,
            summary,
        })
    }

    /// This run as `plan`, where `plan` differs from it in its tip bound alone and the
    /// rehearsal, flown at the first-order bound, held its tolerance throughout: every other
    /// bound reads the same estimates at no more than the first order's
    /// ([`TipBound::of_first_order`]), so it holds there too, and only the summary's largest
    /// bound and its name change (a mode's pilot that holds at its second level is held to the
    /// order its two levels show, which is known only once it has flown). `None` otherwise.
    pub fn held_to(mut self, plan: &RunPlan) -> Option<Self> {
        if self.plan == *plan {
            return Some(self);
        }
        let rebound = RunPlan {
            tip_bound: plan.tip_bound,
            ..self.plan.clone()
        };
        let held = self.summary.tolerance_met == Some(true);
        if rebound != *plan || self.plan.tip_bound != TipBound::FirstOrder || !held {
            return None;
        }
        let ratio = plan.segments as f64 / Shadow::segments_of(plan.segments) as f64;
        let scale = plan.tip_bound.of_first_order(ratio);
        if let Some(estimate) = self.summary.error_estimate.as_mut() {
            estimate.max_tip_bound *= scale;
        }
        self.summary.tolerance_bound = Some(plan.tip_bound);
        self.plan = rebound;
        Some(self)
    }

    /// Hands the kept frames to `sink` as [`pipeline::run`] hands a run's (`progress` hearing
    /// each first; paced to the wall clock where the plan asks it), and returns the summary:
    /// the rehearsal's, its CPU the flight's, with the recording's error if the sink failed.
    /// The run is already made, so a `stop` set meanwhile ends the pacing, not the run: the
    /// frames left are handed over at once, and nothing made is lost.
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
            if failed.is_some() {
                break;
            }
            for frame in frames {
                progress(frame);
                let paced = self.plan.realtime.filter(|_| !stop.load(Ordering::Relaxed));
                if let Some(speed) = paced {
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
        summary.frames_logged = delivered as u64;
        summary.recording_error = failed;
        summary.wall_seconds += started.elapsed().as_secs_f64();
        summary
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::MethodKind;
    use crate::model::Scene;
    use crate::run::RunConfig;

    #[test]
    fn a_run_kept_at_first_order_and_held_to_a_tighter_bound_says_what_a_flight_at_it_says() {
        // Mode 1 at N = 32, as a mode's pilot at its second level flies: at the first-order
        // bound, then held to the order its levels show.
        let config = RunConfig {
            method: MethodKind::Chain,
            scene: Scene::Mode {
                number: 1,
                amplitude: 0.05,
            },
            segments: 32,
            dt: Some(1.0 / 120.0),
            duration: 3.0,
            tolerance: Some(1e-4),
            ..RunConfig::default()
        };
        let first = config.validate().unwrap();
        let tip_bound = TipBound::Observed {
            order: 1.7,
            safety: 1.5,
        };
        let observed = RunConfig {
            tip_bound,
            ..config.clone()
        }
        .validate()
        .unwrap();
        let kept = Rehearsal::fly(first.clone()).unwrap();
        let held = kept
            .clone()
            .held_to(&observed)
            .expect("it held at first order");
        let (frames, again) = pipeline::run_in_memory(&observed).unwrap();
        assert_eq!(held.plan, observed);
        assert_eq!(frames.len(), held.frames.len());
        assert_eq!(held.summary.tolerance_bound, again.tolerance_bound);
        assert_eq!(held.summary.tolerance_met, Some(true));
        assert_eq!(again.tolerance_met, Some(true));
        let bound = |s: &Summary| s.error_estimate.as_ref().unwrap().max_tip_bound;
        let (held, again) = (bound(&held.summary), bound(&again));
        assert!(held < bound(&kept.summary));
        assert!((held - again).abs() <= 1e-12 * again, "{held:e} {again:e}");
        // A plan that differs in anything else is another run.
        let other = RunConfig {
            segments: 30,
            tip_bound,
            ..config
        }
        .validate()
        .unwrap();
        assert!(kept.held_to(&other).is_none());
    }
}
