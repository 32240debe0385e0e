//! The command line: `rope run` ([`RunArgs`]) and `rope study` ([`StudyArgs`]), the scene flags
//! they share ([`SceneArgs`]), the limits both keep, and the checks of the paths they write. Flags
//! become the library's requests and plans here; what is done with them is decided in the
//! layers below (`plan`) and done by the services above (`service`).

mod limits;
mod paths;
mod run;
mod scene;
mod study;

pub use limits::{LimitArgs, MemorySize};
pub use paths::{check_writable_file, writable_dir, write_whole};
pub use run::{DefaultMethod, Passes, RunArgs};
pub use scene::{SceneArgs, SceneKind};
pub use study::{CheckSize, LongRunPlan, StudyArgs, StudyPlan, reference_file};

/// Simulate an inextensible string swinging under gravity and stream it to the Rerun viewer.
#[derive(Debug, clap::Parser)]
#[command(name = "rope", version, about, max_term_width = 80)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// What `rope run --help` ends with: examples and what the exit status says.
const RUN_EXAMPLES: &str = "\
Examples:
  rope run --save swing.rrd
      the report's run (seed, N = 100, from 30°) into a file
  rope run --web --realtime --duration inf
      a page to leave open: the rope live, its history to scrub
  rope run --method seed,chain,midpoint --angle 60 --save three.rrd
      three methods side by side on the same frame times
  rope run --tolerance 1e-3 --save chosen.rrd
      method, N and step chosen for a tip error of at most 1e-3
  rope run --scene fold --gap 0.02 --segments 200 --save fold.rrd
      a folded chain let go at one end: faster than gravity, against theory
  rope run --scene shake --from rest --amplitude 1e-4 --sweep 0.2..5:120 --duration 40 --segments 50 --save sweep.rrd
      a support shaken at 120 frequencies: the resonances one after another (sweep-sweep.png)

Exit status:
  0    the run ended as asked
  1    an error, said (a recording that could not be completed among them)
  2    bad input, naming the flag and what would work
  3    a method diverged: said when and why, its frames until then kept
  4    the run ended, but its live error estimate passed --tolerance (said when)
  130  interrupted (Ctrl-C or SIGTERM): the frames until then kept, the file valid";

/// What `rope study --help` ends with: examples and what the exit status says.
const STUDY_EXAMPLES: &str = "\
Examples:
  rope study --segments 16,32 --dts 1e-3,3e-3 --out small
      a small grid in seconds: study.csv, findings.md and the charts
  rope study --out study
      the default grid (280 runs, about 15 minutes on two cores)
  rope study --blow-up 200 --out blow-up
      when the report's scheme blows up, against N and k

Exit status:
  0    the study was written
  1    an error, said
  2    bad input, naming the flag and what would work (a grid none of whose
       methods can start from the scene among them)
  130  stopped (Ctrl-C or SIGTERM): no more runs started, nothing written";

/// What to do.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Simulate one scene and stream it to a viewer, an .rrd file or stdout.
    #[command(after_help = RUN_EXAMPLES)]
    Run(RunArgs),
    /// Run a grid of simulations (methods × segments × time steps) and chart speed against
    /// accuracy, stability, and the report's figures.
    #[command(after_help = STUDY_EXAMPLES)]
    Study(StudyArgs),
}
