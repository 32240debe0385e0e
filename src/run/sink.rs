//! Where a run's frames go: the seam between running and recording. The pipeline hands every
//! frame to a [`FrameSink`] and knows nothing of what it does with them; Rerun's recording is
//! one sink, `()` drops them, and a channel hands them to another thread (a consumer that is
//! not Rerun: a CSV writer, a test).

use super::config::RunPlan;
use super::simulate::Frame;
use crate::error::Diverged;

/// Receives the frames of runs, in order. For each run the pipeline calls [`begin_run`]
/// once, [`frames`] with batches in time order, [`flush`] once after the last frame, and
/// [`end_run`] once, from one thread at a time.
///
/// [`begin_run`]: FrameSink::begin_run
/// [`frames`]: FrameSink::frames
/// [`flush`]: FrameSink::flush
/// [`end_run`]: FrameSink::end_run
pub trait FrameSink: Send {
    /// Why frames could not be taken; it ends the run, and the summary reports it.
    type Error: std::error::Error + Send + Sync + 'static;

    /// A run starts, with these parameters.
    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), Self::Error>;

    /// The next frames of the run, oldest first.
    fn frames(&mut self, frames: &[Frame]) -> Result<(), Self::Error>;

    /// The run has produced its last frame: deliver everything taken so far.
    fn flush(&mut self) -> Result<(), Self::Error>;

    /// The run reached simulated `time` after `steps` steps (the next one starts there).
    fn end_run(&mut self, time: f64, steps: u64);

    /// Several methods start side by side (`--method A,B,…`), one plan each, on the same
    /// frame times; their frames carry a [`Lane`](super::simulate::Lane). Called instead of
    /// [`begin_run`](FrameSink::begin_run); by default, it begins the first method's run.
    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), Self::Error> {
        match plans.first() {
            Some(plan) => self.begin_run(plan),
            None => Ok(()),
        }
    }

    /// The method at `lane` in the plans of [`begin_lanes`](FrameSink::begin_lanes) stopped
    /// early, for `why` (the others go on). By default, nothing is done with it.
    fn lane_ended(&mut self, _lane: usize, _why: &Diverged) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// Takes every frame and keeps none: a run measured, not recorded.
impl FrameSink for () {
    type Error = std::convert::Infallible;

    fn begin_run(&mut self, _plan: &RunPlan) -> Result<(), Self::Error> {
        Ok(())
    }

    fn frames(&mut self, _frames: &[Frame]) -> Result<(), Self::Error> {
        Ok(())
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }

    fn end_run(&mut self, _time: f64, _steps: u64) {}
}

/// Several sinks that each take every frame (a file that keeps every frame beside viewers
/// that get a live picture): each call goes to each in turn, the first error ends it.
impl<S: FrameSink> FrameSink for Vec<S> {
    type Error = S::Error;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), Self::Error> {
        self.iter_mut().try_for_each(|s| s.begin_run(plan))
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), Self::Error> {
        self.iter_mut().try_for_each(|s| s.frames(frames))
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        self.iter_mut().try_for_each(FrameSink::flush)
    }

    fn end_run(&mut self, time: f64, steps: u64) {
        self.iter_mut().for_each(|s| s.end_run(time, steps));
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), Self::Error> {
        self.iter_mut().try_for_each(|s| s.begin_lanes(plans))
    }

    fn lane_ended(&mut self, lane: usize, why: &Diverged) -> Result<(), Self::Error> {
        self.iter_mut().try_for_each(|s| s.lane_ended(lane, why))
    }
}

/// The receiving end of the channel has gone: nobody takes the frames any more.
#[derive(Debug, thiserror::Error)]
#[error("the frames' receiver has gone")]
pub struct ReceiverGone;

/// Hands each frame to another thread.
impl FrameSink for crossbeam_channel::Sender<Frame> {
    type Error = ReceiverGone;

    fn begin_run(&mut self, _plan: &RunPlan) -> Result<(), Self::Error> {
        Ok(())
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), Self::Error> {
        frames
            .iter()
            .try_for_each(|frame| self.send(frame.clone()).map_err(|_| ReceiverGone))
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }

    fn end_run(&mut self, _time: f64, _steps: u64) {}
}
