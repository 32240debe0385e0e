//! The run's summary: a JSON document (field names are a contract) and a short text for
//! people.

use super::config::RunPlan;
use super::estimate::{Shadow, TipBound};
use super::probe::{FoldFall, Probes};
use super::shake_figures::{ShakeFigures, SweepPoint};
use super::simulate::{EstimateOutcome, Outcome, REFERENCE_STEP};
use super::theory_figures::{FALL_WINDOW, TheoryAt, TheoryFigures};
use crate::error::Diverged;
use crate::methods::{MethodKind, StepStatistics};
use crate::model::theory::Comparison;
use crate::model::{Point, Scene};
use serde::Serialize;
use std::collections::VecDeque;
use std::time::Duration;

/// Tip samples the summary keeps (the latest), so that an endless run's memory stays flat.
pub const MAX_TIP_SAMPLES: usize = 1 << 16;

pub use super::probe::{FREE_FALL_UNTIL, FreeFall};

/// The tip's latest `[t, x, y]` samples at the frames, at most [`MAX_TIP_SAMPLES`], and what
/// the run measured at every step or on the fine grid, whatever the frames.
#[derive(Clone, Debug, Default)]
pub struct TipSamples {
    pub(super) latest: VecDeque<[f64; 3]>,
    /// What the run measured against the scene's theory at every step, where the scene quotes
    /// it at instants (a fold's falls).
    pub theory: TheoryFigures,
    /// What the run measured on the fine grid: a release's free fall, a mode's period, a
    /// shake's swing and balance.
    pub probes: Option<Probes>,
}

impl TipSamples {
    /// Adds the tip at the frame at `time`, forgetting the oldest sample when full.
    pub fn push(&mut self, time: f64, tip: Point) {
        if self.latest.len() == MAX_TIP_SAMPLES {
            self.latest.pop_front();
        }
        self.latest.push_back([time, tip.x, tip.y]);
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

/// What a run's exit status says of it, most serious first: a script tells them apart by the
/// status alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// The recording could not be completed (status 1).
    RecordingIncomplete,
    /// A method diverged (3; side by side, any one of them).
    Diverged,
    /// Ctrl-C or SIGTERM ended the run (130).
    Interrupted,
    /// The run ended as asked, but its live error estimate passed `--tolerance` (4).
    ToleranceMissed,
    /// The run ended as asked (0).
    Ok,
}

impl Verdict {
    /// The process's exit status for it.
    pub fn exit_status(self) -> u8 {
        match self {
            Self::Ok => 0,
            Self::RecordingIncomplete => 1,
            Self::Diverged => 3,
            Self::ToleranceMissed => 4,
            Self::Interrupted => 130,
        }
    }
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
    /// CPU seconds of the simulation thread (each method's own, side by side): the steps,
    /// the estimate's shadow and the frames built, not the waits nor the recording.
    pub cpu_seconds: f64,
    /// `cpu_seconds` per step per segment, in ns.
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
    /// The largest support tension of the run (up to the last trusted state), and when.
    pub max_support_tension: f64,
    pub max_support_tension_time: f64,
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
    /// tip values (at every step the two share), its largest shape value at the frames;
    /// absent for a run without a shadow.
    pub error_estimate: Option<EstimateOutcome>,
    /// The tip error `--tolerance` asked for.
    pub tolerance: Option<f64>,
    /// Whether the live tip estimate's bound ([`Summary::tolerance_bound`]) stayed within the
    /// tolerance at every step the run shares with its shadow: true where the tolerance held (the
    /// bound errs on the safe side), false where it may not have (a run whose true error is above
    /// half the tolerance may be false though it held); absent without a tolerance, where the
    /// estimate was lost before the end (`error_estimate.lost`), or where the run was
    /// interrupted before it passed.
    pub tolerance_met: Option<bool>,
    /// How the live estimate bounded the tip's error for the tolerance: at first order (a
    /// whip's), or, for a mode, at the order `--tolerance`'s pilots observed or its linear theory
    /// works out, times a safety factor; absent without a tolerance.
    pub tolerance_bound: Option<TipBound>,
    /// When the tip estimate first passed the tolerance.
    pub tolerance_exceeded_at: Option<f64>,
    /// `[t, x, y]` of the tip at every logged frame.
    pub tip_samples: Vec<[f64; 3]>,
    /// Oscillation period from the tip's zero crossings on the fine grid (`run::probe`), for
    /// the `mode` scene (it needs three crossings, 1.25 periods).
    pub period: Option<f64>,
    /// The small-oscillation period 2π/ω_n from the Bessel zero, for the `mode` scene.
    pub period_theory: Option<f64>,
    /// For a release: the largest distance of the tip from the free-fall law on the fine grid
    /// up to [`FREE_FALL_UNTIL`] (exact for the string until the bend arrives).
    pub free_fall: Option<FreeFall>,
    /// For a fold: the free end's time, speed and the support's tension where it has fallen
    /// 0.25, 0.5 and 0.75, each against Calkin & March's string (`model::fold`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub theory: Vec<TheoryAt>,
    /// For a fold: the free end's deepest fall (on the fine grid) and when, against where the
    /// free arm runs out, 1 − πd/2; the snap is the largest support tension and its time.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fold: Option<FoldFall>,
    /// For a shake: the free end's largest sideways swing against the linear steady state,
    /// and the energy balance E − E₀ − W, on the fine grid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shake: Option<ShakeFigures>,
    /// For a sweep of the shaking frequency: each frequency's largest sideways swing and its
    /// swing at Ω alone, in the order run (the other fields are the last frequency's).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sweep: Vec<SweepPoint>,
    /// Why the recording could not be completed (e.g. the viewer went away), if it could not.
    pub recording_error: Option<String>,
    /// In a run of several methods side by side: the largest distance, at equal arc length,
    /// between this method's string and that of the most accurate method running, at the
    /// frames (`None` for the most accurate itself, and in a run of one method).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub disagreement: Option<f64>,
    /// Why the method ran when none was named and it is not the report's: for a run left
    /// running (endless, looping or served), the one that keeps the energy at every frame.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method_chosen_because: Option<String>,
    /// In a run of several methods side by side, each one's summary, in the order named
    /// (the fields above are the first one's); absent in a run of one method.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub methods: Vec<Summary>,
}

impl Summary {
    /// The summary of a run of `plan` that ended in `outcome`. `cpu` is the simulation
    /// thread's CPU time, `wall` the whole run's.
    pub fn new(
        plan: &RunPlan,
        outcome: &Outcome,
        tip_samples: TipSamples,
        cpu: Duration,
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
        let probes = tip_samples.probes.as_ref();
        let free_fall = probes.and_then(|p| p.free_fall);
        let period = probes.and_then(Probes::period);
        let shake = probes.and_then(|p| p.shake);
        let fold = probes.and_then(|p| p.fold);
        let theory = tip_samples.theory.read();
        let samples: Vec<[f64; 3]> = tip_samples.latest.into();
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
            cpu_seconds: cpu.as_secs_f64(),
            ns_per_segment_step: cpu.as_secs_f64() * 1e9 / segment_steps,
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
            max_support_tension: outcome.max_support_tension.0,
            max_support_tension_time: outcome.max_support_tension.1,
            constraint_residual: outcome.max_constraint_residual,
            velocity_residual: outcome.max_velocity_residual,
            step_statistics: outcome.step_statistics,
            error_estimate: outcome.estimate.clone(),
            tolerance: plan.tolerance,
            tolerance_met: tolerance_met(plan, outcome),
            tolerance_bound: plan.tolerance.map(|_| plan.tip_bound),
            tolerance_exceeded_at: outcome.tolerance_exceeded_at,
            tip_samples: samples,
            period,
            period_theory: plan.scene.mode_period(),
            free_fall,
            theory,
            fold,
            shake,
            recording_error,
            sweep: Vec::new(),
            method_chosen_because: None,
            disagreement: None,
            methods: Vec::new(),
        }
    }

    /// A few lines for a person at the terminal (side by side, each method's, then how far
    /// each strayed from the most accurate).
    pub fn human(&self) -> String {
        if !self.methods.is_empty() {
            let each: Vec<String> = self.methods.iter().map(Summary::human).collect();
            return format!("{}\n{}", each.join("\n"), side_by_side(&self.methods));
        }
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
        if let Some(why) = &self.method_chosen_because {
            text.push_str(&format!("  method: {why}\n"));
        }
        let last = if self.status == Status::Diverged {
            format!(
                "last trusted state (t = {:.4}, step {})",
                self.trusted.time, self.trusted.step
            )
        } else {
            "final".to_owned()
        };
        // Under a moving support the energy changes by the support's work: what is kept is
        // E − W.
        let kept = if self.initial.support().moves() {
            "E − W"
        } else {
            "energy"
        };
        text += &format!(
            "  {kept}: E_ref = {} (after step {REFERENCE_STEP}), {last} {}, max deviation {:.3e} ({:.3e} relative)\n",
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
            "  tip at ({:.5}, {:.5}), support tension F(0) = {:.4}{at}; at most {:.4} (t = {:.3})\n",
            self.tip.x,
            self.tip.y,
            self.support_tension,
            self.max_support_tension,
            self.max_support_tension_time
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
                "  estimated error (against the run at N = {}): tip {:.1e} at worst (t = {:.3}), {} at the end; shape {:.1e} at worst at the frames\n",
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
                (_, Some(t)) => {
                    let bound = self.tolerance_bound.unwrap_or_default();
                    format!(
                        "  tolerance {eps:.1e}: NOT confirmed, the tip error's {} passed it at t = {t:.4} (the truth may be anywhere above {})\n",
                        bound.name(),
                        bound.truth_from()
                    )
                }
                (Some(true), None) => {
                    format!(
                        "  tolerance {eps:.1e}: met (by the estimate, at every step the run shares with its shadow)\n"
                    )
                }
                (None, None) if self.status == Status::Interrupted => format!(
                    "  tolerance {eps:.1e}: unknown, the run was interrupted at t = {:.4} (the estimate held it to there)\n",
                    self.steps as f64 * self.dt
                ),
                _ => format!("  tolerance {eps:.1e}: unknown, the estimate was lost\n"),
            };
        }
        text += &self.theory_lines();
        text += &format!(
            "  {:.3} s wall, {:.3} s CPU simulating ({:.1} ns per segment-step), {} frames logged",
            self.wall_seconds, self.cpu_seconds, self.ns_per_segment_step, self.frames_logged
        );
        text
    }
}

impl Summary {
    /// What the run's exit status says: the recording's failure first, then a divergence
    /// (side by side, any method's: enough for the status to say so), an interrupt, a
    /// tolerance the live estimate passed, and otherwise a run that ended as asked.
    pub fn verdict(&self) -> Verdict {
        if self.recording_error.is_some() {
            return Verdict::RecordingIncomplete;
        }
        let statuses = || std::iter::once(self.status).chain(self.methods.iter().map(|m| m.status));
        if statuses().any(|s| s == Status::Diverged) {
            Verdict::Diverged
        } else if statuses().any(|s| s == Status::Interrupted) {
            Verdict::Interrupted
        } else if self.tolerance_met == Some(false) {
            Verdict::ToleranceMissed
        } else {
            Verdict::Ok
        }
    }
}

impl Summary {
    /// What the program knows of the scene's physics beside what the run measured: the
    /// Bessel period of a mode, the free fall of a released tip.
    fn theory_lines(&self) -> String {
        let mut text = String::new();
        for at in &self.theory {
            let each: Vec<String> = at
                .quantities
                .iter()
                .map(|q| {
                    let against = match (q.predicted, q.relative_error) {
                        (Some(p), Some(e)) => format!(" (theory {p:.4}, {:+.2} %)", 100.0 * e),
                        _ => String::new(),
                    };
                    let window = match q.window_relative_error {
                        Some(e) if q.quantity == Comparison::SUPPORT_TENSION => format!(
                            ", {:.4} averaged over ±{FALL_WINDOW} of fall ({:+.2} %)",
                            q.window_measured,
                            100.0 * e
                        ),
                        _ => String::new(),
                    };
                    format!("{} {:.4}{against}{window}", q.quantity, q.measured)
                })
                .collect();
            text += &format!(
                "  fallen {:.2} at t = {:.4} (Calkin–March: t = {:.4}; free fall: {:.4}): {}\n",
                at.fall,
                at.time,
                crate::model::fold::time_to_fall(at.fall),
                (2.0 * at.fall).sqrt(),
                each.join("; ")
            );
        }
        if let Some(f) = self.fold {
            text += &format!(
                "  deepest fall {:.4} at t = {:.4} (the free arm runs out at a fall of 1 − πd/2 = {:.4}, where the bend's half circle is left to swing down); the snap, the support's largest pull: {:.4} at t = {:.4}\n",
                f.deepest_fall,
                f.deepest_fall_time,
                f.arm_limit,
                self.max_support_tension,
                self.max_support_tension_time
            );
        }
        if let Some(f) = self.shake {
            text += &f.lines(self.initial);
        }
        if let Some(f) = self.free_fall {
            text += &format!(
                "  free fall of the tip (exact until the bend reaches it, near t = 1.2): off by at most {:.1e} up to t = {:.3}\n",
                f.max_gap, f.until
            );
        }
        let (Some(theory), Scene::Mode { number, amplitude }) = (self.period_theory, self.initial)
        else {
            return text;
        };
        let tau = std::f64::consts::TAU;
        match self.period {
            Some(period) => {
                let difference = 100.0 * (period - theory) / theory;
                text += &format!(
                    "  period {period:.4} measured (angular frequency {:.4}); Bernoulli's small oscillations give {theory:.4} (ω_{number} = {:.4}, from the zero of J₀): {difference:+.2} %\n",
                    tau / period,
                    tau / theory
                );
                if difference.abs() > PERIOD_NOTE_PERCENT && amplitude.abs() > 0.01 {
                    text += &format!(
                        "  the theory is for small amplitudes: at a tip amplitude of {amplitude} the swing is large enough to shift the period (a smaller --amplitude, e.g. 0.01, comes closer)\n"
                    );
                } else if difference.abs() > PERIOD_NOTE_PERCENT {
                    text += &format!(
                        "  at a tip amplitude of {amplitude} the swing is small enough for the theory: the difference is the {} rods' own (the rods start on the string's mode sampled at their centres); more --segments come closer\n",
                        self.segments
                    );
                }
            }
            None => {
                text += &format!(
                    "  period not measured: it takes three zero crossings of the tip, 1.25 periods ({:.2} for mode {number}, whose period is {theory:.4}), and the run lasted {:.4}; give --duration {:.0} or more\n",
                    1.25 * theory,
                    self.steps as f64 * self.dt,
                    (1.25 * theory).ceil()
                );
            }
        }
        text
    }
}

/// One line for methods run side by side: how far each strayed from the most accurate one's
/// string, and which stopped early.
pub fn side_by_side(summaries: &[Summary]) -> String {
    let best = summaries
        .iter()
        .min_by_key(|s| s.method.accuracy_rank())
        .map_or("", |s| s.method.name());
    let each: Vec<String> = summaries
        .iter()
        .filter(|s| s.method.name() != best)
        .map(|s| {
            let stopped = match &s.diverged {
                Some(d) => format!(", diverged at t = {:.3}", d.time),
                None => String::new(),
            };
            match s.disagreement {
                Some(d) => format!("{} {d:.1e}{stopped}", s.method),
                None => format!("{} none measured{stopped}", s.method),
            }
        })
        .collect();
    format!(
        "rope: side by side, the largest distance from {best}'s string at equal arc length, at the frames: {}",
        each.join("; ")
    )
}

/// The difference from the Bessel period, in %, past which the summary says the amplitude
/// may be the cause (N = 100 at the default step is within 0.03 %).
const PERIOD_NOTE_PERCENT: f64 = 0.2;

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
/// the estimate lasted to the end, unknown otherwise (a run interrupted before its end among
/// them: what it held to there says nothing of the rest).
fn tolerance_met(plan: &RunPlan, outcome: &Outcome) -> Option<bool> {
    plan.tolerance?;
    if outcome.tolerance_exceeded_at.is_some() {
        return Some(false);
    }
    if outcome.cancelled {
        return None;
    }
    match &outcome.estimate {
        Some(e) if e.lost.is_none() && e.final_tip.is_some() => Some(true),
        _ => None,
    }
}
