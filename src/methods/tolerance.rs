//! The rule `rope run --tolerance EPS` uses to model a scene with no more than it needs: the
//! cheapest method, N and k whose predicted tip error is at most EPS, from each method's
//! error model and cost in its [`Descriptor`](super::Descriptor).

use super::registry::MethodKind;
use crate::model::Scene;

/// How far below the tolerance the predicted error is aimed.
const SAFETY: f64 = 2.0;

/// Fewest segments the rule chooses: fewer is a pendulum, not a rope.
const MIN_SEGMENTS: usize = 4;

/// The longest run the rule will choose, in predicted CPU seconds.
pub const MAX_SECONDS: f64 = 3600.0;

/// What the tolerance rule chose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    pub predicted_error: f64,
    /// Predicted CPU seconds for the duration asked.
    pub predicted_seconds: f64,
}

/// The cheapest method, N and k whose predicted tip error is at most `tolerance`, among the
/// methods that can start from `scene`. Each method's N comes from its error model (aiming
/// at `tolerance / SAFETY`), its k is the method's default for that N.
pub fn choose(tolerance: f64, duration: f64, scene: &Scene) -> Option<Choice> {
    MethodKind::ALL
        .iter()
        .filter_map(|&method| {
            let d = method.descriptor();
            let segments = d
                .error_model
                .segments_for(tolerance / SAFETY)
                .max(MIN_SEGMENTS);
            let dt = d.default_dt(segments);
            method.build(scene, segments, dt).ok()?;
            let steps = (duration / dt).round().max(1.0);
            Some(Choice {
                method,
                segments,
                dt,
                predicted_error: d.error_model.predict(segments),
                predicted_seconds: d.ns_per_segment_step * 1e-9 * segments as f64 * steps,
            })
        })
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
}
