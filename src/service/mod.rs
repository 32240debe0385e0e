//! The commands as services the binary, and tests, call in-process: `rope run`
//! ([`run::run`]) and `rope study` ([`study::study`]). Each takes the parsed flags and a
//! [`Session`] (the flag that stops it, and who hears what it says), does the whole job and
//! returns how it ended; the binary only parses, dispatches, prints the final error and
//! maps the outcome to an exit code. What rope tells the user is made in [`notices`] (the
//! pilots' lines in [`pilot_notices`], a sweep's in [`sweep_notices`]).

pub mod notices;
pub mod pilot_notices;
pub mod run;
pub mod study;
pub mod sweep_notices;

use crate::error::ConfigError;
use crate::run::Verdict;
use notices::{Listener, Terminal};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// Exit status of input that cannot run (as clap's own errors). A run's own statuses are
/// [`crate::run::Verdict::exit_status`]'s: 3 a diverged run, 4 a run whose live estimate
/// passed `--tolerance`, 130 an interrupted one; 1 is anything else.
pub const EXIT_BAD_INPUT: u8 = 2;

/// What a command runs with: the flag that stops it, who hears what it says, and the
/// command line its findings cite.
#[derive(Clone)]
pub struct Session {
    /// Set by Ctrl-C or SIGTERM (or a test): the run finishes its recording and ends.
    pub stop: Arc<AtomicBool>,
    pub listener: Arc<dyn Listener>,
    /// The command line as typed, for a study's findings to cite.
    pub command: String,
}

impl Session {
    /// A session for `listener`, never stopped but by its `stop` flag.
    pub fn new(listener: Arc<dyn Listener>, command: impl Into<String>) -> Self {
        Self {
            stop: Arc::new(AtomicBool::new(false)),
            listener,
            command: command.into(),
        }
    }

    /// The terminal's session: notices on stderr (the findings on stdout), stopped by
    /// Ctrl-C or SIGTERM (a second one leaves at once), the command line from the process.
    pub fn terminal() -> anyhow::Result<Self> {
        let command = std::env::args().collect::<Vec<_>>().join(" ");
        Ok(Self {
            stop: interrupt_flag()?,
            ..Self::new(Arc::new(Terminal), command)
        })
    }
}

/// The flag that Ctrl-C or SIGTERM sets, its handler installed once for the process.
fn interrupt_flag() -> anyhow::Result<Arc<AtomicBool>> {
    static FLAG: OnceLock<Result<Arc<AtomicBool>, String>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        ctrlc::set_handler(move || {
            if flag.swap(true, Ordering::SeqCst) {
                // A second Ctrl-C: leave now, as an interrupted run.
                std::process::exit(i32::from(Verdict::Interrupted.exit_status()));
            }
            eprintln!(
                "rope: interrupted, finishing the recording or the runs under way (again to leave at once)…"
            );
        })
        .map(|()| stop)
        .map_err(|err| format!("installing the Ctrl-C / SIGTERM handler: {err}"))
    })
    .clone()
    .map_err(anyhow::Error::msg)
}

/// Why a command did not run to its end.
#[derive(Debug, thiserror::Error)]
pub enum ServiceError {
    /// Input that cannot run, named with what would work (exit status 2).
    #[error("{0}")]
    BadInput(String),
    /// Anything else, with its context (exit status 1).
    #[error(transparent)]
    Failed(#[from] anyhow::Error),
}

impl ServiceError {
    /// Input that cannot run, said as `err` says it.
    pub fn bad_input(err: impl std::fmt::Display) -> Self {
        Self::BadInput(err.to_string())
    }
}

impl From<ConfigError> for ServiceError {
    fn from(err: ConfigError) -> Self {
        Self::bad_input(err)
    }
}
