//! `rope run`'s flags, and the request for each scene they become.

use super::limits::LimitArgs;
use super::scene::SceneArgs;
use crate::error::ConfigError;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::plan::pilot::FirstPilot;
use crate::plan::runs::{Planned, RunRequest, plan_scene};
use crate::recording::destinations::OutputArgs;
use std::path::PathBuf;

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
    /// and N, printed at the start; for midpoint, stable at any step, the step its tip needs
    /// where that is longer: 0.8 h (1600 / N)^0.4 at most 1e-3 from the horizontal (1/1080 at
    /// N = 1000), twice that from 10° below it on, where the free end whips less (1/600 at
    /// N = 1000), 1 to 2 times between; its time error stays below the rope's own spatial
    /// error]. For midpoint and chain a step over twice the one --tolerance takes is taken as
    /// asked while the rods turn slowly, and still split where the free end whips.
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
    /// lengths) over the whole run, at every instant whatever --log-rate says: pilot runs of the
    /// scene at N = 16, 32, 64 (a fold's from 16 / gap) measure its own error (as far as
    /// measuring costs less than it can save), beside the committed error models of releases
    /// and modes (the release atlases, measured at every 1/3000 of a time unit to t = 3); a
    /// fold is served to its snap, a shake by its pilots alone. Prints what the pilots
    /// measured, the choice, its predicted error and cost. The choice never depends on
    /// --log-rate or where the run goes. The run then watches its live error estimate at every
    /// step it shares with its shadow, at first order (a whip's), says when it passes EPS,
    /// reports `tolerance_met` in the summary and exits with status 4.
    #[arg(long, value_name = "EPS", allow_negative_numbers = true, allow_hyphen_values = true, conflicts_with_all = ["method", "segments", "dt"])]
    pub tolerance: Option<f64>,

    /// Numerical method [default: the report's (seed); for a run left running (--duration
    /// inf, --loop, --serve-grpc, --web) and for the fold and shake scenes, the one that keeps
    /// the energy (or its balance with the support's work) at every frame (midpoint), as
    /// printed at the start]. A list (e.g. seed,chain,rattle)
    /// runs the methods side by side on the same frame times, in one recording: each at
    /// --segments and its own default step (or --dt), brought down so that 30 instants a
    /// time unit fall on its steps (whatever --log-rate).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub method: Vec<MethodKind>,

    /// Frames logged per time unit [default: 60; for several methods side by side, which
    /// send a frame per method, 30, also the most: their frames fall on 30 shared instants a
    /// time unit, nearest each frame's time; for a --sweep, whose many runs would make a
    /// recording of gigabytes, 10 (each run's largest swing is read at its frames)]. Viewers of a served, endless or looping run get each
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

    /// Write the run's frames as tables, CSV or Parquet by FILE's extension: the series (time,
    /// method, tip, energies, support tension, live estimate; a shake's work and balance) at
    /// FILE, the tension profiles (time, method, s, x, y, F) beside it as STEM-profiles.EXT.
    /// Float64 values; y points down (docs/data.md).
    #[arg(long, value_name = "FILE")]
    pub table: Option<PathBuf>,

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

/// Why a run's method is a default that the run announces and its summary explains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DefaultMethod {
    /// A run left running (endless, looping or served): [`MethodKind::DEFAULT_LASTING`].
    Lasting,
    /// A scene with a method of its own ([`MethodKind::scene_default`]): the fold, the shake.
    Scene {
        scene: &'static str,
        method: MethodKind,
        because: &'static str,
    },
}

impl RunArgs {
    /// Validates the flags into the runs to make, in order.
    pub fn plans(&self) -> Result<Vec<Planned>, ConfigError> {
        self.plans_telling(|_, _| {})
    }

    /// As [`RunArgs::plans`], telling `before_pilots` of each scene's first `--tolerance`
    /// pilot before it flies.
    pub fn plans_telling(
        &self,
        before_pilots: impl Fn(&Scene, FirstPilot),
    ) -> Result<Vec<Planned>, ConfigError> {
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
        let request = self.request();
        scenes
            .into_iter()
            .map(|scene| plan_scene(&request, scene, |first| before_pilots(&scene, first)))
            .collect()
    }

    /// The method asked for (the first of a list), or the default: for a run that lasts
    /// (endless, looping or served) and for a fold, one whose energy is kept at every frame.
    pub fn method(&self) -> MethodKind {
        self.method
            .first()
            .copied()
            .unwrap_or_else(|| match self.default_method() {
                Some(DefaultMethod::Scene { method, .. }) => method,
                _ => MethodKind::default_for(self.lasts()),
            })
    }

    /// Why the method is a default the run announces, if it is: none named, and a scene with
    /// a method of its own (a fold, a shake), or none chosen by `--tolerance` for a run that
    /// [`lasts`](Self::lasts).
    pub fn default_method(&self) -> Option<DefaultMethod> {
        if !self.method.is_empty() {
            return None;
        }
        let scene = self.scene.scene.name();
        if let Some((method, because)) = MethodKind::scene_default(scene) {
            return Some(DefaultMethod::Scene {
                scene,
                method,
                because,
            });
        }
        (self.tolerance.is_none() && self.lasts()).then_some(DefaultMethod::Lasting)
    }

    /// Whether the run is meant to be left running: endless (`--duration inf`), looping, or
    /// served to viewers who join at any time.
    pub fn lasts(&self) -> bool {
        self.endless() || self.output.served_at().is_some()
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
        self.log_rate.unwrap_or(if self.compares() {
            30.0
        } else if self.scene.sweep.is_some() {
            Self::SWEEP_LOG_RATE
        } else {
            60.0
        })
    }

    /// Frames per time unit of a sweep when --log-rate is not given: few, since a sweep's
    /// figures are measured on the summary's fine grid whatever the frames, and its many runs
    /// would otherwise fill a recording (the README's 120 frequencies over 40 units each
    /// wrote 175 MB at 10 a unit).
    pub const SWEEP_LOG_RATE: f64 = 2.0;

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

    /// What the flags ask of each scene, resolved (the default method, the frame rate).
    fn request(&self) -> RunRequest {
        RunRequest {
            method: self.method(),
            others: self.method.iter().skip(1).copied().collect(),
            segments: self.segments,
            dt: self.dt,
            duration: self.duration,
            log_rate: self.log_rate(),
            log_rate_asked: self.log_rate.is_some(),
            realtime: self.realtime,
            allow_unstable: self.allow_unstable,
            limits: self.limits.limits(),
            error_estimate: !self.no_error_estimate,
            tolerance: self.tolerance,
        }
    }
}
