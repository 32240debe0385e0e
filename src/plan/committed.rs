//! The committed error models of one scene: what each method's tip error is known to be
//! without flying it, before the pilots measure the scene itself. For a release, the release
//! atlas of the method's rods where it serves ([`from_atlas`]); for a small mode, the linear
//! theory of the equal rods' small oscillations ([`mode_theory`]); else the method's one law
//! ([`law`]), fitted to the worst of six scenes.

use super::atlas::Atlas;
use super::error_model::{ErrorModel, MIN_SEGMENTS, SAFETY, law};
use super::mode_theory;
use crate::run::estimate::TipBound;

use crate::methods::MethodKind;
use crate::model::Scene;

/// Where a method's committed error model comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The release atlas, measured at this angle or from its neighbours ([`from_atlas`]).
    Atlas,
    /// The method's one law, fitted to the worst of six scenes ([`law`]).
    Law,
    /// The linear theory of equal rods started in a mode ([`mode_theory`], [`from_theory`]):
    /// their error at every instant of the run, worked out before it.
    Theory,
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
    /// The order the theory's error falls at where it holds the tolerance ([`from_theory`]), for
    /// the methods it serves: the order a run's live estimate is read at.
    pub theory_order: Option<f64>,
}

impl Committed {
    /// Each method's committed model from `scene` to `duration` for `tolerance`: the release
    /// atlas's ([`from_atlas`]) where it serves, else the method's one law, fitted to the
    /// worst of six scenes. None for a fold or a shake ([`Committed::measured_here`]).
    // Never inlined: an earlier form of this, inlined into `tolerance::choose`, read the
    // theory's model with its order as 0 (where it is 1.84), and read it right once a print
    // was added or when called from a test; one compiled copy serves every caller alike.
    #[inline(never)]
    pub fn look_up(scene: &Scene, duration: f64, tolerance: f64) -> Self {
        let measured_here = matches!(scene, Scene::Release { .. } | Scene::Mode { .. });
        let floors_pilots = matches!(scene, Scene::Release { .. });
        let theory = from_theory(scene, duration, tolerance);
        let mut models = Vec::with_capacity(MethodKind::ALL.len());
        for method in MethodKind::ALL {
            let entry = if let Some(model) = theory.filter(|_| mode_theory::of_rods(method)) {
                (method, model, Source::Theory)
            } else if let Some(model) = from_atlas(method, scene, duration, tolerance) {
                (method, model, Source::Atlas)
            } else {
                (method, law(method), Source::Law)
            };
            models.push(entry);
        }
        Self {
            models,
            duration,
            measured_here,
            floors_pilots,
            theory_order: theory.map(|model| model.order),
        }
    }

    /// Whether `method`'s committed model was measured over the run's whole duration: an
    /// atlas's always (one serves only runs within its window), the theory's always (it is
    /// worked out over the run's own), the one law up to
    /// [`LAW_UNTIL`]. One that does not may not overrule a looser figure the pilots measured
    /// over the run's own time.
    pub fn covers(&self, method: MethodKind) -> bool {
        self.measured_here
            && match self.source(method) {
                Source::Atlas | Source::Theory => true,
                Source::Law => self.duration <= LAW_UNTIL,
            }
    }

    /// Whether a pilot of `method` at `segments` could change the choice for `eps`. Where the
    /// release atlas serves the method ([`Source::Atlas`]: it covers the run, and rules over the
    /// pilots' own, [`Committed::floors_pilots`]), or the mode theory does ([`Source::Theory`]:
    /// the scene's own error at every instant, which no pilot's fit at N ≤ 64 betters), a
    /// pilot changes it only by holding EPS at its
    /// own level, and its bound there is about [`SAFETY`] times the error there (the difference
    /// to its shadow at N/2, times the safety), so it holds only where the error is within
    /// `eps` / [`SAFETY`]. It flies only where the committed model's error at `segments`,
    /// without its margin, is within `eps`: where that model may overstate the scene's error by
    /// up to [`SAFETY`] (an angle between two of the atlas's, whose error is below the larger
    /// of theirs), the pilot still flies. Elsewhere every pilot may: the one law is the worst
    /// of six scenes, and a scene far from it holds by its pilot (from 90°, hanging still, the
    /// seed at N = 16, where its law reads 0.2).
    ///
    /// From 10° at 1e-2 the pilots took 9.5 ms, more than the 8.6 ms of the run the atlas
    /// chose (the chain at N = 50, its own row's first that holds), and none could hold.
    pub fn may_hold(&self, method: MethodKind, segments: usize, eps: f64) -> bool {
        let ruled = match self.source(method) {
            Source::Atlas => self.floors_pilots,
            Source::Theory => true,
            Source::Law => false,
        };
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

/// How far below EPS the mode theory keeps the live estimate's bound it predicts: the swing's
/// own nonlinearity adds to what the linear theory reads (mode 2 at a tip amplitude of 0.05,
/// N = 30: the bound read 1.0e-3 where the theory's was 9.8e-4; its error up to 1.19 times
/// the theory's for modes 1 and 2 to a tip amplitude of 0.1).
pub const LIVE_MARGIN: f64 = 0.9;

/// The linear theory's error model of a small mode to `duration` at `tolerance`
/// ([`mode_theory`]); `None` where the theory does not serve the scene
/// ([`mode_theory::serves`]) or reaches no N for it. A law through the theory's errors at two
/// segment counts a doubling apart, the fewer past `tolerance` and the more within it, times
/// [`SAFETY`] as a pilot's model is: its order that of the two, held between 1 and 2 (the
/// rods' nominal), its constant the larger of the two points', so that it bounds both. Its
/// order is also the one the run's live estimate is read at, and where that estimate would
/// read past [`LIVE_MARGIN`] × `tolerance` at the N the law asks ([`mode_theory::live_bound`]:
/// the run would be flagged though it held), the law asks a tenth more, until it would not.
#[inline(never)]
pub fn from_theory(scene: &Scene, duration: f64, tolerance: f64) -> Option<ErrorModel> {
    let Scene::Mode { number, amplitude } = *scene else {
        return None;
    };
    let bracket = mode_theory::bracket(scene, duration, tolerance, SAFETY, MIN_SEGMENTS)?;
    let order = bracket.order().clamp(1.0, 2.0);
    let constant = f64::max(
        bracket.fewer.1 * (bracket.fewer.0 as f64).powf(order),
        bracket.more.1 * (bracket.more.0 as f64).powf(order),
    );
    let model = ErrorModel {
        constant,
        order,
        safety: SAFETY,
    };
    let bound = TipBound::Observed {
        order,
        safety: SAFETY,
    };
    let reads = |n| mode_theory::live_bound(number, amplitude, n, duration, bound);
    let asked = model.segments_for(tolerance).max(MIN_SEGMENTS);
    let mut segments = asked;
    while reads(segments).is_some_and(|b| b > LIVE_MARGIN * tolerance)
        && segments < 4 * bracket.more.0
    {
        segments += (segments / 10).max(1);
    }
    Some(match segments == asked {
        true => model,
        // Raised to ask exactly `segments`: its bound there just under `tolerance`.
        false => ErrorModel {
            constant: f64::max(
                constant,
                tolerance / SAFETY * (segments as f64 - 0.5).powf(order),
            ),
            ..model
        },
    })
}
