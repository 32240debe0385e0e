//! What a study tells its caller as it goes, and how the caller stops it: each piece of work
//! done is counted ([`Progress::done`]), and before each run it starts the study asks whether
//! it should stop ([`Progress::check`]). A stopped study starts no more runs, lets those under
//! way finish and writes nothing: its files are made from every run or not at all.

/// A study's caller: counts the work done, and may stop the study.
pub trait Progress: Sync {
    /// One more piece of work (a run, a reference, a time unit of a long run) is done.
    fn done(&self);

    /// Whether the caller has asked the study to stop.
    fn stopped(&self) -> bool {
        false
    }

    /// `Err(Stopped)` once the caller has asked the study to stop: asked before each run.
    fn check(&self) -> Result<(), Stopped> {
        match self.stopped() {
            true => Err(Stopped),
            false => Ok(()),
        }
    }
}

/// A plain closure counts the work and never stops the study.
impl<F: Fn() + Sync> Progress for F {
    fn done(&self) {
        self();
    }
}

/// Why a study ended without writing its files: its caller stopped it (Ctrl-C or SIGTERM).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the study was stopped before its last run, so it wrote nothing")]
pub struct Stopped;

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

    struct Flagged {
        stop: AtomicBool,
        done: AtomicUsize,
    }

    impl Progress for Flagged {
        fn done(&self) {
            self.done.fetch_add(1, Ordering::SeqCst);
        }
        fn stopped(&self) -> bool {
            self.stop.load(Ordering::SeqCst)
        }
    }

    #[test]
    fn a_closure_counts_and_never_stops() {
        let count = AtomicUsize::new(0);
        let progress = || {
            count.fetch_add(1, Ordering::SeqCst);
        };
        progress.done();
        progress.done();
        assert_eq!(count.load(Ordering::SeqCst), 2);
        assert_eq!(progress.check(), Ok(()));
    }

    #[test]
    fn a_caller_that_stops_is_heard_at_the_next_check() {
        let progress = Flagged {
            stop: AtomicBool::new(false),
            done: AtomicUsize::new(0),
        };
        assert_eq!(progress.check(), Ok(()));
        progress.stop.store(true, Ordering::SeqCst);
        assert_eq!(progress.check(), Err(Stopped));
        progress.done();
        assert_eq!(progress.done.load(Ordering::SeqCst), 1);
    }
}
