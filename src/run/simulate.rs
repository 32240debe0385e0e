//! Drives a method from t = 0 to a final time: takes the steps, watches for divergence, and
//! hands out frames at a fixed rate of simulated time. Pure: what happens to a frame is the
//! caller's business (the logger streams it; studies and tests read it).

use super::estimate::{STRIDE, Shadow, TipBound};
pub use super::frame::{EnergyBase, Exceeded, Frame, Lane, frame};
pub use super::trust::{ENERGY_BLOWUP, REFERENCE_STEP, TENSION_BLOWUP, reference_energy};
use crate::error::Diverged;
use crate::methods::{
    Method, MethodKind, Observation, StepStatistics, stability_hint, whole_division,
};
use crate::model::Scene;
use crate::model::geometry::Point;
use crate::model::support::{point_in_the_room, tip_in_the_room};
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
    /// The largest bound of the tip's error there (the run's [`TipBound`])
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

/// The largest time step at most `dt` that puts frames `1 / log_rate` apart on whole
/// numbers of [`STRIDE`] steps: methods at such steps share every frame time exactly (and
/// each its shadow's), so that their strings can be compared frame by frame.
pub fn step_on_frame_grid(dt: f64, log_rate: f64) -> f64 {
    whole_division(1.0 / (log_rate * STRIDE as f64), dt)
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
    /// The largest bound there (as `bound` says): what a tolerance is held to.
    pub max_tip_bound: Option<f64>,
}

/// `method` from `scene` at N = `segments` and step `dt`, with its shadow at N/2 bounding the
/// tip's error as `bound` says, to `options.duration`: the run the study's checks and the
/// tolerance's pilots make. `on_frame` sees every frame, its estimate in it.
pub fn run_shadowed(
    method: MethodKind,
    scene: &Scene,
    segments: usize,
    dt: f64,
    bound: TipBound,
    options: &Options,
    mut on_frame: impl FnMut(&Frame),
) -> Shadowed {
    let built = method
        .build(scene, segments, dt)
        .and_then(|m| Ok((m, Shadow::new(method, scene, segments, dt, bound)?)));
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
/// on the frames reads. The energy's reference is the run's own after [`REFERENCE_STEP`]
/// steps: the frames before it wait there for their deviation (a copy stepped ahead would
/// repeat those steps, half a small run's), unless the run is shorter.
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
    let waits = total_steps >= REFERENCE_STEP && method.steps() == 0;
    let mut base = match waits {
        true => EnergyBase::at_start(method),
        false => EnergyBase::of(method),
    };
    // The frames before the reference step wait for it: at most one a step.
    let mut waiting = Vec::with_capacity(match waits && options.log_rate > 0.0 {
        true => REFERENCE_STEP as usize,
        false => 0,
    });
    // Check the energy on the fine grid: cheap against the steps between.
    let check_every = super::trust::steps_between(dt);
    let mut outcome = Outcome {
        steps: 0,
        time: 0.0,
        energy_reference: base.reference,
        energy_scale: base.scale,
        energy_final: method.energy_less_work(),
        max_abs_deviation: 0.0,
        frames: 0,
        tip: point_in_the_room(method.support(), method.tip()),
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
            if waits && step < REFERENCE_STEP {
                waiting.push(f);
            } else if on_frame(f).is_break() {
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
        if waits && step == REFERENCE_STEP {
            base = EnergyBase::measured(base.start, method.energy_less_work());
            (outcome.energy_reference, outcome.energy_scale) = (base.reference, base.scale);
            if deliver(&mut waiting, base, &mut on_frame).is_break() {
                outcome.cancelled = true;
                break;
            }
        }
        if step.is_multiple_of(check_every) || step == total_steps || step == REFERENCE_STEP {
            if let Some(d) = watch(method, base.reference, &mut outcome) {
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
    // Ended before the reference step (diverged or stopped): measured from the start.
    if deliver(&mut waiting, base, &mut on_frame).is_break() {
        outcome.cancelled = true;
    }
    outcome.steps = method.steps();
    outcome.time = method.time();
    outcome.step_statistics = method.step_statistics();
    if outcome.diverged.is_none() {
        outcome.energy_final = method.energy_less_work();
        outcome.tip = point_in_the_room(method.support(), method.tip());
        outcome.support_tension = method.support_tension();
        outcome.trusted = (outcome.steps, outcome.time);
    } else {
        outcome.tip = tip_in_the_room(trusted_support, &trusted_angles, method.lengths());
    }
    outcome
}

/// Hands the frames that waited for the energy's reference to `on_frame`, their deviation
/// now measured from `base`.
fn deliver(
    waiting: &mut Vec<Frame>,
    base: EnergyBase,
    on_frame: &mut impl FnMut(Frame) -> ControlFlow<()>,
) -> ControlFlow<()> {
    for mut f in waiting.drain(..) {
        f.energy_deviation = base.deviation(&f.energy, f.support);
        on_frame(f)?;
    }
    ControlFlow::Continue(())
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
    let tip = point_in_the_room(method.support(), method.tip());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::MethodKind;

    /// Every frame of the seed scheme from 30° at N = 20 (a frame at every step), its energy
    /// measured from the run's own tenth step.
    fn deviations(duration: f64) -> Vec<(u64, f64)> {
        let mut method = MethodKind::Seed
            .build(&Scene::Release { angle_deg: 30.0 }, 20, 1e-3)
            .expect("valid");
        let options = Options {
            duration,
            log_rate: 1000.0,
            frame_grid: None,
        };
        let mut seen = Vec::new();
        run(method.as_mut(), &options, None, |f| {
            seen.push((f.step, f.energy_deviation));
            ControlFlow::Continue(())
        });
        seen
    }

    #[test]
    fn frames_before_the_reference_step_wait_for_it_and_read_as_a_copy_stepped_ahead_would() {
        // The seed scheme's start-up burst makes E at step 10 differ from E at the start.
        let seen = deviations(0.05);
        assert_eq!(seen.len(), 51, "a frame at every step, in order");
        assert!(seen.iter().zip(0..).all(|(&(step, _), i)| step == i));
        assert_eq!(seen[REFERENCE_STEP as usize].1, 0.0);
        // A copy stepped ten steps ahead, as a run shorter than that measures it.
        let method = MethodKind::Seed
            .build(&Scene::Release { angle_deg: 30.0 }, 20, 1e-3)
            .expect("valid");
        let ahead = EnergyBase::of(method.as_ref());
        let start = (ahead.start - ahead.reference) / ahead.scale;
        assert!(start != 0.0);
        assert_eq!(seen[0].1, start);
        // A run of fewer steps than the reference's looks ahead and reads the same.
        let short = deviations(0.005);
        assert_eq!(short.len(), 6);
        assert_eq!(short[0].1, start);
    }
}
