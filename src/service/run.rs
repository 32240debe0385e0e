//! `rope run` as a service: it opens the outputs, watches the viewer, runs the passes (the
//! scenes in turn, again with `--loop`, methods side by side), writes the summary, serves a
//! finished run until stopped, and returns how the last run ended. What it says goes to the
//! [`Listener`] of its [`Session`] as notices.

use super::notices::{self, Listener, Notice, Topic};
use super::{ServiceError, Session};
use crate::cli::{RunArgs, check_writable_file, write_whole};
use crate::methods::MethodKind;
use crate::model::{Scene, analysis};
use crate::plan::Planned;
use crate::plan::pilot::Basis;
use crate::recording::blueprint;
use crate::recording::budget::Budget;
use crate::recording::destinations::{Layouts, Output, Recording};
use crate::recording::error::OutputError;
use crate::recording::logger::RopeLogger;
use crate::recording::table::Tables;
use crate::recording::viewer_sinks::ViewerLink;
use crate::run::cost;
use crate::run::progress::{Counter, Progress};
use crate::run::shake_figures::SweepPoint;
use crate::run::{Status, Summary};
use crate::study::sweep_chart;
use anyhow::Context as _;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How the last run ended.
#[derive(Debug)]
pub struct Outcome {
    /// The last run's summary (side by side: the first method's, each one's under `methods`).
    pub summary: Summary,
    /// The process's exit status for it ([`crate::run::Verdict::exit_status`]).
    pub exit_status: u8,
}

/// Predicted CPU seconds of a first `--tolerance` pilot from which the run says it before it
/// flies.
const SAY_PILOTS_FROM: f64 = 2.0;

/// `rope run`: the scenes in turn (and again, with `--loop`), into one recording.
pub fn run(args: &RunArgs, session: &Session) -> Result<Outcome, ServiceError> {
    let tell = |n| session.listener.tell(n);
    // Pilots that take a while are said before they fly (a narrow fold's start at sixteen
    // rods across the gap): the first line of a run is not a long silence.
    let plans = args.plans_telling(|scene, first| {
        if first.seconds >= SAY_PILOTS_FROM {
            tell(Notice::new(
                Topic::Pilots,
                format!(
                    "rope: tolerance pilots: measuring the {scene} first, from {} at N = {} to t = {} (about {} of CPU for that one)…",
                    first.method,
                    first.segments,
                    first.duration,
                    cost::seconds_text(first.seconds)
                ),
            ));
        }
    })?;
    let asked = notices::Asked {
        tolerance: args.tolerance,
        dt_given: args.dt.is_some(),
        log_rate: args.log_rate,
        default_method: args.default_method().map(|why| (args.method(), why)),
    };
    notices::announce(&asked, &plans).into_iter().for_each(tell);
    if let Some(path) = args.summary.as_deref() {
        check_writable_file("summary", path)?;
    }
    // The tables, before the recording opens: a wrong extension is said at once.
    let shakes = plans.iter().any(|p| p.plan.scene.support().moves());
    let tables = match args.table.as_deref() {
        Some(path) => Some(Tables::create(path, shakes).map_err(ServiceError::bad_input)?),
        None => None,
    };
    let stop = &session.stop;
    let headline = shared_headline(&plans);
    let lanes = plans.first().map(Planned::lanes).unwrap_or_default();
    let rates = args.output.history_rates();
    let sweep = is_sweep(&plans);
    let layouts = Layouts {
        everything: blueprint::blueprint(headline.as_deref(), &lanes, sweep),
        live: blueprint::live(headline.as_deref(), &lanes, rates.shape_interval(), sweep),
    };
    if let Some(path) = args.output.misnamed_file() {
        tell(notices::misnamed_file(path));
    }
    let output = match args.output.open("rope", layouts, args.endless()) {
        Ok(output) => output,
        Err(err @ OutputError::Save { .. }) => return Err(ServiceError::bad_input(err)),
        Err(err) => Err(err).context("opening the Rerun recording")?,
    };
    if let (Some(url), Some(live)) = (&output.serving, &output.serving_live) {
        let limit = args.output.server_memory_limit.to_string();
        tell(notices::serving(url, live, &limit));
    }
    if let Some(page) = &output.web_page {
        tell(notices::web_page(page));
    }
    let live = output
        .recordings
        .iter()
        .any(|r| matches!(r, Recording::Live { .. }));
    let mut loggers = Vec::new();
    for recording in &output.recordings {
        loggers.push(
            match recording {
                Recording::Everything(rec) if live => RopeLogger::file_beside_viewers(rec.clone()),
                Recording::Everything(rec) => RopeLogger::new(rec.clone()),
                Recording::Live { history, live } => {
                    RopeLogger::live(history.clone(), live.clone(), rates)
                }
            }
            .context("logging the recording's styling")?,
        );
    }
    if live {
        let text = Budget::measure(&lanes, rates).text();
        tell(notices::viewer_budget(
            rates.series_per_unit,
            rates.shape_interval(),
            &text,
        ));
        for logger in &mut loggers {
            logger.note_in_parameters(format!("**For viewers:** {text}."));
        }
    }
    if let Some(link) = output.viewer.clone() {
        watch_viewer(
            link,
            output.survives_viewer_loss,
            Arc::clone(stop),
            Arc::clone(&session.listener),
        );
    }
    let mut sinks = (loggers, tables);
    let (mut summary, strayed, swept) = run_passes(args, &plans, &mut sinks, session)?;
    let (loggers, tables) = sinks;
    // A Parquet table is read from its footer: written now, whatever ended the run.
    if let Some(Err(err)) = tables.map(Tables::finish) {
        summary.recording_error.get_or_insert(err.to_string());
    }
    if swept.points.len() >= 2 {
        tell(finish_sweep(args, &swept));
        summary.sweep = swept.points.clone();
    }
    if let Some(reason) = lost_viewer(&output) {
        summary.recording_error = Some(format!(
            "{reason} (the run reached t = {:.3})",
            summary.steps as f64 * summary.dt
        ));
    }
    if let Some(path) = &args.summary {
        let json = serde_json::to_string_pretty(&summary).context("encoding the summary")?;
        // Whole or not at all: a script may be waiting for it to appear.
        write_whole(path, json.as_bytes())
            .with_context(|| format!("writing the summary to {}", path.display()))?;
    }
    if plans.len() == 1 && args.passes() == Some(1) {
        tell(summary_notice(&summary));
    }
    if let Some(hint) = strayed.and_then(|(method, worst)| notices::energy_hint(method, worst)) {
        tell(hint);
    }
    if let Some(dropped) = output
        .live_dropped
        .as_ref()
        .map(|d| d.count())
        .filter(|&n| n > 0)
    {
        tell(notices::live_dropped(dropped));
    }
    serve_until_stopped(&output, stop, &*session.listener);
    drop(loggers); // closes the recordings: the file's footer, the last data to viewers
    drop(output);
    if let Some(err) = &summary.recording_error {
        tell(notices::recording_incomplete(err));
    }
    let exit_status = summary.verdict().exit_status();
    Ok(Outcome {
        summary,
        exit_status,
    })
}

/// A run's summary, as the terminal prints it.
fn summary_notice(summary: &Summary) -> notices::Notice {
    notices::Notice::new(notices::Topic::Summary, summary.human())
}

/// The method whose energy strayed most, and by how much relative to |E_ref|, among the
/// runs of methods that do not keep it.
type Strayed = Option<(MethodKind, f64)>;

/// The runs' method, scene, N and k in one line, when every run shares them (the rope
/// view's title); `None` when they differ, or for methods side by side (the caption over
/// the support names each run's).
fn shared_headline(plans: &[Planned]) -> Option<String> {
    if plans.iter().any(|p| !p.others.is_empty()) {
        return None;
    }
    let headlines: Vec<String> = plans.iter().map(|p| p.plan.headline()).collect();
    match headlines.as_slice() {
        [first, rest @ ..] if rest.iter().all(|h| h == first) => Some(first.clone()),
        _ => None,
    }
}

/// Whether the plans are a sweep of the shaken support's frequency: several shakes, each of
/// one method.
fn is_sweep(plans: &[Planned]) -> bool {
    plans.len() > 1
        && plans
            .iter()
            .all(|p| p.others.is_empty() && matches!(p.plan.scene, Scene::Shake { .. }))
}

/// A sweep of the shaking frequency as it goes: what each run measured of the free end, for
/// a support of `amplitude`, and the CPU time of its runs.
#[derive(Debug, Default)]
struct Swept {
    amplitude: f64,
    points: Vec<SweepPoint>,
    cpu_seconds: f64,
}

/// What a sweep found, and its chart and CSV beside the `--save` file, if there is one. A
/// chart that cannot be written is said, not an error: the recording and the summary stand.
fn finish_sweep(args: &RunArgs, swept: &Swept) -> notices::Notice {
    let chart = args.output.save.as_deref().map(|save| {
        let stem = save.file_stem().unwrap_or_default().to_string_lossy();
        save.with_file_name(format!("{stem}-response"))
    });
    let written = match &chart {
        Some(chart) => {
            let dir = chart.parent().unwrap_or(std::path::Path::new("."));
            let name = chart.file_name().unwrap_or_default().to_string_lossy();
            sweep_chart::write(dir, &name, swept.amplitude, &swept.points)
                .map(|()| Some(chart.as_path()))
                .map_err(|err| format!("{err:#}"))
        }
        None => Ok(None),
    };
    let peaks = |swing: fn(&SweepPoint) -> f64| {
        let curve: Vec<(f64, f64)> = swept
            .points
            .iter()
            .map(|p| (p.frequency, swing(p)))
            .collect();
        analysis::peaks(&curve)
    };
    super::sweep_notices::sweep(
        SweepPoint::span(&swept.points),
        swept.points.len(),
        &peaks(|p| p.largest),
        &peaks(|p| p.driven),
        swept.cpu_seconds,
        written,
    )
}

/// Runs the plans in turn, `--loop` times over, until one does not end well or the session
/// is stopped. Returns the last run's summary, the method whose energy strayed most, and
/// for a sweep of the shaking frequency what its first pass found (drawn in the viewer as
/// each run ends).
fn run_passes(
    args: &RunArgs,
    plans: &[Planned],
    sinks: &mut (Vec<RopeLogger>, Option<Tables>),
    session: &Session,
) -> anyhow::Result<(Summary, Strayed, Swept)> {
    let sweep = is_sweep(plans);
    let mut swept = Swept::default();
    let stop: &AtomicBool = &session.stop;
    let several = plans.len() > 1 || args.passes() != Some(1);
    let mut last = None;
    let mut strayed: Strayed = None;
    let mut pass = 0;
    // A sweep counts its frequencies on one bar, and says what it found once, at the end.
    let counter =
        sweep.then(|| Counter::new(plans.len() as u64, "rope run --sweep", "frequencies"));
    'passes: while args.passes().is_none_or(|passes| pass < passes) {
        pass += 1;
        for planned in plans {
            let plan = &planned.plan;
            let progress = match sweep {
                true => Progress::silent(),
                false => Progress::new(plan.duration),
            };
            let on_frame = |frame: &crate::run::Frame| {
                progress.at(frame.time);
                if let Some(passed) = frame.tolerance_exceeded {
                    let notice = notices::tolerance_exceeded(plan, passed);
                    // Above the progress bar, where the terminal draws one.
                    progress.suspend(|| session.listener.tell(notice));
                }
            };
            let summary = if let Some(rehearsal) = &planned.rehearsal {
                // The pilot that held is this run: handed over, not flown again.
                rehearsal.replay(sinks, stop, &on_frame)
            } else if planned.others.is_empty() {
                crate::run::pipeline::run(plan, sinks, stop, &on_frame)?
            } else {
                let lanes = crate::run::lanes::run(&planned.lanes(), sinks, stop, &on_frame)?;
                side_by_side(lanes)?
            };
            progress.finish();
            let mut summary = summary;
            if let (Some(choice), Some(eps)) = (&planned.choice, plan.tolerance) {
                let basis = planned
                    .pilots
                    .as_ref()
                    .map_or(Basis::Committed, |p| p.basis);
                summary.method_chosen_because = Some(format!(
                    "{}, chosen by --tolerance {eps:e} at N = {}: the predicted tip error {:.1e} rests on {}",
                    choice.method,
                    choice.segments,
                    choice.predicted_error,
                    basis.meaning()
                ));
            }
            if let Some(why) = args.default_method() {
                summary.method_chosen_because =
                    Some(notices::default_method_because(summary.method, why));
            }
            if let (
                true,
                1,
                Scene::Shake {
                    amplitude,
                    frequency,
                    ..
                },
                Some(f),
            ) = (sweep, pass, plan.scene, summary.shake)
            {
                swept.amplitude = amplitude;
                swept.points.push(SweepPoint {
                    frequency,
                    largest: f.tip_amplitude,
                    driven: f.driven_amplitude,
                });
                swept.cpu_seconds += summary.cpu_seconds;
                for logger in &sinks.0 {
                    logger
                        .log_sweep(amplitude, &swept.points)
                        .context("logging the sweep")?;
                }
            }
            if let Some(counter) = counter.as_ref().filter(|_| pass == 1) {
                counter.inc();
            } else if several && !sweep {
                // Each run of several says all it has as it ends; the last is not repeated.
                session.listener.tell(summary_notice(&summary));
            }
            // Side by side, a method that diverged stops alone: the others, and the loop, go on.
            let failed = match summary.methods.as_slice() {
                [] => summary.status != Status::Ok,
                lanes => lanes.iter().all(|l| l.status != Status::Ok),
            };
            let ended = failed || summary.recording_error.is_some();
            let each = match summary.methods.as_slice() {
                [] => std::slice::from_ref(&summary),
                lanes => lanes,
            };
            for run in each {
                let deviation = run.energy.max_rel_deviation;
                if !run.method.descriptor().keeps_energy
                    && strayed.is_none_or(|(_, worst)| deviation > worst)
                {
                    strayed = Some((run.method, deviation));
                }
            }
            last = Some(summary);
            if ended || stop.load(Ordering::SeqCst) {
                break 'passes;
            }
        }
    }
    if let Some(counter) = counter {
        counter.finish();
    }
    Ok((last.context("no run was made")?, strayed, swept))
}

/// The summary of methods side by side: the first one's fields, and each one's under
/// `methods` (its text says each one's lines, and how far each strayed).
fn side_by_side(lanes: Vec<Summary>) -> anyhow::Result<Summary> {
    let mut first = lanes.first().cloned().context("no method was run")?;
    first.methods = lanes;
    Ok(first)
}

/// Why the viewer that was the only destination is gone, if it is: that says more than a
/// flush that failed for want of it (a lost link stays lost).
fn lost_viewer(output: &Output) -> Option<String> {
    match &output.viewer {
        Some(link) if !output.survives_viewer_loss => link.lost(),
        _ => None,
    }
}

/// A served recording stays up for late viewers after a finite run, until stopped.
fn serve_until_stopped(output: &Output, stop: &AtomicBool, listener: &dyn Listener) {
    let Some(url) = &output.serving else { return };
    if stop.load(Ordering::SeqCst) {
        return;
    }
    listener.tell(notices::still_serving(url));
    while !stop.load(Ordering::SeqCst) {
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Watches the viewer from a thread of its own (a viewer already gone, as one that refused
/// the connection, is reported at once, before the run). When it is gone: if a file or a
/// served endpoint keeps the recording, says so once and lets the run go on; otherwise stops
/// the run (the link keeps the reason, for the summary).
fn watch_viewer(
    link: ViewerLink,
    survives: bool,
    stop: Arc<AtomicBool>,
    listener: Arc<dyn Listener>,
) {
    if viewer_gone(&link, survives, &stop, &*listener) {
        return;
    }
    std::thread::spawn(move || {
        while !viewer_gone(&link, survives, &stop, &*listener) {
            std::thread::sleep(Duration::from_millis(100));
        }
    });
}

/// Whether the viewer is gone; if it is, acts on it (see [`watch_viewer`]).
fn viewer_gone(
    link: &ViewerLink,
    survives: bool,
    stop: &AtomicBool,
    listener: &dyn Listener,
) -> bool {
    let Some(reason) = link.lost() else {
        return false;
    };
    if survives {
        listener.tell(notices::viewer_lost(&reason));
    } else {
        stop.store(true, Ordering::SeqCst);
    }
    true
}
