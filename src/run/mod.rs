//! Running a scene: what a run is asked to do ([`config`]), the pure driver that takes a
//! method to its final time and makes frames ([`simulate`](mod@simulate)), a frame and how it
//! is built from the method's state ([`frame`](mod@frame)), when its numbers
//! can no longer be trusted ([`trust`]), the live error estimate from a shadow at half the
//! segments ([`estimate`]), the two-thread pipeline that hands the frames to a
//! [`sink::FrameSink`] ([`pipeline`]), several methods side by side in lockstep ([`lanes`]),
//! a run flown before it was asked for, its frames kept ([`rehearsal`]),
//! what a run reports ([`summary`]; with the program, `progress`), and a whole run in one
//! call ([`whole`]). Nothing here knows where frames end up.
pub mod config;
pub mod cost;
pub mod estimate;
pub mod frame;
pub mod lanes;
pub mod pipeline;
pub mod probe;
#[cfg(feature = "app")]
pub mod progress;
pub mod rehearsal;
mod shadow_steps;
pub mod shake_figures;
pub mod simulate;
pub mod sink;
pub mod summary;
pub mod theory_figures;
pub mod trust;
pub mod whole;

pub use config::{RunConfig, RunPlan};
pub use cost::{Cost, Limits};
pub use simulate::Frame;
pub use sink::FrameSink;
pub use summary::{Status, Summary, Verdict};
pub use whole::{Simulated, simulate};
