//! What a run is asked to do ([`RunConfig`], every default documented) and what it will do
//! once checked ([`RunPlan`], validated once, every value resolved).

use super::cost::{self, Cost, Limits};
use super::estimate::{Shadow, TipBound};
use super::simulate::step_on_frame_grid;
use crate::error::ConfigError;
use crate::methods::{Method, MethodKind};
use crate::model::Scene;

/// Side by side, the instants per time unit that every method's step divides: each
/// method's step is the largest at most its own that puts these instants on whole numbers of
/// its steps, and the frames fall on them (at most this many frames per time unit). Fixed,
/// so that the steps, and so the outcome, do not depend on `--log-rate` or on where the
/// recording goes. 30 brings the seed's default step at N = 100, 2e-3, to 1.852e-3.
pub const SHARED_FRAME_GRID: f64 = 30.0;

/// A run as asked for. Build it with struct update syntax over [`RunConfig::default`], then
/// [`validate`](RunConfig::validate) it into a [`RunPlan`].
#[derive(Clone, Debug, PartialEq)]
pub struct RunConfig {
    /// The numerical method. Default: [`MethodKind::DEFAULT`], the report's scheme.
    pub method: MethodKind,
    /// The initial state. Default: straight and at rest, 30° below the horizontal.
    pub scene: Scene,
    /// Segments N (h = 1/N). Default: 100, the report's.
    pub segments: usize,
    /// Time step k; `None` (the default) takes the method's own default for N.
    pub dt: Option<f64>,
    /// Simulated time to run, in time units sqrt(L/g); `f64::INFINITY` runs until stopped.
    /// Default: 3.
    pub duration: f64,
    /// Frames per time unit. Default: 60.
    pub log_rate: f64,
    /// Pace to the wall clock, this many time units per second; `None` (the default) runs as
    /// fast as it can.
    pub realtime: Option<f64>,
    /// Run a time step past the stability limit of a method that refuses one, to watch it
    /// fail. Default: false.
    pub allow_unstable: bool,
    /// The memory the run may use, and whether a run longer than a day may start. Default:
    /// the machine's available memory, and no.
    pub limits: Limits,
    /// Carry a shadow at N/2 for the live error estimate (`error/tip_estimate`). Default:
    /// true (it costs about a fifth of the run: `cargo bench --bench estimate`).
    pub error_estimate: bool,
    /// The tip error the run is meant to stay within (`--tolerance`), watched through the
    /// live estimate. Default: none.
    pub tolerance: Option<f64>,
    /// How the live estimate bounds the tip's error, what a tolerance is watched by.
    /// Default: at first order, a whip's ([`TipBound::FirstOrder`]); `--tolerance` measures
    /// the order of a scene with no whip (a mode) with its pilots.
    pub tip_bound: TipBound,
    /// Bring the time step down onto the grid of [`SHARED_FRAME_GRID`] instants per time unit
    /// ([`step_on_frame_grid`]), and the frames' times onto the same grid, so that the run
    /// shares every frame time with runs of other methods beside it. The step depends on
    /// the method and `dt`, never on `log_rate`. Default: false.
    pub shared_frames: bool,
}

impl Default for RunConfig {
    fn default() -> Self {
        Self {
            method: MethodKind::DEFAULT,
            scene: Scene::Release { angle_deg: 30.0 },
            segments: 100,
            dt: None,
            duration: 3.0,
            log_rate: 60.0,
            realtime: None,
            allow_unstable: false,
            limits: Limits::default(),
            error_estimate: true,
            tolerance: None,
            tip_bound: TipBound::FirstOrder,
            shared_frames: false,
        }
    }
}

/// A validated run: every value checked and resolved (the time step is never missing).
#[derive(Clone, Debug, PartialEq)]
pub struct RunPlan {
    pub method: MethodKind,
    pub scene: Scene,
    pub segments: usize,
    pub dt: f64,
    pub duration: f64,
    pub log_rate: f64,
    pub realtime: Option<f64>,
    /// Whether the run carries a shadow for the live error estimate: asked for, and the run
    /// fine enough to halve.
    pub error_estimate: bool,
    /// The tip error the run is meant to stay within, if one was asked for.
    pub tolerance: Option<f64>,
    /// How the live estimate bounds the tip's error.
    pub tip_bound: TipBound,
    /// Side by side, the instants per time unit the frames fall on
    /// ([`SHARED_FRAME_GRID`]); `None` for a run of one method.
    pub frame_grid: Option<f64>,
    /// What the run is predicted to cost (with its shadow).
    pub cost: Cost,
}

impl RunConfig {
    /// Checks every parameter, naming the one that is wrong and what would work. Nothing of
    /// the size of the run is allocated here: its cost is checked against the limits first.
    pub fn validate(&self) -> Result<RunPlan, ConfigError> {
        let method = self.method;
        let segments = self.segments;
        let dt = self.step();
        let frame_grid = self.shared_frames.then_some(SHARED_FRAME_GRID);
        let dt = match frame_grid {
            Some(grid) if dt.is_finite() && dt > 0.0 => step_on_frame_grid(dt, grid),
            _ => dt,
        };
        if self.duration.is_nan() || self.duration <= 0.0 {
            return Err(ConfigError::Duration(self.duration));
        }
        if !(self.log_rate.is_finite() && self.log_rate > 0.0) {
            return Err(ConfigError::LogRate(self.log_rate));
        }
        if let Some(grid) = frame_grid
            && self.log_rate > grid
        {
            return Err(ConfigError::LogRateAboveSharedGrid {
                log_rate: self.log_rate,
                grid,
            });
        }
        if let Some(speed) = self.realtime
            && !(speed.is_finite() && speed > 0.0)
        {
            return Err(ConfigError::Realtime(speed));
        }
        let d = method.descriptor();
        self.scene.validate()?;
        crate::methods::method::validate_segments(d, segments)?;
        crate::methods::method::validate_dt(dt)?;
        let error_estimate = self.error_estimate && Shadow::possible(method, segments);
        let cost = Cost::of_estimated_run(
            method,
            segments,
            dt,
            self.duration,
            self.log_rate,
            error_estimate,
        );
        self.check_cost(&cost, dt)?;
        // Whether the method can start from the scene does not depend on N, nor need it build.
        method.starts_from(&self.scene)?;
        let limit = method.stability_limit(segments);
        if method.descriptor().refuses_unstable_step && dt > limit && !self.allow_unstable {
            return Err(ConfigError::UnstableTimeStep {
                method: method.name(),
                segments,
                dt,
                limit,
            });
        }
        if self.log_rate * dt > 1.0 + 1e-12 {
            return Err(ConfigError::LogRateAboveSteps {
                log_rate: self.log_rate,
                dt,
                most_frames: at_most_three_digits(1.0 / dt),
                largest_dt: at_most_three_digits(1.0 / self.log_rate),
            });
        }
        Ok(RunPlan {
            method,
            scene: self.scene,
            segments,
            dt,
            duration: self.duration,
            log_rate: self.log_rate,
            realtime: self.realtime,
            error_estimate,
            tolerance: self.tolerance,
            tip_bound: self.tip_bound,
            frame_grid,
            cost,
        })
    }

    /// The time step asked for: `dt`, or the method's default at N in the scene (before a run
    /// side by side brings it onto the shared grid).
    pub fn step(&self) -> f64 {
        self.dt
            .unwrap_or_else(|| self.method.default_step(&self.scene, self.segments.max(1)))
    }

    /// Refuses a run whose memory exceeds the limit, or a finite one longer than a day
    /// without `--yes`.
    fn check_cost(&self, cost: &Cost, dt: f64) -> Result<(), ConfigError> {
        if !self.limits.fits(cost.bytes) {
            let limit = self.limits.memory();
            return Err(ConfigError::TooMuchMemory {
                segments: self.segments,
                needed: cost::bytes_text(cost.bytes),
                limit: cost::bytes_text(limit),
                whose: self.limits.whose_memory(),
                largest: Cost::segments_within(self.method, self.log_rate, limit),
            });
        }
        if self.duration.is_finite() && cost.seconds > cost::LONG_SECONDS && !self.limits.yes {
            return Err(ConfigError::TooLong {
                duration: self.duration,
                cost: cost::seconds_text(cost.seconds),
                segments: self.segments,
                steps: (self.duration / dt).ceil(),
                longest: self.duration * cost::LONG_SECONDS / cost.seconds,
            });
        }
        Ok(())
    }
}

impl RunPlan {
    /// The method at rest in the plan's scene.
    pub fn build(&self) -> Result<Box<dyn Method>, ConfigError> {
        self.method.build(&self.scene, self.segments, self.dt)
    }

    /// The run's shadow at N/2, if it carries one.
    pub fn shadow(&self) -> Result<Option<Shadow>, ConfigError> {
        if !self.error_estimate {
            return Ok(None);
        }
        Shadow::new(
            self.method,
            &self.scene,
            self.segments,
            self.dt,
            self.tip_bound,
        )
    }

    /// The parameters as a Markdown document, so that a recording explains itself.
    pub fn markdown(&self) -> String {
        let theory = self
            .scene
            .theory_note()
            .map_or(String::new(), |note| format!("\n\n{note}"));
        format!(
            "# rope run\n\n| parameter | value |\n|---|---|\n| method | {} |\n| scene | {}, at rest at the start |\n| segments N | {} |\n| time step k | {:.3e} |\n| duration | {} |\n| frames per time unit | {} |\n\nUnits: L = g = 1, time in sqrt(L/g). y points down. Rope colour: tension, RGB (255, 200·F, 0).{theory}",
            self.method, self.scene, self.segments, self.dt, self.duration, self.log_rate
        )
    }

    /// The run in one line, as the viewer shows it over the rope: "chain, release at 30°,
    /// N = 100, k = 5e-4".
    pub fn headline(&self) -> String {
        format!(
            "{}, {}, N = {}, k = {}",
            self.method,
            self.scene,
            self.segments,
            short_step(self.dt)
        )
    }

    /// The initial angle at the support, in degrees below the horizontal.
    pub fn angle_deg(&self) -> f64 {
        match self.scene {
            Scene::Release { angle_deg } => angle_deg,
            Scene::Mode { .. } | Scene::Fold { .. } | Scene::Shake { .. } => 90.0,
        }
    }
}

/// A time step in at most four significant digits, trailing zeros dropped: 5e-4, 3.266e-3.
pub fn short_step(dt: f64) -> String {
    trimmed_scientific(dt, 3)
}

/// `value` with at most `decimals` digits after the point, trailing zeros dropped: 1.5, 2,
/// 0.25 (not 2.000).
pub fn trimmed_fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    }
}

/// `value` (> 0) rounded down to three significant digits and written out, so that an
/// advised bound is one that holds: 1/k = 0.1 for k = 10 reads 0.1, 1/60 reads 0.0166.
pub fn at_most_three_digits(value: f64) -> String {
    let unit = 10f64.powi(value.log10().floor() as i32 - 2);
    let down = (value / unit * (1.0 + 1e-12)).floor() * unit;
    if (1e-3..1e6).contains(&down) {
        trimmed_fixed(down, (2 - down.log10().floor() as i32).max(0) as usize)
    } else {
        trimmed_scientific(down, 2)
    }
}

/// `value` in scientific notation with at most `decimals` digits after the point, trailing
/// zeros dropped: 1.5e-3, 2e-3 (not 2.00e-3).
pub fn trimmed_scientific(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => format!(
            "{}e{exponent}",
            mantissa.trim_end_matches('0').trim_end_matches('.')
        ),
        _ => text,
    }
}
