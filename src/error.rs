//! Errors a user can cause (bad configuration) and the one a run can end with (divergence):
//! the vocabulary every layer shares.

use serde::Serialize;

/// A configuration the simulation cannot run, with the parameter named and what would work.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ConfigError {
    #[error("segments = {segments}: the {method} method needs at least {min} segments")]
    TooFewSegments {
        method: &'static str,
        segments: usize,
        min: usize,
    },
    #[error(
        "dt = {0}: the time step must be a positive, finite number of time units (for example 1e-4)"
    )]
    TimeStep(f64),
    #[error(
        "dt = {dt}: exceeds the estimated stability limit {limit:.3e} of the {method} method at {segments} segments; use dt ≤ {limit:.3e}, or --allow-unstable to watch it fail"
    )]
    UnstableTimeStep {
        method: &'static str,
        segments: usize,
        dt: f64,
        limit: f64,
    },
    #[error(
        "duration = {0}: must be a number of time units > 0 (a run of none takes no step and measures nothing), or inf for an endless run"
    )]
    Duration(f64),
    #[error("log-rate = {0}: must be a finite number of frames per time unit > 0")]
    LogRate(f64),
    #[error(
        "log-rate = {log_rate}: more frames per time unit than time steps at k = {dt:e} ({most_frames} steps a time unit); use --log-rate {most_frames} or less, or --dt {largest_dt} or less"
    )]
    LogRateAboveSteps {
        log_rate: f64,
        dt: f64,
        /// 1/k, rounded down to three digits: a rate that works.
        most_frames: String,
        /// 1/log_rate, rounded down to three digits: a step that works.
        largest_dt: String,
    },
    #[error(
        "log-rate = {log_rate}: side by side the frames fall on instants that every method's step divides, {grid} per time unit, so that no method's step depends on the frames; use --log-rate {grid} or less"
    )]
    LogRateAboveSharedGrid { log_rate: f64, grid: f64 },
    #[error(
        "tolerance = {0}: must be a finite tip error > 0, in string lengths (for example 1e-4)"
    )]
    Tolerance(f64),
    #[error(
        "tolerance = {tolerance:e}: no method reaches it within {limit}; the tightest reachable is about {tightest:.1e} (the {method} method at N = {segments}, about {cost}); ask for a looser tolerance"
    )]
    ToleranceUnreachable {
        tolerance: f64,
        limit: String,
        tightest: f64,
        method: &'static str,
        segments: usize,
        cost: String,
    },
    #[error(
        "gap = {gap:e}: --tolerance flies the fold's pilots from sixteen rods across the gap, N = 16 / gap = {segments:.2e}, which does not fit in {limit}; widen --gap (0.02 to 0.05 are served in seconds), or leave out --tolerance and choose --segments (at least 2 / gap)"
    )]
    ToleranceFoldPilots {
        gap: f64,
        segments: f64,
        limit: String,
    },
    #[error("tolerance = {0:e}: no method can start from this scene")]
    ToleranceNoMethod(f64),
    #[error(
        "segments = {segments}: the run would need about {needed} of memory, more than the {limit} it may use ({whose}); at most {largest} segments fit"
    )]
    TooMuchMemory {
        segments: usize,
        needed: String,
        limit: String,
        whose: &'static str,
        largest: usize,
    },
    #[error(
        "duration = {duration:e}: the run is predicted to take about {cost} of CPU ({segments} segments, {steps:.2e} steps), more than a day; at most {longest:.3e} time units fit in a day at this N and k. Lower --duration or --segments, or add --yes to run it anyway"
    )]
    TooLong {
        duration: f64,
        cost: String,
        segments: usize,
        steps: f64,
        longest: f64,
    },
    #[error(
        "segments: the study is predicted to take about {cost} of CPU ({cells} runs), more than a day; use fewer or smaller --segments, fewer or larger --dts, a shorter --duration, split it over machines with --shard I/N, or add --yes"
    )]
    StudyTooLong { cost: String, cells: usize },
    #[error(
        "segments: the study would need about {needed} of memory, more than the {limit} it may use ({whose}); use smaller --segments or --reference-segments"
    )]
    StudyTooMuchMemory {
        needed: String,
        limit: String,
        whose: &'static str,
    },
    #[error("{flag} = {}: cannot write there ({reason})", path.display())]
    OutputPath {
        flag: &'static str,
        path: std::path::PathBuf,
        reason: String,
    },
    #[error(
        "tolerance = {0}: is the tip error at the final time, and an endless run (--duration inf) has none; give a finite --duration, or choose --method, --segments and --dt"
    )]
    ToleranceEndless(f64),
    #[error("loop: {0}")]
    Loop(String),
    #[error("realtime = {0}: the speed must be a finite number > 0 (1 = one time unit per second)")]
    Realtime(f64),
    #[error(
        "angle = {0}°: must lie within [0°, 90°] below the horizontal; held above the horizontal (a negative angle) the straight string would start in compression, which a string cannot carry"
    )]
    Angle(f64),
    #[error(
        "angle = 0°: the seed scheme cannot start from the horizontal: its support tension F_0 = sin φ0 is zero there and the support condition (11) divides by it; start from a small angle (e.g. 1°) or use the chain method, which starts from the horizontal"
    )]
    SeedFromHorizontal,
    #[error(
        "scene = fold: the seed scheme cannot carry the folded chain: its equations move each angle by the tension's pull, and the fold's free arm falls with no tension at all: it diverges before t = 0.6 at any step (docs/physics.md), so no smaller --dt helps; use --method midpoint (which keeps the energy through the snap), chain or rattle"
    )]
    SeedFold,
    #[error(
        "scene = shake: the seed scheme cannot carry a moving support: its support condition (11) holds the first point still, and its angle equations have no term for the support's acceleration; use --method midpoint (which keeps the energy balance E − E₀ − W exact), chain or rattle"
    )]
    SeedShake,
    #[error(
        "scene = {0}: the graded method starts from a release only (a release is straight, so every rod starts at its angle whatever its length); use --method chain, rattle or midpoint for the {0} scene, or start the graded rods from a release (--scene release --angle …)"
    )]
    GradedScene(&'static str),
    #[error("{flag}: a study is of one scene, {count} given; run one study per scene")]
    StudyScenes { flag: &'static str, count: usize },
    #[error("duration = {0}: a study's runs must end, at a finite number of time units > 0")]
    StudyDuration(f64),
    #[error("{flag} = {duration}: give a finite number of time units > 0 (for example 10000)")]
    LongRunDuration { flag: &'static str, duration: f64 },
    #[error(
        "{flag}: the {runs} runs are predicted to take about {cost} of CPU, more than a day; give a shorter --{flag}{fewer}, or --yes to run them anyway"
    )]
    LongRunTooLong {
        flag: &'static str,
        /// What else would shorten them.
        fewer: &'static str,
        runs: usize,
        cost: String,
    },
    #[error("dts: {0} is not a positive, finite time step (for example 1e-4)")]
    StudyTimeStep(f64),
    #[error("segments: {segments} is too few (every method needs at least {min})")]
    StudySegments { segments: usize, min: usize },
    #[error(
        "reference-segments = {0}: must be an even number ≥ 4 (the reference is extrapolated from N and N/2)"
    )]
    ReferenceSegments(usize),
    #[error(
        "reference-segments = {reference}: no finer than the study's finest N = {finest}, so its tip errors would be measured below the reference's own resolution; use --reference-segments {suggested} or more (the default is twice the finest N)"
    )]
    ReferenceTooCoarse {
        reference: usize,
        finest: usize,
        suggested: usize,
    },
    #[error("{flag}: {value} is given twice; list each value once")]
    StudyRepeated { flag: &'static str, value: String },
    #[error(
        "methods: none of the study's methods can start from this scene, so it would have nothing to measure ({reasons}); add a method that can, for example --methods chain, or change the scene"
    )]
    StudyNothingStarts { reasons: String },
    #[error(
        "reference = {path}: it is the reference of the {theirs}; this study is of the {ours}; compute one with `rope study --reference-only` and the same scene, --duration and --reference-segments"
    )]
    ReferenceOfAnotherStudy {
        path: String,
        theirs: String,
        ours: String,
    },
    #[error("reference = {path}: {reason}; write one with `rope study --reference-only --out DIR`")]
    ReferenceUnreadable { path: String, reason: String },
    #[error("references = {path}: {reason}")]
    ReferencesUnreadable { path: String, reason: String },
    #[error(
        "{flag}: the {scene} scene does not take --{flag} (it would be ignored); the release scene takes --angle, the mode scene --mode-number and --amplitude, the fold scene --gap, the shake scene --amplitude, --frequency or --sweep, and --from (choose with --scene)"
    )]
    ForeignSceneFlag {
        flag: &'static str,
        scene: &'static str,
    },
    #[error("method: {0} is named twice; name each method once (e.g. --method seed,chain)")]
    MethodTwice(&'static str),
    #[error(
        "method = {method}: cannot run side by side with the others: {reason}; leave it out of --method"
    )]
    MethodCannotRun {
        method: &'static str,
        reason: String,
    },
    #[error("mode-number = {0}: must be 1, 2, 3 or 4")]
    ModeNumber(u32),
    #[error(
        "amplitude = {0}: must be finite with |A| ≤ 0.2 (A is the tip's sideways displacement in string lengths; the mode shapes are small-oscillation solutions)"
    )]
    Amplitude(f64),
    #[error(
        "gap = {0}: the fold's two ends must be more than 0 and less than 2/π = 0.6366 apart (the half circle at its bottom, of diameter gap, must leave both arms some length); try 0.02 to 0.05, with --segments at least 2 / gap so that two rods or more span it"
    )]
    FoldGap(f64),
    #[error(
        "duration = {duration}: --tolerance serves the fold over its fall, to the snap at t = {snap:.4} (gap {gap}), when the free arm has run out and the bend whips round, the end at {speed:.1} string lengths a unit; past it the tip's path turns on the bend's last rods, which no N within reach draws to {tolerance:e} (docs/measurements.md); ask --duration {within} or less, or leave out --tolerance to watch the snap and after (--method midpoint, --segments at least 2 / gap)",
        within = (.snap * 100.0).floor() / 100.0
    )]
    ToleranceFoldPastSnap {
        tolerance: f64,
        duration: f64,
        gap: f64,
        snap: f64,
        speed: f64,
    },
    #[error(
        "amplitude = {0}: the shaken support's amplitude must be more than 0 and at most 0.05 string lengths (the theory it is held against is linear); try 0.001 to 0.01"
    )]
    ShakeAmplitude(f64),
    #[error(
        "frequency = {0}: the shaking frequency must be more than 0 and at most 20 radians per time unit (g = L = 1; the first resonances are 1.2024, 2.7600 and 4.3269); try 0.6 or 2.0"
    )]
    ShakeFrequency(f64),
    #[error(
        "frequency = {shown}: a steady start there asks the free end to swing {tip:.3} string lengths (A/|J₀(2Ω)| with A = {amplitude}), too near the resonance ω = {resonance:.4} for the linear steady state it starts on (at most 0.2); start from rest (--from rest), which shows the resonance grow, or move Ω away from {resonance:.4}, or lower --amplitude",
        shown = four_decimals(.frequency)
    )]
    SteadyNearResonance {
        frequency: f64,
        amplitude: f64,
        tip: f64,
        resonance: f64,
    },
    #[error(
        "sweep = {text}: {wrong}; give Ω₁..Ω₂ or Ω₁..Ω₂:count, with 0 < Ω₁ < Ω₂ ≤ 20 and a count from 2 to 2000 (for example 0.2..5:120)"
    )]
    Sweep {
        text: String,
        /// Which part is wrong, and how.
        wrong: String,
    },
}

/// Why and when a run stopped producing trustworthy numbers. No value computed after it is
/// ever handed out as a result.
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
#[error("diverged at step {step} (t = {time:.6}): {reason}")]
pub struct Diverged {
    /// The step (counted from 1) that produced the bad state.
    pub step: u64,
    /// The simulated time that step would have reached.
    pub time: f64,
    /// What went wrong, with the stability hint where the time step is to blame.
    pub reason: String,
}

/// `value` to at most four decimals, trailing zeros dropped: a sweep's frequency as typed
/// (1.16, not the float's 1.1600000000000001).
fn four_decimals(value: &f64) -> String {
    let text = format!("{value:.4}");
    match text.contains('.') {
        true => text.trim_end_matches('0').trim_end_matches('.').to_owned(),
        false => text,
    }
}
