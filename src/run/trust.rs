//! When a run's numbers can no longer be trusted: the energy it is measured against, and the
//! bounds past which the swing has blown up. Shared by the run and its shadow.

use crate::methods::Method;

/// The step after which the energy is taken as the reference (the report's criterion: after
/// the start-up burst, since the initial straight state violates the support condition (9)).
pub const REFERENCE_STEP: u64 = 10;

/// An energy change this large, in units of m g L, is beyond anything the swing can do (its
/// whole potential range is 1/2): the run has blown up even if every number is still finite.
pub const ENERGY_BLOWUP: f64 = 1.0;

/// A support tension this large is beyond anything the swing can do (≲ 5/4 from rest).
pub const TENSION_BLOWUP: f64 = 1.0e3;

/// The fine grid's spacing in time units, on which a run's energy is checked and the summary
/// measures the motion (`run::probe`): fine against every motion the summary measures (the
/// fastest, a shake's swing at Ω = 5, moves its peak by (Ω × 1e-3)²/8 ≈ 3e-6 of itself
/// between two instants), and cheap against the steps between.
pub const FINE_GRID: f64 = 1e-3;

/// Steps between two instants of the fine grid at step `dt`: 1 where a step is as long as the
/// grid or longer, at most 1 000.
pub fn steps_between(dt: f64) -> u64 {
    ((FINE_GRID / dt).round() as u64).clamp(1, 1000)
}

/// The energy after [`REFERENCE_STEP`] steps, from a copy of the method (so frames before
/// that step can already report their deviation). Falls back to the initial energy when the
/// copy cannot get there.
pub fn reference_energy(method: &dyn Method) -> f64 {
    let mut probe = method.box_clone();
    for _ in 0..REFERENCE_STEP {
        if probe.step().is_err() {
            return method.energy_less_work();
        }
    }
    probe.energy_less_work()
}
