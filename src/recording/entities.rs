//! What a recording holds, by name: the entity paths (the contract with tests and with
//! users' own queries), the timelines, and every time series with its legend name, colour and
//! how it is read off a frame.

use crate::model::theory::Comparison;
use crate::run::Frame;

/// Entity paths: the contract with tests and with users' own queries.
pub mod path {
    pub const SEGMENTS: &str = "rope/segments";
    pub const SUPPORT: &str = "rope/support";
    /// What is running, over the support: method, scene, N and k, run by run.
    pub const CAPTION: &str = "rope/caption";
    /// Side by side: which colour is which method, at the rope view's top left.
    pub const LEGEND: &str = "rope/legend";
    pub const TIP: &str = "rope/tip";
    /// Side by side: every method's tip in one entity, a point each, in the method's colour
    /// and named by it (the ropes share `rope/segments`, the profiles `tension/profiles`).
    pub const TIPS: &str = "rope/tips";
    pub const PROFILES: &str = "tension/profiles";
    pub const TRAIL: &str = "rope/trail";
    pub const SCALE: &str = "rope/tension_scale";
    pub const PROFILE: &str = "tension/profile";
    pub const PROFILE_AXES: &str = "tension/axes";
    pub const KINETIC: &str = "energy/kinetic";
    pub const POTENTIAL: &str = "energy/potential";
    pub const TOTAL: &str = "energy/total";
    pub const DEVIATION: &str = "energy/deviation";
    /// A shaken support: the work it has done on the string, and E − E₀ − W.
    pub const SUPPORT_WORK: &str = "energy/support_work";
    pub const GAINED: &str = "energy/gained";
    pub const BALANCE: &str = "energy/balance";
    pub const LOG_BALANCE: &str = "log10/energy_balance";
    /// A shaken support's track, ±A about the origin, and where the support is now.
    pub const SUPPORT_TRACK: &str = "rope/support_track";
    pub const SUPPORT_NOW: &str = "rope/support_now";
    pub const SUPPORT_TENSION: &str = "support/tension";
    pub const TIP_SPEED: &str = "tip/speed";
    pub const TIP_ACCELERATION: &str = "tip/acceleration";
    pub const CONSTRAINT_RESIDUAL: &str = "constraint/residual";
    pub const VELOCITY_RESIDUAL: &str = "constraint/velocity_residual";
    pub const TIP_ESTIMATE: &str = "error/tip_estimate";
    pub const SHAPE_ESTIMATE: &str = "error/shape_estimate";
    pub const TOLERANCE: &str = "error/tolerance";
    pub const TOLERANCE_PASSED: &str = "error/tolerance_passed";
    /// Decimal logarithms of the deviation and the estimates, for plots that read at a
    /// glance (Rerun's have no log axis).
    pub const LOG_DEVIATION: &str = "log10/energy_deviation";
    pub const LOG_ERROR: &str = "log10/error";
    pub const LOG_TIP_ESTIMATE: &str = "log10/error/tip_estimate";
    pub const LOG_SHAPE_ESTIMATE: &str = "log10/error/shape_estimate";
    pub const LOG_TOLERANCE: &str = "log10/error/tolerance";
    pub const LOG_TOLERANCE_PASSED: &str = "log10/error/tolerance_passed";
    pub const PROFILE_TICKS: &str = "tension/s_ticks";
    /// Several methods side by side: each one's distance from the most accurate one's
    /// string (the entity paths of each method end in `/{method}`).
    pub const DISAGREEMENT: &str = "disagreement";
    pub const LOG_DISAGREEMENT: &str = "log10/disagreement";
    /// The history's rope, for viewers of a run that never ends: its shape at the time
    /// cursor ("then"), beside the live one, which replaces itself.
    pub const THEN_SEGMENTS: &str = "then/segments";
    pub const THEN_SUPPORT: &str = "then/support";
    pub const THEN_TIP: &str = "then/tip";
    /// Side by side: every method's tip then.
    pub const THEN_TIPS: &str = "then/tips";
    /// A line spanning the swing, so that the "then" view frames it as the live one does.
    pub const THEN_FRAME: &str = "then/frame";
    /// A scene's theory beside the motion (`model::theory`): for a fold, the free end's fall,
    /// its speed and the support's tension, each measured and as Calkin & March's string
    /// and free fall have it.
    pub const THEORY: &str = "theory";
    pub const FALL: &str = "theory/fall";
    pub const FALL_MEASURED: &str = "theory/fall/measured";
    pub const FALL_PREDICTED: &str = "theory/fall/calkin_march";
    pub const FALL_FREE: &str = "theory/fall/free_fall";
    pub const SPEED: &str = "theory/speed";
    pub const SPEED_MEASURED: &str = "theory/speed/measured";
    pub const SPEED_PREDICTED: &str = "theory/speed/calkin_march";
    pub const SPEED_FREE: &str = "theory/speed/free_fall";
    pub const TENSION: &str = "theory/support_tension";
    pub const TENSION_MEASURED: &str = "theory/support_tension/measured";
    pub const TENSION_PREDICTED: &str = "theory/support_tension/calkin_march";
    pub const PULL_MEASURED: &str = "theory/support_tension/pull_measured";
    pub const PULL_PREDICTED: &str = "theory/support_tension/pull_calkin_march";
    /// A shake: the free end's sideways displacement, the linear steady state's, and the
    /// support's own.
    pub const SIDEWAYS: &str = "theory/tip_sideways";
    pub const SIDEWAYS_MEASURED: &str = "theory/tip_sideways/measured";
    pub const SIDEWAYS_PREDICTED: &str = "theory/tip_sideways/steady_state";
    pub const SIDEWAYS_SUPPORT: &str = "theory/tip_sideways/support";
    /// A sweep of the shaking frequency: the free end's largest swing against Ω, and its
    /// guides (decades of swing, the resonances).
    pub const SWEEP: &str = "sweep";
    pub const SWEEP_CURVE: &str = "sweep/curve";
    pub const SWEEP_GUIDES: &str = "sweep/guides";
    pub const SWEEP_LABELS: &str = "sweep/labels";
    pub const EVENTS: &str = "events";
    pub const PARAMETERS: &str = "parameters";
}

/// Timelines: simulated seconds, and the step count.
pub const SIM_TIME: &str = "sim_time";
pub const STEP: &str = "step";

/// A time series: its entity path, legend name, colour, and how to read it off a frame.
pub type Series = (&'static str, &'static str, [u8; 3], fn(&Frame) -> f64);

/// The decimal logarithm of |x| as the plots draw it: a deviation below `LOG_FLOOR` (an
/// exact zero among them) at the floor, a value a frame does not have (NaN) left out.
pub fn log10_abs(x: f64) -> f64 {
    if x.is_nan() {
        f64::NAN
    } else {
        x.abs().log10().max(LOG_FLOOR)
    }
}

/// Where the logarithmic plots stop: round-off of a double.
const LOG_FLOOR: f64 = -16.0;

/// Every time series the recording carries, styled once and filled by each batch.
pub const SERIES: [Series; 33] = [
    (path::KINETIC, "kinetic", [230, 120, 30], |f| {
        f.energy.kinetic()
    }),
    (path::POTENTIAL, "potential", [60, 120, 220], |f| {
        f.energy.potential
    }),
    // Mid grey: it reads on the viewer's dark theme and on the browser's light one.
    (path::TOTAL, "total", [125, 125, 125], |f| f.energy.total()),
    (
        path::DEVIATION,
        "(E − E_ref)/|E_ref|",
        [200, 40, 40],
        |f| f.energy_deviation,
    ),
    (path::SUPPORT_TENSION, "F_0", [200, 150, 0], |f| {
        f.support_tension
    }),
    (path::TIP_SPEED, "|v_tip|", [40, 150, 80], |f| {
        f.tip_velocity.norm()
    }),
    (path::TIP_ACCELERATION, "|a_tip|", [120, 60, 160], |f| {
        f.tip_acceleration.norm()
    }),
    // Only a method that solves for its joints has one; the others leave it empty.
    (
        path::CONSTRAINT_RESIDUAL,
        "max |g_j|",
        [150, 150, 150],
        |f| f.constraint_residual.unwrap_or(f64::NAN),
    ),
    // Only a method whose velocities leave the joints between projections has this.
    (
        path::VELOCITY_RESIDUAL,
        "max |G v| before projection",
        [90, 40, 160],
        |f| f.velocity_residual.unwrap_or(f64::NAN),
    ),
    // A run with a shadow has these at the frames it shares with it.
    (
        path::TIP_ESTIMATE,
        "estimated tip error",
        [200, 40, 160],
        |f| f.error_estimate.map_or(f64::NAN, |e| e.tip),
    ),
    (
        path::SHAPE_ESTIMATE,
        "estimated shape error",
        [110, 110, 200],
        |f| f.error_estimate.map_or(f64::NAN, |e| e.shape),
    ),
    (
        path::LOG_DEVIATION,
        "log₁₀ |E − E_ref|/|E_ref|",
        [200, 40, 40],
        |f| log10_abs(f.energy_deviation),
    ),
    (
        path::LOG_TIP_ESTIMATE,
        "log₁₀ estimated tip error",
        [200, 40, 160],
        |f| log10_abs(f.error_estimate.map_or(f64::NAN, |e| e.tip)),
    ),
    (
        path::LOG_SHAPE_ESTIMATE,
        "log₁₀ estimated shape error",
        [110, 110, 200],
        |f| log10_abs(f.error_estimate.map_or(f64::NAN, |e| e.shape)),
    ),
    // Only a method side by side with a more accurate one has these.
    (
        path::DISAGREEMENT,
        "distance from the most accurate",
        [120, 120, 120],
        |f| disagreement(f),
    ),
    (
        path::LOG_DISAGREEMENT,
        "log₁₀ distance from the most accurate",
        [120, 120, 120],
        |f| log10_abs(disagreement(f)),
    ),
    // Only a scene with a theory beside its motion (a fold) has these.
    (
        path::FALL_MEASURED,
        "fall x, measured",
        [40, 150, 80],
        |f| theory(f, Comparison::FALL, None),
    ),
    (path::FALL_PREDICTED, "Calkin–March", [200, 40, 40], |f| {
        theory(f, Comparison::FALL, Some(0))
    }),
    (path::FALL_FREE, "free fall t²/2", [125, 125, 125], |f| {
        theory(f, Comparison::FALL, Some(1))
    }),
    (
        path::SPEED_MEASURED,
        "|v_tip|, measured",
        [40, 150, 80],
        |f| theory(f, Comparison::SPEED, None),
    ),
    (
        path::SPEED_PREDICTED,
        "Calkin–March at the measured x",
        [200, 40, 40],
        |f| theory(f, Comparison::SPEED, Some(0)),
    ),
    (
        path::SPEED_FREE,
        "free fall at the measured x",
        [125, 125, 125],
        |f| theory(f, Comparison::SPEED, Some(1)),
    ),
    (path::TENSION_MEASURED, "F_0, raw", [200, 150, 0], |f| {
        theory(f, Comparison::SUPPORT_TENSION, None)
    }),
    (
        path::TENSION_PREDICTED,
        "(1 + x)/2 + v²/4 at x",
        [200, 40, 40],
        |f| theory(f, Comparison::SUPPORT_TENSION, Some(0)),
    ),
    (
        path::PULL_MEASURED,
        "F_0 averaged (momentum)",
        [120, 60, 160],
        |f| theory(f, Comparison::SUPPORT_PULL, None),
    ),
    (
        path::PULL_PREDICTED,
        "formula, averaged alike",
        [40, 150, 200],
        |f| theory(f, Comparison::SUPPORT_PULL, Some(0)),
    ),
    // Only a run whose support moves (a shake) has these.
    (
        path::SUPPORT_WORK,
        "W, the support's work",
        [40, 150, 200],
        |f| f.support.map_or(f64::NAN, |s| s.work),
    ),
    (
        path::GAINED,
        "E − E₀, the energy gained",
        [230, 120, 30],
        |f| {
            f.balance
                .zip(f.support)
                .map_or(f64::NAN, |(b, s)| b + s.work)
        },
    ),
    (path::BALANCE, "E − E₀ − W", [200, 40, 40], |f| {
        f.balance.unwrap_or(f64::NAN)
    }),
    (
        path::LOG_BALANCE,
        "log₁₀ |E − E₀ − W|",
        [200, 40, 40],
        |f| log10_abs(f.balance.unwrap_or(f64::NAN)),
    ),
    (
        path::SIDEWAYS_MEASURED,
        "free end x, measured",
        [40, 150, 80],
        |f| theory(f, Comparison::TIP_SIDEWAYS, None),
    ),
    (
        path::SIDEWAYS_PREDICTED,
        "linear theory: A sin Ωt / J₀(2Ω), or a resonance's envelope",
        [200, 40, 40],
        |f| theory(f, Comparison::TIP_SIDEWAYS, Some(0)),
    ),
    (
        path::SIDEWAYS_SUPPORT,
        "support x_s = A sin Ωt",
        [125, 125, 125],
        |f| f.support.map_or(f64::NAN, |s| s.position),
    ),
];

/// The time series each of several methods side by side sends: what the plots show. A frame
/// per method already multiplies what a viewer takes; the rest (kinetic and potential energy,
/// the raw deviation and estimates, the tip's speed) stay with a run of one method, and so do
/// the tip's trails.
pub const SIDE_BY_SIDE: [&str; 7] = [
    path::TOTAL,
    path::SUPPORT_TENSION,
    path::LOG_DEVIATION,
    path::LOG_TIP_ESTIMATE,
    path::DISAGREEMENT,
    path::LOG_DISAGREEMENT,
    path::CONSTRAINT_RESIDUAL,
];

/// The time series a history beside a live picture leaves out: the raw values whose decimal
/// logarithms the plots show.
pub const HISTORY_LEAVES_OUT: [&str; 4] = [
    path::DEVIATION,
    path::TIP_ESTIMATE,
    path::SHAPE_ESTIMATE,
    path::BALANCE,
];

/// A frame's `quantity` of its scene's theory: measured (`prediction` `None`), or the
/// prediction at that index; NaN (not drawn) where the frame has none.
fn theory(f: &Frame, quantity: &str, prediction: Option<usize>) -> f64 {
    let Some(c) = f.theory.iter().find(|c| c.quantity == quantity) else {
        return f64::NAN;
    };
    match prediction {
        None => c.measured,
        Some(i) => c.predictions.get(i).and_then(|p| p.1).unwrap_or(f64::NAN),
    }
}

/// A frame's distance from the most accurate method's string, if it has one.
fn disagreement(f: &Frame) -> f64 {
    f.lane.and_then(|l| l.disagreement).unwrap_or(f64::NAN)
}
