//! What every numerical method offers the driver: advance one step, and be observed.

use crate::chain::Chain;
use crate::error::{ConfigError, Diverged};
use crate::geometry::Energy;
use crate::scene::Scene;
use crate::seed::Seed;

/// The methods a run can choose by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MethodKind {
    /// The report's finite-difference scheme: first order in h, explicit, cannot start from
    /// the horizontal.
    Seed,
    /// A chain of N uniform rigid rods, joint forces from an O(N) block-tridiagonal solve,
    /// RK4 in time: second order in h, exact inextensibility, starts from the horizontal.
    Chain,
}

impl MethodKind {
    /// Every method, in the order charts list them.
    pub const ALL: [MethodKind; 2] = [MethodKind::Seed, MethodKind::Chain];

    /// The name used on the command line and in summaries.
    pub fn name(self) -> &'static str {
        match self {
            Self::Seed => "seed",
            Self::Chain => "chain",
        }
    }

    /// Estimated largest stable time step at `segments` segments.
    pub fn stability_limit(self, segments: usize) -> f64 {
        match self {
            Self::Seed => Seed::stability_limit(segments),
            Self::Chain => Chain::stability_limit(segments),
        }
    }

    /// A stable time step that is accurate for this method at `segments` segments.
    pub fn default_dt(self, segments: usize) -> f64 {
        match self {
            Self::Seed => Seed::default_dt(segments),
            Self::Chain => Chain::default_dt(segments),
        }
    }

    /// Builds the method for `scene`, validating everything it needs.
    pub fn build(
        self,
        scene: &Scene,
        segments: usize,
        dt: f64,
    ) -> Result<Box<dyn Method>, ConfigError> {
        Ok(match self {
            Self::Seed => Box::new(Seed::new(scene, segments, dt)?),
            Self::Chain => Box::new(Chain::new(scene, segments, dt)?),
        })
    }
}

impl std::fmt::Display for MethodKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The state of the string at one instant, for output: everything per segment.
#[derive(Clone, Debug, Default)]
pub struct Observation {
    /// Segment angles φ_i below the horizontal.
    pub angle: Vec<f64>,
    /// φ̇_i.
    pub angular_velocity: Vec<f64>,
    /// φ̈_i.
    pub angular_acceleration: Vec<f64>,
    /// Tension F_i on each segment (F ≥ 0 for a string; 0 at the free end).
    pub tension: Vec<f64>,
}

/// A numerical method advancing the string in time. Pure: state in, state out, no I/O.
pub trait Method: Send {
    /// Which method this is.
    fn kind(&self) -> MethodKind;
    /// Number of segments N.
    fn segments(&self) -> usize;
    /// Time step k.
    fn dt(&self) -> f64;
    /// Simulated time reached.
    fn time(&self) -> f64;
    /// Steps taken.
    fn steps(&self) -> u64;
    /// Advances one time step, or says why the new state cannot be trusted.
    fn step(&mut self) -> Result<(), Diverged>;
    /// Total energy now (eqs. 13–16), second-order accurate in the time step.
    fn energy(&self) -> Energy;
    /// Tension at the support, F_0, from the latest solve.
    fn support_tension(&self) -> f64;
    /// Fills `out` with the state now (tension freshly solved for the current time).
    fn observe(&mut self, out: &mut Observation);
    /// A copy of the method in its current state.
    fn box_clone(&self) -> Box<dyn Method>;
}

/// The largest of 1, 2 or 5 × 10^k not above `x`: default steps are round numbers, so that
/// whole durations are whole numbers of steps.
pub fn round_down_nicely(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor());
    let mantissa = x / decade;
    let nice = if mantissa >= 5.0 {
        5.0
    } else if mantissa >= 2.0 {
        2.0
    } else {
        1.0
    };
    nice * decade
}

/// Checks what every method needs of a time step.
pub(crate) fn validate_dt(dt: f64) -> Result<(), ConfigError> {
    if dt.is_finite() && dt > 0.0 {
        Ok(())
    } else {
        Err(ConfigError::TimeStep(dt))
    }
}

/// The reason text of a divergence caused by a non-finite value, with the stability hint.
pub(crate) fn non_finite_reason(kind: MethodKind, segments: usize, dt: f64, what: &str) -> String {
    let limit = kind.stability_limit(segments);
    let hint = if dt > limit {
        format!("k = {dt:.3e} exceeds the estimated limit {limit:.3e}")
    } else {
        format!("k = {dt:.3e} is within the estimated limit {limit:.3e}")
    };
    format!("{what} became non-finite ({hint})")
}
