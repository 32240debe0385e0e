//! Pilot runs for `--tolerance`: the scene itself at a few coarse segment counts, each with
//! its live error estimate (the shadow at N/2), so that the rule models the scene at hand
//! rather than the worst of the six scenes the committed error models were fitted to.

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
    /// The largest live tip estimate over the frames, at each level.
    pub measured: Vec<(usize, f64)>,
    /// The scene's own error model for this method, fitted to `measured`, its safety factor
    /// times [`SAFETY`]; `None` if the pilots could not fit one.
    pub model: Option<ErrorModel>,
    /// Why a pilot of this method diverged, if one did: the method is ruled out.
    pub diverged: Option<Diverged>,
    /// CPU seconds the pilots took (one thread).
    pub seconds: f64,
}

/// The CPU seconds `method`'s pilots are predicted to take for a run of `duration`.
pub fn predicted_seconds(method: MethodKind, duration: f64) -> f64 {
    LEVELS
        .iter()
        .map(|&n| {
            let dt = method.default_dt(n);
            Cost::of_estimated_run(method, n, dt, duration.min(WINDOW), RATE, true).seconds
        })
        .sum()
}

/// Runs `method`'s pilots in `scene` to `duration` (at most [`WINDOW`]) at each of
/// [`LEVELS`], at the method's default step for each.
pub fn fly(method: MethodKind, scene: &Scene, duration: f64) -> Pilot {
    let started = Instant::now();
    let options = Options {
        duration: duration.min(WINDOW),
        log_rate: RATE,
    };
    let mut pilot = Pilot {
        method,
        measured: Vec::new(),
        model: None,
        diverged: None,
        seconds: 0.0,
    };
    for segments in LEVELS {
        let dt = method.default_dt(segments);
        let run = simulate::run_shadowed(method, scene, segments, dt, &options, |_| {});
        if run.refused.is_some() {
            continue;
        }
        if let Some(why) = run.diverged.or(run.lost) {
            pilot.diverged = Some(why);
            break;
        }
        if let Some(max_tip) = run.max_tip {
            pilot.measured.push((segments, max_tip));
        }
    }
    if pilot.diverged.is_none() {
        pilot.model = own_model(method, &pilot.measured);
    }
    pilot.seconds = started.elapsed().as_secs_f64();
    pilot
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
    let model = ErrorModel::fit(measured.iter().map(|&(n, e)| (n, e * rescale)))?;
    Some(ErrorModel {
        order: model.order.max(1.0),
        safety: model.safety * SAFETY,
        ..model
    })
}

/// What `--tolerance EPS` chooses for `scene`, for a run of `duration` logging `log_rate`
/// frames per time unit within `memory` bytes: the cheapest choice whose run fits in
/// [`tolerance::MAX_SECONDS`] of CPU and that memory, from the scene's own error models
/// measured by pilot runs ([`fly`]), or from the committed models where those already prove a
/// run cheaper than the pilots (or the pilots found none). Returns the pilots flown.
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
    // The pilots cost what runs at their levels cost; a choice the committed models already
    // prove cheaper than that is taken as it is.
    let pilots_cost: f64 = tolerance::startable(scene)
        .map(|m| predicted_seconds(m, duration))
        .sum();
    if let Some(choice) = committed
        && cost_of(choice.method, choice.segments, choice.dt).seconds <= pilots_cost
    {
        return Ok((choice, Vec::new()));
    }
    let pilots: Vec<Pilot> = tolerance::startable(scene)
        .map(|m| fly(m, scene, duration))
        .collect();
    let own_model = |m: MethodKind| pilots.iter().find(|p| p.method == m).and_then(|p| p.model);
    if let Some(choice) =
        tolerance::choose_with(eps, duration, scene, own_model, LEVELS[0], fits).or(committed)
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
