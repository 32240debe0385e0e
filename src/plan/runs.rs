//! The runs a request asks for, one [`Planned`] per scene: each method's validated
//! [`RunPlan`], and with `--tolerance` what the rule chose and what it rests on.

use super::choice::Choice;
use super::pilot::{FirstPilot, Pilots, Rehearse};
use super::tolerance;
use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::cost::Limits;
use crate::run::estimate::TipBound;
use crate::run::rehearsal::Rehearsal;
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
    /// The pilot that held, flown as `plan` with its frames kept: the run, made already
    /// ([`Rehearsal::replay`] hands it to the sink).
    pub rehearsal: Option<Rehearsal>,
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
    let (mut config, choice, mut pilots) = match request.tolerance {
        None => (asked, None, None),
        Some(eps) => {
            // `--tolerance EPS` for this scene, this run's duration and memory: never its
            // frames, so that where and how often it is drawn changes nothing it models.
            let memory = request.limits.memory();
            // A pilot of a single method's run flies as the run its choice would make, so
            // that the one that holds is not flown again.
            let rehearse = |choice: &Choice| {
                let plan = chosen(&asked, request, choice).validate().ok()?;
                Rehearsal::fits(&plan).then_some(plan)
            };
            let rehearse: Rehearse<'_> = match compares {
                true => &|_| None,
                false => &rehearse,
            };
            let duration = request.duration;
            let (choice, pilots) =
                tolerance::choose_telling(eps, &scene, duration, memory, rehearse, before_pilots)?;
            (chosen(&asked, request, &choice), Some(choice), Some(pilots))
        }
    };
    // A step the user did not set (the default) does not refuse the frames they asked for:
    // past its rate, a frame at every step, as for a step --tolerance chose ([`chosen`]).
    let step_not_set = request.dt.is_none() && !compares;
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
    // The pilot that held, flown as this very run (a check: the plan it flew is this one, but
    // perhaps for the tip bound its levels showed once it had flown).
    let rehearsal = pilots
        .as_mut()
        .and_then(|p| p.rehearsal.take())
        .and_then(|r| r.held_to(&plan));
    Ok(Planned {
        plan,
        choice,
        others,
        pilots,
        rehearsal,
    })
}

/// The run `choice` makes of what was `asked`: its method, N, k and tip bound, with a frame at
/// every step the estimate's shadow shares where a loose tolerance chose a step longer than the
/// default frame interval, unless --log-rate asked for more, and never more than a frame a step
/// (the frames fall on the steps: the step does not follow the frames).
fn chosen(asked: &RunConfig, request: &RunRequest, choice: &Choice) -> RunConfig {
    let shared = 1.0 / (choice.dt * crate::run::estimate::STRIDE as f64);
    let log_rate = match request.log_rate_asked {
        true => request.log_rate,
        false => asked.log_rate.min(shared),
    };
    RunConfig {
        method: choice.method,
        segments: choice.segments,
        dt: Some(choice.dt),
        log_rate: log_rate.min(1.0 / choice.dt),
        tip_bound: choice.tip_bound,
        ..asked.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::pilot::Basis;
    use crate::run::pipeline;
    use std::sync::atomic::AtomicBool;

    /// `rope run --scene mode --tolerance EPS --duration 3` at `log_rate` frames a unit (asked),
    /// side by side with `others` where there are some.
    fn mode_request(eps: f64, log_rate: f64, others: Vec<MethodKind>) -> RunRequest {
        RunRequest {
            method: MethodKind::Chain,
            others,
            segments: 100,
            dt: None,
            duration: 3.0,
            log_rate,
            log_rate_asked: true,
            realtime: None,
            allow_unstable: false,
            limits: Limits::default(),
            error_estimate: true,
            tolerance: Some(eps),
        }
    }

    // Past the mode theory's small swings, so that its pilots fly.
    const MODE_1: Scene = Scene::Mode {
        number: 1,
        amplitude: 0.2,
    };

    #[test]
    fn a_pilot_that_holds_is_the_run_frame_for_frame_and_is_not_flown_again() {
        // Mode 1 at 1e-3 is held by the chain's first pilot (N = 16); at 600 frames a unit
        // asked, a frame at each of its steps.
        for log_rate in [10.0, 600.0] {
            let planned = plan_scene(&mode_request(1e-3, log_rate, vec![]), MODE_1, |_| {})
                .expect("mode 1 at 1e-3 is served");
            assert_eq!(planned.pilots.as_ref().map(|p| p.basis), Some(Basis::Held));
            let rehearsal = planned
                .rehearsal
                .expect("the held pilot was flown as the run");
            assert_eq!(rehearsal.plan, planned.plan);
            // A second flight of the plan makes the same frames, bit for bit.
            let (frames, summary) = pipeline::run_in_memory(&planned.plan).unwrap();
            assert_eq!(frames.len(), rehearsal.frames.len());
            assert!(frames.len() > 30, "{} frames", frames.len());
            for (again, kept) in frames.iter().zip(&rehearsal.frames) {
                assert_eq!(again.time, kept.time);
                assert_eq!(again.nodes, kept.nodes);
                assert_eq!(again.tension, kept.tension);
                assert_eq!(again.error_estimate, kept.error_estimate);
            }
            let tips = [summary.tip, rehearsal.summary.tip].map(|t| (t.x, t.y));
            assert_eq!(tips[0], tips[1]);
            assert_eq!(summary.tolerance_met, Some(true));
            assert_eq!(rehearsal.summary.tolerance_met, Some(true));
            // Handed to a sink: every frame, in order, and the run's summary.
            let (mut tx, rx) = crossbeam_channel::unbounded();
            let replayed = rehearsal.replay(&mut tx, &AtomicBool::new(false), &|_| {});
            drop(tx);
            let times: Vec<f64> = rx.iter().map(|f| f.time).collect();
            let kept: Vec<f64> = rehearsal.frames.iter().map(|f| f.time).collect();
            assert_eq!(times, kept);
            assert_eq!(replayed.frames_logged, kept.len() as u64);
            assert_eq!(replayed.status, crate::run::Status::Ok);
            assert!(replayed.recording_error.is_none());
        }
    }

    #[test]
    fn a_replay_stopped_while_paced_hands_over_every_frame_at_once() {
        // Paced to the wall clock, and stopped before it starts: the run is made already, so
        // the stop ends the pacing, and every frame reaches the sink at once.
        let request = RunRequest {
            realtime: Some(1.0),
            ..mode_request(1e-3, 60.0, vec![])
        };
        let planned = plan_scene(&request, MODE_1, |_| {}).unwrap();
        let rehearsal = planned
            .rehearsal
            .expect("the held pilot was flown as the run");
        let (mut tx, rx) = crossbeam_channel::unbounded();
        let started = std::time::Instant::now();
        let replayed = rehearsal.replay(&mut tx, &AtomicBool::new(true), &|_| {});
        assert!(
            started.elapsed().as_secs_f64() < 1.0,
            "paced though stopped"
        );
        drop(tx);
        assert_eq!(rx.iter().count(), rehearsal.frames.len());
        assert_eq!(replayed.frames_logged, rehearsal.frames.len() as u64);
        assert_eq!(replayed.status, crate::run::Status::Ok);
    }

    #[test]
    fn runs_side_by_side_or_chosen_by_a_model_are_flown_as_before() {
        // Side by side, the pilot that holds is not the run (the lanes fly together).
        let side = mode_request(1e-3, 30.0, vec![MethodKind::Midpoint]);
        let planned = plan_scene(&side, MODE_1, |_| {}).unwrap();
        assert_eq!(planned.pilots.as_ref().map(|p| p.basis), Some(Basis::Held));
        assert!(planned.rehearsal.is_none());
        // At 1e-4 no pilot holds: the run chosen by the pilots' model is flown.
        let planned = plan_scene(&mode_request(1e-4, 60.0, vec![]), MODE_1, |_| {}).unwrap();
        assert_ne!(planned.pilots.as_ref().map(|p| p.basis), Some(Basis::Held));
        assert!(planned.rehearsal.is_none());
    }
}
