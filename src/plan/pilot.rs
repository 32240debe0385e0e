//! Pilot runs for `--tolerance`: the scene itself at a few coarse segment counts, each with
//! its live error estimate (the shadow at N/2), so that the rule models the scene at hand
//! rather than the worst of the six scenes the committed error models were fitted to.
//!
//! The pilots climb a ladder: every method at the first level (cheapest first), then every
//! method at the next; of the methods that share a discretization (the chain of rods), only
//! the cheapest flies, since the others' error at their tolerance steps is the same. A pilot
//! whose own estimate already holds EPS (with the safety factor) is the run to make, and the
//! climb stops there. After each pilot, each method's own error model is fitted to the levels
//! it has flown, and the cheapest run those models (or the committed ones) allow is the best
//! known so far; the climb also stops where the next pilot would take the pilots' cost past
//! that run's, and passes over a pilot that could not save its own cost: a scene that needs few
//! segments pays for little more than one cheap run twice. Where the release atlas rules a
//! method's choice, its pilot could change it only by holding at its own level, and flies only
//! where the atlas's error there is within EPS ([`Committed::may_hold`]).

pub use super::basis::Basis;
use super::choice::{self, Choice};
use super::committed::{Committed, Source};
use super::error_model::ErrorModel;
use crate::error::Diverged;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::cost::Cost;
use crate::run::estimate::TipBound;
use crate::run::rehearsal::Rehearsal;
use crate::run::simulate::{self, Options};
use crate::run::{RunPlan, Summary};
use std::time::Instant;

/// The pilots' segment counts: three levels, so that the order is observed, not assumed.
pub const LEVELS: [usize; 3] = [16, 32, 64];

/// Rods across a fold's gap at its first pilot ([`levels`]).
pub const FOLD_RODS_ACROSS_GAP: f64 = 16.0;

/// The pilots' segment counts for `scene`: [`LEVELS`], but for a fold, whose bend must be
/// drawn before its error shrinks at an order the pilots can read: from sixteen rods across
/// the gap (eight in the shadow at N/2), N₀ = ⌈16 / gap⌉, then 2N₀ and 4N₀ (800, 1 600 and
/// 3 200 for a gap of 0.02). Coarser, the error has not reached its order and the estimate
/// reads less than it: from a gap of 0.02 to t = 1.18 the tip's error at every step is 2.7e-3
/// at N = 200, 1.7e-3 at 400 and 6.9e-4 at 800 (falling 1.6, 2.5, then 3.4 times a
/// doubling), and the live estimate's first-order bound is 0.58 of the error at eight rods
/// across the gap, 1.5 times it from sixteen (both gaps measured, 0.02 and 0.04:
/// `cargo run --release --example fold_levels`, docs/measurements.md).
pub fn levels(scene: &Scene) -> [usize; 3] {
    match *scene {
        Scene::Fold { gap } => {
            // (At most 2^40: a narrower gap asks more than any machine holds, and is refused
            // as such before a pilot flies.)
            let first = (FOLD_RODS_ACROSS_GAP / gap).ceil().min(2f64.powi(40)) as usize;
            let first = first.max(LEVELS[0]);
            [first, 2 * first, 4 * first]
        }
        _ => LEVELS,
    }
}

/// The longest simulated time a pilot runs: a long run is judged on its opening stretch (its
/// live estimate goes on watching the rest).
pub const WINDOW: f64 = 10.0;

pub use super::error_model::SAFETY;

/// Frames per time unit at which the pilots read their estimate.
const RATE: f64 = 60.0;

/// What the pilots of one method measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Pilot {
    pub method: MethodKind,
    /// The largest live tip estimate at every step the pilot shares with its shadow, at each
    /// level flown.
    pub measured: Vec<(usize, f64)>,
    /// The scene's own error model for this method, fitted to `measured` after each level
    /// flown, its safety factor times [`SAFETY`]; `None` before its first pilot, or if one
    /// diverged.
    pub model: Option<ErrorModel>,
    /// The level at which this method's own pilot held EPS ([`Pilot::bound`]), if it did: the
    /// run chosen.
    pub held_at: Option<usize>,
    /// Why a pilot of this method diverged, if one did: the method is ruled out.
    pub diverged: Option<Diverged>,
    /// The levels at which the method ran but its estimate did not: the shadow at N/2 (a
    /// coarser run, which may fail where the method does not) diverged, and why. Such a
    /// level measures nothing and rules nothing out: the next level flies.
    pub shadow_lost: Vec<(usize, Diverged)>,
    /// The cheaper method of the same discretization whose pilots stand for this one's, if
    /// there is one: this one is not flown (it would measure the same spatial error), and is
    /// chosen, if at all, by its committed model.
    pub measured_by: Option<MethodKind>,
    /// CPU seconds the pilots took (one thread).
    pub seconds: f64,
    /// Why the climb passed this method's pilot over, and at which levels, if it did.
    pub passed_over: Option<PassedOver>,
}

/// Why the climb passed a method's pilot over, and at which levels, so that the announcement
/// can say why a method was not flown.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PassedOver {
    pub why: PassedOverWhy,
    /// The levels passed over for that reason, lowest first.
    pub levels: Vec<usize>,
}

/// Why the climb passed a pilot over at a level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PassedOverWhy {
    /// Its committed model (the release atlas, or the mode theory) puts its error there past
    /// EPS: the pilot could change the choice only by holding, and could not
    /// ([`Committed::may_hold`]).
    CannotHold(Source),
    /// It could not save what it costs: the best run known costs less than the pilots spent
    /// so far, this one and its method's likeliest run together.
    CannotSave,
}

impl Pilot {
    /// Whether this method's pilots flew: measured a level, lost its shadow, or diverged.
    pub fn flew(&self) -> bool {
        !self.measured.is_empty() || self.diverged.is_some() || !self.shadow_lost.is_empty()
    }

    fn new(method: MethodKind) -> Self {
        Self {
            method,
            measured: Vec::new(),
            model: None,
            held_at: None,
            diverged: None,
            shadow_lost: Vec::new(),
            measured_by: None,
            seconds: 0.0,
            passed_over: None,
        }
    }

    /// Notes that the climb passed this pilot over at `segments`, and why: a reason other
    /// than the last one noted replaces it.
    fn pass_over(&mut self, segments: usize, why: PassedOverWhy) {
        match &mut self.passed_over {
            Some(p) if p.why == why => p.levels.push(segments),
            _ => {
                self.passed_over = Some(PassedOver {
                    why,
                    levels: vec![segments],
                })
            }
        }
    }

    /// Flies `segments` (at the method's tolerance step, to `duration`, at most [`WINDOW`]):
    /// as the run its choice would make, where the pilot is the whole run and `rehearse` gives
    /// that run's plan (its frames kept, the rehearsal returned), else bare.
    fn fly_at(
        &mut self,
        scene: &Scene,
        segments: usize,
        duration: f64,
        rehearse: Rehearse<'_>,
    ) -> Option<Rehearsal> {
        let started = Instant::now();
        let dt = self.method.tolerance_dt(segments);
        let whole = duration <= WINDOW;
        let plan = whole
            .then(|| rehearse(&choice::at(self.method, segments, f64::NAN, duration)))
            .flatten();
        let (run, rehearsal) = match plan.map(Rehearsal::fly) {
            Some(Ok(rehearsal)) => (Flight::of(&rehearsal.summary), Some(rehearsal)),
            Some(Err(_)) => (Flight::default(), None),
            None => (
                Flight::bare(self.method, scene, segments, dt, duration),
                None,
            ),
        };
        if let Some(why) = run.diverged {
            self.diverged = Some(why);
        } else if let Some(why) = run.lost {
            self.shadow_lost.push((segments, why));
        } else if let Some(max_tip) = run.max_tip {
            self.measured.push((segments, max_tip));
        }
        self.seconds += started.elapsed().as_secs_f64();
        rehearsal
    }

    /// A bound on the error of the last level flown: its largest live estimate, rescaled from
    /// the method's nominal order to the order observed from the level below, times
    /// [`SAFETY`]. With one level no order is observed, and the lowest any method shows is
    /// taken: first, a whip's (where the live estimate, made at the nominal second order, is
    /// a third of the error).
    pub fn bound(&self) -> Option<(usize, f64)> {
        let nominal = f64::from(self.method.descriptor().order_in_h);
        let (segments, estimate) = *self.measured.last()?;
        let observed = self.observed_order().unwrap_or(1.0);
        let rescale = (2f64.powf(nominal) - 1.0) / (2f64.powf(observed) - 1.0);
        Some((segments, estimate * rescale * SAFETY))
    }

    /// The fewest segments this method is likely to need for `eps`, at least `first`: from its
    /// last level flown, were its error to fall at the method's nominal order from the
    /// estimate there, with no safety (the estimate is made at that order); `first` before a
    /// level. An estimate, not a bound (an error may fall faster than the nominal order for a
    /// while): it only rules which pilots are worth flying, never what the run may claim.
    pub fn fewest(&self, eps: f64, first: usize) -> usize {
        let nominal = f64::from(self.method.descriptor().order_in_h).max(1.0);
        match self.measured.last() {
            Some(&(segments, estimate)) if estimate > eps => {
                let wanted = segments as f64 * (estimate / eps).powf(1.0 / nominal);
                (wanted.min(1e12).ceil() as usize).max(first)
            }
            _ => first,
        }
    }

    /// The order the estimates fell at between the last two levels flown, between 1 (a
    /// whip's, the lowest any method shows) and the method's nominal order; `None` before two.
    pub fn observed_order(&self) -> Option<f64> {
        let nominal = f64::from(self.method.descriptor().order_in_h);
        match self.measured.as_slice() {
            [.., (_, below), (_, last)] if *last > 0.0 && *below > 0.0 => {
                Some((below / last).log2().clamp(1.0, nominal.max(1.0)))
            }
            _ => None,
        }
    }
}

/// The plan a pilot of a choice's method, N and k flies as, the very run that choice would make,
/// where its frames can be kept ([`Rehearsal::fits`]); `None`: it flies bare.
pub type Rehearse<'a> = &'a dyn Fn(&Choice) -> Option<RunPlan>;

/// What one pilot's flight measured.
#[derive(Default)]
struct Flight {
    diverged: Option<Diverged>,
    /// Why its shadow stopped before it, if it did.
    lost: Option<Diverged>,
    /// The largest live tip estimate at any step it shares with its shadow; `None` where it
    /// could not start or carry a shadow.
    max_tip: Option<f64>,
}

impl Flight {
    /// The pilot flown bare: the method and its shadow, frames at [`RATE`] (none kept).
    fn bare(method: MethodKind, scene: &Scene, segments: usize, dt: f64, duration: f64) -> Self {
        let options = Options {
            duration: duration.min(WINDOW),
            log_rate: RATE,
            frame_grid: None,
        };
        let bound = TipBound::FirstOrder;
        let run = simulate::run_shadowed(method, scene, segments, dt, bound, &options, |_| {});
        match run.refused {
            Some(_) => Self::default(),
            None => Self {
                diverged: run.diverged,
                lost: run.lost,
                max_tip: run.max_tip,
            },
        }
    }

    /// What a rehearsal's summary says of the same.
    fn of(summary: &Summary) -> Self {
        let estimate = summary.error_estimate.as_ref();
        Self {
            diverged: summary.diverged.clone(),
            lost: estimate.and_then(|e| e.lost.clone()),
            max_tip: estimate.map(|e| e.max_tip),
        }
    }
}

/// How the chosen run's live estimate bounds its tip error ([`TipBound`]): for a mode, at the
/// order the pilots of its rods observed ([`Pilot::observed_order`]) times [`SAFETY`], as a
/// pilot's own bound is, or where they observed none, at the order the linear theory shows
/// for the chosen rods ([`Committed::theory_order`]); elsewhere at first order. A mode swings
/// with no whip, and its error keeps the order the pilots saw: mode 2 at 1e-4, the chain's
/// pilots saw 1.75 from N = 32 to 64, and at the N = 134 chosen the tip erred by 4.2e-5 where
/// the first-order bound read 1.1e-4, a false alarm, and the bound at 1.75 with its safety
/// 6.9e-5. A release whips past the pilots' N, and a fold's order climbs between its levels
/// (1.6, 2.5, then 3.4 a doubling): those keep the first order.
pub fn tip_bound(
    scene: &Scene,
    flown: &[Pilot],
    method: MethodKind,
    models: &Committed,
) -> TipBound {
    let of = |m: MethodKind| flown.iter().find(|p| p.method == m);
    let pilot = of(method).and_then(|p| p.measured_by.map_or(Some(p), of));
    let theory = (models.source(method) == Source::Theory)
        .then_some(models.theory_order)
        .flatten();
    match (scene, pilot.and_then(Pilot::observed_order).or(theory)) {
        (Scene::Mode { .. }, Some(order)) => TipBound::Observed {
            order,
            safety: SAFETY,
        },
        _ => TipBound::FirstOrder,
    }
}

/// The CPU seconds `method`'s pilot at `segments` is predicted to take.
fn level_seconds(method: MethodKind, segments: usize, duration: f64) -> f64 {
    let dt = method.tolerance_dt(segments);
    Cost::of_estimated_run(method, segments, dt, duration.min(WINDOW), RATE, true).seconds
}

/// What the pilots flew for a choice, and what the choice rests on.
#[derive(Clone, Debug)]
pub struct Pilots {
    /// One per method that can start from the scene, cheapest first (some perhaps not flown).
    pub flown: Vec<Pilot>,
    pub basis: Basis,
    /// The pilot that held, flown as the run its choice makes, its frames kept (where the
    /// caller asked it and they fit: [`Rehearse`]): that run, not to be flown again.
    pub rehearsal: Option<Rehearsal>,
}

impl Pilots {
    /// CPU seconds the pilots took (one thread).
    pub fn seconds(&self) -> f64 {
        self.flown.iter().map(|p| p.seconds).sum()
    }
}

/// The best choice known so far during the climb, and what it would cost.
#[derive(Clone, Copy)]
pub(super) struct Best {
    pub(super) choice: Choice,
    seconds: f64,
    pub(super) basis: Basis,
}

/// The ladder: each level for every method not ruled out, cheapest first, until a pilot holds
/// `eps` by its own [`Pilot::bound`] (and its run `fits`), or the next pilot would take the
/// pilots' predicted CPU past what the best choice known so far would cost (measuring must
/// cost less than it can save). Passed over: a pilot that could not hold where the atlas or the
/// mode theory rules ([`Committed::may_hold`]), and one that could not save its own cost, the
/// best less its method's likeliest run ([`Pilot::fewest`]). That best is at first the
/// committed models' choice ([`choice::from_committed`]), then after each pilot the cheapest
/// that the pilots' own models allow, where cheaper. `seconds` is a run's predicted CPU, shadow included; each pilot flies as `rehearse` says;
/// `before_flying` is told of the first pilot just before it flies (not at all where none does).
pub(super) fn climb(
    asked: Asked<'_>,
    seconds: impl Fn(&Choice) -> f64,
    fits: impl Fn(MethodKind, usize, f64) -> bool + Copy,
    rehearse: Rehearse<'_>,
    before_flying: impl FnOnce(FirstPilot),
) -> Climbed {
    let Asked {
        eps,
        scene,
        duration,
        models,
    } = asked;
    let mut before_flying = Some(before_flying);
    let mut pilots: Vec<Pilot> = choice::startable(scene, duration).map(Pilot::new).collect();
    let levels = levels(scene);
    pilots.sort_by(|a, b| {
        let cost = |p: &Pilot| level_seconds(p.method, levels[0], duration);
        cost(a).total_cmp(&cost(b))
    });
    for i in 1..pilots.len() {
        let discretization = pilots[i].method.descriptor().discretization;
        pilots[i].measured_by = pilots[..i]
            .iter()
            .find(|p| p.method.descriptor().discretization == discretization)
            .map(|p| p.method);
    }
    let committed = choice::from_committed(eps, duration, scene, models, fits);
    let by_committed = committed.map(|choice| Best {
        choice,
        seconds: seconds(&choice),
        basis: Basis::Committed,
    });
    let mut best = by_committed;
    // Predicted, not measured, so that the same command makes the same choice on any machine
    // and under any load.
    let mut spent = 0.0;
    for segments in levels {
        for i in 0..pilots.len() {
            let pilot = &mut pilots[i];
            if pilot.diverged.is_some() || pilot.measured_by.is_some() {
                continue;
            }
            if !models.may_hold(pilot.method, segments, eps) {
                pilot.pass_over(
                    segments,
                    PassedOverWhy::CannotHold(models.source(pilot.method)),
                );
                continue;
            }
            let cost = level_seconds(pilot.method, segments, duration);
            if best.is_some_and(|b| spent + cost > b.seconds) {
                return Climbed::to(pilots, best);
            }
            // A pilot that cannot save what it costs does not fly: where the best known is
            // measured (not a committed model outside its window), the most it could save is
            // that run's cost less its method's likeliest run ([`Pilot::fewest`]).
            let trusted =
                best.filter(|b| b.basis != Basis::Committed || models.covers(b.choice.method));
            if let Some(b) = trusted {
                let mut fewest = pilot.fewest(eps, levels[0]);
                if models.covers(pilot.method) {
                    // Its committed model may rule once it has flown ([`ruling_model`]).
                    fewest =
                        fewest.min(models.model(pilot.method).segments_for(eps).max(levels[0]));
                }
                let floor = seconds(&choice::at(pilot.method, fewest, eps, duration));
                if spent + cost > b.seconds - floor {
                    pilot.pass_over(segments, PassedOverWhy::CannotSave);
                    continue;
                }
            }
            spent += cost;
            if let Some(tell) = before_flying.take() {
                tell(FirstPilot {
                    method: pilot.method,
                    segments,
                    duration: duration.min(WINDOW),
                    seconds: cost,
                });
            }
            let rehearsal = pilot.fly_at(scene, segments, duration, rehearse);
            if let Some((flown, bound)) = pilot.bound() {
                let dt = pilot.method.tolerance_dt(flown);
                let held = flown == segments && bound <= eps && pilot.diverged.is_none();
                if held && fits(pilot.method, flown, dt) {
                    pilot.held_at = Some(flown);
                    let choice = choice::at(pilot.method, flown, bound, duration);
                    let seconds = seconds(&choice);
                    return Climbed {
                        pilots,
                        best: Some(Best {
                            choice,
                            seconds,
                            basis: Basis::Held,
                        }),
                        rehearsal,
                    };
                }
            }
            pilot.model = match pilot.diverged {
                None => own_model(pilot.method, &pilot.measured),
                Some(_) => None,
            };
            // Every model as it now stands: a method's older choice goes with its older model.
            let modelled =
                cheapest_modelled(eps, duration, levels[0], models, &pilots, &seconds, fits);
            // Past the committed models' window, what the pilots measured rules.
            best = match (modelled, by_committed) {
                (Some(m), Some(c)) if c.seconds < m.seconds && models.covers(c.choice.method) => {
                    Some(c)
                }
                (Some(m), _) => Some(m),
                (None, c) => c,
            };
        }
    }
    Climbed::to(pilots, best)
}

/// What the pilots are asked: `eps` for `scene` to `duration`, its committed models `models`
/// ([`Committed::look_up`]).
pub(super) struct Asked<'a> {
    pub(super) eps: f64,
    pub(super) scene: &'a Scene,
    pub(super) duration: f64,
    pub(super) models: &'a Committed,
}

/// Where the ladder ended.
pub(super) struct Climbed {
    pub(super) pilots: Vec<Pilot>,
    pub(super) best: Option<Best>,
    /// The pilot that held, flown as its run, where it could be ([`Rehearse`]).
    pub(super) rehearsal: Option<Rehearsal>,
}

impl Climbed {
    fn to(pilots: Vec<Pilot>, best: Option<Best>) -> Self {
        Self {
            pilots,
            best,
            rehearsal: None,
        }
    }
}

/// The cheapest run, by `seconds`, of at least `fewest` segments (the pilots' first level),
/// that the pilots' models allow (each method's [`ruling_model`]) and that `fits`.
fn cheapest_modelled(
    eps: f64,
    duration: f64,
    fewest: usize,
    models: &Committed,
    pilots: &[Pilot],
    seconds: impl Fn(&Choice) -> f64,
    fits: impl Fn(MethodKind, usize, f64) -> bool + Copy,
) -> Option<Best> {
    pilots
        .iter()
        .filter_map(|pilot| {
            let method = pilot.method;
            let (model, basis) = ruling_model(pilot, eps, models)?;
            let choice = choice::by_model(method, &model, eps, fewest, duration);
            if !fits(method, choice.segments, choice.dt) {
                return None;
            }
            Some(Best {
                choice,
                seconds: seconds(&choice),
                basis,
            })
        })
        .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
}

/// The scene's error model from the pilots' largest estimates at each N. The live estimate is
/// |x_N − x_{N/2}| / (2^p − 1) with p the method's nominal order; where the pilots observe a
/// lower order (a whip's error is first order), the estimates are rescaled to it, and the
/// model refitted.
fn own_model(method: MethodKind, measured: &[(usize, f64)]) -> Option<ErrorModel> {
    // An order below 1 (a scene still far from its asymptote at these N) would ask for absurd
    // N, and one level shows none: the first order every method has is taken instead.
    let observed = ErrorModel::fit(measured.iter().copied()).map_or(1.0, |m| m.order.max(1.0));
    let nominal = f64::from(method.descriptor().order_in_h);
    let rescale = (2f64.powf(nominal) - 1.0) / (2f64.powf(observed.min(nominal)) - 1.0);
    let rescaled = measured.iter().map(|&(n, e)| (n, e * rescale));
    let model = match ErrorModel::fit(rescaled.clone()) {
        Some(model) if model.order >= 1.0 => model,
        // Refitted at first order: raising the order of the fitted line alone would predict
        // less than the pilots measured (a whip's error constant still grows at these N).
        _ => ErrorModel::fit_at_order(rescaled, 1.0)?,
    };
    Some(ErrorModel {
        safety: model.safety * SAFETY,
        ..model
    })
}

/// Of `pilot`'s method's own model (from its pilots) and its committed one (in `models`, for this
/// scene, duration and tolerance: [`Committed::look_up`]), the one the choice rests on, and which
/// it is; `None` without an own model. The committed one only where it was measured over the run's
/// duration ([`Committed::covers`]: from 45° to t = 5, the law fitted to t ≤ 3 asked N = 491 where
/// the pilots' 0.93/N was near the truth, and the run missed 1e-3), and there:
/// - for a release, always ([`Committed::floors_pilots`]): its error constant goes on growing
///   past the pilots' N (from 80°, fitted at 0.14/N at N ≤ 64, it is 0.30/N at N = 2 639,
///   where the pilots' own model asked N = 2 639 for 1e-4 and the run missed it by 15 %);
/// - else where it asks fewer segments for `eps`.
///
/// Both bound measured errors: the own model the scene's at N ≤ 64, extrapolated; the
/// committed one the release atlas's at this angle or its neighbours, or the worst of six
/// scenes, up to large N. Where a whip's error constant falls at large N, which the pilots
/// cannot see, the committed model is the tighter (from 30°: 0.49/N against the pilots'
/// 0.84/N).
pub fn ruling_model(pilot: &Pilot, eps: f64, models: &Committed) -> Option<(ErrorModel, Basis)> {
    let own = pilot.model?;
    let committed = models.model(pilot.method);
    let tighter = committed.segments_for(eps) < own.segments_for(eps);
    Some(match models.covers(pilot.method) {
        true if tighter => (committed, Basis::CommittedTighter),
        true if models.floors_pilots => (committed, Basis::CommittedOverPilots),
        _ => (own, Basis::OwnModel),
    })
}

/// The first pilot a choice flies, before it flies: the cheapest method at the first level,
/// and its predicted CPU seconds (shadow included, as the climb counts them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstPilot {
    pub method: MethodKind,
    pub segments: usize,
    /// The simulated time it runs: the run's duration, at most [`WINDOW`].
    pub duration: f64,
    pub seconds: f64,
}
