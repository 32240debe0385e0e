//! The committed error models of one scene: what each method's tip error is known to be
//! without flying it, before the pilots measure the scene itself. For a release, the release
//! atlas of the method's rods where it serves ([`from_atlas`]); else the method's one law
//! ([`law`]), fitted to the worst of six scenes.

use super::atlas::Atlas;
use super::error_model::{ErrorModel, law};

use crate::methods::MethodKind;
use crate::model::Scene;

/// Where a method's committed error model comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The release atlas, measured at this angle or from its neighbours ([`from_atlas`]).
    Atlas,
    /// The method's one law, fitted to the worst of six scenes ([`law`]).
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
                    None => (method, law(method), Source::Law),
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

    /// Whether a pilot of `method` at `segments` could change the choice for `eps`. Where the
    /// release atlas serves the method ([`Source::Atlas`]: it covers the run, and rules over the
    /// pilots' own, [`Committed::floors_pilots`]), a pilot changes it only by holding EPS at its
    /// own level, and its bound there is about [`SAFETY`](super::pilot::SAFETY) times the error there (the difference
    /// to its shadow at N/2, times the safety), so it holds only where the error is within
    /// `eps` / [`SAFETY`](super::pilot::SAFETY). It flies only where the committed model's error at `segments`,
    /// without its margin, is within `eps`: where that model may overstate the scene's error by
    /// up to [`SAFETY`](super::pilot::SAFETY) (an angle between two of the atlas's, whose error is below the larger
    /// of theirs), the pilot still flies. Elsewhere every pilot may: the one law is the worst
    /// of six scenes, and a scene far from it holds by its pilot (from 90°, hanging still, the
    /// seed at N = 16, where its law reads 0.2).
    ///
    /// From 10° at 1e-2 the pilots took 9.5 ms, more than the 8.6 ms of the run the atlas
    /// chose (the chain at N = 50, its own row's first that holds), and none could hold.
    pub fn may_hold(&self, method: MethodKind, segments: usize, eps: f64) -> bool {
        let ruled = self.source(method) == Source::Atlas && self.floors_pilots;
        !ruled || self.model(method).predict(segments) <= eps
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
        self.models
            .iter()
            .find(|(m, ..)| *m == method)
            .map_or((law(method), Source::Law), |&(_, model, source)| {
                (model, source)
            })
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
