//! `rope run`: a simulation thread produces frames, a logger thread writes them to a Rerun
//! recording; a bounded channel between them applies back-pressure, so no frame is dropped.

use crate::analysis;
use crate::error::ConfigError;
use crate::geometry::Point;
use crate::logger::RopeLogger;
use crate::method::MethodKind;
use crate::scene::Scene;
use crate::simulate::{self, Frame, Options};
use crate::summary::{EnergySummary, Status, Summary, Xy};
use anyhow::Context as _;
use crossbeam_channel::RecvTimeoutError;
use std::collections::VecDeque;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Frames in flight between the threads: enough to ride out a slow flush, small enough that
/// an interrupted run drains at once.
const CHANNEL_FRAMES: usize = 64;

/// Frames logged together as columns when the run is not paced to the wall clock.
const BATCH_FRAMES: usize = 16;

/// How long a partly filled batch waits for more frames before it is sent.
const BATCH_WAIT: Duration = Duration::from_millis(50);

/// How long the end of a run waits for a viewer to take the last data.
const FLUSH_TIMEOUT: Duration = Duration::from_secs(5);

/// Tip samples the summary keeps (the latest), so that an endless run's memory stays flat.
pub const MAX_TIP_SAMPLES: usize = 1 << 16;

/// A validated run.
#[derive(Clone, Debug, PartialEq)]
pub struct RunConfig {
    pub method: MethodKind,
    pub scene: Scene,
    pub segments: usize,
    pub dt: f64,
    pub duration: f64,
    pub log_rate: f64,
    /// Pace to the wall clock: 1 time unit = 1 s / speed.
    pub realtime: Option<f64>,
}

impl RunConfig {
    /// Checks every parameter, naming the one that is wrong and what would work.
    /// `dt: None` picks the method's default for the segment count. A seed time step past
    /// the estimated stability limit is refused unless `allow_unstable`.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        method: MethodKind,
        scene: Scene,
        segments: usize,
        dt: Option<f64>,
        duration: f64,
        log_rate: f64,
        realtime: Option<f64>,
        allow_unstable: bool,
    ) -> Result<Self, ConfigError> {
        let dt = dt.unwrap_or_else(|| method.default_dt(segments.max(1)));
        if duration.is_nan() || duration < 0.0 {
            return Err(ConfigError::Duration(duration));
        }
        if !(log_rate.is_finite() && log_rate > 0.0) {
            return Err(ConfigError::LogRate(log_rate));
        }
        if let Some(speed) = realtime
            && !(speed.is_finite() && speed > 0.0)
        {
            return Err(ConfigError::Realtime(speed));
        }
        // Building the method validates the scene, segments and dt as the method needs.
        method.build(&scene, segments, dt)?;
        let limit = method.stability_limit(segments);
        if method == MethodKind::Seed && dt > limit && !allow_unstable {
            return Err(ConfigError::UnstableTimeStep {
                method: method.name(),
                segments,
                dt,
                limit,
            });
        }
        if log_rate * dt > 1.0 {
            return Err(ConfigError::LogRateAboveSteps {
                log_rate,
                steps_per_unit: 1.0 / dt,
            });
        }
        Ok(Self {
            method,
            scene,
            segments,
            dt,
            duration,
            log_rate,
            realtime,
        })
    }

    /// The parameters as a Markdown document, logged so that a recording explains itself.
    pub fn markdown(&self) -> String {
        let scene = match self.scene {
            Scene::Release { angle_deg } => {
                format!("release: straight, at rest, {angle_deg}° below the horizontal")
            }
            Scene::Mode { number, amplitude } => {
                format!("mode {number} of the hanging string, tip amplitude {amplitude}")
            }
        };
        format!(
            "# rope run\n\n| parameter | value |\n|---|---|\n| method | {} |\n| scene | {} |\n| segments N | {} |\n| time step k | {:.3e} |\n| duration | {} |\n| frames per time unit | {} |\n\nUnits: L = g = 1, time in sqrt(L/g). y points down. Rope colour: tension, RGB (255, 200·F, 0).",
            self.method, scene, self.segments, self.dt, self.duration, self.log_rate
        )
    }

    fn angle_deg(&self) -> f64 {
        match self.scene {
            Scene::Release { angle_deg } => angle_deg,
            Scene::Mode { .. } => 90.0,
        }
    }
}

/// Runs `config`, streaming frames through `logger` when given (logging off otherwise), until
/// the final time, divergence, or `stop`. Returns the summary; the recording is flushed, or
/// the summary's `recording_error` says why it could not be. The run is placed on the
/// logger's timelines after the runs it logged before. `progress` hears the simulated time
/// of each frame, from the simulation thread.
pub fn run(
    config: &RunConfig,
    mut logger: Option<&mut RopeLogger>,
    stop: &AtomicBool,
    progress: &(dyn Fn(f64) + Sync),
) -> anyhow::Result<Summary> {
    let mut method = config
        .method
        .build(&config.scene, config.segments, config.dt)?;
    let options = Options {
        duration: config.duration,
        log_rate: config.log_rate,
    };
    let started = Instant::now();
    let (tx, rx) = crossbeam_channel::bounded::<Frame>(CHANNEL_FRAMES);
    let streaming = logger.is_some();
    if let Some(logger) = logger.as_deref_mut() {
        logger
            .begin_run(&config.markdown())
            .context("logging the run's parameters")?;
    }
    let (outcome, samples, busy, logged) = std::thread::scope(|scope| {
        let logger_thread = scope.spawn(|| -> anyhow::Result<()> {
            let Some(logger) = logger.as_deref_mut() else {
                return Ok(());
            };
            // Frames go out in batches of up to BATCH_FRAMES, or as soon as the simulation
            // pauses for BATCH_WAIT (a slow run still shows live); paced runs send each frame.
            // Each batch carries its own time columns, so no per-thread time context is used.
            let batch_frames = if config.realtime.is_some() {
                1
            } else {
                BATCH_FRAMES
            };
            let mut batch = Vec::with_capacity(batch_frames);
            let mut open = true;
            while open {
                match rx.recv() {
                    Ok(frame) => batch.push(frame),
                    Err(_) => break, // the simulation has ended and every frame is logged
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
                logger
                    .log_frames(&batch)
                    .context("writing frames to the recording")?;
                batch.clear();
            }
            logger
                .send_series()
                .context("writing frames to the recording")?;
            logger
                .recording()
                .flush_with_timeout(FLUSH_TIMEOUT)
                .context("flushing the recording")?;
            Ok(())
        });
        let simulation = scope.spawn(|| {
            let mut samples = VecDeque::new();
            let mut waiting = Duration::ZERO;
            let outcome = simulate::run(method.as_mut(), &options, Some(stop), |frame| {
                let tip = frame.tip();
                if samples.len() == MAX_TIP_SAMPLES {
                    samples.pop_front();
                }
                samples.push_back([frame.time, tip.x, tip.y]);
                progress(frame.time);
                let wait_started = Instant::now();
                if let Some(speed) = config.realtime {
                    pace(started, frame.time / speed, stop);
                }
                let sent = if streaming {
                    tx.send(frame).is_ok()
                } else {
                    true
                };
                waiting += wait_started.elapsed();
                if sent {
                    ControlFlow::Continue(())
                } else {
                    ControlFlow::Break(())
                }
            });
            drop(tx); // ends the logger's loop once it has drained the channel
            (outcome, samples, started.elapsed().saturating_sub(waiting))
        });
        let (outcome, samples, busy) = simulation.join().expect("the simulation thread panicked");
        let logged = logger_thread.join().expect("the logger thread panicked");
        (outcome, samples, busy, logged)
    });
    // A recording that could not be completed (a viewer gone, a disk full) does not undo the
    // run: the summary still says what was computed, and carries the error for the caller.
    let recording_error = logged.err().map(|err| format!("{err:#}"));
    if let Some(logger) = logger {
        logger.end_run(outcome.time, outcome.steps);
    }
    let wall = started.elapsed().as_secs_f64();
    let status = if outcome.diverged.is_some() {
        Status::Diverged
    } else if outcome.cancelled {
        Status::Interrupted
    } else {
        Status::Ok
    };
    let period = match config.scene {
        Scene::Mode { .. } => {
            analysis::period_from_zero_crossings(samples.iter().map(|s| (s[0], s[1])))
        }
        Scene::Release { .. } => None,
    };
    let segment_steps = (outcome.steps as f64 * config.segments as f64).max(1.0);
    let tip: Point = outcome.tip;
    Ok(Summary {
        method: config.method,
        scene: config.scene.name(),
        segments: config.segments,
        dt: config.dt,
        angle_deg: config.angle_deg(),
        duration: config.duration,
        steps: outcome.steps,
        status,
        diverged: outcome.diverged.clone(),
        wall_seconds: wall,
        ns_per_segment_step: busy.as_secs_f64() * 1e9 / segment_steps,
        frames_logged: outcome.frames,
        energy: EnergySummary {
            reference: outcome.energy_reference,
            r#final: outcome.energy_final,
            max_abs_deviation: outcome.max_abs_deviation,
            max_rel_deviation: outcome.max_rel_deviation(),
        },
        tip: Xy { x: tip.x, y: tip.y },
        support_tension: outcome.support_tension,
        tip_samples: samples.into(),
        period,
        recording_error,
    })
}

/// Sleeps until `target_seconds` after `started`, waking early when `stop` is set.
fn pace(started: Instant, target_seconds: f64, stop: &AtomicBool) {
    let target = started + Duration::from_secs_f64(target_seconds);
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        if now >= target {
            return;
        }
        std::thread::sleep((target - now).min(Duration::from_millis(50)));
    }
}
