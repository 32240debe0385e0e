//! The command line: `rope run` and its flags.

use crate::app::RunConfig;
use crate::error::ConfigError;
use crate::method::MethodKind;
use crate::output::OutputArgs;
use crate::scene::Scene;
use crate::study::model::{self, Choice};
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
    /// Run a grid of simulations (methods × segments × time steps) and chart speed against
    /// accuracy, stability, and the report's figures.
    Study(StudyArgs),
}

/// The scene flags shared by `run` and `study`.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Initial state.
    #[arg(long, value_enum, default_value_t = SceneKind::Release)]
    pub scene: SceneKind,

    /// Initial angle below the horizontal, in degrees (release scene), 0 to 90. `rope run`
    /// takes a list (e.g. the report's 30,60,90) and runs the scenes one after another.
    #[arg(long, value_delimiter = ',', default_values_t = [30.0], allow_negative_numbers = true)]
    pub angle: Vec<f64>,

    /// Which small-oscillation mode the `mode` scene starts in (1 to 4); `rope run` takes a
    /// list, as for --angle.
    #[arg(long, value_delimiter = ',', default_values_t = [1])]
    pub mode_number: Vec<u32>,

    /// Tip displacement of the `mode` scene, in string lengths (|A| ≤ 0.2).
    #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
    pub amplitude: f64,
}

impl SceneArgs {
    /// The scenes the flags describe, in the order given.
    pub fn scenes(&self) -> Vec<Scene> {
        match self.scene {
            SceneKind::Release => self
                .angle
                .iter()
                .map(|&angle_deg| Scene::Release { angle_deg })
                .collect(),
            SceneKind::Mode => self
                .mode_number
                .iter()
                .map(|&number| Scene::Mode {
                    number,
                    amplitude: self.amplitude,
                })
                .collect(),
        }
    }

    /// The one scene a study is about.
    pub fn scene(&self) -> Result<Scene, String> {
        match self.scenes().as_slice() {
            [scene] => Ok(*scene),
            scenes => Err(format!(
                "{}: a study is of one scene, {} given; run one study per scene",
                match self.scene {
                    SceneKind::Release => "angle",
                    SceneKind::Mode => "mode-number",
                },
                scenes.len()
            )),
        }
    }
}

/// `rope study` flags.
#[derive(Debug, clap::Args)]
pub struct StudyArgs {
    #[command(flatten)]
    pub scene: SceneArgs,

    /// Simulated time of every run; errors are measured at its end.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub duration: f64,

    /// Methods to compare.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = MethodKind::ALL)]
    pub methods: Vec<MethodKind>,

    /// Segment counts N.
    #[arg(long, value_delimiter = ',', default_values_t = [10, 20, 50, 100, 200, 500, 1000])]
    pub segments: Vec<usize>,

    /// Time steps k [default: 1e-6 to 3e-2 in half-decades].
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    pub dts: Option<Vec<f64>>,

    /// Segments of the reference's finest run [default: twice the largest N].
    #[arg(long)]
    pub reference_segments: Option<usize>,

    /// Directory for study.csv, findings.md and the charts (SVG and PNG).
    #[arg(long, default_value = "study")]
    pub out: PathBuf,

    /// Also put the charts' data into this Rerun recording.
    #[arg(long, value_name = "FILE.rrd")]
    pub save: Option<PathBuf>,
}

impl StudyArgs {
    /// The time steps to run.
    pub fn dts(&self) -> Vec<f64> {
        self.dts.clone().unwrap_or_else(|| {
            (0..10)
                .map(|i| if i % 2 == 0 { 1.0 } else { 3.0 } * 10f64.powi(-6 + i / 2))
                .collect()
        })
    }
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

    #[command(flatten)]
    pub scene: SceneArgs,

    /// Simulated time to run, in time units; `inf` runs until Ctrl-C (with --realtime, a
    /// rope that swings on a screen for as long as it is left).
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub duration: f64,

    /// Run the scenes (see --angle) again and again, PASSES times over the list [default:
    /// until Ctrl-C]. Each run starts where the previous one ended on the timelines, with its
    /// parameters logged there.
    #[arg(long = "loop", value_name = "PASSES", num_args = 0..=1)]
    #[allow(clippy::option_option)]
    pub repeat: Option<Option<u64>>,

    /// Choose method, segments and time step for a tip-position error of at most EPS (string
    /// lengths) at the final time, from the error model fitted to `rope study`; prints the
    /// choice, its predicted error and cost.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true, conflicts_with_all = ["method", "segments", "dt"])]
    pub tolerance: Option<f64>,

    /// Numerical method [default: seed; chain for --duration inf, as the seed scheme
    /// diverges after some tens of time units whatever its time step].
    #[arg(long, value_enum)]
    pub method: Option<MethodKind>,

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
    pub output: OutputArgs,
}

impl RunArgs {
    /// Validates the flags into the runs to make, in order; with `--tolerance`, each also
    /// says what the rule chose for it.
    pub fn configs(&self) -> Result<Vec<(RunConfig, Option<Choice>)>, ConfigError> {
        let scenes = self.scene.scenes();
        if self.duration.is_infinite() && (self.repeat.is_some() || scenes.len() > 1) {
            return Err(ConfigError::Loop(
                "an endless run (--duration inf) never ends, so no other run can follow it; give a finite --duration to --loop or to a list of scenes".to_owned(),
            ));
        }
        if self.repeat == Some(Some(0)) {
            return Err(ConfigError::Loop(
                "0 passes: give at least 1, or --loop alone to repeat until Ctrl-C".to_owned(),
            ));
        }
        scenes.into_iter().map(|scene| self.config(scene)).collect()
    }

    /// The method asked for, or the default for the duration: an endless run needs one that
    /// stays stable for ever.
    pub fn method(&self) -> MethodKind {
        match self.method {
            Some(method) => method,
            None if self.duration.is_infinite() => MethodKind::Chain,
            None => MethodKind::Seed,
        }
    }

    /// How many times to go through the list of scenes; `None` for until Ctrl-C.
    pub fn passes(&self) -> Option<u64> {
        match self.repeat {
            None => Some(1),
            Some(passes) => passes,
        }
    }

    /// Validates the flags for one scene; with `--tolerance`, also says what the rule chose.
    fn config(&self, scene: Scene) -> Result<(RunConfig, Option<Choice>), ConfigError> {
        let (method, segments, dt, choice) = match self.tolerance {
            None => (self.method(), self.segments, self.dt, None),
            Some(eps) => {
                scene.validate()?;
                if !(eps.is_finite() && eps > 0.0) {
                    return Err(ConfigError::Tolerance(eps));
                }
                if self.duration.is_infinite() {
                    return Err(ConfigError::ToleranceEndless(eps));
                }
                let choice = model::choose(eps, self.duration.max(0.0), &scene)
                    .ok_or(ConfigError::Tolerance(eps))?;
                if choice.predicted_seconds > MAX_TOLERANCE_SECONDS {
                    return Err(ConfigError::ToleranceTooCostly {
                        tolerance: eps,
                        segments: choice.segments,
                        seconds: choice.predicted_seconds,
                    });
                }
                (
                    choice.method,
                    choice.segments,
                    Some(choice.dt),
                    Some(choice),
                )
            }
        };
        let config = RunConfig::new(
            method,
            scene,
            segments,
            dt,
            self.duration,
            self.log_rate,
            self.realtime,
            self.allow_unstable,
        )?;
        Ok((config, choice))
    }
}

/// The longest run `--tolerance` will choose (predicted CPU seconds).
const MAX_TOLERANCE_SECONDS: f64 = 3600.0;
