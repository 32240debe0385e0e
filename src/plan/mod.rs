//! What a run will be, decided once before it starts: the runs a request asks for, scene by
//! scene ([`runs`]), and, for `--tolerance`, the cheapest method, N and k that hold it.
//!
//! A `--tolerance` request goes one way through the files here: [`tolerance`] checks it and
//! drives it; [`committed`] looks up what each method's error is known to be (the release atlas,
//! [`atlas`], where it serves, the linear theory of a small mode, [`mode_theory`], else the
//! method's one law in [`error_model`]); [`pilot`] flies
//! the scene itself at a few coarse N while measuring can still save more than it costs; and
//! [`choice`] turns each model into a run and takes the cheapest. The run's own live estimate
//! verifies the choice at every step.
//!
//! This layer sits above `run`, because the pilots fly runs, and below the command line,
//! which only turns flags into a [`runs::RunRequest`]. Adding a planning rule: a file here,
//! called from [`runs::plan_scene`], whose choice says what it rests on (a
//! [`basis::Basis`]).

pub mod atlas;
pub mod basis;
pub mod choice;
pub mod committed;
pub mod error_model;
pub mod mode_theory;
pub mod pilot;
pub mod runs;
pub mod tolerance;

pub use runs::{Planned, RunRequest};
