//! What the summary says of a shaken support: the free end's largest sideways swing against
//! linear theory's, at the same instants, its swing at the shaking frequency alone, and how
//! well the energy balance E − E₀ − W closed. Read on the summary's fine grid
//! ([`super::probe`]), never at the frames.

use crate::model::{Scene, ShakeStart};
use serde::Serialize;

/// What a shake's summary says of its physics.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ShakeFigures {
    /// The free end's largest sideways excursion in the room, on the fine grid.
    pub tip_amplitude: f64,
    /// The largest the theory's prediction reached at the same instants: the linear steady
    /// state's A/|J₀(2Ω)|, or near a resonance, started at rest, its growing envelope's.
    pub predicted_amplitude: f64,
    /// Which prediction.
    pub prediction: &'static str,
    /// tip_amplitude / predicted_amplitude − 1.
    pub relative_error: f64,
    /// The largest |E − E₀ − W| on the fine grid, in m g L.
    pub max_abs_balance: f64,
    /// The support's work W at the end.
    pub work: f64,
    /// The free end's swing at the shaking frequency Ω alone: twice the magnitude of the mean
    /// of x_tip e^{−iΩt} over the fine grid (a lock-in amplifier's reading). The free modes a
    /// start from rest excites, at their own frequencies, mostly average out of it.
    pub driven_amplitude: f64,
    /// Σ x_tip cos Ωt, Σ x_tip sin Ωt and the instants summed, for `driven_amplitude`.
    #[serde(skip)]
    lock_in: (f64, f64, u64),
}

/// What [`ShakeFigures`] reads of a shake at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShakeSample {
    pub time: f64,
    /// The free end's x in the room.
    pub tip_x: f64,
    /// E − E₀ − W.
    pub balance: f64,
    /// The support's work W so far.
    pub work: f64,
}

/// One frequency of a sweep: what its run measured of the free end.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SweepPoint {
    /// Ω.
    pub frequency: f64,
    /// The largest sideways swing over the run (on the fine grid).
    pub largest: f64,
    /// The swing at Ω alone, its Fourier component over the run.
    pub driven: f64,
}

impl SweepPoint {
    /// The lowest and the highest frequency of `points` (∞ and 0 for none).
    pub fn span(points: &[Self]) -> (f64, f64) {
        points.iter().fold((f64::INFINITY, 0.0), |(lo, hi), p| {
            (lo.min(p.frequency), hi.max(p.frequency))
        })
    }
}

impl ShakeFigures {
    /// Takes a sample of the motion into `figures` (nothing for a scene that is not a shake):
    /// the free end's sideways excursion in the room, the balance and the support's work.
    pub fn push(figures: &mut Option<Self>, scene: Scene, sample: ShakeSample) {
        let (Some((prediction, predicted)), Scene::Shake { frequency, .. }) =
            (scene.sideways_prediction(sample.time), scene)
        else {
            return;
        };
        let figures = figures.get_or_insert(Self {
            tip_amplitude: 0.0,
            predicted_amplitude: 0.0,
            prediction,
            relative_error: 0.0,
            max_abs_balance: 0.0,
            work: 0.0,
            driven_amplitude: 0.0,
            lock_in: (0.0, 0.0, 0),
        });
        let x = sample.tip_x;
        figures.tip_amplitude = figures.tip_amplitude.max(x.abs());
        figures.predicted_amplitude = figures.predicted_amplitude.max(predicted.abs());
        figures.relative_error = figures.tip_amplitude / figures.predicted_amplitude - 1.0;
        figures.max_abs_balance = figures.max_abs_balance.max(sample.balance.abs());
        figures.work = sample.work;
        let (sin, cos) = (frequency * sample.time).sin_cos();
        let (c, s, n) = &mut figures.lock_in;
        (*c, *s, *n) = (*c + x * cos, *s + x * sin, *n + 1);
        figures.driven_amplitude = 2.0 * c.hypot(*s) / *n as f64;
    }

    /// The summary's lines for a run from `scene`.
    pub fn lines(&self, scene: Scene) -> String {
        let from = match scene {
            Scene::Shake {
                start: ShakeStart::Rest,
                ..
            } if self.prediction.starts_with("steady") => {
                "; started at rest, the free modes add to it"
            }
            _ => "",
        };
        format!(
            "  free end's sideways swing: at most {:.4e}; linear theory ({}) {:.4e} ({:+.2} %{from}); at Ω alone (its Fourier component over the run) {:.4e}\n  energy balance: |E − E₀ − W| ≤ {:.1e} checked every 1e-3 of a time unit (or every step, if longer); the support's work W = {:.4e} at the end\n",
            self.tip_amplitude,
            self.prediction,
            self.predicted_amplitude,
            100.0 * self.relative_error,
            self.driven_amplitude,
            self.max_abs_balance,
            self.work
        )
    }
}
