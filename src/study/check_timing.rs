//! How the tolerance check times its runs: a run as `rope run` makes it (`timed_run`), one
//! of milliseconds the fastest of a few timings ([`fastest`]), and the parts of a ratio side
//! by side ([`fastest_side_by_side`]), so that it is read from timings made in the same
//! minutes.

use super::tip_reference::LOG_RATE;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::estimate::TipBound;
use crate::run::simulate::{self, Options};
use std::ops::ControlFlow;
use std::time::Instant;

/// Runs under this many wall seconds are timed again ([`fastest`]).
pub const RETIMED_BELOW: f64 = 0.05;

/// At most this many timings of a run under [`RETIMED_BELOW`].
pub const TIMINGS: usize = 7;

/// Each of `works`' wall seconds, the fastest of [`TIMINGS`], timed in turn, one after the
/// other, round after round: the parts of a ratio, each timed in the same minutes. A choice's
/// planning and run and the grid's cheapest, each some milliseconds, timed minutes apart,
/// moved the ratio by a third from one check to the next (mode 2 at 1e-3: 3.15× and 3.70×,
/// where its run alone read 2.0 and 2.8 ms).
pub fn fastest_side_by_side<const K: usize>(mut works: [&mut dyn FnMut(); K]) -> [f64; K] {
    let mut seconds = [f64::INFINITY; K];
    for _ in 0..TIMINGS {
        for (work, fastest) in works.iter_mut().zip(&mut seconds) {
            let started = Instant::now();
            work();
            *fastest = fastest.min(started.elapsed().as_secs_f64());
        }
    }
    seconds
}

/// `work`'s wall seconds, the fastest of up to [`TIMINGS`] where it takes under
/// [`RETIMED_BELOW`] (a run of milliseconds moves by half from one timing to the next on a
/// busy machine), and what it returned the first time.
pub fn fastest<T>(mut work: impl FnMut() -> T) -> (f64, T) {
    let started = Instant::now();
    let first = work();
    let mut seconds = started.elapsed().as_secs_f64();
    let mut spent = seconds;
    for _ in 1..TIMINGS {
        if seconds >= RETIMED_BELOW || spent >= RETIMED_BELOW * 2.0 {
            break;
        }
        let again = Instant::now();
        std::hint::black_box(work());
        let took = again.elapsed().as_secs_f64();
        seconds = seconds.min(took);
        spent += took;
    }
    (seconds, first)
}

/// The run the check times: `method` at N = `segments` and step `dt` from `scene` to
/// `duration`, as `rope run` makes it (frames at [`LOG_RATE`], its shadow with it where
/// `shadow` says how it bounds the tip). Whether it stopped (refused or diverged), and the
/// largest bound its live estimate made; `None` if it could not start.
pub(super) fn timed_run(
    scene: &Scene,
    (method, segments, dt): (MethodKind, usize, f64),
    duration: f64,
    shadow: Option<TipBound>,
) -> Option<(bool, Option<f64>)> {
    let options = Options {
        duration,
        log_rate: LOG_RATE,
        frame_grid: None,
    };
    Some(if let Some(bound) = shadow {
        let run = simulate::run_shadowed(method, scene, segments, dt, bound, &options, |_| {});
        (
            run.refused.is_some() || run.diverged.is_some(),
            run.max_tip_bound,
        )
    } else {
        let mut run = method.build(scene, segments, dt).ok()?;
        let outcome = simulate::run(run.as_mut(), &options, None, |_| ControlFlow::Continue(()));
        (outcome.diverged.is_some(), None)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    /// The parts are timed in turn, round after round, each [`TIMINGS`] times: never one part's
    /// timings all together.
    #[test]
    fn the_parts_of_a_ratio_are_timed_in_turn_round_after_round() {
        let order = RefCell::new(Vec::new());
        let mut first = || order.borrow_mut().push(0);
        let mut second = || order.borrow_mut().push(1);
        let mut third = || order.borrow_mut().push(2);
        let seconds = fastest_side_by_side([&mut first, &mut second, &mut third]);
        let rounds: Vec<usize> = (0..TIMINGS).flat_map(|_| [0, 1, 2]).collect();
        assert_eq!(order.into_inner(), rounds);
        assert!(
            seconds.iter().all(|s| s.is_finite() && *s >= 0.0),
            "{seconds:?}"
        );
    }
}
