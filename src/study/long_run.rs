//! `rope study --long-run T`: each method from each release, left to swing for T time units
//! at N = 100 and its default step (or each of the steps asked for). What it measures is
//! whether the energy error stays bounded: |E − E_ref| at every frame (ten per time unit),
//! kept as the largest in each of 50 log-spaced bins per decade of t, the least-squares slope of E(t), the largest joint gap
//! (for `rattle`), and where a method diverged.

use super::progress::Progress;
use crate::error::Diverged;
use crate::methods::{MethodKind, REPORT, StepStatistics};
use crate::model::Scene;
use crate::run::simulate::{self, Options};
use std::ops::ControlFlow;
use std::time::Instant;

/// Frames per time unit: every one is checked.
const FRAMES_PER_UNIT: f64 = 10.0;
/// The energy error a long run is measured against: the time |E − E_ref| first passes it
/// is kept (docs/measurements.md, "Long runs", says why this bound).
pub const ENERGY_BOUND: f64 = 1e-5;
/// Bins of the chart and CSV per decade of t.
const BINS_PER_DECADE: f64 = 50.0;
/// The first bin starts here.
const FIRST_TIME: f64 = 0.1;

/// The largest |E − E_ref| in one bin of time.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Bin {
    /// The bin's end, in time units.
    pub t: f64,
    pub max_abs_deviation: f64,
}

/// One method from one release, swung for a long time.
#[derive(Clone, Debug)]
pub struct LongRun {
    pub method: MethodKind,
    pub scene: Scene,
    pub segments: usize,
    pub dt: f64,
    /// Time reached (the duration, unless it diverged).
    pub time: f64,
    pub bins: Vec<Bin>,
    /// Largest |E − E_ref| over every frame.
    pub max_abs_deviation: f64,
    /// Least-squares slope of E(t) over every frame, per time unit.
    pub slope: f64,
    /// The first frame's time at which |E − E_ref| passed [`ENERGY_BOUND`].
    pub first_past_bound: Option<f64>,
    /// The fastest the tip moved at any frame: how hard the free end whips.
    pub max_tip_speed: f64,
    pub max_constraint_residual: Option<f64>,
    /// How the method's own steps went, for a method that chooses them.
    pub step_statistics: Option<StepStatistics>,
    pub diverged: Option<Diverged>,
    /// Wall time of the run (the runs share the machine's cores, one each).
    pub wall_seconds: f64,
}

/// The least-squares slope of a series (E against t), kept as running means and centred
/// sums (Welford's update), so that a long series loses no digits to cancellation.
#[derive(Default)]
pub struct Trend {
    n: f64,
    mean_t: f64,
    mean_e: f64,
    /// Σ (t − t̄)(e − ē) and Σ (t − t̄)².
    co: f64,
    var: f64,
}

impl Trend {
    /// Adds the point (t, e).
    pub fn add(&mut self, t: f64, e: f64) {
        self.n += 1.0;
        let dt = t - self.mean_t;
        self.mean_t += dt / self.n;
        self.mean_e += (e - self.mean_e) / self.n;
        self.co += dt * (e - self.mean_e);
        self.var += dt * (t - self.mean_t);
    }

    /// The least-squares slope of the points added.
    pub fn slope(&self) -> f64 {
        self.co / self.var
    }
}

/// The bin of time `t`: 0 for t ≤ [`FIRST_TIME`], then 50 per decade.
fn bin_of(t: f64) -> usize {
    if t <= FIRST_TIME {
        0
    } else {
        1 + ((t / FIRST_TIME).log10() * BINS_PER_DECADE).floor() as usize
    }
}

/// The end of bin `i`.
fn bin_end(i: usize) -> f64 {
    FIRST_TIME * 10f64.powf(i as f64 / BINS_PER_DECADE)
}

/// The long runs to make: each method of `methods` at each step of `dts` (its default step
/// at N = 100 if `None`) from each scene of `scenes`, in that order.
pub fn runs(
    methods: &[MethodKind],
    scenes: &[Scene],
    dts: Option<&[f64]>,
) -> Vec<(MethodKind, Scene, f64)> {
    let mut runs = Vec::new();
    for &method in methods {
        let steps = dts.map_or_else(|| vec![method.default_dt(REPORT.segments)], <[f64]>::to_vec);
        for dt in steps {
            runs.extend(scenes.iter().map(|&scene| (method, scene, dt)));
        }
    }
    runs
}

/// Swings `method` from `scene` for `duration` time units at N = 100 and step `dt`;
/// `progress` counts each time unit simulated, and may stop the run at the next
/// ([`Stopped`](super::Stopped)).
pub fn run(
    method: MethodKind,
    scene: Scene,
    dt: f64,
    duration: f64,
    progress: &impl Progress,
) -> anyhow::Result<LongRun> {
    let segments = REPORT.segments;
    let mut stepper = method.build(&scene, segments, dt)?;
    let reference = simulate::reference_energy(stepper.as_ref());
    let mut bins: Vec<Bin> = Vec::new();
    let mut trend = Trend::default();
    let mut worst: f64 = 0.0;
    let mut first_past_bound = None;
    let mut max_tip_speed: f64 = 0.0;
    let mut units = 0.0;
    let wall = Instant::now();
    let options = Options {
        duration,
        log_rate: FRAMES_PER_UNIT,
        frame_grid: None,
    };
    let outcome = simulate::run(stepper.as_mut(), &options, None, |frame| {
        let deviation = frame.energy.total() - reference;
        trend.add(frame.time, frame.energy.total());
        worst = worst.max(deviation.abs());
        if deviation.abs() > ENERGY_BOUND && first_past_bound.is_none() {
            first_past_bound = Some(frame.time);
        }
        max_tip_speed = max_tip_speed.max(frame.tip_velocity.norm());
        let i = bin_of(frame.time);
        if bins.len() <= i {
            bins.resize_with(i + 1, || Bin {
                t: 0.0,
                max_abs_deviation: 0.0,
            });
        }
        bins[i].t = bin_end(i);
        bins[i].max_abs_deviation = bins[i].max_abs_deviation.max(deviation.abs());
        while frame.time >= units + 1.0 {
            units += 1.0;
            progress.done();
        }
        match progress.stopped() {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    });
    progress.check()?;
    bins.retain(|b| b.t > 0.0);
    // A run that ended early has no more work to show.
    for _ in (units as u64)..(duration.ceil() as u64) {
        progress.done();
    }
    Ok(LongRun {
        method,
        scene,
        segments,
        dt,
        time: outcome.time,
        bins,
        max_abs_deviation: worst,
        slope: trend.slope(),
        first_past_bound,
        max_tip_speed,
        max_constraint_residual: outcome.max_constraint_residual,
        step_statistics: outcome.step_statistics,
        diverged: outcome.diverged,
        wall_seconds: wall.elapsed().as_secs_f64(),
    })
}

/// The runs as a Markdown table, with the command that made them.
pub fn markdown(runs: &[LongRun], duration: f64, command: &str) -> String {
    let mut text = format!(
        "# Long runs: the energy over {duration} time units\n\n`{command}`\n\n\
         N = {}, each method at the step k; E_ref is the energy after 10 steps, and every \
         frame (ten per time unit) is checked.\n\n\
         | method | scene | k | reached t | max \\|E − E_ref\\| | first past {ENERGY_BOUND:.0e} at t | slope of E(t) per unit | fastest tip | largest joint gap | diverged | wall s |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
        REPORT.segments
    );
    for r in runs {
        text += &format!(
            "| {} | {} | {:.3e} | {:.1} | {:.2e} | {} | {:.2e} | {:.1} | {} | {} | {:.0} |\n",
            r.method,
            r.scene,
            r.dt,
            r.time,
            r.max_abs_deviation,
            r.first_past_bound
                .map_or("never".to_owned(), |t| format!("{t:.1}")),
            r.slope,
            r.max_tip_speed,
            r.max_constraint_residual
                .map_or("–".to_owned(), |g| format!("{g:.1e}")),
            r.diverged.as_ref().map_or("no".to_owned(), |d| format!(
                "t = {:.2}: {}",
                d.time, d.reason
            )),
            r.wall_seconds
        );
    }
    let adaptive: Vec<_> = runs
        .iter()
        .filter_map(|r| r.step_statistics.map(|s| (r, s)))
        .collect();
    if !adaptive.is_empty() {
        text += "\nThe steps of a method that chooses its own, and the kinetic energy its velocity \
                 projections removed and its rescale put back (see `docs/physics.md`):\n\n\
                 | method | scene | own steps | shortest | fastest rod (rad per unit) | Newton failures | solves per step | put back after projections | round-off taken back | not restored |\n\
                 |---|---|---|---|---|---|---|---|---|---|\n";
        for (r, s) in adaptive {
            text += &format!(
                "| {} | {} | {} | {:.2e} | {:.0} | {} | {:.2} | {:.2e} | {:.1e} | {:.1e} |\n",
                r.method,
                r.scene,
                s.steps,
                s.smallest_step,
                s.fastest_rotation,
                s.newton_failures,
                s.solves as f64 / s.steps.max(1) as f64,
                s.restored_energy,
                s.roundoff_energy,
                s.unrestored_energy,
            );
        }
    }
    text
}

/// A CSV row: one bin of one run.
#[derive(serde::Serialize)]
struct CsvRow<'a> {
    method: &'a str,
    angle_deg: f64,
    dt: f64,
    t: f64,
    max_abs_deviation: f64,
}

/// Writes every run's bins to `path`.
pub fn write_csv(runs: &[LongRun], path: &std::path::Path) -> anyhow::Result<()> {
    let mut out = csv::Writer::from_path(path)?;
    for r in runs {
        for b in &r.bins {
            out.serialize(CsvRow {
                method: r.method.name(),
                angle_deg: r.scene.support_angle().to_degrees(),
                dt: r.dt,
                t: b.t,
                max_abs_deviation: b.max_abs_deviation,
            })?;
        }
    }
    out.flush()?;
    Ok(())
}
