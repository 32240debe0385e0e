//! The numerical methods: each advances the string one time step, pure (state in, state out,
//! no I/O), and describes itself once, in its [`Descriptor`].
//!
//! * [`method`]: what every method is: the [`Method`] trait and its [`Descriptor`];
//! * [`accurate_step`]: the step a method stable at any step needs for its tip, by N and by
//!   how hard the scene whips, on the grid of frame instants;
//! * [`seed`]: the report's finite-difference scheme, first order in h;
//! * [`chain`]: a chain of rigid rods with RK4, second order in h;
//! * [`graded`]: the chain's method on rods graded towards the free end, which resolve the whip;
//! * [`rattle`]: the same chain in maximal coordinates with RATTLE: symplectic, bounded energy;
//! * [`midpoint`]: the same chain and coordinates with an energy–momentum midpoint rule: the
//!   energy kept exactly whatever the steps, which follow the motion;
//! * [`registry`]: the methods a run can choose by name ([`MethodKind`]), each mapped to its
//!   descriptor, and the report's own setting;
//! * [`tridiagonal`]: the bare Thomas solve the seed scheme's step is measured against.
//!
//! Adding a method: one file here that implements [`Method`] and defines its `DESCRIPTOR`,
//! plus its variant in [`MethodKind`] and its line in [`MethodKind::descriptor`] (and, for
//! `--tolerance` to choose it, its error law in `crate::plan::error_model::law`). Files here
//! import what they use from the file that defines it, never through this one, so that no
//! two of them import each other.

pub mod accurate_step;
pub mod chain;
pub(crate) mod constraint_matrix;
pub mod graded;
pub(crate) mod joint_forces;
pub mod method;
pub mod midpoint;
pub mod rattle;
pub mod registry;
pub mod seed;
pub mod tridiagonal;

pub use accurate_step::whole_division;
pub use method::{
    BlowUp, Descriptor, Method, Observation, StepStatistics, TENSION_MAX, round_down_nicely,
    stability_hint,
};
pub use registry::{MethodKind, REPORT, ReportSetting};
