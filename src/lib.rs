//! # rope
//!
//! An inextensible string (a rope or chain fixed at one end, free at the other) swinging under
//! gravity, after Miha Čančula's 2012 report (`docs/physics.md` restates the model and the
//! scheme), simulated and streamed to the Rerun viewer.
//!
//! The crate is built in layers; each imports only from the layers above it in this list
//! (`docs/architecture.md` has the table, and `tests/architecture.rs` checks it):
//!
//! * [`error`]: the errors a user can cause, and the divergence a run can end with;
//! * [`model`]: the physics with no method in it: scenes, geometry and energy, the hanging
//!   string's modes;
//! * [`methods`]: the numerical methods, pure (state in, state out), each described once in
//!   its [`methods::Descriptor`];
//! * [`run`]: the driver that takes a method to its final time and makes frames, and the
//!   pipeline that hands them to a [`run::FrameSink`];
//! * [`plan`]: what a run will be: `--tolerance`'s choice from the error models, the release
//!   atlas and the pilot runs of the scene, and each scene's runs from the flags' request;
//! * [`recording`]: the Rerun sink, the viewer's layout, and where a recording goes;
//!   [`study`]: grids of runs, charted speed against accuracy;
//! * [`cli`]: the command line, turning flags into validated runs and studies;
//! * [`service`]: `rope run` and `rope study` as calls: the outputs opened, the runs made,
//!   what rope tells the user ([`service::notices`]), and how each ended.
//!
//! Units are dimensionless: length L = 1, gravity g = 1, mass per length 1, time in sqrt(L/g).
//! Coordinates: x horizontal away from the support, **y pointing down**; φ is the angle of the
//! tangent below the horizontal.

#[cfg(feature = "app")]
pub mod cli;
pub mod error;
pub mod methods;
pub mod model;
pub mod plan;
#[cfg(feature = "app")]
pub mod recording;
pub mod run;
#[cfg(feature = "app")]
pub mod service;
#[cfg(feature = "app")]
pub mod study;

pub use error::{ConfigError, Diverged};
pub use methods::{Method, MethodKind};
pub use model::Scene;
pub use run::{Frame, RunConfig, Simulated, Summary, simulate};
