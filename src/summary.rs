//! The run's summary: a JSON document (field names are a contract) and a short text for
//! people.

use crate::error::Diverged;
use crate::method::MethodKind;
use serde::Serialize;

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

/// Energy statistics (eqs. 13–16), relative to the value after step 10.
#[derive(Clone, Debug, Serialize)]
pub struct EnergySummary {
    pub reference: f64,
    pub r#final: f64,
    pub max_abs_deviation: f64,
    pub max_rel_deviation: f64,
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
    pub energy: EnergySummary,
    pub tip: Xy,
    pub support_tension: f64,
    /// `[t, x, y]` of the tip at every logged frame.
    pub tip_samples: Vec<[f64; 3]>,
    /// Oscillation period from the tip's zero crossings, for the `mode` scene.
    pub period: Option<f64>,
    /// Why the recording could not be completed (e.g. the viewer went away), if it could not.
    pub recording_error: Option<String>,
}

impl Summary {
    /// A few lines for a person at the terminal.
    pub fn human(&self) -> String {
        let status = match (&self.status, &self.diverged) {
            (Status::Diverged, Some(d)) => format!("DIVERGED: {d}"),
            (Status::Interrupted, _) => "interrupted".to_owned(),
            _ => "ok".to_owned(),
        };
        let scene = match self.scene {
            "release" => format!("release at {}°", self.angle_deg),
            other => format!("{other} scene"),
        };
        let mut text = format!(
            "rope: {method}, {scene}, N = {n}, k = {dt:.3e}: {steps} steps to t = {t:.4} ({status})\n",
            method = self.method,
            n = self.segments,
            dt = self.dt,
            steps = self.steps,
            t = self.steps as f64 * self.dt,
        );
        text += &format!(
            "  energy: E_ref = {:.6} (after step 10), final {:.6}, max deviation {:.3e} ({:.3e} relative)\n",
            self.energy.reference,
            self.energy.r#final,
            self.energy.max_abs_deviation,
            self.energy.max_rel_deviation
        );
        text += &format!(
            "  tip at ({:.5}, {:.5}), support tension F_0 = {:.4}\n",
            self.tip.x, self.tip.y, self.support_tension
        );
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
