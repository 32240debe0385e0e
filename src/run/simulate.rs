//! Drives a method from t = 0 to a final time: takes the steps, watches for divergence, and
//! hands out frames at a fixed rate of simulated time. Pure: what happens to a frame is the
//! caller's business (the logger streams it; studies and tests read it).

use super::estimate::{ErrorEstimate, STRIDE, Shadow};
pub use super::trust::{ENERGY_BLOWUP, REFERENCE_STEP, TENSION_BLOWUP, reference_energy};
use crate::error::Diverged;
use crate::methods::{
    Method, MethodKind, Observation, StepStatistics, stability_hint, whole_division,
};
use crate::model::Scene;
use crate::model::geometry::{self, Energy, Point};
use crate::model::support::{self, SupportNow, tip_in_the_room};
use nalgebra::Vector2;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// What the driver should do.
#[derive(Clone, Debug)]
pub struct Options {
    /// Final simulated time.
    pub duration: f64,
    /// Frames per unit of simulated time; 0 for none.
    pub log_rate: f64,
    /// Side by side: each frame's time is brought to the nearest multiple of
    /// `1 / frame_grid`, an instant that every method's step divides
    /// ([`step_on_frame_grid`]), so that the frames follow the steps and the steps do not
    /// follow the frames. `None`: a frame at the step nearest its time.
    pub frame_grid: Option<f64>,
}

/// The live error estimate a run carries: its shadow at N/2, and the tolerance the estimate
/// is held to, if one was asked for. The tip's estimate is made at every step the run shares
/// with its shadow, so that what it says of the run does not depend on the frames.
pub struct Watch<'a> {
    pub shadow: &'a mut Shadow,
    /// EPS of `--tolerance`: the first step whose tip bound (the estimate at first order,
    /// [`TipEstimate::bound`](super::estimate::TipEstimate::bound)) passes it says so.
    pub tolerance: Option<f64>,
}

/// What the live error estimate said over a run.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct EstimateOutcome {
    /// The largest tip estimate at any step the run shares with its shadow (every
    /// [`STRIDE`] steps: at every instant, whatever the frames), and when.
    pub max_tip: f64,
    pub max_tip_time: f64,
    /// The largest first-order bound of the tip's error there
    /// ([`TipEstimate::bound`](super::estimate::TipEstimate::bound)): what a tolerance is held
    /// to.
    pub max_tip_bound: f64,
    /// The largest shape estimate at any frame (the shape is compared at the frames alone,
    /// hence its name in the summary).
    #[serde(rename = "max_shape_at_frames")]
    pub max_shape: f64,
    /// The tip estimate at the last step that had one.
    pub final_tip: Option<f64>,
    /// Why the shadow stopped before the run did, if it did: no estimate after that.
    pub lost: Option<Diverged>,
}

/// One logged instant: the rope's shape and everything the viewer and the summary show.
#[derive(Clone, Debug)]
pub struct Frame {
    pub step: u64,
    pub time: f64,
    /// Node positions in the room, support … tip (N + 1 points, eqs. 14–15, from the
    /// support where it is now).
    pub nodes: Vec<Point>,
    /// Where each node sits along the string (s = 0 at the support, 1 at the tip) for rods of
    /// unequal lengths ([`Method::lengths`]); `None` for equal segments, node i at i/N.
    pub edges: Option<Vec<f64>>,
    /// Tension on each segment, the first at [`Frame::tension_first_at`] segments from the
    /// support, the others a segment apart.
    pub tension: Vec<f64>,
    /// Where the first tension sits, in segments from the support
    /// ([`crate::methods::Descriptor::tension_first_at`]).
    pub tension_first_at: f64,
    /// In the room: under a shaken support, the kinetic energy of its motion included.
    pub energy: Energy,
    /// (E − W − E_ref) / scale, E_ref the same after [`REFERENCE_STEP`] steps, W the work the
    /// support has done (none unless it moves).
    pub energy_deviation: f64,
    /// A moving support: where it is, how it moves, and the work it has done since the
    /// start; `None` for a fixed one.
    pub support: Option<SupportNow>,
    /// E − E₀ − W, E₀ the energy at the start: what the energy gained beyond the support's
    /// work (zero for the ideal string); `None` under a fixed support, where it is E − E₀.
    pub balance: Option<f64>,
    pub tip_velocity: Vector2<f64>,
    pub tip_acceleration: Vector2<f64>,
    /// The string's momentum (mass 1, [`geometry::momentum`]): what the support's force
    /// changes, beside gravity.
    pub momentum: Vector2<f64>,
    /// The tension at the support, s = 0 ([`Method::support_tension`]): the first of
    /// `tension` sits below it.
    pub support_tension: f64,
    /// The largest joint gap, for a method that solves for its joints (see
    /// [`Method::constraint_residual`]).
    pub constraint_residual: Option<f64>,
    /// |G v| before the latest velocity projection, for a method whose velocities can leave
    /// the constraints between projections (see [`Method::velocity_residual`]).
    pub velocity_residual: Option<f64>,
    /// Richardson's estimate of this frame's error, for a run with a shadow at an instant the
    /// shadow shares.
    pub error_estimate: Option<ErrorEstimate>,
    /// On the first frame at or after the instant the tip estimate first passed the
    /// tolerance (watched at every step the run shares with its shadow, frames or none): that
    /// instant and the estimate there.
    pub tolerance_exceeded: Option<Exceeded>,
    /// In a run of several methods side by side: which one this frame is of, and how far its
    /// string is from the most accurate one's. `None` in a run of one method.
    pub lane: Option<Lane>,
    /// What the scene's theory predicts of this frame's motion, beside the measurement
    /// ([`Scene::theory`]); empty for a scene without one.
    pub theory: Vec<crate::model::theory::Comparison>,
}

/// The instant a run's tip estimate first passed its tolerance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exceeded {
    pub step: u64,
    pub time: f64,
    /// The tip's first-order bound there, which passed the tolerance.
    pub estimate: f64,
}

/// A frame's place in a run of several methods side by side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lane {
    /// Where the method stands in the run's list (the plans of `FrameSink::begin_lanes`).
    pub index: usize,
    pub method: crate::methods::MethodKind,
    /// The largest distance, at equal arc length, between this string and that of the most
    /// accurate method still running (`MethodKind::BY_ACCURACY`); `None` for that one.
    pub disagreement: Option<f64>,
}

/// The largest time step at most `dt` that puts frames `1 / log_rate` apart on whole
/// numbers of [`STRIDE`] steps: methods at such steps share every frame time exactly (and
/// each its shadow's), so that their strings can be compared frame by frame.
pub fn step_on_frame_grid(dt: f64, log_rate: f64) -> f64 {
    whole_division(1.0 / (log_rate * STRIDE as f64), dt)
}

impl Frame {
    /// The free end.
    pub fn tip(&self) -> Point {
        self.nodes.last().copied().unwrap_or_else(Point::origin)
    }

    /// Where `tension[i]` sits along the string, s = 0 at the support and 1 at the tip,
    /// [`Frame::tension_first_at`] of its own segment along (graded rods: of its own rod).
    pub fn tension_s(&self, i: usize) -> f64 {
        match &self.edges {
            None => (i as f64 + self.tension_first_at) / self.tension.len() as f64,
            Some(e) => e[i] + self.tension_first_at * (e[i + 1] - e[i]),
        }
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
    /// Tip position at the last trusted state: the end of the run, or for a run that
    /// diverged the last state that passed the divergence checks ([`Outcome::trusted`]).
    pub tip: Point,
    /// Support tension (at s = 0) at the same state.
    pub support_tension: f64,
    /// The largest support tension seen at the checks (about every 1e-3 time units), and
    /// when: the load the support must bear.
    pub max_support_tension: (f64, f64),
    /// The step and time of the state that `energy_final`, `tip` and `support_tension`
    /// describe: the last one reached, or the last that passed the checks before a divergence.
    pub trusted: (u64, f64),
    /// The largest joint gap seen, for a method that solves for its joints.
    pub max_constraint_residual: Option<f64>,
    /// The largest |G v| seen, for a method that projects its velocities.
    pub max_velocity_residual: Option<f64>,
    /// How the method's own steps went, for a method that chooses them.
    pub step_statistics: Option<StepStatistics>,
    /// What the live error estimate said, for a run with a shadow.
    pub estimate: Option<EstimateOutcome>,
    /// When the tip estimate first passed the tolerance, if it did.
    pub tolerance_exceeded_at: Option<f64>,
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

/// The step at which frame `j` is taken: the multiple of `stride` steps nearest to time
/// j / rate (a run with a shadow logs at the steps its shadow shares).
fn frame_step(j: u64, options: &Options, dt: f64, stride: u64) -> u64 {
    let time = j as f64 / options.log_rate;
    let time = match options.frame_grid {
        Some(grid) => (time * grid).round() / grid,
        None => time,
    };
    stride * (time / (dt * stride as f64)).round() as u64
}

/// The energies a frame's deviation and balance are measured from: E − W after
/// [`REFERENCE_STEP`] steps and at the start, and what deviations are divided by.
#[derive(Clone, Copy, Debug)]
pub struct EnergyBase {
    pub reference: f64,
    pub start: f64,
    pub scale: f64,
}

impl EnergyBase {
    /// The base of a run of `method` from its start.
    pub fn of(method: &dyn Method) -> Self {
        let reference = reference_energy(method);
        Self {
            reference,
            start: method.energy_less_work(),
            scale: if reference.abs() >= 0.01 {
                reference.abs()
            } else {
                1.0
            },
        }
    }
}

/// Builds a frame from the method's current state.
pub fn frame(method: &mut dyn Method, obs: &mut Observation, base: EnergyBase) -> Frame {
    method.observe(obs);
    let support = method.support();
    let lengths = method.lengths();
    let mut nodes = Vec::with_capacity(obs.angle.len() + 1);
    geometry::nodes_of(&obs.angle, lengths, &mut nodes);
    let edges = lengths.map(|l| {
        let mut edges = Vec::with_capacity(l.len() + 1);
        geometry::edges(l.len(), Some(l), &mut edges);
        edges
    });
    support::into_the_room(support, &mut nodes);
    let moving = Vector2::new(support.map_or(0.0, |s| s.velocity), 0.0);
    let energy = method.energy();
    let first_at = method.descriptor().tension_first_at;
    // E − W from the energy and the support already in hand ([`Method::energy_less_work`]).
    let kept = energy.total() - support.map_or(0.0, |s| s.work);
    Frame {
        step: method.steps(),
        time: method.time(),
        nodes,
        edges,
        tension: obs.tension.clone(),
        tension_first_at: first_at,
        energy,
        energy_deviation: (kept - base.reference) / base.scale,
        balance: support.map(|_| kept - base.start),
        support,
        tip_velocity: geometry::tip_velocity_of(&obs.angle, &obs.angular_velocity, lengths)
            + moving,
        momentum: geometry::momentum_of(&obs.angle, &obs.angular_velocity, lengths) + moving,
        tip_acceleration: geometry::tip_acceleration_of(
            &obs.angle,
            &obs.angular_velocity,
            &obs.angular_acceleration,
            lengths,
        ) + Vector2::new(support.map_or(0.0, |s| s.acceleration), 0.0),
        support_tension: method.support_tension(),
        constraint_residual: method.constraint_residual(),
        velocity_residual: method.velocity_residual(),
        error_estimate: None,
        tolerance_exceeded: None,
        lane: None,
        theory: Vec::new(),
    }
}

/// Runs `method` to `options.duration`. Calls `on_frame` at every frame time; a `Break` from
/// it, or `stop` set by another thread, ends the run early (`cancelled`). Divergence ends the
/// run with `diverged` set; every frame before it has been delivered.
pub fn run(
    method: &mut dyn Method,
    options: &Options,
    stop: Option<&AtomicBool>,
    on_frame: impl FnMut(Frame) -> ControlFlow<()>,
) -> Outcome {
    run_watched(method, None, options, stop, |_| {}, on_frame)
}

/// How a run with its shadow at N/2 went ([`run_shadowed`]).
#[derive(Debug, Default)]
pub struct Shadowed {
    /// Why the run could not start (the method cannot start from the scene, or N is too
    /// coarse to halve), if it could not.
    pub refused: Option<String>,
    pub diverged: Option<Diverged>,
    /// Why the shadow stopped before the run, if it did.
    pub lost: Option<Diverged>,
    /// The largest live tip estimate at any step the run shares with its shadow.
    pub max_tip: Option<f64>,
    /// The largest first-order bound there: what a tolerance is held to.
    pub max_tip_bound: Option<f64>,
}

/// `method` from `scene` at N = `segments` and step `dt`, with its shadow at N/2, to
/// `options.duration`: the run the study's estimate check and the tolerance's pilots both
/// make. `on_frame` sees every frame, its estimate in it.
pub fn run_shadowed(
    method: MethodKind,
    scene: &Scene,
    segments: usize,
    dt: f64,
    options: &Options,
    mut on_frame: impl FnMut(&Frame),
) -> Shadowed {
    let built = method
        .build(scene, segments, dt)
        .and_then(|m| Ok((m, Shadow::new(method, scene, segments, dt)?)));
    let (mut run, mut shadow) = match built {
        Ok((run, Some(shadow))) => (run, shadow),
        Ok((_, None)) => {
            return Shadowed {
                refused: Some(format!("N = {segments} is too coarse to halve")),
                ..Shadowed::default()
            };
        }
        Err(err) => {
            return Shadowed {
                refused: Some(err.to_string()),
                ..Shadowed::default()
            };
        }
    };
    let watch = Watch {
        shadow: &mut shadow,
        tolerance: None,
    };
    let outcome = run_watched(
        run.as_mut(),
        Some(watch),
        options,
        None,
        |_| {},
        |frame| {
            on_frame(&frame);
            ControlFlow::Continue(())
        },
    );
    Shadowed {
        refused: None,
        diverged: outcome.diverged,
        lost: outcome.estimate.as_ref().and_then(|e| e.lost.clone()),
        max_tip: outcome.estimate.as_ref().map(|e| e.max_tip),
        max_tip_bound: outcome.estimate.map(|e| e.max_tip_bound),
    }
}

/// As [`run`], with the live error estimate of `watch` (if any) in every frame the shadow
/// shares, and the tolerance watched; `on_step` is shown the method at the start and after
/// every step (before that step's frame, if it has one): what a figure that must not depend
/// on the frames reads.
pub fn run_watched(
    method: &mut dyn Method,
    mut estimating: Option<Watch<'_>>,
    options: &Options,
    stop: Option<&AtomicBool>,
    mut on_step: impl FnMut(&mut dyn Method),
    mut on_frame: impl FnMut(Frame) -> ControlFlow<()>,
) -> Outcome {
    let dt = method.dt();
    // With a shadow, frames fall on the steps it shares, unless that would merge frames (a
    // log rate above 1/(2k)): then every frame is taken, and those at odd steps go without an
    // estimate.
    let shared = estimating.is_some() && options.log_rate * dt * STRIDE as f64 <= 1.0;
    let stride = if shared { STRIDE } else { 1 };
    let total_steps = (options.duration / dt).round() as u64;
    let base = EnergyBase::of(method);
    let (energy_reference, energy_scale) = (base.reference, base.scale);
    // Check the energy on the fine grid: cheap against the steps between.
    let check_every = super::trust::steps_between(dt);
    let mut outcome = Outcome {
        steps: 0,
        time: 0.0,
        energy_reference,
        energy_scale,
        energy_final: method.energy_less_work(),
        max_abs_deviation: 0.0,
        frames: 0,
        tip: tip_in_the_room(method.support(), method.angles(), method.lengths()),
        support_tension: method.support_tension(),
        max_support_tension: (method.support_tension(), method.time()),
        trusted: (method.steps(), method.time()),
        max_constraint_residual: method.constraint_residual(),
        max_velocity_residual: method.velocity_residual(),
        step_statistics: method.step_statistics(),
        estimate: estimating.as_ref().map(|_| EstimateOutcome::default()),
        tolerance_exceeded_at: None,
        diverged: None,
        cancelled: false,
    };
    let mut obs = Observation::default();
    // The shape at the last state that passed the checks: what a diverged run's summary
    // describes (its energy and support tension are in `outcome` as of that state).
    let mut trusted_angles = method.angles().to_vec();
    let mut trusted_support = method.support();
    let logging = options.log_rate > 0.0;
    let mut next_frame = 0;
    // The instant the tolerance was passed, until a frame carries it.
    let mut exceeded = None;
    loop {
        let step = method.steps();
        if let Some(watch) = estimating.as_mut() {
            exceeded = exceeded.or(watch_tip(method, watch, &mut outcome));
        }
        on_step(&mut *method);
        let at_frame = frame_step(next_frame, options, dt, stride).min(total_steps);
        if logging && at_frame <= step {
            let mut f = frame(method, &mut obs, base);
            if let Some(watch) = estimating.as_mut() {
                estimate(watch, &mut f, &mut outcome);
                f.tolerance_exceeded = exceeded.take();
            }
            outcome.frames += 1;
            // Frames closer together than a step (log rate above 1/k) share this one.
            while frame_step(next_frame, options, dt, stride) <= step {
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
            trusted_angles.copy_from_slice(method.angles());
            trusted_support = method.support();
            if stop.is_some_and(|s| s.load(Ordering::Relaxed)) {
                outcome.cancelled = true;
                break;
            }
        }
    }
    outcome.steps = method.steps();
    outcome.time = method.time();
    outcome.step_statistics = method.step_statistics();
    if outcome.diverged.is_none() {
        outcome.energy_final = method.energy_less_work();
        method.observe(&mut obs);
        outcome.tip = tip_in_the_room(method.support(), &obs.angle, method.lengths());
        outcome.support_tension = method.support_tension();
        outcome.trusted = (outcome.steps, outcome.time);
    } else {
        outcome.tip = tip_in_the_room(trusted_support, &trusted_angles, method.lengths());
    }
    outcome
}

/// At a step the run shares with its shadow, the tip's live estimate, what it says put into
/// `outcome`; the instant it first passed the tolerance, if that is this step.
fn watch_tip(
    method: &dyn Method,
    watch: &mut Watch<'_>,
    outcome: &mut Outcome,
) -> Option<Exceeded> {
    let step = method.steps();
    let said = outcome.estimate.as_mut()?;
    if said.lost.is_some() || !step.is_multiple_of(STRIDE) {
        return None;
    }
    let tip = tip_in_the_room(method.support(), method.angles(), method.lengths());
    let Some(e) = watch.shadow.tip_estimate(step, tip) else {
        said.lost = watch.shadow.lost().cloned();
        return None;
    };
    let time = method.time();
    if e.estimate > said.max_tip {
        said.max_tip = e.estimate;
        said.max_tip_time = time;
    }
    said.max_tip_bound = said.max_tip_bound.max(e.bound);
    said.final_tip = Some(e.estimate);
    let eps = watch.tolerance?;
    (e.bound > eps && outcome.tolerance_exceeded_at.is_none()).then(|| {
        outcome.tolerance_exceeded_at = Some(time);
        Exceeded {
            step,
            time,
            estimate: e.bound,
        }
    })
}

/// Puts the live error estimate into frame `f` (its tip's and its shape's), the shape's into
/// `outcome`.
fn estimate(watch: &mut Watch<'_>, f: &mut Frame, outcome: &mut Outcome) {
    let Some(said) = outcome.estimate.as_mut() else {
        return;
    };
    f.error_estimate = watch.shadow.estimate(f.step, &f.nodes, f.edges.as_deref());
    match f.error_estimate {
        Some(e) => said.max_shape = said.max_shape.max(e.shape),
        None => said.lost = said.lost.take().or_else(|| watch.shadow.lost().cloned()),
    }
}

/// Runs `method` to `duration` with no frames and no way to stop it early: the bare
/// simulation, for measurements.
pub fn run_to(method: &mut dyn Method, duration: f64) -> Outcome {
    let options = Options {
        duration,
        log_rate: 0.0,
        frame_grid: None,
    };
    run(method, &options, None, |_| ControlFlow::Continue(()))
}

/// Updates the energy statistics and says whether the run has blown up.
fn watch(method: &dyn Method, energy_reference: f64, outcome: &mut Outcome) -> Option<Diverged> {
    let step = method.steps();
    let energy = method.energy_less_work();
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
    if let Some(residual) = method.velocity_residual() {
        let largest = outcome.max_velocity_residual.unwrap_or(0.0);
        outcome.max_velocity_residual = Some(largest.max(residual));
    }
    outcome.energy_final = energy;
    outcome.support_tension = support;
    if support > outcome.max_support_tension.0 {
        outcome.max_support_tension = (support, method.time());
    }
    outcome.trusted = (step, method.time());
    None
}
