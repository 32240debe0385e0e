//! The rule `rope run --tolerance EPS` uses to model a scene with no more than it needs: the
//! cheapest method, N and k whose tip error is predicted to stay within EPS, from each
//! method's committed error model ([`Committed`]: the release atlas where it serves,
//! else the one law with its measured safety factor in its
//! [`Descriptor`](crate::methods::Descriptor)) and its cost.

use super::atlas::Atlas;
use crate::methods::MethodKind;
use crate::methods::error_model::ErrorModel;
use crate::model::Scene;

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
    /// Predicted CPU seconds of the steps for the duration asked: what the rule ranks the
    /// methods by (the run's whole cost, frames and the estimate's shadow with it, is
    /// `run::Cost`'s).
    pub predicted_seconds: f64,
}

/// The cheapest method, N and k whose tip error is predicted to stay within `tolerance`,
/// among the methods that can start from `scene` and whose run `fits` (the caller's limits on
/// time and memory, asked as `fits(method, N, k)`). Each method's N comes from its error
/// model's bound (prediction × measured safety factor), its k is the method's tolerance step
/// for that N ([`Descriptor::tolerance_dt`](crate::methods::Descriptor::tolerance_dt)).
pub fn choose(
    tolerance: f64,
    duration: f64,
    scene: &Scene,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> Option<Choice> {
    let committed = Committed::look_up(scene, duration, tolerance);
    choose_committed(tolerance, duration, scene, &committed, fits)
}

/// As [`choose`], with the committed models already looked up for this scene, duration and
/// tolerance: of the models measured over the whole duration ([`Committed::covers`]) where one
/// of them reaches `tolerance`, else of all.
pub fn choose_committed(
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

/// Where a method's committed error model comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The release atlas, measured at this angle or from its neighbours ([`from_atlas`]).
    Atlas,
    /// The method's one law, fitted to the worst of six scenes (its descriptor's).
    Law,
}

/// Every method's committed error model for one scene, duration and tolerance, and where it
/// comes from: looked up once, before the choice, which then reads it.
#[derive(Clone, Debug)]
pub struct Committed {
    models: Vec<(MethodKind, ErrorModel, Source)>,
    duration: f64,
    /// Whether the committed models were measured on scenes of this kind (releases and
    /// modes); for a fold or a shake they were not, and only the pilots measure.
    pub measured_here: bool,
    /// Whether the pilots' own model may not ask fewer segments than a committed model that
    /// covers the run ([`Committed::covers`]): for a release, whose error constant goes on
    /// growing past the pilots' N ≤ 64 (from 80° the chain's pilots fit 0.14/N, ×1.9 for
    /// safety, and at the N = 2 639 that asked, the tip erred by 1.15e-4 at 1e-4, 0.30/N).
    /// A mode's error settles within the pilots' N, and its own model stands.
    pub floors_pilots: bool,
}

impl Committed {
    /// Each method's committed model from `scene` to `duration` for `tolerance`: the release
    /// atlas's ([`from_atlas`]) where it serves, else the method's one law, fitted to the
    /// worst of six scenes. None for a fold or a shake ([`Committed::measured_here`]).
    pub fn look_up(scene: &Scene, duration: f64, tolerance: f64) -> Self {
        let measured_here = matches!(scene, Scene::Release { .. } | Scene::Mode { .. });
        let floors_pilots = matches!(scene, Scene::Release { .. });
        let models = MethodKind::ALL
            .into_iter()
            .map(
                |method| match from_atlas(method, scene, duration, tolerance) {
                    Some(model) => (method, model, Source::Atlas),
                    None => (method, method.descriptor().error_model, Source::Law),
                },
            )
            .collect();
        Self {
            models,
            duration,
            measured_here,
            floors_pilots,
        }
    }

    /// Whether `method`'s committed model was measured over the run's whole duration: an
    /// atlas's always (one serves only runs within its window), the one law up to
    /// [`LAW_UNTIL`]. One that does not may not overrule a looser figure the pilots measured
    /// over the run's own time.
    pub fn covers(&self, method: MethodKind) -> bool {
        self.measured_here && (self.source(method) == Source::Atlas || self.duration <= LAW_UNTIL)
    }

    /// `method`'s committed model.
    pub fn model(&self, method: MethodKind) -> ErrorModel {
        self.entry(method).0
    }

    /// Where `method`'s committed model comes from.
    pub fn source(&self, method: MethodKind) -> Source {
        self.entry(method).1
    }

    fn entry(&self, method: MethodKind) -> (ErrorModel, Source) {
        self.models.iter().find(|(m, ..)| *m == method).map_or(
            (method.descriptor().error_model, Source::Law),
            |&(_, model, source)| (model, source),
        )
    }
}

/// The longest run the methods' one laws were measured over: the six scenes they were fitted
/// to, to t = 3, as the shorter release atlases. Past it a law may not overrule the pilots,
/// which measure the run's own duration.
pub const LAW_UNTIL: f64 = super::atlas::WINDOW;

/// The release atlas's error model for `method` from `scene` to `duration` at `tolerance`:
/// `None` unless the method is of rods an atlas measured over at least `duration` (the
/// chain's to t = 3, or the graded rods' to t = 3 or 5: [`Atlas::of`]), the scene a release
/// and the tolerance within its N.
pub fn from_atlas(
    method: MethodKind,
    scene: &Scene,
    duration: f64,
    tolerance: f64,
) -> Option<ErrorModel> {
    Atlas::of(method, duration)?.model(scene, duration, tolerance)
}

/// As [`choose`], with each method's error model given by `model_of` (the scene's own, from
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
            Some(choice(
                method,
                &method.descriptor().error_model,
                good,
                duration,
            ))
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
    let model = method.descriptor().error_model;
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
    }
}
