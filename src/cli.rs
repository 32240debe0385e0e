//! The command line: `rope run` and `rope study`, their flags, and how the flags become a
//! validated run or study.

use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::methods::tolerance::Choice;
use crate::model::Scene;
use crate::recording::destinations::OutputArgs;
use crate::run::cost::{self, Cost, Limits};
use crate::run::pilot::{self, Pilots};
use crate::run::{RunConfig, RunPlan};
use crate::study::Spec;
use std::path::PathBuf;

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
       methods can start from the scene among them)";

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

/// The scene flags shared by `run` and `study`.
#[derive(Debug, clap::Args)]
pub struct SceneArgs {
    /// Initial state.
    #[arg(long, value_enum, default_value_t = SceneKind::Release)]
    pub scene: SceneKind,

    /// Initial angle below the horizontal, in degrees (release scene), 0 to 90 [default: 30].
    /// `rope run` takes a list (e.g. the report's 30,60,90) and runs the scenes one after
    /// another.
    #[arg(
        long,
        value_delimiter = ',',
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub angle: Vec<f64>,

    /// Which small-oscillation mode the `mode` scene starts in (1 to 4) [default: 1]; `rope run`
    /// takes a list, as for --angle.
    #[arg(long, value_delimiter = ',')]
    pub mode_number: Vec<u32>,

    /// Tip displacement of the `mode` scene, in string lengths (|A| ≤ 0.2) [default: 0.05].
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub amplitude: Option<f64>,
}

impl SceneArgs {
    /// The release angle when none is given.
    pub const DEFAULT_ANGLE: f64 = 30.0;
    /// The mode when none is given.
    pub const DEFAULT_MODE: u32 = 1;
    /// The mode's tip displacement when none is given.
    pub const DEFAULT_AMPLITUDE: f64 = 0.05;

    /// The scenes the flags describe, in the order given. A flag of the other scene is
    /// refused, naming it, rather than silently ignored.
    pub fn scenes(&self) -> Result<Vec<Scene>, ConfigError> {
        let foreign = |flag: &'static str| ConfigError::ForeignSceneFlag {
            flag,
            scene: self.scene.name(),
        };
        match self.scene {
            SceneKind::Release => {
                if !self.mode_number.is_empty() {
                    return Err(foreign("mode-number"));
                }
                if self.amplitude.is_some() {
                    return Err(foreign("amplitude"));
                }
                let angles = if self.angle.is_empty() {
                    &[Self::DEFAULT_ANGLE][..]
                } else {
                    &self.angle[..]
                };
                Ok(angles
                    .iter()
                    .map(|&angle_deg| Scene::Release { angle_deg })
                    .collect())
            }
            SceneKind::Mode => {
                if !self.angle.is_empty() {
                    return Err(foreign("angle"));
                }
                let numbers = if self.mode_number.is_empty() {
                    &[Self::DEFAULT_MODE][..]
                } else {
                    &self.mode_number[..]
                };
                let amplitude = self.amplitude.unwrap_or(Self::DEFAULT_AMPLITUDE);
                Ok(numbers
                    .iter()
                    .map(|&number| Scene::Mode { number, amplitude })
                    .collect())
            }
        }
    }

    /// The one scene a study is about, validated.
    pub fn scene(&self) -> Result<Scene, ConfigError> {
        match self.scenes()?.as_slice() {
            [scene] => {
                scene.validate()?;
                Ok(*scene)
            }
            scenes => Err(ConfigError::StudyScenes {
                flag: match self.scene {
                    SceneKind::Release => "angle",
                    SceneKind::Mode => "mode-number",
                },
                count: scenes.len(),
            }),
        }
    }
}

/// `rope study` flags.
#[derive(Debug, clap::Args)]
pub struct StudyArgs {
    #[command(flatten)]
    pub scene: SceneArgs,

    /// Simulated time of every run. A run's tip error is the largest over its frames (30 a
    /// time unit, each against the reference at that frame's time), as --tolerance means
    /// it; study.csv also keeps the error at the final time alone (final_tip_error).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub duration: f64,

    /// Methods to compare.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = MethodKind::ALL)]
    pub methods: Vec<MethodKind>,

    /// Segment counts N.
    #[arg(long, value_delimiter = ',', default_values_t = [10, 20, 50, 100, 200, 500, 1000])]
    pub segments: Vec<usize>,

    /// Time steps k [default: 1e-6 to 3e-2 in half-decades; with --long-run, each method's
    /// default step].
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

    /// Instead of the grid: swing each method of --methods from each --angle (a list) for
    /// this many time units at N = 100 and its default step (or at each of --dts), and chart
    /// |E − E_ref| against t (--segments and --duration are not used).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub long_run: Option<f64>,

    /// Instead of the grid: run the report's scheme from the scene over N × k until it
    /// blows up (or T time units), map when, and chart the sawtooth that grows first.
    #[arg(
        long,
        value_name = "T",
        allow_negative_numbers = true,
        conflicts_with = "long_run"
    )]
    pub blow_up: Option<f64>,

    /// Instead of the grid: check the live error estimate against the truth. Each method of
    /// --methods at N = 25, 50, 100, 200 with its shadow at N/2, from the releases at 0°, 30°,
    /// 60°, 90° and modes 1 and 2, to t = 3, against the reference method at N = 1600 at every
    /// frame; also fits each method's error model over all those scenes (the scene flags,
    /// --segments, --dts and --duration are not used).
    #[arg(long, conflicts_with_all = ["long_run", "blow_up"])]
    pub estimate_check: bool,

    /// Instead of the grid: check what `--tolerance` chooses against the truth. For the six
    /// scenes of --estimate-check and EPS = 1e-2, 1e-3, 1e-4 (where the reference, the chain
    /// extrapolated from N = 400, 800, 1600, is fine enough), the chosen run's largest tip
    /// error over the frames to t = 3, and its CPU (pilots included) beside the cheapest run
    /// of a grid (N = 16 … 400) that holds EPS; writes tolerance_check.md. `quick`: the
    /// release from 30° and mode 1 at 1e-2 only (what CI runs).
    #[arg(long, value_enum, value_name = "SIZE", num_args = 0..=1, default_missing_value = "full", conflicts_with_all = ["long_run", "blow_up", "estimate_check"])]
    pub tolerance_check: Option<CheckSize>,

    /// Run only shard I of N of the grid (the cells whose place in the grid's fixed order is
    /// I modulo N) and write a partial study.csv and its manifest shard.json into --out, for
    /// `--merge` to put together. Shards may run anywhere: in parallel here, or as a job array.
    #[arg(long, value_name = "I/N", conflicts_with_all = ["long_run", "blow_up", "estimate_check", "merge", "reference_only", "save"])]
    pub shard: Option<crate::study::shard::Shard>,

    /// Compute only the reference and write it to --out/reference.json, for every shard to
    /// read with --reference instead of computing it again.
    #[arg(long, conflicts_with_all = ["long_run", "blow_up", "estimate_check", "merge", "save"])]
    pub reference_only: bool,

    /// The reference to measure against, as written by --reference-only (of the same scene,
    /// --duration and --reference-segments).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["long_run", "blow_up", "estimate_check", "merge", "reference_only"])]
    pub reference: Option<PathBuf>,

    /// Put the shards in these directories together (each the --out of a `--shard I/N`
    /// run of one study) and write the whole study's study.csv, findings.md and charts into
    /// --out. Every shard must be there once.
    #[arg(long, value_name = "DIR", num_args = 1.., conflicts_with_all = ["long_run", "blow_up", "estimate_check"])]
    pub merge: Option<Vec<PathBuf>>,

    #[command(flatten)]
    pub limits: LimitArgs,
}

/// The reference `--reference FILE` names, read and checked against the study `plan`.
pub fn reference_file(
    path: &std::path::Path,
    plan: &StudyPlan,
) -> Result<crate::study::shard::ReferenceFile, ConfigError> {
    let shown = path.display().to_string();
    let unreadable = |reason: String| ConfigError::ReferenceUnreadable {
        path: shown.clone(),
        reason,
    };
    let text = std::fs::read_to_string(path).map_err(|e| unreadable(e.to_string()))?;
    let file: crate::study::shard::ReferenceFile =
        serde_json::from_str(&text).map_err(|e| unreadable(format!("not a reference: {e}")))?;
    let ours = (plan.spec.scene, plan.spec.duration, plan.reference_segments);
    let theirs = (file.scene, file.duration, file.finest);
    if ours != theirs {
        let of = |(scene, duration, finest): (Scene, f64, usize)| {
            format!("{scene} to t = {duration} at N = {finest}")
        };
        return Err(ConfigError::ReferenceOfAnotherStudy {
            path: shown,
            theirs: of(theirs),
            ours: of(ours),
        });
    }
    Ok(file)
}

/// Every study step must be a positive, finite number.
/// Refuses a list of a study's grid values with one given twice (it would run twice).
fn repeated<T: PartialEq + std::fmt::Display>(
    flag: &'static str,
    values: &[T],
) -> Result<(), ConfigError> {
    match values
        .iter()
        .enumerate()
        .find(|(i, v)| values[..*i].contains(v))
    {
        Some((_, v)) => Err(ConfigError::StudyRepeated {
            flag,
            value: v.to_string(),
        }),
        None => Ok(()),
    }
}

fn check_dts(dts: &[f64]) -> Result<(), ConfigError> {
    match dts.iter().find(|dt| !(dt.is_finite() && **dt > 0.0)) {
        Some(&dt) => Err(ConfigError::StudyTimeStep(dt)),
        None => Ok(()),
    }
}

/// A validated `rope study --long-run`: its runs and what they will cost.
#[derive(Clone, Debug)]
pub struct LongRunPlan {
    pub duration: f64,
    /// Method, scene and step of each run (see [`crate::study::long_run::runs`]).
    pub runs: Vec<(MethodKind, Scene, f64)>,
    pub cost: Cost,
}

/// A validated study: the grid, the reference's finest N, and what it will cost.
#[derive(Clone, Debug)]
pub struct StudyPlan {
    pub spec: Spec,
    pub reference_segments: usize,
    pub cost: Cost,
}

impl StudyArgs {
    /// The time steps to run.
    pub fn dts(&self) -> Vec<f64> {
        // Written out, so that each prints as it reads (3e-4, not 3.0000000000000003e-4).
        self.dts
            .clone()
            .unwrap_or_else(|| vec![1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2])
    }

    /// Checks the flags of `--blow-up`: the one scene and the duration.
    pub fn blow_up_plan(&self, duration: f64) -> Result<Scene, ConfigError> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(ConfigError::LongRunDuration {
                flag: "blow-up",
                duration,
            });
        }
        let scene = self.scene.scene()?;
        let method = crate::methods::REPORT.method;
        method.build(&scene, 4, 1e-3)?;
        // Every run of the map may last the whole duration.
        let runs = crate::study::blow_up::cells();
        let seconds: f64 = runs
            .iter()
            .map(|&(n, dt)| Cost::of_run(method, n, dt, duration, 0.0).seconds)
            .sum();
        if seconds > cost::LONG_SECONDS && !self.limits.yes {
            return Err(ConfigError::LongRunTooLong {
                flag: "blow-up",
                fewer: "",
                runs: runs.len(),
                cost: cost::seconds_text(seconds),
            });
        }
        Ok(scene)
    }

    /// Checks the flags of `--long-run`, naming the one that is wrong and what would work.
    pub fn long_run_plan(&self, duration: f64) -> Result<LongRunPlan, ConfigError> {
        if !(duration.is_finite() && duration > 0.0) {
            return Err(ConfigError::LongRunDuration {
                flag: "long-run",
                duration,
            });
        }
        let scenes = self.scene.scenes()?;
        for scene in &scenes {
            scene.validate()?;
        }
        if let Some(dts) = &self.dts {
            check_dts(dts)?;
        }
        let segments = crate::methods::REPORT.segments;
        let runs = crate::study::long_run::runs(&self.methods, &scenes, self.dts.as_deref());
        let costs: Vec<Cost> = runs
            .iter()
            .map(|&(m, _, dt)| Cost::of_run(m, segments, dt, duration, 10.0))
            .collect();
        let cost = Cost {
            seconds: costs.iter().map(|c| c.seconds).sum(),
            bytes: costs.iter().map(|c| c.bytes).sum(),
        };
        if cost.seconds > cost::LONG_SECONDS && !self.limits.yes {
            return Err(ConfigError::LongRunTooLong {
                flag: "long-run",
                fewer: " (or fewer --methods, --angle or --dts)",
                runs: costs.len(),
                cost: cost::seconds_text(cost.seconds),
            });
        }
        Ok(LongRunPlan {
            duration,
            runs,
            cost,
        })
    }

    /// Checks every flag, naming the one that is wrong and what would work.
    pub fn plan(&self) -> Result<StudyPlan, ConfigError> {
        let scene = self.scene.scene()?;
        if !(self.duration.is_finite() && self.duration > 0.0) {
            return Err(ConfigError::StudyDuration(self.duration));
        }
        let dts = self.dts();
        check_dts(&dts)?;
        let min = MethodKind::ALL
            .iter()
            .map(|m| m.descriptor().min_segments)
            .min()
            .unwrap_or(1);
        if let Some(&segments) = self.segments.iter().find(|n| **n < min) {
            return Err(ConfigError::StudySegments { segments, min });
        }
        repeated("segments", &self.segments)?;
        repeated("dts", &dts)?;
        let finest = self.segments.iter().copied().max().unwrap_or(100);
        let reference_segments = self.reference_segments.unwrap_or(2 * finest);
        if reference_segments < 4 || !reference_segments.is_multiple_of(2) {
            return Err(ConfigError::ReferenceSegments(reference_segments));
        }
        if self.reference.is_none() && !self.reference_only && reference_segments <= finest {
            return Err(ConfigError::ReferenceTooCoarse {
                reference: reference_segments,
                finest,
                suggested: (finest + 2) & !1,
            });
        }
        // A method that cannot start from the scene is refused at each of its runs (a row
        // that says why); a study none of whose methods can start has nothing to measure.
        let refusals: Vec<String> = self
            .methods
            .iter()
            .filter_map(|m| {
                let dt = dts.first().copied().unwrap_or(1e-3);
                let err = m.build(&scene, m.descriptor().min_segments, dt).err()?;
                Some(format!("{m}: {err}"))
            })
            .collect();
        if !self.methods.is_empty() && refusals.len() == self.methods.len() {
            return Err(ConfigError::StudyNothingStarts {
                reasons: refusals.join("; "),
            });
        }
        let spec = Spec {
            scene,
            duration: self.duration,
            methods: self.methods.clone(),
            segments: self.segments.clone(),
            dts,
        };
        // What this command runs: the whole grid, one shard of it, or the reference alone;
        // the reference unless it is read from a file.
        let cells = match (self.reference_only, self.shard) {
            (true, _) => Vec::new(),
            (false, Some(shard)) => shard.cells(&spec),
            (false, None) => spec.cells(),
        };
        let computed = self.reference.is_none().then_some(reference_segments);
        let cost = crate::study::cost_of(&spec, &cells, computed, rayon::current_num_threads());
        let limits = self.limits.limits();
        if cost.bytes > limits.memory() {
            return Err(ConfigError::StudyTooMuchMemory {
                needed: cost::bytes_text(cost.bytes),
                limit: cost::bytes_text(limits.memory()),
                whose: limits.whose_memory(),
            });
        }
        if cost.seconds > cost::LONG_SECONDS && !limits.yes {
            return Err(ConfigError::StudyTooLong {
                cost: cost::seconds_text(cost.seconds),
                cells: cells.len(),
            });
        }
        Ok(StudyPlan {
            spec,
            reference_segments,
            cost,
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

impl SceneKind {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Release => "release",
            Self::Mode => "mode",
        }
    }
}

/// `rope run` flags.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// Number of segments N (h = 1/N).
    #[arg(
        long,
        default_value_t = 100,
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub segments: usize,

    /// Time step k in time units sqrt(L/g) [default: a stable, accurate value for the method
    /// and N, printed at the start].
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub dt: Option<f64>,

    #[command(flatten)]
    pub scene: SceneArgs,

    /// Simulated time to run, in time units; `inf` runs until Ctrl-C (with --realtime, a
    /// rope that swings on a screen for as long as it is left).
    #[arg(
        long,
        default_value_t = 3.0,
        allow_negative_numbers = true,
        allow_hyphen_values = true
    )]
    pub duration: f64,

    /// Run the scenes (see --angle) again and again, PASSES times over the list [default:
    /// until Ctrl-C]. Each run starts where the previous one ended on the timelines, with its
    /// parameters logged there.
    #[arg(long = "loop", value_name = "PASSES", num_args = 0..=1, default_missing_value = "forever", value_parser = parse_passes)]
    pub repeat: Option<Passes>,

    /// Choose method, segments and time step for a tip-position error of at most EPS (string
    /// lengths) at every frame: pilot runs of the scene at N = 16, 32, 64 measure its own error
    /// (as far as measuring costs less than it can save), beside the error models `rope study
    /// --estimate-check` fitted over six scenes; prints what the pilots measured, the choice,
    /// its predicted error and cost. The run then watches its live error estimate, says when
    /// it passes EPS, and reports `tolerance_met` in the summary.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true, allow_hyphen_values = true, conflicts_with_all = ["method", "segments", "dt"])]
    pub tolerance: Option<f64>,

    /// Numerical method [default: the report's (seed); for a run left running (--duration
    /// inf, --loop, --serve-grpc, --web), the one that keeps the energy at every frame
    /// (midpoint), as printed at the start]. A list (e.g. seed,chain,rattle)
    /// runs the methods side by side on the same frame times, in one recording: each at
    /// --segments and its own default step (or --dt), brought down so that 30 instants a
    /// time unit fall on its steps (whatever --log-rate).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub method: Vec<MethodKind>,

    /// Frames logged per time unit [default: 60; for several methods side by side, which
    /// send a frame per method, 30, also the most: their frames fall on 30 shared instants a
    /// time unit, nearest each frame's time]. Viewers of a served, endless or looping run get each
    /// frame as a live picture that replaces itself, and a history at --history-rate.
    #[arg(long, allow_negative_numbers = true, allow_hyphen_values = true)]
    pub log_rate: Option<f64>,

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

    /// Leave out the live error estimate: the shadow run at N/2 that puts
    /// `error/tip_estimate` on the timeline and in the summary (it costs about a fifth of
    /// the run; --tolerance needs it).
    #[arg(long, conflicts_with = "tolerance")]
    pub no_error_estimate: bool,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub output: OutputArgs,
}

/// How much of `--tolerance-check` to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CheckSize {
    /// Six scenes, three tolerances.
    Full,
    /// Two scenes at 1e-2.
    Quick,
}

/// How many times `--loop` goes through the list of scenes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Passes {
    /// Until Ctrl-C (`--loop` alone).
    Forever,
    /// This many times (`--loop N`).
    Times(u64),
}

/// `--loop [PASSES]`: a number of passes, or nothing for until Ctrl-C.
fn parse_passes(text: &str) -> Result<Passes, String> {
    match text {
        "forever" => Ok(Passes::Forever),
        _ => text.parse().map(Passes::Times).map_err(|_| {
            format!("{text:?} is not a number of passes; give a whole number ≥ 1, or --loop alone to repeat until Ctrl-C")
        }),
    }
}

/// One run to make, and what `--tolerance` chose for it, if it chose.
#[derive(Clone, Debug)]
pub struct Planned {
    /// The run of the first method named (the only one, but for a comparison).
    pub plan: RunPlan,
    pub choice: Option<Choice>,
    /// The runs of the other methods of a comparison (`--method A,B,…`), side by side with
    /// `plan` on the same frame times; empty for a run of one method.
    pub others: Vec<RunPlan>,
    /// What the pilot runs of `--tolerance` measured, and what its choice rests on.
    pub pilots: Option<Pilots>,
}

impl Planned {
    /// Every run of this scene: `plan`, then the others of a comparison.
    pub fn lanes(&self) -> Vec<RunPlan> {
        std::iter::once(self.plan.clone())
            .chain(self.others.iter().cloned())
            .collect()
    }
}

impl RunArgs {
    /// Validates the flags into the runs to make, in order.
    pub fn plans(&self) -> Result<Vec<Planned>, ConfigError> {
        let scenes = self.scene.scenes()?;
        if self.duration.is_infinite() && (self.repeat.is_some() || scenes.len() > 1) {
            return Err(ConfigError::Loop(
                "an endless run (--duration inf) never ends, so no other run can follow it; give a finite --duration to --loop or to a list of scenes".to_owned(),
            ));
        }
        if self.repeat == Some(Passes::Times(0)) {
            return Err(ConfigError::Loop(
                "0 passes: give at least 1, or --loop alone to repeat until Ctrl-C".to_owned(),
            ));
        }
        self.check_methods()?;
        scenes.into_iter().map(|scene| self.plan(scene)).collect()
    }

    /// The method asked for (the first of a list), or the default: for a run that lasts
    /// (endless, looping or served), one whose energy is kept at every frame.
    pub fn method(&self) -> MethodKind {
        self.method
            .first()
            .copied()
            .unwrap_or_else(|| MethodKind::default_for(self.lasts()))
    }

    /// Whether the run is meant to be left running: endless (`--duration inf`), looping, or
    /// served to viewers who join at any time.
    pub fn lasts(&self) -> bool {
        self.endless() || self.output.served_at().is_some()
    }

    /// Whether the method is the default for a run left running: none named, none chosen
    /// by `--tolerance`, and the run [`lasts`](Self::lasts).
    pub fn lasting_default(&self) -> bool {
        self.method.is_empty() && self.tolerance.is_none() && self.lasts()
    }

    /// Whether the run never ends by itself: `--duration inf`, or `--loop` until Ctrl-C.
    pub fn endless(&self) -> bool {
        self.duration.is_infinite() || self.repeat == Some(Passes::Forever)
    }

    /// Frames per time unit: as asked, or 60; side by side (a frame per method), 30. The
    /// same wherever the recording goes: a served viewer gets a live picture and a slow
    /// history, whatever the frame rate. The steps never depend on it (side by side they
    /// are brought onto a fixed grid, `SHARED_FRAME_GRID`).
    pub fn log_rate(&self) -> f64 {
        self.log_rate
            .unwrap_or(if self.compares() { 30.0 } else { 60.0 })
    }

    /// Whether several methods are to run side by side.
    pub fn compares(&self) -> bool {
        self.method.len() > 1
    }

    /// Checks a list of methods: each named once.
    fn check_methods(&self) -> Result<(), ConfigError> {
        for (i, m) in self.method.iter().enumerate() {
            if self.method[..i].contains(m) {
                return Err(ConfigError::MethodTwice(m.name()));
            }
        }
        Ok(())
    }

    /// How many times to go through the list of scenes; `None` for until Ctrl-C.
    pub fn passes(&self) -> Option<u64> {
        match self.repeat {
            None => Some(1),
            Some(Passes::Times(n)) => Some(n),
            Some(Passes::Forever) => None,
        }
    }

    /// Validates the flags for one scene; with `--tolerance`, also says what the rule chose;
    /// with a list of methods, validates each (naming the one that cannot run).
    fn plan(&self, scene: Scene) -> Result<Planned, ConfigError> {
        let asked = RunConfig {
            method: self.method(),
            shared_frames: self.compares(),
            scene,
            segments: self.segments,
            dt: self.dt,
            duration: self.duration,
            log_rate: self.log_rate(),
            realtime: self.realtime,
            allow_unstable: self.allow_unstable,
            limits: self.limits.limits(),
            error_estimate: !self.no_error_estimate,
            tolerance: self.tolerance,
        };
        let (config, choice, pilots) = match self.tolerance {
            None => (asked, None, None),
            Some(eps) => {
                let (choice, pilots) = self.choose(eps, &scene)?;
                // A loose tolerance may choose a step longer than the default frame
                // interval: then a frame at every step the estimate's shadow shares (where
                // the tolerance is watched), unless --log-rate asked for more.
                let most = 1.0 / (choice.dt * crate::run::estimate::STRIDE as f64);
                let log_rate = match self.log_rate {
                    Some(rate) => rate,
                    None => asked.log_rate.min(most),
                };
                let chosen = RunConfig {
                    method: choice.method,
                    segments: choice.segments,
                    dt: Some(choice.dt),
                    log_rate,
                    ..asked
                };
                (chosen, Some(choice), Some(pilots))
            }
        };
        let lane = |method: MethodKind| {
            RunConfig {
                method,
                ..config.clone()
            }
            .validate()
            .map_err(|err| match self.compares() {
                true => ConfigError::MethodCannotRun {
                    method: method.name(),
                    reason: err.to_string(),
                },
                false => err,
            })
        };
        let plan = lane(config.method)?;
        let others = self
            .method
            .iter()
            .skip(1)
            .map(|&m| lane(m))
            .collect::<Result<_, _>>()?;
        Ok(Planned {
            plan,
            choice,
            others,
            pilots,
        })
    }

    /// `--tolerance EPS` for `scene`: the run layer's choice ([`pilot::choose`]) for this
    /// run's duration, log rate and memory limit.
    fn choose(&self, eps: f64, scene: &Scene) -> Result<(Choice, Pilots), ConfigError> {
        pilot::choose(
            eps,
            scene,
            self.duration,
            self.log_rate(),
            self.limits.limits().memory(),
        )
    }
}

/// The limits a run or a study must keep, shared by both commands.
#[derive(Debug, clap::Args)]
pub struct LimitArgs {
    /// Memory it may use, e.g. 4GB or 50% [default: what the machine has available]. A run
    /// or study predicted to need more is refused before it starts.
    #[arg(long, value_name = "SIZE", value_parser = parse_memory_size)]
    pub max_memory: Option<MemorySize>,

    /// Start it even if it is predicted to take more than a day of CPU (a finite run).
    #[arg(long)]
    pub yes: bool,
}

impl LimitArgs {
    /// The limits the flags set.
    pub fn limits(&self) -> Limits {
        Limits {
            max_memory: self.max_memory.map(|m| m.bytes),
            yes: self.yes,
        }
    }
}

/// `--max-memory SIZE`: a size in bytes, as the user wrote it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemorySize {
    pub bytes: u64,
}

/// `--max-memory SIZE`: 512MB, 8GB, or a share of the machine's memory (50%).
fn parse_memory_size(text: &str) -> Result<MemorySize, String> {
    match rerun::MemoryLimit::parse(&cost::size_spelling(text)) {
        Ok(limit) if !limit.is_unlimited() && limit.as_bytes() > 0 => Ok(MemorySize {
            bytes: limit.as_bytes(),
        }),
        Ok(_) => Err(format!(
            "{text}: give a size above zero, e.g. 512MB, 8GB or 50%"
        )),
        Err(err) => Err(format!("{err}; give e.g. 512MB, 8GB or 50%")),
    }
}

/// Checks that the file `path` that flag `flag` names can be written, so that a path where
/// nothing can be written is refused before a run, not after it. Leaves no file behind (an
/// existing one is opened for appending, and kept as it was).
pub fn check_writable_file(flag: &'static str, path: &std::path::Path) -> Result<(), ConfigError> {
    let existed = path.exists();
    std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(path)
        .map_err(|err| ConfigError::OutputPath {
            flag,
            path: path.to_owned(),
            reason: err.to_string(),
        })?;
    if !existed {
        std::fs::remove_file(path).ok();
    }
    Ok(())
}

/// Creates the folder `path` that flag `flag` names (and its parents), and checks that a
/// file can be written in it.
pub fn writable_dir(flag: &'static str, path: &std::path::Path) -> Result<(), ConfigError> {
    let refuse = |err: std::io::Error| ConfigError::OutputPath {
        flag,
        path: path.to_owned(),
        reason: err.to_string(),
    };
    std::fs::create_dir_all(path).map_err(refuse)?;
    let probe = path.join(".rope-write-check");
    std::fs::write(&probe, b"").map_err(refuse)?;
    std::fs::remove_file(&probe).map_err(refuse)
}
