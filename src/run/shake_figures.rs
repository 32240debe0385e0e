//! What the summary says of a shaken support: the free end's largest sideways swing against
//! linear theory's, at the same frames, its swing at the shaking frequency alone, and how well
//! the energy balance E − E₀ − W closed.

use super::simulate::Frame;
use crate::model::theory::Comparison;
use crate::model::{Scene, ShakeStart};
use serde::Serialize;

/// What a shake's summary says of its physics.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ShakeFigures {
    /// The free end's largest sideways excursion in the room, over the frames.
    pub tip_amplitude: f64,
    /// The largest the theory's prediction reached at the same frames: the linear steady
    /// state's A/|J₀(2Ω)|, or near a resonance, started at rest, its growing envelope's.
    pub predicted_amplitude: f64,
    /// Which prediction.
    pub prediction: &'static str,
    /// tip_amplitude / predicted_amplitude − 1.
    pub relative_error: f64,
    /// The largest |E − E₀ − W| at any frame, in m g L.
    pub max_abs_balance: f64,
    /// The support's work W at the last frame.
    pub work: f64,
    /// The free end's swing at the shaking frequency Ω alone: twice the magnitude of the mean
    /// of x_tip e^{−iΩt} over the frames (a lock-in amplifier's reading). The free modes a
    /// start from rest excites, at their own frequencies, mostly average out of it.
    pub driven_amplitude: f64,
    /// Σ x_tip cos Ωt, Σ x_tip sin Ωt and the frames summed, for `driven_amplitude`.
    #[serde(skip)]
    lock_in: (f64, f64, u64),
}

/// One frequency of a sweep: what its run measured of the free end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// Ω.
    pub frequency: f64,
    /// The largest sideways swing over the run's frames.
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
    /// Takes a frame into `figures`: the free end's sideways excursion in the room, the
    /// balance and the support's work (nothing for a frame under a fixed support).
    pub fn push(figures: &mut Option<Self>, scene: Scene, frame: &Frame) {
        let (Some(balance), Some(support), Scene::Shake { frequency, .. }) =
            (frame.balance, frame.support, scene)
        else {
            return;
        };
        let sideways = frame
            .theory
            .iter()
            .find(|c| c.quantity == Comparison::TIP_SIDEWAYS);
        let figures = figures.get_or_insert(Self {
            tip_amplitude: 0.0,
            predicted_amplitude: 0.0,
            prediction: sideways
                .and_then(|c| c.predictions.first())
                .map_or("", |p| p.0),
            relative_error: 0.0,
            max_abs_balance: 0.0,
            work: 0.0,
            driven_amplitude: 0.0,
            lock_in: (0.0, 0.0, 0),
        });
        figures.tip_amplitude = figures.tip_amplitude.max(frame.tip().x.abs());
        if let Some(p) = sideways.and_then(Comparison::first_prediction) {
            figures.predicted_amplitude = figures.predicted_amplitude.max(p.abs());
        }
        figures.relative_error = figures.tip_amplitude / figures.predicted_amplitude - 1.0;
        figures.max_abs_balance = figures.max_abs_balance.max(balance.abs());
        figures.work = support.work;
        let (sin, cos) = (frequency * frame.time).sin_cos();
        let x = frame.tip().x;
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
            "  free end's sideways swing: at most {:.4e}; linear theory ({}) {:.4e} ({:+.2} %{from}); at Ω alone (its Fourier component over the run) {:.4e}\n  energy balance: |E − E₀ − W| ≤ {:.1e} at every frame; the support's work W = {:.4e} at the end\n",
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
