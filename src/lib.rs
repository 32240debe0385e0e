//! # rope
//!
//! An inextensible string (a rope or chain fixed at one end, free at the other) swinging under
//! gravity, after Miha Čančula's 2012 report (`shared/physics.md` restates it in English).
//!
//! The crate is split in two halves that know nothing of each other:
//!
//! * the **numeric core**, pure and free of I/O: [`scene`] builds initial states, [`method`]
//!   advances them (the report's finite-difference scheme [`seed::Seed`] and a chain of rigid
//!   rods [`chain::Chain`]), [`geometry`] turns angles into positions and energy, and
//!   [`simulate`] drives a method to a final time, producing [`simulate::Frame`]s and watching
//!   for divergence;
//! * the **edges**: [`logger`] writes frames to a Rerun recording stream, [`output`] opens
//!   where it goes (a spawned or connected viewer, a gRPC endpoint viewers join at any time,
//!   an `.rrd` file, stdout, or several at once) and [`viewer_link`] keeps a viewer that went
//!   away from ever stalling a run; [`app`] wires the simulation and the logger threads
//!   together for `rope run`, [`progress`] shows how far it has got, and [`study`] runs
//!   grids of simulations and charts speed against accuracy for `rope study`.
//!
//! Units are dimensionless: length L = 1, gravity g = 1, mass per length 1, time in sqrt(L/g).
//! Coordinates: x horizontal away from the support, **y pointing down**; φ is the angle of the
//! tangent below the horizontal.

pub mod analysis;
pub mod app;
pub mod bessel;
pub mod chain;
pub mod cli;
pub mod color;
pub mod error;
pub mod geometry;
pub mod logger;
pub mod method;
pub mod output;
pub mod progress;
pub mod scene;
pub mod seed;
pub mod simulate;
pub mod study;
pub mod summary;
pub mod tridiagonal;
pub mod viewer_link;

pub use error::{ConfigError, Diverged};
pub use method::{Method, MethodKind};
pub use scene::Scene;
