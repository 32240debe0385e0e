//! What rope tells the user, as values: each announcement, warning, hint and report is a
//! [`Notice`] of a [`Topic`], made here and handed to a [`Listener`]. The terminal prints
//! them ([`Terminal`]); a test collects them ([`Collected`]) and asks which were told, with
//! no stderr to parse.

use super::pilot_notices;
use crate::cli::DefaultMethod;
use crate::methods::MethodKind;
use crate::model::Scene;
use crate::model::scene::{FOLD_RODS_ACROSS_GAP, FOLD_THEORY_GAP};
use crate::plan::Planned;
use crate::plan::pilot::{Basis, Pilots};
use crate::run::config::{at_most_three_digits, short_step, trimmed_fixed};
use crate::run::simulate::Exceeded;
use crate::run::{RunPlan, cost};
use std::sync::{Mutex, PoisonError};

/// The relative energy deviation past which a run is told which method keeps the energy.
pub const ENERGY_HINT: f64 = 0.01;

/// What a notice is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Topic {
    /// What `--tolerance` chose, and what the choice rests on.
    ToleranceChoice,
    /// What the pilot runs of `--tolerance` measured.
    Pilots,
    /// A run predicted to take more than a minute.
    PredictedCost,
    /// Each method's step, side by side.
    SideBySideSteps,
    /// The step used where `--dt` was not given.
    DefaultStep,
    /// A step past a method's stability limit that the method survives.
    PastLimit,
    /// A run longer than its method is known to last.
    BlowUp,
    /// A fold whose bend is drawn by too few rods to follow its theory.
    CoarseBend,
    /// A fold whose gap is too wide for its theory, which is for no gap.
    WideGap,
    /// The method a run left running, or a fold, uses by default, and why.
    LastingDefault,
    /// A `--save` file not named `.rrd`.
    FileName,
    /// Where viewers can join a served run.
    Serving,
    /// How long a browser page can stay open.
    ViewerBudget,
    /// The live estimate passed `--tolerance`.
    ToleranceExceeded,
    /// What a run did: its summary.
    Summary,
    /// A method let the energy stray: which one keeps it.
    EnergyHint,
    /// Live pictures not sent while viewers were behind.
    LiveDropped,
    /// A viewer is gone and the run goes on without it.
    ViewerLost,
    /// A finite run has ended and is still served.
    StillServing,
    /// The recording could not be completed.
    RecordingIncomplete,
    /// What a study is about to do, and what it wrote.
    Study,
    /// What a sweep of the shaking frequency found, and where its chart is.
    Sweep,
    /// A study's result that may mislead (a choice at the grid's edge).
    StudyWarning,
    /// A study's findings: the report itself, in Markdown.
    Report,
}

/// One thing rope tells the user: its topic and the line(s) the terminal prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Notice {
    pub topic: Topic,
    pub text: String,
}

impl Notice {
    pub fn new(topic: Topic, text: impl Into<String>) -> Self {
        Self {
            topic,
            text: text.into(),
        }
    }
}

impl std::fmt::Display for Notice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

/// Who hears the notices (shared with the threads that watch a viewer).
pub trait Listener: Send + Sync {
    fn tell(&self, notice: Notice);
}

/// Hears nothing.
impl Listener for () {
    fn tell(&self, _: Notice) {}
}

/// The terminal: each notice on stderr, as it comes; a study's report on stdout.
pub struct Terminal;

impl Listener for Terminal {
    fn tell(&self, notice: Notice) {
        match notice.topic {
            Topic::Report => println!("{notice}"),
            _ => eprintln!("{notice}"),
        }
    }
}

/// Keeps every notice, in order, for a caller to read back.
#[derive(Default)]
pub struct Collected(Mutex<Vec<Notice>>);

impl Collected {
    /// The notices told so far.
    pub fn notices(&self) -> Vec<Notice> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    /// Whether a notice of `topic` was told.
    pub fn told(&self, topic: Topic) -> bool {
        self.notices().iter().any(|n| n.topic == topic)
    }
}

impl Listener for Collected {
    fn tell(&self, notice: Notice) {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .push(notice);
    }
}

/// A `--log-rate` above the rate of a step the user did not set (the default one, or the one
/// `--tolerance` chose): a frame at every step instead, and how to have more.
fn fewer_frames(asked: &Asked, plan: &RunPlan, chosen: bool) -> Option<Notice> {
    let rate = asked.log_rate.filter(|&rate| rate > plan.log_rate)?;
    let (step, topic, then) = match chosen {
        true => (
            "the chosen step",
            Topic::ToleranceChoice,
            "The tolerance is watched at every step whatever the frames".to_owned(),
        ),
        false => (
            "the default step",
            Topic::DefaultStep,
            format!(
                "For more, give --dt {} or less",
                at_most_three_digits(1.0 / rate)
            ),
        ),
    };
    Some(Notice::new(
        topic,
        format!(
            "rope: --log-rate {rate} asks more frames than {step} takes (k = {}); a frame at every step instead ({} a time unit). {then}",
            step_text(plan.dt),
            trimmed_fixed(plan.log_rate, 1)
        ),
    ))
}

/// What the flags of a run chose for the user, before it starts.
pub struct Asked {
    /// `--tolerance`, if given.
    pub tolerance: Option<f64>,
    /// Whether `--dt` was given.
    pub dt_given: bool,
    /// `--log-rate`, if given.
    pub log_rate: Option<f64>,
    /// The method, when it is a default the run announces, and why it is.
    pub default_method: Option<(MethodKind, DefaultMethod)>,
}

/// What was chosen for the user: the tolerance rule's choice, a default step, a default
/// method for an endless run, and the predicted cost of a run that takes more than a minute;
/// warns of a step past a method's limit and of a run the method is known not to last.
pub fn announce(asked: &Asked, plans: &[Planned]) -> Vec<Notice> {
    let mut notices = Vec::new();
    let several = plans.len() > 1;
    for Planned {
        plan,
        choice,
        pilots,
        rehearsal,
        ..
    } in plans
    {
        let Some(choice) = choice else { continue };
        let scene = if several {
            format!(" ({})", plan.scene)
        } else {
            String::new()
        };
        let basis = pilots
            .as_ref()
            .map_or(Basis::Committed, |p| p.basis)
            .meaning();
        let flew = |p: &&Pilots| p.flown.iter().any(|f| f.flew());
        if let Some(pilots) = pilots.as_ref().filter(flew) {
            notices.push(Notice::new(
                Topic::Pilots,
                pilot_notices::pilot_lines(pilots, plan.duration),
            ));
        }
        let verified = match rehearsal {
            Some(_) => "that pilot was this very run, its frames kept: it is not flown again",
            None => "the live estimate will say if it holds",
        };
        notices.push(Notice::new(
            Topic::ToleranceChoice,
            format!(
                "rope: tolerance {:e}{scene}: chose the {} method, N = {}, k = {}; predicted tip error at most {:.1e}, predicted cost {:.2e} CPU s with its frames and the estimate's shadow ({basis}; {verified})",
                asked.tolerance.unwrap_or_default(),
                choice.method,
                choice.segments,
                step_text(choice.dt),
                choice.predicted_error,
                plan.cost.seconds
            ),
        ));
    }
    for Planned { plan, choice, .. } in plans {
        if let Some(notice) = fewer_frames(asked, plan, choice.is_some()) {
            notices.push(notice);
        }
        if let Some(notice) = coarse_bend(plan) {
            notices.push(notice);
        }
        if let Some(notice) = wide_gap(plan.scene) {
            notices.push(notice);
        }
        if plan.cost.seconds > cost::ANNOUNCE_SECONDS {
            notices.push(Notice::new(
                Topic::PredictedCost,
                format!(
                    "rope: {} is predicted to take about {} of CPU and {} of memory",
                    plan.scene,
                    cost::seconds_text(plan.cost.seconds),
                    cost::bytes_text(plan.cost.bytes)
                ),
            ));
        }
    }
    if let Some(Planned { plan, others, .. }) = plans.first() {
        let method = plan.method.descriptor();
        let limit = method.stability_limit(plan.segments);
        if !others.is_empty() {
            let steps: Vec<String> = std::iter::once(plan)
                .chain(others)
                .map(|p| format!("{} k = {:.3e}", p.method, p.dt))
                .collect();
            notices.push(Notice::new(
                Topic::SideBySideSteps,
                format!(
                    "rope: side by side at N = {}, each at {} brought down so that {} instants a time unit, shared by all, fall on its steps (the frames fall on them): {}",
                    plan.segments,
                    if asked.dt_given {
                        "--dt"
                    } else {
                        "its default step"
                    },
                    plan.frame_grid.unwrap_or(plan.log_rate),
                    steps.join(", ")
                ),
            ));
        } else if asked.tolerance.is_none() && !asked.dt_given {
            let why = match method.accurate_step {
                Some(a) if plan.dt > method.default_step_fraction * limit => format!(
                    "what its tip needs, {}, above {} of its estimated stability limit {limit:.3e}: {}",
                    a.rule_in(&plan.scene),
                    method.default_step_fraction,
                    method.past_limit
                ),
                _ => format!(
                    "estimated stability limit {limit:.3e}: {}",
                    method.past_limit
                ),
            };
            notices.push(Notice::new(
                Topic::DefaultStep,
                format!(
                    "rope: --dt not given: using k = {:.3e} for the {} method at N = {} ({why})",
                    plan.dt, plan.method, plan.segments
                ),
            ));
        } else if plan.dt > limit && !method.refuses_unstable_step {
            notices.push(Notice::new(
                Topic::PastLimit,
                format!(
                    "rope: k = {:e} is {:.1} times the {} method's estimated stability limit {limit:.3e} at N = {}; {}",
                    plan.dt,
                    plan.dt / limit,
                    plan.method,
                    plan.segments,
                    method.past_limit
                ),
            ));
        }
        for lane in std::iter::once(plan).chain(others) {
            notices.extend(blow_up_warning(lane, !others.is_empty()));
        }
    }
    // (--tolerance with an endless run was refused before.)
    if let Some((method, why)) = asked.default_method {
        notices.push(default_method(method, why));
    }
    notices
}

/// The method a run uses by default, and why, as the run announces it.
fn default_method(method: MethodKind, why: DefaultMethod) -> Notice {
    let text = match why {
        DefaultMethod::Lasting => format!(
            "rope: a run left running (endless, looping or served) uses the {method} method: {} (the report's scheme blows up after tens of time units, the chain's energy drifts down, rattle's jumps at violent snaps; --method to choose another)",
            MethodKind::DEFAULT_LASTING_BECAUSE
        ),
        DefaultMethod::Scene { scene, because, .. } => format!(
            "rope: the {scene} uses the {method} method: {because} (--method to choose another)"
        ),
    };
    Notice::new(Topic::LastingDefault, text)
}

/// The summary's `method_chosen_because` for a method that is a default.
pub fn default_method_because(method: MethodKind, why: DefaultMethod) -> String {
    match why {
        DefaultMethod::Lasting => format!(
            "{method}, the default for a run left running (endless, looping or served): {}",
            MethodKind::DEFAULT_LASTING_BECAUSE
        ),
        DefaultMethod::Scene { scene, because, .. } => {
            format!("{method}, the {scene}'s default: {because}")
        }
    }
}

/// A step as the user reads it: in four significant digits, and as 1/m where it is the
/// reciprocal of a whole number that those digits do not give exactly (`6.41e-4 = 1/1560`).
fn step_text(dt: f64) -> String {
    let short = short_step(dt);
    let whole = (1.0 / dt).round();
    match short.parse::<f64>() {
        Ok(v) if v != dt && (1.0 / whole - dt).abs() <= 1e-12 * dt => {
            format!("{short} = 1/{whole}")
        }
        _ => short,
    }
}

/// Warns of a fold whose gap spans fewer than [`FOLD_RODS_ACROSS_GAP`] rods: its bend is
/// then too coarse for the free end to follow Calkin & March's prediction.
pub fn coarse_bend(plan: &RunPlan) -> Option<Notice> {
    coarse_bends(plan.scene, &[plan.segments])
}

/// As [`coarse_bend`], for runs of `scene` at each of `segments` (a study's grid): the
/// segment counts whose bend is too coarse, in one warning.
pub fn coarse_bends(scene: Scene, segments: &[usize]) -> Option<Notice> {
    let Scene::Fold { gap } = scene else {
        return None;
    };
    let coarse: Vec<usize> = segments
        .iter()
        .copied()
        .filter(|&n| gap * (n as f64) < FOLD_RODS_ACROSS_GAP)
        .collect();
    let across = gap * *coarse.iter().max()? as f64;
    let at: Vec<String> = coarse.iter().map(usize::to_string).collect();
    Some(Notice::new(
        Topic::CoarseBend,
        format!(
            "rope: warning: the fold's gap of {gap} spans {}{across:.1} rods at N = {}: a bend of fewer than {FOLD_RODS_ACROSS_GAP} rods is too coarse for the free end to follow Calkin & March (below one, up to 11 % off in speed); give --segments {} or more, or a wider --gap",
            if coarse.len() > 1 { "at most " } else { "" },
            at.join(", "),
            (FOLD_RODS_ACROSS_GAP / gap).ceil()
        ),
    ))
}

/// Warns of a fold whose gap is past [`FOLD_THEORY_GAP`]: its comparisons with Calkin &
/// March's string, a theory for no gap, are then off by the gap's own effect.
pub fn wide_gap(scene: Scene) -> Option<Notice> {
    let Scene::Fold { gap } = scene else {
        return None;
    };
    (gap > FOLD_THEORY_GAP).then(|| {
        Notice::new(
            Topic::WideGap,
            format!(
                "rope: warning: Calkin & March's theory is for a fold with no gap; at --gap {gap} its comparisons are off by the gap's own effect (at N = 200 the free end's speed to a fall of 0.75: within 0.7 % of it at 0.1, 2.9 % at 0.2, 7.4 % at 0.3, 19 % at 0.4); a gap of {FOLD_THEORY_GAP} or less keeps them to about 1 %"
            ),
        )
    })
}

/// Warns of a run longer than its method is known to last (the blow-up map's earliest at
/// its N), suggesting the methods that last; side by side, says the others go on.
pub fn blow_up_warning(plan: &RunPlan, side_by_side: bool) -> Option<Notice> {
    let method = plan.method.descriptor();
    let blow_up = method.blow_up_at(plan.segments)?;
    if plan.duration <= blow_up.earliest {
        return None;
    }
    let seen = format!(
        "the {} method blows up in a long run at any step (from the release at 30° at N = {}, `rope study --blow-up 200` saw it diverge between t = {} and {})",
        plan.method, blow_up.segments, blow_up.earliest, blow_up.latest
    );
    if side_by_side {
        return Some(Notice::new(
            Topic::BlowUp,
            format!(
                "rope: note: side by side, {} will most likely stop before t = {}: {seen}; the others go on",
                plan.method, plan.duration
            ),
        ));
    }
    let stable: Vec<&str> = MethodKind::ALL
        .iter()
        .filter(|m| m.descriptor().blow_up.is_empty() && m.descriptor().steady_cost)
        .map(|m| m.name())
        .collect();
    Some(Notice::new(
        Topic::BlowUp,
        format!(
            "rope: warning: a run to t = {} will most likely stop early: {seen}; for a long run use --method {}",
            plan.duration,
            stable.join(" or ")
        ),
    ))
}

/// Once, after the runs: a method that let the energy stray by more than [`ENERGY_HINT`]
/// of |E_ref| (`deviation`, the worst among the methods that do not keep it) is told which
/// method keeps it.
pub fn energy_hint(method: MethodKind, deviation: f64) -> Option<Notice> {
    let keeper = MethodKind::ALL
        .iter()
        .find(|m| m.descriptor().keeps_energy)?;
    (deviation > ENERGY_HINT).then(|| {
        Notice::new(
            Topic::EnergyHint,
            format!(
                "rope: the {method} method let the energy stray by up to {:.1} % of |E_ref|; the {keeper} method keeps it exactly (--method {keeper})",
                100.0 * deviation
            ),
        )
    })
}

/// What a run says, once, when its error estimate passes the tolerance.
pub fn tolerance_exceeded(plan: &RunPlan, passed: Exceeded) -> Notice {
    Notice::new(
        Topic::ToleranceExceeded,
        format!(
            "rope: at t = {:.4} the tip error's {} {:.1e} passed the tolerance {:.1e} (N = {}): the run may miss it; it goes on; its summary says tolerance_met: false, and it exits with status 4",
            passed.time,
            plan.tip_bound.name(),
            passed.estimate,
            plan.tolerance.unwrap_or(f64::NAN),
            plan.segments
        ),
    )
}

/// A `--save` file whose name does not say it is a Rerun recording.
pub fn misnamed_file(path: &std::path::Path) -> Notice {
    Notice::new(
        Topic::FileName,
        format!(
            "rope: warning: --save {}: the file is a Rerun recording whatever its name; \
             name it with .rrd so that `rerun` and other tools recognise it",
            path.display()
        ),
    )
}

/// Where viewers of a served run join: the history's endpoint and the live picture's.
pub fn serving(url: &str, live: &str, memory_limit: &str) -> Notice {
    Notice::new(
        Topic::Serving,
        format!(
            "rope: serving at {url} (the history: any number of viewers can join, at any time, and get it first; memory is kept within {memory_limit} by dropping the oldest) and {live} (the live picture); watch with `rerun {url} {live}`"
        ),
    )
}

/// The page a browser opens to watch.
pub fn web_page(page: &str) -> Notice {
    Notice::new(
        Topic::Serving,
        format!("rope: watch it in a browser at {page}"),
    )
}

/// What viewers of a run left running get, and how long a page lasts (`budget`, in words).
pub fn viewer_budget(series_per_unit: f64, shape_interval: f64, budget: &str) -> Notice {
    Notice::new(
        Topic::ViewerBudget,
        format!(
            "rope: viewers get a live picture that replaces itself and a history: {series_per_unit} rows of each plot per time unit and the rope's shape every {} time units (--history-rate); {budget}",
            trimmed_fixed(shape_interval, 3)
        ),
    )
}

/// Live pictures not sent while their viewers were behind.
pub fn live_dropped(dropped: u64) -> Notice {
    Notice::new(
        Topic::LiveDropped,
        format!(
            "rope: {dropped} messages of the live picture were not sent while its viewers were behind (the history and any file are whole)"
        ),
    )
}

/// A viewer is gone, and a file or a served endpoint keeps the recording.
pub fn viewer_lost(reason: &str) -> Notice {
    Notice::new(
        Topic::ViewerLost,
        format!("rope: warning: {reason}; the run goes on without it"),
    )
}

/// A finite served run has ended, and stays up for late viewers.
pub fn still_serving(url: &str) -> Notice {
    Notice::new(
        Topic::StillServing,
        format!("rope: the run has ended; still serving it at {url} until Ctrl-C"),
    )
}

/// The recording could not be completed.
pub fn recording_incomplete(err: &str) -> Notice {
    Notice::new(
        Topic::RecordingIncomplete,
        format!("rope: error: the recording is incomplete: {err}"),
    )
}
