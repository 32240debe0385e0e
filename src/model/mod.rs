//! The physics, with no numerical method in it: the scenes a run starts from, the geometry
//! and energy of a chain of segments, the string's small-oscillation modes, and measurements
//! on sampled motion. Everything here is a pure function of its arguments.

pub mod analysis;
pub mod bessel;
pub mod energy;
pub mod fold;
pub mod geometry;
pub mod scene;
pub mod support;
pub mod theory;

pub use energy::Energy;
pub use geometry::Point;
pub use scene::{Scene, ShakeStart};
pub use support::{Support, SupportLedger, SupportNow};
