//! `rope study`'s flags, and the study plans they become.

use super::limits::LimitArgs;
use super::scene::SceneArgs;
use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::run::cost::{self, Cost};
use crate::study::Spec;
use std::path::PathBuf;

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

    /// Methods to compare. The graded rods only when named: near the horizontal and over long
    /// runs their spinning end rods cost far more than the study predicts.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "seed,chain,rattle,midpoint"
    )]
    pub methods: Vec<MethodKind>,

    /// Segment counts N.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "10,20,50,100,200,500,1000"
    )]
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

    /// Instead of the grid: check what `--tolerance` chooses against the truth. For the
    /// releases from 0°, 10°, …, 90°, 37° and 52°, modes 1 and 2, and EPS = 1e-2, 1e-3, 1e-4
    /// (where the reference, the graded rods from 20° up or else the chain, extrapolated from
    /// N/2, N and 2N with N up to 3200, or 6400 where that can get there, is fine enough),
    /// the chosen run's largest tip error over the frames to t = 3, and its CPU (pilots
    /// included) beside the cheapest run of a grid (N = 16 … 1131, on to 3200 where nothing in
    /// it holds) that holds EPS; writes tolerance_check.md, references.csv (each
    /// reference's tip every 1/3000) and a chart; about an hour and a half on 2 cores, some
    /// 20 minutes with every reference read (--references).
    /// `quick`: the release from 30° and mode 1 at 1e-2 only (what CI runs); `unseen`: the
    /// releases from 37° and 52° alone, which no atlas measured (about half an hour); `modes`:
    /// modes 1 and 2 alone, which the linear theory chooses for (seconds with --references).
    #[arg(long, value_enum, value_name = "SIZE", num_args = 0..=1, default_missing_value = "full", conflicts_with_all = ["long_run", "blow_up", "estimate_check"])]
    pub tolerance_check: Option<CheckSize>,

    /// With --tolerance-check: references to read instead of computing them again, each a
    /// references.csv as the check writes it (a row at every 1/3000 of a time unit), or a
    /// folder of such files. A scene's reference is read where one of them has it (the least
    /// own error among those), else computed; a tolerance it cannot judge (its own error above
    /// a tenth of EPS at every 1/3000) is skipped, and said.
    #[arg(long, value_name = "PATH", num_args = 1.., requires = "tolerance_check")]
    pub references: Vec<PathBuf>,

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
                let err = m.starts_from(&scene).err()?;
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

/// How much of `--tolerance-check` to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum CheckSize {
    /// Fourteen scenes (releases and modes), three tolerances.
    Full,
    /// Two scenes at 1e-2.
    Quick,
    /// The full check's two releases between the atlas's measured angles (37° and 52°).
    Unseen,
    /// The full check's two small modes (modes 1 and 2), which the linear theory chooses for.
    Modes,
}
