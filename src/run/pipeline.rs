//! One run, on two threads: the simulation thread drives the method and produces frames, the
//! sink thread hands them to a [`FrameSink`] in batches; a bounded channel between them
//! applies back-pressure, so no frame is dropped.

use super::config::RunPlan;
use super::estimate::Shadow;
use super::probe::Probes;
use super::simulate::{self, Frame, Options, Outcome, Watch};
use super::sink::FrameSink;
use super::summary::{MAX_TIP_SAMPLES, Summary, TipSamples};
use super::theory_figures::{PullWindow, TheoryFigures};
use crate::error::ConfigError;
use crate::model::theory::Reading;
use crossbeam_channel::{Receiver, RecvTimeoutError};
use std::collections::VecDeque;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Frames in flight between the threads: enough to ride out a slow flush, small enough that
/// an interrupted run drains at once.
pub(super) const CHANNEL_FRAMES: usize = 64;

/// Frames handed to the sink together when the run is not paced to the wall clock.
pub(super) const BATCH_FRAMES: usize = 16;

/// How long a partly filled batch waits for more frames before it is handed over.
const BATCH_WAIT: Duration = Duration::from_millis(50);

/// The most frames a run makes room for at its start (a run of more grows its vectors).
const FRAMES_RESERVED: f64 = 4096.0;

/// The frames `plan` will make, as room to hold them: every frame of a run of ordinary
/// length at once, not grown as they come.
fn frames_expected(plan: &RunPlan) -> usize {
    let expected = (plan.duration * plan.log_rate).ceil() + 2.0;
    expected.clamp(0.0, FRAMES_RESERVED) as usize
}

/// Runs `plan`, handing its frames to `sink`, until the final time, divergence, or `stop`.
/// The summary says what was computed; if the sink failed, its `recording_error` says why
/// (a recording that could not be completed does not undo the run). `progress` hears each
/// frame before the sink does, from the simulation thread (its time for a progress bar, its
/// `tolerance_exceeded` for a notice).
pub fn run<S: FrameSink>(
    plan: &RunPlan,
    sink: &mut S,
    stop: &AtomicBool,
    progress: &(dyn Fn(&Frame) + Sync),
) -> Result<Summary, ConfigError> {
    let mut method = plan.build()?;
    let mut shadow = match plan.shadow()? {
        Some(shadow) if shadow_ahead(plan) => Some(shadow.ahead()),
        shadow => shadow,
    };
    let started = Instant::now();
    let (tx, rx) = crossbeam_channel::bounded::<Frame>(CHANNEL_FRAMES);
    // Paced runs show each frame as soon as it is made.
    let batch_frames = if plan.realtime.is_some() {
        1
    } else {
        BATCH_FRAMES
    };
    let (simulated, delivered) = std::thread::scope(|scope| {
        let sink = &mut *sink;
        // The receiver moves to the sink thread: if the sink fails, it is dropped with it,
        // and the simulation's next send ends the run instead of waiting for ever.
        let sink_thread = scope.spawn(move || deliver(plan, sink, rx, batch_frames));
        let simulated = simulate_and_send(
            plan,
            Simulation::of(plan, method.as_mut(), shadow.as_mut()),
            |frame| tx.send(frame).is_ok(),
            stop,
            progress,
            started,
        );
        drop(tx); // ends the sink thread's loop once it has drained the channel
        let delivered = sink_thread
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (simulated, delivered)
    });
    let (outcome, tip_samples, busy) = simulated;
    // A shadow stepped ahead spent its CPU on a thread of its own: the run's all the same.
    let busy =
        busy + Duration::from_secs_f64(shadow.as_ref().map_or(0.0, Shadow::own_thread_seconds));
    sink.end_run(outcome.time, outcome.steps);
    let recording_error = delivered.err().map(|err| err.to_string());
    Ok(Summary::new(
        plan,
        &outcome,
        tip_samples,
        busy,
        started.elapsed(),
        recording_error,
    ))
}

/// Segments from which a run of one method steps its shadow ahead on a core of its own,
/// where the machine has two or more: `rope run --method midpoint --segments 1000
/// --duration 3` (the served default, measured at k = 1/1080, its step before a calm
/// release's was doubled) then took 0.67 to 0.94 s of wall where it took 0.83 to 1.20, for
/// about 4 % more CPU (the channel, the thread); at N = 3 000, 2.83 to 3.02 s
/// where it took 3.31 to 3.48, for 8 % more (`docs/measurements.md`, "The fine rope: Newton's
/// loops by kind, the shadow's states in batches"). A coarser run's shadow costs too little
/// for it to pay.
pub const SHADOW_AHEAD_FROM: usize = 1000;

/// Whether `plan`'s shadow is stepped ahead on a core of its own: a run of one method (side by
/// side, each method already has a thread) from [`SHADOW_AHEAD_FROM`] segments, on a machine
/// with a core to spare. The estimates are the same either way, bit for bit.
fn shadow_ahead(plan: &RunPlan) -> bool {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    plan.frame_grid.is_none() && plan.segments >= SHADOW_AHEAD_FROM && cores >= 2
}

/// Runs `plan` on this thread alone, every frame kept in memory: [`run`] for a sink that does
/// no I/O (a program embedding rope, [`simulate`](super::whole::simulate)), without the
/// second thread and the channel, which cost a small run several times its steps (from 30°
/// to t = 1 at N = 12, 250 µs against 67 µs: `cargo bench --bench small_run`).
pub fn run_in_memory(plan: &RunPlan) -> Result<(Vec<Frame>, Summary), ConfigError> {
    let mut method = plan.build()?;
    let mut shadow = plan.shadow()?;
    let started = Instant::now();
    let mut frames = Vec::with_capacity(frames_expected(plan));
    let simulation = Simulation::of(plan, method.as_mut(), shadow.as_mut());
    let keep = |frame| {
        frames.push(frame);
        true
    };
    let stop = AtomicBool::new(false);
    let (outcome, tip_samples, busy) =
        simulate_and_send(plan, simulation, keep, &stop, &|_| {}, started);
    let summary = Summary::new(plan, &outcome, tip_samples, busy, started.elapsed(), None);
    Ok((frames, summary))
}

/// Why the sink could not take the run, in words: the step that failed and the sink's
/// own reason.
#[derive(Debug, thiserror::Error)]
pub(super) enum Delivery<E: std::error::Error> {
    #[error("logging the run's parameters: {0}")]
    Begin(E),
    #[error("writing frames to the recording: {0}")]
    Frames(E),
    #[error("flushing the recording: {0}")]
    Flush(E),
}

/// The sink thread: batches of up to `batch_frames`, or whatever came within [`BATCH_WAIT`]
/// (so a slow run still shows live), until the simulation has ended; then the flush.
fn deliver<S: FrameSink>(
    plan: &RunPlan,
    sink: &mut S,
    rx: Receiver<Frame>,
    batch_frames: usize,
) -> Result<(), Delivery<S::Error>> {
    sink.begin_run(plan).map_err(Delivery::Begin)?;
    let mut batch = Vec::with_capacity(batch_frames);
    let mut open = true;
    while open {
        match rx.recv() {
            Ok(frame) => batch.push(frame),
            Err(_) => break, // the simulation has ended and every frame is delivered
        }
        while batch.len() < batch_frames {
            match rx.recv_timeout(BATCH_WAIT) {
                Ok(frame) => batch.push(frame),
                Err(RecvTimeoutError::Timeout) => break,
                Err(RecvTimeoutError::Disconnected) => {
                    open = false;
                    break;
                }
            }
        }
        sink.frames(&batch).map_err(Delivery::Frames)?;
        batch.clear();
    }
    sink.flush().map_err(Delivery::Flush)
}

/// What the simulation thread steps: the method, and its shadow if it has one.
pub(super) struct Simulation<'a> {
    pub method: &'a mut dyn crate::methods::Method,
    pub watch: Option<Watch<'a>>,
}

impl<'a> Simulation<'a> {
    /// `plan`'s `method`, watched by its `shadow` (if it has one) against the plan's tolerance.
    pub fn of(
        plan: &RunPlan,
        method: &'a mut dyn crate::methods::Method,
        shadow: Option<&'a mut Shadow>,
    ) -> Self {
        let watch = shadow.map(|shadow| Watch {
            shadow,
            tolerance: plan.tolerance,
        });
        Self { method, watch }
    }
}

/// The simulation thread's work: runs the method, keeps the tip's latest samples, paces to
/// the wall clock if asked, and sends each frame (`send` says false when nobody takes them
/// any more, which ends the run). Returns the outcome, the tip samples, and the thread's CPU
/// time: what the steps and the frames cost, not the waits (pacing, a full channel), nor
/// what other threads did meanwhile.
pub(super) fn simulate_and_send(
    plan: &RunPlan,
    simulation: Simulation<'_>,
    mut send: impl FnMut(Frame) -> bool,
    stop: &AtomicBool,
    progress: &(dyn Fn(&Frame) + Sync),
    started: Instant,
) -> (Outcome, TipSamples, Duration) {
    let options = Options {
        duration: plan.duration,
        log_rate: plan.log_rate,
        frame_grid: plan.frame_grid,
    };
    let mut pull = PullWindow::default();
    let cpu = cpu_time::ThreadTime::now();
    let Simulation { method, watch } = simulation;
    // The method at its start: its tip is the scene's.
    let initial_tip = method.tip();
    let reading = |frame: &Frame| Reading {
        time: frame.time,
        initial_tip,
        tip: frame.tip(),
        tip_velocity: frame.tip_velocity,
        support_tension: frame.support_tension,
        momentum: frame.momentum,
    };
    // A scene whose summary quotes its theory at instants (the fold, at its falls) reads it
    // at every step, so that what it quotes does not depend on the frames.
    let base = simulate::EnergyBase::at_start(method);
    let mut observation = crate::methods::Observation::default();
    let quoted = plan.scene.compares_falls();
    let mut figures = TheoryFigures::default();
    // What the summary measures of the motion, on its fine grid: never at the frames.
    let mut probes = Probes::new(plan.scene, plan.dt, plan.duration, base);
    let on_step = |method: &mut dyn crate::methods::Method| {
        probes.step(method);
        if quoted {
            let frame = simulate::frame(method, &mut observation, base);
            figures.push(frame.time, &plan.scene.theory(&reading(&frame)));
        }
    };
    let mut latest = TipSamples {
        latest: VecDeque::with_capacity(frames_expected(plan).min(MAX_TIP_SAMPLES)),
        ..TipSamples::default()
    };
    let on_frame = |mut frame: Frame| {
        frame.theory = plan.scene.theory(&reading(&frame));
        latest.push(frame.time, frame.tip());
        // The plot's averaged pull, after the summary's reading (which averages its own).
        if let Some(pull) = pull.push(frame.time, &frame.theory) {
            frame.theory.push(pull);
        }
        progress(&frame);
        if let Some(speed) = plan.realtime {
            pace(started, frame.time / speed, stop);
        }
        if send(frame) {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    };
    let outcome = simulate::run_watched(method, watch, &options, Some(stop), on_step, on_frame);
    latest.theory = figures;
    latest.probes = Some(probes);
    (outcome, latest, cpu.elapsed())
}

/// Sleeps until `target_seconds` after `started`, waking early when `stop` is set.
pub(super) fn pace(started: Instant, target_seconds: f64, stop: &AtomicBool) {
    let target = started + Duration::from_secs_f64(target_seconds);
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        if now >= target {
            return;
        }
        std::thread::sleep((target - now).min(Duration::from_millis(50)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::RunConfig;

    #[test]
    fn a_channel_sink_receives_every_frame_of_the_run() {
        let plan = RunConfig {
            duration: 0.5,
            ..RunConfig::default()
        }
        .validate()
        .unwrap();
        let (mut tx, rx) = crossbeam_channel::unbounded();
        let summary = run(&plan, &mut tx, &AtomicBool::new(false), &|_| {}).unwrap();
        drop(tx);
        let times: Vec<f64> = rx.iter().map(|f| f.time).collect();
        assert_eq!(times.len() as u64, summary.frames_logged);
        assert_eq!(times.len(), 31); // t = 0, 1/60, …, 0.5
        assert!(times.windows(2).all(|w| w[0] < w[1]));
        assert!(summary.recording_error.is_none());
    }
}
