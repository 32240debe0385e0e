//! Pilot runs for `--tolerance`: the scene itself at a few coarse segment counts, each with
//! its live error estimate (the shadow at N/2), so that the rule models the scene at hand
//! rather than the worst of the six scenes the committed error models were fitted to.
//!
//! The pilots climb a ladder: every method at the first level (cheapest first), then every
//! method at the next. A pilot whose own estimate already holds EPS (with the safety factor)
//! is the run to make, and the climb stops there: a scene that needs few segments pays for
//! little more than one cheap run twice. Past the last level, each method's error model is
//! fitted to its three levels and the cheapest N that model allows is chosen.

use super::cost::{self, Cost};
use super::simulate::{self, Options};
use crate::error::{ConfigError, Diverged};
use crate::methods::MethodKind;
use crate::methods::error_model::ErrorModel;
use crate::methods::tolerance::{self, Choice};
use crate::model::Scene;
use std::time::Instant;

/// The pilots' segment counts: three levels, so that the order is observed, not assumed.
pub const LEVELS: [usize; 3] = [16, 32, 64];

/// The longest simulated time a pilot runs: a long run is judged on its opening stretch (its
/// live estimate goes on watching the rest).
pub const WINDOW: f64 = 10.0;

/// What the pilots' model is multiplied by, beyond the scatter of its own fit: the margin
/// for an error that grows faster between the pilots' N and the chosen one than between the
/// pilots. (The live estimate's misses of the whip, by a factor near 3, come from dividing by
/// the method's nominal order; the pilots divide by the order they observe.)
pub const SAFETY: f64 = 1.5;

/// Frames per time unit at which the pilots read their estimate.
const RATE: f64 = 60.0;

/// What the pilots of one method measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Pilot {
    pub method: MethodKind,
    /// The largest live tip estimate over the frames, at each level flown.
    pub measured: Vec<(usize, f64)>,
    /// The scene's own error model for this method, fitted to `measured`, its safety factor
    /// times [`SAFETY`]; `None` if the pilots could not fit one (or the climb stopped before
    /// the last level).
    pub model: Option<ErrorModel>,
    /// The level at which this method's own pilot held EPS ([`Pilot::bound`]), if it did: the
    /// run chosen.
    pub held_at: Option<usize>,
    /// Why a pilot of this method diverged, if one did: the method is ruled out.
    pub diverged: Option<Diverged>,
    /// CPU seconds the pilots took (one thread).
    pub seconds: f64,
}

impl Pilot {
    fn new(method: MethodKind) -> Self {
        Self {
            method,
            measured: Vec::new(),
            model: None,
            held_at: None,
            diverged: None,
            seconds: 0.0,
        }
    }

    /// Flies `segments` (at the method's default step, to `duration`, at most [`WINDOW`]).
    fn fly_at(&mut self, scene: &Scene, segments: usize, duration: f64) {
        let started = Instant::now();
        let options = Options {
            duration: duration.min(WINDOW),
            log_rate: RATE,
        };
        let dt = self.method.default_dt(segments);
        let run = simulate::run_shadowed(self.method, scene, segments, dt, &options, |_| {});
        if run.refused.is_none() {
            if let Some(why) = run.diverged.or(run.lost) {
                self.diverged = Some(why);
            } else if let Some(max_tip) = run.max_tip {
                self.measured.push((segments, max_tip));
            }
        }
        self.seconds += started.elapsed().as_secs_f64();
    }

    /// A bound on the error of the last level flown: its largest live estimate, rescaled from
    /// the method's nominal order to the order observed from the level below, times
    /// [`SAFETY`]. With one level no order is observed, and the lowest any method shows is
    /// taken: first, a whip's (where the live estimate, made at the nominal second order, is
    /// a third of the error).
    pub fn bound(&self) -> Option<(usize, f64)> {
        let nominal = f64::from(self.method.descriptor().order_in_h);
        let (segments, estimate) = *self.measured.last()?;
        let observed = match self.measured.as_slice() {
            [.., (_, below), _] if estimate > 0.0 && *below > 0.0 => {
                (below / estimate).log2().clamp(1.0, nominal.max(1.0))
            }
            _ => 1.0,
        };
        let rescale = (2f64.powf(nominal) - 1.0) / (2f64.powf(observed) - 1.0);
        Some((segments, estimate * rescale * SAFETY))
    }
}

/// The CPU seconds `method`'s pilot at `segments` is predicted to take.
fn level_seconds(method: MethodKind, segments: usize, duration: f64) -> f64 {
    let dt = method.default_dt(segments);
    Cost::of_estimated_run(method, segments, dt, duration.min(WINDOW), RATE, true).seconds
}

/// Runs `method`'s pilots in `scene` to `duration` (at most [`WINDOW`]) at each of
/// [`LEVELS`], at the method's default step for each, and fits its model.
pub fn fly(method: MethodKind, scene: &Scene, duration: f64) -> Pilot {
    let mut pilot = Pilot::new(method);
    for segments in LEVELS {
        pilot.fly_at(scene, segments, duration);
        if pilot.diverged.is_some() {
            break;
        }
    }
    if pilot.diverged.is_none() {
        pilot.model = own_model(method, &pilot.measured);
    }
    pilot
}

/// How the pilots' ladder ended.
enum Climb {
    /// A pilot held EPS: the run chosen.
    Held(Choice),
    /// Every level flown: the models are fitted.
    Top,
    /// The next pilot would have taken the pilots past the budget.
    OverBudget,
}

/// The ladder: each level for every method not ruled out, cheapest first, until a pilot holds
/// `eps` by its own [`Pilot::bound`] (and its run `fits`), or the next pilot would take the
/// pilots' predicted CPU past `budget` (the committed models' choice's predicted cost:
/// measuring must cost less than what it can save). Past the top level every method's model
/// is fitted.
fn climb(
    eps: f64,
    scene: &Scene,
    duration: f64,
    budget: f64,
    fits: impl Fn(MethodKind, usize, f64) -> bool,
) -> (Vec<Pilot>, Climb) {
    let mut pilots: Vec<Pilot> = tolerance::startable(scene).map(Pilot::new).collect();
    pilots.sort_by(|a, b| {
        let cost = |p: &Pilot| level_seconds(p.method, LEVELS[0], duration);
        cost(a).total_cmp(&cost(b))
    });
    // Predicted, not measured, so that the same command makes the same choice on any machine
    // and under any load.
    let mut spent = 0.0;
    for segments in LEVELS {
        for pilot in pilots.iter_mut() {
            if pilot.diverged.is_some() {
                continue;
            }
            spent += level_seconds(pilot.method, segments, duration);
            if spent > budget {
                return (pilots, Climb::OverBudget);
            }
            pilot.fly_at(scene, segments, duration);
            let Some((flown, bound)) = pilot.bound() else {
                continue;
            };
            let dt = pilot.method.default_dt(flown);
            let held = flown == segments && bound <= eps && pilot.diverged.is_none();
            if held && fits(pilot.method, flown, dt) {
                pilot.held_at = Some(flown);
                let choice = tolerance::at(pilot.method, flown, bound, duration);
                return (pilots, Climb::Held(choice));
            }
        }
    }
    for pilot in pilots.iter_mut().filter(|p| p.diverged.is_none()) {
        pilot.model = own_model(pilot.method, &pilot.measured);
    }
    (pilots, Climb::Top)
}

/// The scene's error model from the pilots' largest estimates at each N. The live estimate is
/// |x_N − x_{N/2}| / (2^p − 1) with p the method's nominal order; where the pilots observe a
/// lower order (a whip's error is first order), the estimates are rescaled to it, and the
/// model refitted.
fn own_model(method: MethodKind, measured: &[(usize, f64)]) -> Option<ErrorModel> {
    let first = ErrorModel::fit(measured.iter().copied())?;
    // An order below 1 (a scene still far from its asymptote at these N) would ask for absurd
    // N: the first order every method has is taken instead.
    let observed = first.order.max(1.0);
    let nominal = f64::from(method.descriptor().order_in_h);
    let rescale = (2f64.powf(nominal) - 1.0) / (2f64.powf(observed.min(nominal)) - 1.0);
    let rescaled = measured.iter().map(|&(n, e)| (n, e * rescale));
    let mut model = ErrorModel::fit(rescaled.clone())?;
    if model.order < 1.0 {
        // Refitted at first order: raising the order of the fitted line alone would predict
        // less than the pilots measured (a whip's error constant still grows at these N).
        model = ErrorModel::fit_at_order(rescaled, 1.0)?;
    }
    Some(ErrorModel {
        safety: model.safety * SAFETY,
        ..model
    })
}

/// Of `method`'s own model (from its pilots) and its committed one, the one that asks fewer
/// segments for `eps`; `None` without an own model. Both bound measured errors: the own
/// model the scene's at N ≤ 64, extrapolated; the committed one the worst of six scenes up to
/// large N. Where a whip's error constant falls at large N, which the pilots cannot see, the
/// committed model is the tighter (from 30°: 0.49/N against the pilots' 0.84/N).
pub fn tighter_model(method: MethodKind, eps: f64, pilots: &[Pilot]) -> Option<ErrorModel> {
    let own = pilots.iter().find(|p| p.method == method)?.model?;
    let committed = method.descriptor().error_model;
    Some(if committed.segments_for(eps) < own.segments_for(eps) {
        committed
    } else {
        own
    })
}

/// What `--tolerance EPS` chooses for `scene`, for a run of `duration` logging `log_rate`
/// frames per time unit within `memory` bytes: the cheapest choice whose run fits in
/// [`tolerance::MAX_SECONDS`] of CPU and that memory: a pilot run that already holds EPS, or
/// the cheapest the scene's own error models allow (measured by the pilots' ladder), or the
/// committed models' choice where the pilots would cost more than it (or found nothing).
/// Returns the pilots flown.
pub fn choose(
    eps: f64,
    scene: &Scene,
    duration: f64,
    log_rate: f64,
    memory: u64,
) -> Result<(Choice, Vec<Pilot>), ConfigError> {
    scene.validate()?;
    if !(eps.is_finite() && eps > 0.0) {
        return Err(ConfigError::Tolerance(eps));
    }
    if duration.is_infinite() {
        return Err(ConfigError::ToleranceEndless(eps));
    }
    let duration = duration.max(0.0);
    // The chosen run carries the live estimate (--tolerance needs it): its shadow counts.
    let cost_of = |method, segments, dt| {
        Cost::of_estimated_run(method, segments, dt, duration, log_rate, true)
    };
    let fits = |method, segments, dt| {
        let cost = cost_of(method, segments, dt);
        cost.bytes <= memory && cost.seconds <= tolerance::MAX_SECONDS
    };
    let committed = tolerance::choose(eps, duration, scene, fits);
    // The pilots may spend no more than the committed models' choice would cost.
    let budget = committed.map_or(f64::INFINITY, |c| {
        cost_of(c.method, c.segments, c.dt).seconds
    });
    let (mut pilots, climbed) = climb(eps, scene, duration, budget, fits);
    match (climbed, committed) {
        (Climb::Held(choice), _) => return Ok((choice, pilots)),
        (Climb::OverBudget, Some(choice)) => {
            pilots.retain(|p| !p.measured.is_empty() || p.diverged.is_some());
            return Ok((choice, pilots));
        }
        _ => {}
    }
    let model = |m: MethodKind| tighter_model(m, eps, &pilots);
    if let Some(choice) =
        tolerance::choose_with(eps, duration, scene, model, LEVELS[0], fits).or(committed)
    {
        return Ok((choice, pilots));
    }
    let best =
        tolerance::tightest(duration, scene, fits).ok_or(ConfigError::ToleranceNoMethod(eps))?;
    let cost = cost_of(best.method, best.segments, best.dt);
    Err(ConfigError::ToleranceUnreachable {
        tolerance: eps,
        limit: format!(
            "{} of CPU and {} of memory",
            cost::seconds_text(tolerance::MAX_SECONDS),
            cost::bytes_text(memory)
        ),
        tightest: best.predicted_error,
        method: best.method.name(),
        segments: best.segments,
        cost: format!(
            "{} of CPU, {}",
            cost::seconds_text(cost.seconds),
            cost::bytes_text(cost.bytes)
        ),
    })
}
