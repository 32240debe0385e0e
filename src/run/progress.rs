//! How far a `rope run` has got, for the person waiting: a bar on a terminal (a spinner for
//! an endless run), a line now and then off one (logs, services).

use std::sync::{Mutex, PoisonError};
use std::time::{Duration, Instant};

/// Shows how far a run has got: a bar (a spinner for an endless run) on a terminal; off a
/// terminal (logs, services), a line every [`PROGRESS_LINE_EVERY`] of wall time.
pub struct Progress {
    bar: indicatif::ProgressBar,
    plain: bool,
    duration: f64,
    last_line: Mutex<Instant>,
}

/// How often a run off a terminal says how far it has got.
pub const PROGRESS_LINE_EVERY: Duration = Duration::from_secs(30);

impl Progress {
    /// Progress for a run to `duration` (which may be infinite).
    pub fn new(duration: f64) -> Self {
        let plain = !std::io::IsTerminal::is_terminal(&std::io::stderr());
        let bar = if plain {
            indicatif::ProgressBar::hidden()
        } else if duration.is_finite() {
            indicatif::ProgressBar::new((duration * 1000.0).round() as u64).with_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:40} t = {msg}, {elapsed} elapsed, ~{eta} left",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            )
        } else {
            let spinner = indicatif::ProgressBar::new_spinner().with_style(
                indicatif::ProgressStyle::with_template(
                    "{spinner} t = {msg}, {elapsed} elapsed; Ctrl-C to stop",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
            );
            spinner.enable_steady_tick(Duration::from_millis(200));
            spinner
        };
        Self {
            bar,
            plain,
            duration,
            last_line: Mutex::new(Instant::now()),
        }
    }

    /// The run has reached simulated `time`.
    pub fn at(&self, time: f64) {
        if self.plain {
            let mut last = self
                .last_line
                .lock()
                .unwrap_or_else(PoisonError::into_inner);
            if last.elapsed() >= PROGRESS_LINE_EVERY {
                *last = Instant::now();
                eprintln!("rope: t = {time:.1} of {}", self.duration);
            }
        } else {
            self.bar.set_position((time * 1000.0).round() as u64);
            self.bar
                .set_message(format!("{time:.2} of {}", self.duration));
        }
    }

    /// No progress shown: a run that is one of many counted elsewhere (a sweep's
    /// frequencies, on a [`Counter`]).
    pub fn silent() -> Self {
        Self {
            bar: indicatif::ProgressBar::hidden(),
            plain: false,
            duration: 0.0,
            last_line: Mutex::new(Instant::now()),
        }
    }

    /// Runs `print` with the bar out of the way: a line for the person waiting goes above
    /// the bar, which is redrawn under it.
    pub fn suspend<R>(&self, print: impl FnOnce() -> R) -> R {
        match self.plain {
            true => print(),
            false => self.bar.suspend(print),
        }
    }

    /// The run has ended: the bar goes.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// Counts finished pieces of a long job (the runs of a study): a bar on a terminal, a line
/// every tenth of the job off one.
pub struct Counter {
    bar: indicatif::ProgressBar,
    plain: bool,
    job: &'static str,
    what: &'static str,
    started: Instant,
}

impl Counter {
    /// A counter of `total` pieces of `job` ("rope study"), each called `what` ("runs").
    pub fn new(total: u64, job: &'static str, what: &'static str) -> Self {
        let template =
            format!("{{bar:40}} {{pos}}/{{len}} {what}, {{elapsed}} elapsed, ~{{eta}} left");
        let bar = indicatif::ProgressBar::new(total).with_style(
            indicatif::ProgressStyle::with_template(&template)
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        let plain = !std::io::IsTerminal::is_terminal(&std::io::stderr());
        if plain {
            bar.set_draw_target(indicatif::ProgressDrawTarget::hidden());
        }
        Self {
            bar,
            plain,
            job,
            what,
            started: Instant::now(),
        }
    }

    /// One more piece is done.
    pub fn inc(&self) {
        self.bar.inc(1);
        let (done, total) = (self.bar.position(), self.bar.length().unwrap_or(0).max(1));
        if self.plain && (done * 10 / total != (done - 1) * 10 / total || done == total) {
            eprintln!(
                "{}: {done}/{total} {} done, {:.0} s",
                self.job,
                self.what,
                self.started.elapsed().as_secs_f64()
            );
        }
    }

    /// The job has ended: the bar goes.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
