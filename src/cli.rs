//! The command line: `rope run` and its flags.

use crate::app::RunConfig;
use crate::error::ConfigError;
use crate::method::MethodKind;
use crate::scene::Scene;
use std::path::PathBuf;

/// Simulate an inextensible string swinging under gravity and stream it to the Rerun viewer.
#[derive(Debug, clap::Parser)]
#[command(name = "rope", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// What to do.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// Simulate one scene and stream it to a viewer, an .rrd file or stdout.
    Run(RunArgs),
}

/// Which initial state to start from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SceneKind {
    /// Straight and at rest at --angle below the horizontal, then let go.
    Release,
    /// Hanging at rest, displaced by --amplitude in the shape of mode --mode-number.
    Mode,
}

/// `rope run` flags.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// Number of segments N (h = 1/N).
    #[arg(long, default_value_t = 100, allow_negative_numbers = true)]
    pub segments: usize,

    /// Time step k in time units sqrt(L/g) [default: a stable, accurate value for the method
    /// and N, printed at the start].
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,

    /// Initial angle below the horizontal, in degrees (release scene), 0 to 90.
    #[arg(long, default_value_t = 30.0, allow_negative_numbers = true)]
    pub angle: f64,

    /// Simulated time to run, in time units.
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub duration: f64,

    /// Initial state.
    #[arg(long, value_enum, default_value_t = SceneKind::Release)]
    pub scene: SceneKind,

    /// Which small-oscillation mode the `mode` scene starts in (1 to 4).
    #[arg(long, default_value_t = 1)]
    pub mode_number: u32,

    /// Tip displacement of the `mode` scene, in string lengths (|A| ≤ 0.2).
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub amplitude: f64,

    /// Numerical method.
    #[arg(long, value_enum, default_value_t = MethodKind::Seed)]
    pub method: MethodKind,

    /// Frames logged per time unit.
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
    pub log_rate: f64,

    /// Pace the simulation to the wall clock, SPEED time units per second (default 1), for
    /// watching live. Without it the run goes as fast as it can.
    #[arg(long, value_name = "SPEED", num_args = 0..=1, default_missing_value = "1", allow_negative_numbers = true)]
    pub realtime: Option<f64>,

    /// Write the run's summary as JSON to FILE.
    #[arg(long, value_name = "FILE")]
    pub summary: Option<PathBuf>,

    /// Run a seed time step past the estimated stability limit anyway (to watch it fail).
    #[arg(long)]
    pub allow_unstable: bool,

    #[command(flatten)]
    pub rerun: rerun::clap::RerunArgs,
}

impl RunArgs {
    /// The scene the flags describe.
    pub fn scene(&self) -> Scene {
        match self.scene {
            SceneKind::Release => Scene::Release {
                angle_deg: self.angle,
            },
            SceneKind::Mode => Scene::Mode {
                number: self.mode_number,
                amplitude: self.amplitude,
            },
        }
    }

    /// Validates the flags into a run.
    pub fn config(&self) -> Result<RunConfig, ConfigError> {
        RunConfig::new(
            self.method,
            self.scene(),
            self.segments,
            self.dt,
            self.duration,
            self.log_rate,
            self.realtime,
            self.allow_unstable,
        )
    }
}
