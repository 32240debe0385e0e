//! What the summary says of a shaken support: the free end's largest sideways swing against
//! linear theory's, at the same frames, and how well the energy balance E − E₀ − W closed.

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
}

impl ShakeFigures {
    /// Takes a frame into `figures`: the free end's sideways excursion in the room, the
    /// balance and the support's work (nothing for a frame under a fixed support).
    pub fn push(figures: &mut Option<Self>, frame: &Frame) {
        let (Some(balance), Some(support)) = (frame.balance, frame.support) else {
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
        });
        figures.tip_amplitude = figures.tip_amplitude.max(frame.tip().x.abs());
        if let Some(p) = sideways.and_then(Comparison::first_prediction) {
            figures.predicted_amplitude = figures.predicted_amplitude.max(p.abs());
        }
        figures.relative_error = figures.tip_amplitude / figures.predicted_amplitude - 1.0;
        figures.max_abs_balance = figures.max_abs_balance.max(balance.abs());
        figures.work = support.work;
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
            "  free end's sideways swing: at most {:.4e}; linear theory ({}) {:.4e} ({:+.2} %{from})\n  energy balance: |E − E₀ − W| ≤ {:.1e} at every frame; the support's work W = {:.4e} at the end\n",
            self.tip_amplitude,
            self.prediction,
            self.predicted_amplitude,
            100.0 * self.relative_error,
            self.max_abs_balance,
            self.work
        )
    }
}
