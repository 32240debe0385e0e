//! The request `rope run --tolerance EPS` makes, in one pass: the request checked (a tolerance,
//! a finite duration, a fold before its snap and wide enough for its pilots), the committed
//! models looked up ([`Committed`]), the pilots flown over the scene itself while they can
//! still save more than they cost ([`pilot`]), and the cheapest run the models allow
//! ([`choice`]), or a refusal that says what would work. The run's own live estimate then
//! verifies it at every step.

use super::choice::{self, Choice};
use super::committed::{Committed, Source};
use super::pilot::{self, Basis, FOLD_RODS_ACROSS_GAP, FirstPilot, Pilots, Rehearse, levels};
use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::model::{Scene, fold};
use crate::run::cost::{self, Cost};

/// Frames per time unit a choice's cost counts, whatever the run will log: the frames cost
/// little beside the steps, and a choice that followed them would change with `--log-rate`
/// (from 30° at 1e-3 it did, between 60 and 600 frames a unit). Where the run goes, or how
/// often it is drawn, never changes what it models.
pub const COSTED_LOG_RATE: f64 = 60.0;

/// What `--tolerance EPS` chooses for `scene`, for a run of `duration` within `memory` bytes (its
/// frames costed at [`COSTED_LOG_RATE`], whatever it logs): the cheapest choice whose run fits in
/// [`choice::MAX_SECONDS`] of CPU and that memory: a pilot run that already holds EPS, or the
/// cheapest the scene's own error models allow (measured by the pilots' ladder), or the committed
/// models' choice where the pilots would cost more than it (or found nothing). Returns the pilots
/// flown.
pub fn choose(
    eps: f64,
    scene: &Scene,
    duration: f64,
    memory: u64,
) -> Result<(Choice, Pilots), ConfigError> {
    choose_telling(eps, scene, duration, memory, &|_| None, |_| {})
}

/// As [`choose`], each pilot flown as the run its choice would make where `rehearse` gives
/// that run's plan (a pilot that holds is then that run, kept in [`Pilots::rehearsal`]), and
/// telling `before_flying` of the first pilot just before it flies, once the request has passed
/// every refusal (not at all where no pilot flies): a run says it where the pilots take a while
/// (a narrow fold's pilots start at sixteen rods across its gap: from a gap of 0.005,
/// N = 3 200, 12 s of CPU to t = 1).
pub fn choose_telling(
    eps: f64,
    scene: &Scene,
    duration: f64,
    memory: u64,
    rehearse: Rehearse<'_>,
    before_flying: impl FnOnce(FirstPilot),
) -> Result<(Choice, Pilots), ConfigError> {
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
        Cost::of_estimated_run(method, segments, dt, duration, COSTED_LOG_RATE, true)
    };
    let fits = |method, segments, dt| {
        let cost = cost_of(method, segments, dt);
        cost.bytes <= memory && cost.seconds <= choice::MAX_SECONDS
    };
    let limit = || {
        format!(
            "{} of CPU and {} of memory",
            cost::seconds_text(choice::MAX_SECONDS),
            cost::bytes_text(memory)
        )
    };
    // A fold is served to its snap, by pilots from N = 16 / gap: past the snap, or with a gap
    // so narrow that the first pilot cannot fit, it is refused before one flies.
    if let Scene::Fold { gap } = *scene {
        let snap = fold::snap_time(gap);
        if duration > snap {
            return Err(ConfigError::ToleranceFoldPastSnap {
                tolerance: eps,
                duration,
                gap,
                snap,
                speed: fold::speed(fold::arm_runs_out(gap)),
            });
        }
        let first = levels(scene)[0];
        let flies = |m: MethodKind| fits(m, first, m.tolerance_dt(first));
        if !choice::startable(scene, duration).any(flies) {
            return Err(ConfigError::ToleranceFoldPilots {
                gap,
                segments: FOLD_RODS_ACROSS_GAP / gap,
                limit: limit(),
            });
        }
    }
    // The committed models, looked up once: the choice and the pilots' climb read them.
    let models = Committed::look_up(scene, duration, eps);
    let seconds = |c: &Choice| cost_of(c.method, c.segments, c.dt).seconds;
    let asked = pilot::Asked {
        eps,
        scene,
        duration,
        models: &models,
    };
    let climbed = pilot::climb(asked, seconds, fits, rehearse, before_flying);
    let (flown, rehearsal) = (climbed.pilots, climbed.rehearsal);
    if let Some(best) = climbed.best {
        let basis = match (best.basis, models.source(best.choice.method)) {
            (Basis::Committed | Basis::CommittedTighter | Basis::CommittedOverPilots, source)
                if source != Source::Law =>
            {
                match source {
                    Source::Atlas => Basis::Atlas,
                    _ => Basis::Theory,
                }
            }
            (basis, _) => basis,
        };
        let tip_bound = pilot::tip_bound(scene, &flown, best.choice.method, &models);
        let choice = Choice {
            tip_bound,
            ..best.choice
        };
        return Ok((
            choice,
            Pilots {
                flown,
                basis,
                rehearsal,
            },
        ));
    }
    let best =
        choice::tightest(duration, scene, fits).ok_or(ConfigError::ToleranceNoMethod(eps))?;
    let cost = cost_of(best.method, best.segments, best.dt);
    Err(ConfigError::ToleranceUnreachable {
        tolerance: eps,
        limit: limit(),
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
