//! What a run will be, decided once before it starts: the runs a request asks for, scene by
//! scene ([`runs`]), and, for `--tolerance`, the cheapest method, N and k that hold it
//! ([`tolerance`]'s rule over each method's committed error model, the release atlas where it
//! serves ([`atlas`]), and the pilot runs that measure the scene itself ([`pilot`])).
//!
//! This layer sits above `run`, because the pilots fly runs, and below the command line,
//! which only turns flags into a [`runs::RunRequest`]. Adding a planning rule: a file here,
//! called from [`runs::plan_scene`], whose choice says what it rests on (as
//! [`pilot::Basis`] does).

pub mod atlas;
pub mod pilot;
pub mod runs;
pub mod tolerance;

pub use runs::{Planned, RunRequest};
