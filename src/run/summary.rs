//! The run's summary: a JSON document (field names are a contract) and a short text for
//! people.

use super::config::RunPlan;
use super::estimate::Shadow;
use super::simulate::{EstimateOutcome, Outcome, REFERENCE_STEP};
use crate::error::Diverged;
use crate::methods::{MethodKind, StepStatistics};
use crate::model::analysis;
use crate::model::{Point, Scene};
use serde::Serialize;
use std::collections::VecDeque;
use std::time::Duration;

/// Tip samples the summary keeps (the latest), so that an endless run's memory stays flat.
pub const MAX_TIP_SAMPLES: usize = 1 << 16;

/// The tip's latest `[t, x, y]` samples, at most [`MAX_TIP_SAMPLES`].
#[derive(Clone, Debug, Default)]
pub struct TipSamples(VecDeque<[f64; 3]>);

impl TipSamples {
    /// Adds the tip at `time`, forgetting the oldest sample when full.
    pub fn push(&mut self, time: f64, tip: Point) {
        if self.0.len() == MAX_TIP_SAMPLES {
            self.0.pop_front();
        }
        self.0.push_back([time, tip.x, tip.y]);
    }
}

/// How the run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// Reached the final time.
    Ok,
    /// Stopped because its numbers could no longer be trusted (see `diverged`).
    Diverged,
    /// Stopped early by Ctrl-C / SIGTERM; everything up to then is kept.
    Interrupted,
}

/// Energy statistics (eqs. 13–16), relative to the value after [`REFERENCE_STEP`] steps.
#[derive(Clone, Debug, Serialize)]
pub struct EnergySummary {
    pub reference: f64,
    pub r#final: f64,
    pub max_abs_deviation: f64,
    pub max_rel_deviation: f64,
}

/// The step and time of the state a summary describes.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Trusted {
    pub step: u64,
    pub time: f64,
}

/// A position in the plane (x away from the support, y down).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Xy {
    pub x: f64,
    pub y: f64,
}

/// Everything a run reports, written by `--summary FILE`.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    pub method: MethodKind,
    /// The scene itself, for the text (the JSON has its name and angle).
    #[serde(skip)]
    pub initial: Scene,
    pub scene: &'static str,
    pub segments: usize,
    pub dt: f64,
    pub angle_deg: f64,
    pub duration: f64,
    pub steps: u64,
    pub status: Status,
    pub diverged: Option<Diverged>,
    pub wall_seconds: f64,
    pub ns_per_segment_step: f64,
    pub frames_logged: u64,
    /// `final` is the energy of the last trusted state (see `trusted`).
    pub energy: EnergySummary,
    /// The state that `energy.final`, `tip` and `support_tension` describe: the end of the
    /// run, or, for a run that diverged, the last state that passed the divergence checks
    /// (the diverged values themselves are only in `diverged.reason`).
    pub trusted: Trusted,
    pub tip: Xy,
    pub support_tension: f64,
    /// The largest joint gap |g_j| seen, for a method that solves for its joints (`rattle`,
    /// `midpoint`): how far the rods came apart, at round-off when all is well.
    pub constraint_residual: Option<f64>,
    /// The largest |G v| seen before a velocity projection, for a method whose velocities
    /// leave the constraints between projections (`midpoint`).
    pub velocity_residual: Option<f64>,
    /// How the method's own steps went, for a method that chooses them (`midpoint`): how
    /// many, the shortest, the fastest rod, Newton's failures and solves, and the kinetic
    /// energy the velocity projections removed and put back.
    pub step_statistics: Option<StepStatistics>,
    /// The live error estimate (Richardson against the shadow at N/2): its largest and final
    /// tip values, its largest shape value; absent for a run without a shadow.
    pub error_estimate: Option<EstimateOutcome>,
    /// The tip error `--tolerance` asked for.
    pub tolerance: Option<f64>,
    /// Whether the live tip estimate stayed within the tolerance for the whole run; absent
    /// without a tolerance, or where the estimate was lost before the end (`error_estimate.lost`).
    pub tolerance_met: Option<bool>,
    /// When the tip estimate first passed the tolerance.
    pub tolerance_exceeded_at: Option<f64>,
    /// `[t, x, y]` of the tip at every logged frame.
    pub tip_samples: Vec<[f64; 3]>,
    /// Oscillation period from the tip's zero crossings, for the `mode` scene.
    pub period: Option<f64>,
    /// Why the recording could not be completed (e.g. the viewer went away), if it could not.
    pub recording_error: Option<String>,
}

impl Summary {
    /// The summary of a run of `plan` that ended in `outcome`. `busy` is the time spent
    /// computing, `wall` the whole run's.
    pub fn new(
        plan: &RunPlan,
        outcome: &Outcome,
        tip_samples: TipSamples,
        busy: Duration,
        wall: Duration,
        recording_error: Option<String>,
    ) -> Self {
        let status = if outcome.diverged.is_some() {
            Status::Diverged
        } else if outcome.cancelled {
            Status::Interrupted
        } else {
            Status::Ok
        };
        let samples: Vec<[f64; 3]> = tip_samples.0.into();
        let period = match plan.scene {
            Scene::Mode { .. } => {
                analysis::period_from_zero_crossings(samples.iter().map(|s| (s[0], s[1])))
            }
            Scene::Release { .. } => None,
        };
        let segment_steps = (outcome.steps as f64 * plan.segments as f64).max(1.0);
        Self {
            method: plan.method,
            initial: plan.scene,
            scene: plan.scene.name(),
            segments: plan.segments,
            dt: plan.dt,
            angle_deg: plan.angle_deg(),
            duration: plan.duration,
            steps: outcome.steps,
            status,
            diverged: outcome.diverged.clone(),
            wall_seconds: wall.as_secs_f64(),
            ns_per_segment_step: busy.as_secs_f64() * 1e9 / segment_steps,
            frames_logged: outcome.frames,
            energy: EnergySummary {
                reference: outcome.energy_reference,
                r#final: outcome.energy_final,
                max_abs_deviation: outcome.max_abs_deviation,
                max_rel_deviation: outcome.max_rel_deviation(),
            },
            trusted: Trusted {
                step: outcome.trusted.0,
                time: outcome.trusted.1,
            },
            tip: Xy {
                x: outcome.tip.x,
                y: outcome.tip.y,
            },
            support_tension: outcome.support_tension,
            constraint_residual: outcome.max_constraint_residual,
            velocity_residual: outcome.max_velocity_residual,
            step_statistics: outcome.step_statistics,
            error_estimate: outcome.estimate.clone(),
            tolerance: plan.tolerance,
            tolerance_met: tolerance_met(plan, outcome),
            tolerance_exceeded_at: outcome.tolerance_exceeded_at,
            tip_samples: samples,
            period,
            recording_error,
        }
    }

    /// A few lines for a person at the terminal.
    pub fn human(&self) -> String {
        let status = match (&self.status, &self.diverged) {
            (Status::Diverged, Some(d)) => format!("DIVERGED: {d}"),
            (Status::Interrupted, _) => "interrupted".to_owned(),
            _ => "ok".to_owned(),
        };
        let scene = self.initial;
        let mut text = format!(
            "rope: {method}, {scene}, N = {n}, k = {dt:.3e}: {steps} steps to t = {t:.4} ({status})\n",
            method = self.method,
            n = self.segments,
            dt = self.dt,
            steps = self.steps,
            t = self.steps as f64 * self.dt,
        );
        let last = if self.status == Status::Diverged {
            format!(
                "last trusted state (t = {:.4}, step {})",
                self.trusted.time, self.trusted.step
            )
        } else {
            "final".to_owned()
        };
        text += &format!(
            "  energy: E_ref = {} (after step {REFERENCE_STEP}), {last} {}, max deviation {:.3e} ({:.3e} relative)\n",
            fixed(self.energy.reference),
            fixed(self.energy.r#final),
            self.energy.max_abs_deviation,
            self.energy.max_rel_deviation
        );
        let at = if self.status == Status::Diverged {
            " (last trusted state)"
        } else {
            ""
        };
        text += &format!(
            "  tip at ({:.5}, {:.5}), support tension F_0 = {:.4}{at}\n",
            self.tip.x, self.tip.y, self.support_tension
        );
        if let Some(residual) = self.constraint_residual {
            text += &format!("  joints closed to {residual:.1e} at worst (largest |g_j|)");
            if let Some(velocity) = self.velocity_residual {
                text += &format!(", joint velocities to {velocity:.1e} before projection (|G v|)");
            }
            text += "\n";
        }
        if let Some(s) = &self.step_statistics {
            text += &format!(
                "  own steps: {} (shortest {:.2e}; fastest rod {:.1} rad per time unit), {:.2} solves per step; {}; kinetic energy put back after projections {:.1e}\n",
                s.steps,
                s.smallest_step,
                s.fastest_rotation,
                s.solves as f64 / s.steps.max(1) as f64,
                match s.newton_failures {
                    0 => "Newton never failed".to_owned(),
                    n => format!(
                        "Newton failed {n} times, each time retaking its step at half the length"
                    ),
                },
                s.restored_energy,
            );
        }
        if let Some(e) = &self.error_estimate {
            text += &format!(
                "  estimated error (against the run at N = {}): tip {:.1e} at worst (t = {:.3}), {} at the end; shape {:.1e} at worst\n",
                Shadow::segments_of(self.segments),
                e.max_tip,
                e.max_tip_time,
                e.final_tip
                    .map_or("none".to_owned(), |tip| format!("{tip:.1e}")),
                e.max_shape
            );
            if let Some(lost) = &e.lost {
                text += &format!(
                    "  the estimate stopped at t = {:.3}: {}\n",
                    lost.time, lost.reason
                );
            }
        }
        if let Some(eps) = self.tolerance {
            text += &match (self.tolerance_met, self.tolerance_exceeded_at) {
                (_, Some(t)) => format!(
                    "  tolerance {eps:.1e}: NOT met, the estimated tip error passed it at t = {t:.3}\n"
                ),
                (Some(true), None) => {
                    format!("  tolerance {eps:.1e}: met (by the estimate, at every frame)\n")
                }
                _ => format!("  tolerance {eps:.1e}: unknown, the estimate was lost\n"),
            };
        }
        if let Some(period) = self.period {
            text += &format!(
                "  period {period:.4} (angular frequency {:.4})\n",
                std::f64::consts::TAU / period
            );
        }
        text += &format!(
            "  {:.3} s wall, {:.1} ns per segment-step, {} frames logged",
            self.wall_seconds, self.ns_per_segment_step, self.frames_logged
        );
        text
    }
}

/// An energy with six decimals, without a "−0.000000" for a value that rounds to zero.
fn fixed(value: f64) -> String {
    let text = format!("{value:.6}");
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        text.trim_start_matches('-').to_owned()
    } else {
        text
    }
}

/// Whether the tolerance held by the estimate: false once it passed, true if it never did and
/// the estimate lasted to the end, unknown otherwise.
fn tolerance_met(plan: &RunPlan, outcome: &Outcome) -> Option<bool> {
    plan.tolerance?;
    if outcome.tolerance_exceeded_at.is_some() {
        return Some(false);
    }
    match &outcome.estimate {
        Some(e) if e.lost.is_none() && e.final_tip.is_some() => Some(true),
        _ => None,
    }
}
