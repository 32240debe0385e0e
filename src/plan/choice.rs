//! The candidates of a `--tolerance` choice: each method that can start from the scene, at the
//! fewest segments an error model allows for EPS and its tolerance step, with what that run
//! is predicted to cost; and the cheapest of them. The models come from elsewhere (the
//! committed ones, [`Committed`], or the pilots' own); this file only turns a model into a
//! run and ranks the runs.

use super::committed::Committed;
use super::error_model::{ErrorModel, law};
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::estimate::TipBound;

pub use super::error_model::MIN_SEGMENTS;

/// The longest run the rule will choose, in predicted CPU seconds.
pub const MAX_SECONDS: f64 = 3600.0;

/// What the tolerance rule chose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    pub method: MethodKind,
    pub segments: usize,
    pub dt: f64,
    pub predicted_error: f64,
    /// Predicted CPU seconds of the steps for the duration asked: what the rule ranks the
    /// methods by (the run's whole cost, frames and the estimate's shadow with it, is
    /// `run::Cost`'s).
    pub predicted_seconds: f64,
    /// How the run's live estimate is to bound its tip error: at first order, unless the
    /// pilots measured the scene's own ([`pilot::tip_bound`](super::pilot::tip_bound)).
    pub tip_bound: TipBound,
}

/// The cheapest method, N and k whose tip error `committed` (the committed models for this
/// scene, duration and tolerance) predicts within `tolerance`, among the methods that can
/// start from `scene` and whose run `fits` (the caller's limits on time and memory, asked as
/// `fits(method, N, k)`): of the models measured over the whole duration
/// ([`Committed::covers`]) where one of them reaches `tolerance`, else of all.
pub fn from_committed(
    tolerance: f64,
    duration: f64,
    scene: &Scene,
    committed: &Committed,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> Option<Choice> {
    if !committed.measured_here {
        return None;
    }
    let covering = |m: MethodKind| committed.covers(m).then(|| committed.model(m));
    let any = |m: MethodKind| Some(committed.model(m));
    choose_with(tolerance, duration, scene, covering, MIN_SEGMENTS, &fits)
        .or_else(|| choose_with(tolerance, duration, scene, any, MIN_SEGMENTS, &fits))
}

/// As [`from_committed`], with the committed models looked up here ([`Committed::look_up`]):
/// what the committed models alone choose, before any pilot.
pub fn by_committed(
    tolerance: f64,
    duration: f64,
    scene: &Scene,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> Option<Choice> {
    let committed = Committed::look_up(scene, duration, tolerance);
    from_committed(tolerance, duration, scene, &committed, fits)
}

/// As [`from_committed`], with each method's error model given by `model_of` (the scene's own, from
/// pilot runs; a method it gives none for is left out), and at least `fewest` segments (a
/// model measured from N up is not trusted below it).
pub fn choose_with(
    tolerance: f64,
    duration: f64,
    scene: &Scene,
    model_of: impl Fn(MethodKind) -> Option<ErrorModel>,
    fewest: usize,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> Option<Choice> {
    startable(scene, duration)
        .filter_map(|method| {
            Some(by_model(
                method,
                &model_of(method)?,
                tolerance,
                fewest,
                duration,
            ))
        })
        .filter(|c| fits(c.method, c.segments, c.dt))
        .min_by(|a, b| a.predicted_seconds.total_cmp(&b.predicted_seconds))
}

/// The most accurate run any method can make from `scene` within what `fits`: for each
/// method the largest N that fits (by bisection), then the smallest predicted error.
pub fn tightest(
    duration: f64,
    scene: &Scene,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> Option<Choice> {
    startable(scene, duration)
        .filter_map(|method| {
            let fits_at = |n: usize| fits(method, n, method.tolerance_dt(n));
            if !fits_at(MIN_SEGMENTS) {
                return None;
            }
            let (mut good, mut bad) = (MIN_SEGMENTS, MIN_SEGMENTS);
            while fits_at(bad) && bad < 1 << 40 {
                good = bad;
                bad *= 2;
            }
            while bad - good > 1 {
                let mid = good + (bad - good) / 2;
                if fits_at(mid) { good = mid } else { bad = mid }
            }
            Some(choice(method, &law(method), good, duration))
        })
        .min_by(|a, b| a.predicted_error.total_cmp(&b.predicted_error))
}

/// The methods that can start from `scene` and that the rule may choose there for a run to
/// `duration` ([`Descriptor::plannable`](crate::methods::Descriptor::plannable)): for a scene
/// with a method of its own (a fold, a shake: the one that keeps the energy, or its balance
/// with the support's work, [`MethodKind::scene_default`]), that one alone.
pub fn startable(scene: &Scene, duration: f64) -> impl Iterator<Item = MethodKind> + '_ {
    let own = MethodKind::scene_default(scene.name()).map(|(method, _)| method);
    MethodKind::ALL.into_iter().filter(move |&method| {
        own.is_none_or(|own| own == method)
            && (method.descriptor().plannable)(scene, duration)
            && can_start(method, scene)
    })
}

/// Whether `method` can start from `scene` (independent of N: asked at its fewest segments,
/// so nothing the size of a run is allocated).
fn can_start(method: MethodKind, scene: &Scene) -> bool {
    let d = method.descriptor();
    let segments = d.min_segments.max(MIN_SEGMENTS);
    method
        .build(scene, segments, d.default_dt(segments))
        .is_ok()
}

/// `method` at the fewest segments (at least `fewest`) whose bound by `model` is within
/// `tolerance`, and its tolerance step, to `duration`.
pub fn by_model(
    method: MethodKind,
    model: &ErrorModel,
    tolerance: f64,
    fewest: usize,
    duration: f64,
) -> Choice {
    let segments = model.segments_for(tolerance).max(fewest);
    choice(method, model, segments, duration)
}

/// `method` at `segments` and its tolerance step, to `duration`, its error bounded by
/// `predicted_error` (measured, e.g. by a pilot at that very N).
pub fn at(method: MethodKind, segments: usize, predicted_error: f64, duration: f64) -> Choice {
    let model = law(method);
    Choice {
        predicted_error,
        ..choice(method, &model, segments, duration)
    }
}

/// `method` at `segments` (at least [`MIN_SEGMENTS`]) and its tolerance step, to `duration`,
/// its error predicted by `model`.
fn choice(method: MethodKind, model: &ErrorModel, segments: usize, duration: f64) -> Choice {
    let d = method.descriptor();
    let segments = segments.max(MIN_SEGMENTS);
    let dt = d.tolerance_dt(segments);
    let steps = (duration / dt).round().max(1.0);
    Choice {
        method,
        segments,
        dt,
        predicted_error: model.bound(segments),
        predicted_seconds: d.ns_per_segment_step * 1e-9 * segments as f64 * steps,
        tip_bound: TipBound::FirstOrder,
    }
}
