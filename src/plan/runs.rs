//! The runs a request asks for, one [`Planned`] per scene: each method's validated
//! [`RunPlan`], and with `--tolerance` what the rule chose and what it rests on.

use super::choice::Choice;
use super::pilot::{FirstPilot, Pilots};
use super::tolerance;
use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::cost::Limits;
use crate::run::estimate::TipBound;
use crate::run::{RunConfig, RunPlan};

/// What `rope run` asks of each scene, its flags resolved (the command line makes it).
#[derive(Clone, Debug)]
pub struct RunRequest {
    /// The method asked for (the first of a list), or the default.
    pub method: MethodKind,
    /// The other methods of a comparison, in order, side by side with `method`; empty for
    /// a run of one method.
    pub others: Vec<MethodKind>,
    pub segments: usize,
    pub dt: Option<f64>,
    pub duration: f64,
    /// Frames per time unit: as asked, or the default.
    pub log_rate: f64,
    /// Whether `--log-rate` was given (a loose tolerance's long step then keeps it).
    pub log_rate_asked: bool,
    pub realtime: Option<f64>,
    pub allow_unstable: bool,
    pub limits: Limits,
    pub error_estimate: bool,
    pub tolerance: Option<f64>,
}

/// One run to make, and what `--tolerance` chose for it, if it chose.
#[derive(Clone, Debug)]
pub struct Planned {
    /// The run of the first method named (the only one, but for a comparison).
    pub plan: RunPlan,
    pub choice: Option<Choice>,
    /// The runs of the other methods of a comparison (`--method A,B,…`), side by side with
    /// `plan` on the same frame times; empty for a run of one method.
    pub others: Vec<RunPlan>,
    /// What the pilot runs of `--tolerance` measured, and what its choice rests on.
    pub pilots: Option<Pilots>,
}

impl Planned {
    /// Every run of this scene: `plan`, then the others of a comparison.
    pub fn lanes(&self) -> Vec<RunPlan> {
        std::iter::once(self.plan.clone())
            .chain(self.others.iter().cloned())
            .collect()
    }
}

/// Validates `request` for one scene; with `--tolerance`, also says what the rule chose
/// (telling `before_pilots` of its first pilot before one flies: [`tolerance::choose_telling`]);
/// with a list of methods, validates each (naming the one that cannot run).
pub fn plan_scene(
    request: &RunRequest,
    scene: Scene,
    before_pilots: impl FnOnce(FirstPilot),
) -> Result<Planned, ConfigError> {
    let compares = !request.others.is_empty();
    let asked = RunConfig {
        method: request.method,
        shared_frames: compares,
        scene,
        segments: request.segments,
        dt: request.dt,
        duration: request.duration,
        log_rate: request.log_rate,
        realtime: request.realtime,
        allow_unstable: request.allow_unstable,
        limits: request.limits,
        error_estimate: request.error_estimate,
        tolerance: request.tolerance,
        tip_bound: TipBound::FirstOrder,
    };
    let (mut config, choice, pilots) = match request.tolerance {
        None => (asked, None, None),
        Some(eps) => {
            // `--tolerance EPS` for this scene, this run's duration and memory: never its
            // frames, so that where and how often it is drawn changes nothing it models.
            let memory = request.limits.memory();
            let (choice, pilots) =
                tolerance::choose_telling(eps, &scene, request.duration, memory, before_pilots)?;
            // A loose tolerance may choose a step longer than the default frame
            // interval: then a frame at every step the estimate's shadow shares, unless
            // --log-rate asked for more (never more than a frame a step: below).
            let shared = 1.0 / (choice.dt * crate::run::estimate::STRIDE as f64);
            let log_rate = match request.log_rate_asked {
                true => request.log_rate,
                false => asked.log_rate.min(shared),
            };
            let chosen = RunConfig {
                method: choice.method,
                segments: choice.segments,
                dt: Some(choice.dt),
                log_rate,
                tip_bound: choice.tip_bound,
                ..asked
            };
            (chosen, Some(choice), Some(pilots))
        }
    };
    // A step the user did not set (the default, or the one --tolerance chose) does not
    // refuse the frames they asked for: past its rate, a frame at every step (the frames
    // fall on the steps: the step does not follow the frames).
    let step_not_set = choice.is_some() || (request.dt.is_none() && !compares);
    let steps = 1.0 / config.step();
    if step_not_set && steps.is_finite() && steps > 0.0 {
        config.log_rate = config.log_rate.min(steps);
    }
    let lane = |method: MethodKind| {
        RunConfig {
            method,
            ..config.clone()
        }
        .validate()
        .map_err(|err| match compares {
            true => ConfigError::MethodCannotRun {
                method: method.name(),
                reason: err.to_string(),
            },
            false => err,
        })
    };
    let plan = lane(config.method)?;
    let others = request
        .others
        .iter()
        .map(|&m| lane(m))
        .collect::<Result<_, _>>()?;
    Ok(Planned {
        plan,
        choice,
        others,
        pilots,
    })
}
