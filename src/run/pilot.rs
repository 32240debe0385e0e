//! Pilot runs for `--tolerance`: the scene itself at a few coarse segment counts, each with
//! its live error estimate (the shadow at N/2), so that the rule models the scene at hand
//! rather than the worst of the six scenes the committed error models were fitted to.

use super::cost::Cost;
use super::estimate::Shadow;
use super::simulate::{self, Options, Watch};
use crate::error::Diverged;
use crate::methods::MethodKind;
use crate::methods::error_model::ErrorModel;
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
        let (Ok(mut run), Ok(Some(mut shadow))) = (
            method.build(scene, segments, dt),
            Shadow::new(method, scene, segments, dt),
        ) else {
            continue;
        };
        let watch = Watch {
            shadow: &mut shadow,
            tolerance: None,
        };
        let outcome = simulate::run_watched(run.as_mut(), Some(watch), &options, None, |_| {
            std::ops::ControlFlow::Continue(())
        });
        let lost = outcome.estimate.as_ref().and_then(|e| e.lost.clone());
        if let Some(why) = outcome.diverged.or(lost) {
            pilot.diverged = Some(why);
            break;
        }
        if let Some(estimate) = outcome.estimate {
            pilot.measured.push((segments, estimate.max_tip));
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
