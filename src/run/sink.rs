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

/// A sink that may not be there (a table not asked for): the frames go to it if it is.
impl<S: FrameSink> FrameSink for Option<S> {
    type Error = S::Error;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), Self::Error> {
        self.as_mut().map_or(Ok(()), |s| s.begin_run(plan))
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), Self::Error> {
        self.as_mut().map_or(Ok(()), |s| s.frames(frames))
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        self.as_mut().map_or(Ok(()), FrameSink::flush)
    }

    fn end_run(&mut self, time: f64, steps: u64) {
        if let Some(s) = self.as_mut() {
            s.end_run(time, steps);
        }
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), Self::Error> {
        self.as_mut().map_or(Ok(()), |s| s.begin_lanes(plans))
    }

    fn lane_ended(&mut self, lane: usize, why: &Diverged) -> Result<(), Self::Error> {
        self.as_mut().map_or(Ok(()), |s| s.lane_ended(lane, why))
    }
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

/// Why one of two sinks could not take the run.
#[derive(Debug, thiserror::Error)]
pub enum EitherFailed<A: std::error::Error, B: std::error::Error> {
    #[error(transparent)]
    First(A),
    #[error(transparent)]
    Second(B),
}

/// Two sinks of different kinds that each take every frame (the recording and the tables):
/// each call goes to the first, then the second; the first error ends it.
impl<A: FrameSink, B: FrameSink> FrameSink for (A, B) {
    type Error = EitherFailed<A::Error, B::Error>;

    fn begin_run(&mut self, plan: &RunPlan) -> Result<(), Self::Error> {
        self.0.begin_run(plan).map_err(EitherFailed::First)?;
        self.1.begin_run(plan).map_err(EitherFailed::Second)
    }

    fn frames(&mut self, frames: &[Frame]) -> Result<(), Self::Error> {
        self.0.frames(frames).map_err(EitherFailed::First)?;
        self.1.frames(frames).map_err(EitherFailed::Second)
    }

    fn flush(&mut self) -> Result<(), Self::Error> {
        self.0.flush().map_err(EitherFailed::First)?;
        self.1.flush().map_err(EitherFailed::Second)
    }

    fn end_run(&mut self, time: f64, steps: u64) {
        self.0.end_run(time, steps);
        self.1.end_run(time, steps);
    }

    fn begin_lanes(&mut self, plans: &[RunPlan]) -> Result<(), Self::Error> {
        self.0.begin_lanes(plans).map_err(EitherFailed::First)?;
        self.1.begin_lanes(plans).map_err(EitherFailed::Second)
    }

    fn lane_ended(&mut self, lane: usize, why: &Diverged) -> Result<(), Self::Error> {
        self.0.lane_ended(lane, why).map_err(EitherFailed::First)?;
        self.1.lane_ended(lane, why).map_err(EitherFailed::Second)
    }
}
