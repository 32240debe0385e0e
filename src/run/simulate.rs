//! Drives a method from t = 0 to a final time: takes the steps, watches for divergence, and
//! hands out frames at a fixed rate of simulated time. Pure: what happens to a frame is the
//! caller's business (the logger streams it; studies and tests read it).

use crate::error::Diverged;
use crate::methods::{Method, Observation, stability_hint};
use crate::model::geometry::{self, Energy, Point};
use nalgebra::Vector2;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// The step after which the energy is taken as the reference (the report's criterion: after
/// the start-up burst, since the initial straight state violates the support condition (9)).
pub const REFERENCE_STEP: u64 = 10;

/// An energy change this large, in units of m g L, is beyond anything the swing can do (its
/// whole potential range is 1/2): the run has blown up even if every number is still finite.
pub const ENERGY_BLOWUP: f64 = 1.0;

/// A support tension this large is beyond anything the swing can do (≲ 5/4 from rest).
pub const TENSION_BLOWUP: f64 = 1.0e3;

/// What the driver should do.
#[derive(Clone, Debug)]
pub struct Options {
    /// Final simulated time.
    pub duration: f64,
    /// Frames per unit of simulated time; 0 for none.
    pub log_rate: f64,
}

/// One logged instant: the rope's shape and everything the viewer and the summary show.
#[derive(Clone, Debug)]
pub struct Frame {
    pub step: u64,
    pub time: f64,
    /// Node positions, support … tip (N + 1 points, eqs. 14–15).
    pub nodes: Vec<Point>,
    /// Tension on each segment.
    pub tension: Vec<f64>,
    pub energy: Energy,
    /// (E − E_ref) / scale, E_ref the energy after [`REFERENCE_STEP`] steps.
    pub energy_deviation: f64,
    pub tip_velocity: Vector2<f64>,
    pub tip_acceleration: Vector2<f64>,
    pub support_tension: f64,
    /// The largest joint gap, for a method that solves for its joints (see
    /// [`Method::constraint_residual`]).
    pub constraint_residual: Option<f64>,
}

impl Frame {
    /// The free end.
    pub fn tip(&self) -> Point {
        self.nodes.last().copied().unwrap_or_else(Point::origin)
    }
}

/// How a run ended and what it measured.
#[derive(Clone, Debug)]
pub struct Outcome {
    pub steps: u64,
    pub time: f64,
    /// E_ref, the total energy after [`REFERENCE_STEP`] steps.
    pub energy_reference: f64,
    /// What relative deviations are divided by: |E_ref|, or m g L = 1 where |E_ref| < 0.01
    /// (the horizontal release has E = 0).
    pub energy_scale: f64,
    pub energy_final: f64,
    /// Largest |E − E_ref| seen after the reference step.
    pub max_abs_deviation: f64,
    pub frames: u64,
    /// Tip position at the last state reached.
    pub tip: Point,
    pub support_tension: f64,
    /// The largest joint gap seen, for a method that solves for its joints.
    pub max_constraint_residual: Option<f64>,
    /// Set when the run stopped because its numbers could no longer be trusted.
    pub diverged: Option<Diverged>,
    /// Set when the caller or the stop flag ended the run early.
    pub cancelled: bool,
}

impl Outcome {
    /// Largest relative energy deviation, the report's accuracy criterion.
    pub fn max_rel_deviation(&self) -> f64 {
        self.max_abs_deviation / self.energy_scale
    }
}

/// The step at which frame `j` is taken: the step nearest to time j / rate.
fn frame_step(j: u64, rate: f64, dt: f64) -> u64 {
    (j as f64 / (rate * dt)).round() as u64
}

/// Builds a frame from the method's current state.
pub fn frame(
    method: &mut dyn Method,
    obs: &mut Observation,
    energy_reference: f64,
    energy_scale: f64,
) -> Frame {
    method.observe(obs);
    let mut nodes = Vec::with_capacity(obs.angle.len() + 1);
    geometry::nodes(&obs.angle, &mut nodes);
    let energy = method.energy();
    Frame {
        step: method.steps(),
        time: method.time(),
        nodes,
        tension: obs.tension.clone(),
        energy,
        energy_deviation: (energy.total() - energy_reference) / energy_scale,
        tip_velocity: geometry::tip_velocity(&obs.angle, &obs.angular_velocity),
        tip_acceleration: geometry::tip_acceleration(
            &obs.angle,
            &obs.angular_velocity,
            &obs.angular_acceleration,
        ),
        support_tension: obs.tension.first().copied().unwrap_or(0.0),
        constraint_residual: method.constraint_residual(),
    }
}

/// The energy after [`REFERENCE_STEP`] steps, from a copy of the method (so frames before
/// that step can already report their deviation). Falls back to the initial energy when the
/// copy cannot get there.
pub fn reference_energy(method: &dyn Method) -> f64 {
    let mut probe = method.box_clone();
    for _ in 0..REFERENCE_STEP {
        if probe.step().is_err() {
            return method.energy().total();
        }
    }
    probe.energy().total()
}

/// Runs `method` to `options.duration`. Calls `on_frame` at every frame time; a `Break` from
/// it, or `stop` set by another thread, ends the run early (`cancelled`). Divergence ends the
/// run with `diverged` set; every frame before it has been delivered.
pub fn run(
    method: &mut dyn Method,
    options: &Options,
    stop: Option<&AtomicBool>,
    mut on_frame: impl FnMut(Frame) -> ControlFlow<()>,
) -> Outcome {
    let dt = method.dt();
    let total_steps = (options.duration / dt).round() as u64;
    let energy_reference = reference_energy(method);
    let energy_scale = if energy_reference.abs() >= 0.01 {
        energy_reference.abs()
    } else {
        1.0
    };
    // Check the energy about every 1e-3 time units: cheap against the steps between.
    let check_every = ((1e-3 / dt).round() as u64).clamp(1, 1000);
    let mut outcome = Outcome {
        steps: 0,
        time: 0.0,
        energy_reference,
        energy_scale,
        energy_final: method.energy().total(),
        max_abs_deviation: 0.0,
        frames: 0,
        tip: Point::origin(),
        support_tension: method.support_tension(),
        max_constraint_residual: method.constraint_residual(),
        diverged: None,
        cancelled: false,
    };
    let mut obs = Observation::default();
    let logging = options.log_rate > 0.0;
    let mut next_frame = 0;
    loop {
        let step = method.steps();
        if logging && frame_step(next_frame, options.log_rate, dt) <= step {
            let f = frame(method, &mut obs, energy_reference, energy_scale);
            outcome.frames += 1;
            // Frames closer together than a step (log rate above 1/k) share this one.
            while frame_step(next_frame, options.log_rate, dt) <= step {
                next_frame += 1;
            }
            if on_frame(f).is_break() {
                outcome.cancelled = true;
                break;
            }
        }
        if step >= total_steps {
            break;
        }
        if let Err(d) = method.step() {
            outcome.diverged = Some(d);
            break;
        }
        let step = method.steps();
        if step.is_multiple_of(check_every) || step == total_steps || step == REFERENCE_STEP {
            if let Some(d) = watch(method, energy_reference, &mut outcome) {
                outcome.diverged = Some(d);
                break;
            }
            if stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
                outcome.cancelled = true;
                break;
            }
        }
    }
    outcome.steps = method.steps();
    outcome.time = method.time();
    if outcome.diverged.is_none() {
        outcome.energy_final = method.energy().total();
        method.observe(&mut obs);
        outcome.tip = geometry::tip(&obs.angle);
        outcome.support_tension = obs.tension.first().copied().unwrap_or(0.0);
    }
    outcome
}

/// Runs `method` to `duration` with no frames and no way to stop it early: the bare
/// simulation, for measurements.
pub fn run_to(method: &mut dyn Method, duration: f64) -> Outcome {
    let options = Options {
        duration,
        log_rate: 0.0,
    };
    run(method, &options, None, |_| ControlFlow::Continue(()))
}

/// Updates the energy statistics and says whether the run has blown up.
fn watch(method: &dyn Method, energy_reference: f64, outcome: &mut Outcome) -> Option<Diverged> {
    let step = method.steps();
    let energy = method.energy().total();
    let deviation = (energy - energy_reference).abs();
    if let Some(residual) = method.constraint_residual() {
        let largest = outcome.max_constraint_residual.unwrap_or(0.0);
        outcome.max_constraint_residual = Some(largest.max(residual));
    }
    let support = method.support_tension();
    let hint = || {
        let (d, dt) = (method.descriptor(), method.dt());
        if dt > d.stability_limit(method.segments()) {
            format!(" ({})", stability_hint(d, method.segments(), dt))
        } else {
            String::new()
        }
    };
    // Before the reference step the start-up burst (the initial state violates eq. (9)) is
    // expected and says nothing about stability; only non-finite energy counts then.
    let judged = step >= REFERENCE_STEP;
    if !energy.is_finite() || (judged && deviation > ENERGY_BLOWUP) {
        return Some(Diverged {
            step,
            time: method.time(),
            reason: format!(
                "the energy grew without bound: E = {energy:.3e} against E_ref = {energy_reference:.4}{}",
                hint()
            ),
        });
    }
    if support.abs() > TENSION_BLOWUP {
        return Some(Diverged {
            step,
            time: method.time(),
            reason: format!(
                "the support tension grew without bound: F_0 = {support:.3e}{}",
                hint()
            ),
        });
    }
    if judged {
        outcome.max_abs_deviation = outcome.max_abs_deviation.max(deviation);
    }
    None
}
