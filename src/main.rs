//! The `rope` command: parses the flags, opens the Rerun recording, and hands off to the
//! run pipeline ([`rope::run::pipeline::run`]) or the study ([`rope::study::execute`]).

use anyhow::Context as _;
use clap::Parser as _;
use rope::cli::{
    CheckSize, Cli, Command, Planned, RunArgs, StudyArgs, check_writable_file, writable_dir,
};
use rope::methods::MethodKind;
use rope::recording::blueprint;
use rope::recording::budget::Budget;
use rope::recording::destinations::{Layouts, Output, Recording};
use rope::recording::error::OutputError;
use rope::recording::logger::RopeLogger;
use rope::recording::viewer_sinks::ViewerLink;
use rope::run::cost;
use rope::run::progress::{Counter, Progress};
use rope::run::{Status, Summary};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Exit codes: 2 is bad input (as clap's own errors); a run's own ([`Verdict::exit_status`]):
/// 3 a diverged run, 4 a run whose live estimate passed `--tolerance`, 130 an interrupted
/// one; 1 anything else (among it a recording that could not be completed).
const EXIT_BAD_INPUT: u8 = 2;
const EXIT_INTERRUPTED: u8 = 130;

/// The relative energy deviation past which a run is told which method keeps the energy.
const ENERGY_HINT: f64 = 0.01;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Run(args) => run(args),
        Command::Study(args) => study(args),
    };
    result.unwrap_or_else(|err| {
        eprintln!("rope: error: {err:#}");
        ExitCode::FAILURE
    })
}

/// Reports a configuration that cannot run.
fn bad_input(err: &dyn std::fmt::Display) -> ExitCode {
    eprintln!("rope: bad input: {err}");
    ExitCode::from(EXIT_BAD_INPUT)
}

/// `rope run`: the scenes in turn (and again, with `--loop`), into one recording.
fn run(args: &RunArgs) -> anyhow::Result<ExitCode> {
    let plans = match args.plans() {
        Ok(plans) => plans,
        Err(err) => return Ok(bad_input(&err)),
    };
    announce(args, &plans);
    if let Some(Err(err)) = args
        .summary
        .as_deref()
        .map(|p| check_writable_file("summary", p))
    {
        return Ok(bad_input(&err));
    }
    let stop = stop_on_interrupt()?;
    let headline = shared_headline(&plans);
    let lanes = plans.first().map(Planned::lanes).unwrap_or_default();
    let rates = args.output.history_rates();
    let layouts = Layouts {
        everything: blueprint::blueprint(headline.as_deref(), &lanes),
        live: blueprint::live(headline.as_deref(), &lanes, rates.shape_interval()),
    };
    let output = match args.output.open("rope", layouts, args.endless()) {
        Ok(output) => output,
        Err(err @ OutputError::Save { .. }) => return Ok(bad_input(&err)),
        Err(err) => return Err(err).context("opening the Rerun recording"),
    };
    if let (Some(url), Some(live)) = (&output.serving, &output.serving_live) {
        eprintln!(
            "rope: serving at {url} (the history: any number of viewers can join, at any time, and get it first; memory is kept within {} by dropping the oldest) and {live} (the live picture); watch with `rerun {url} {live}`",
            args.output.server_memory_limit
        );
    }
    if let Some(page) = &output.web_page {
        eprintln!("rope: watch it in a browser at {page}");
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
        let budget = Budget::measure(&lanes, rates);
        let text = budget.text();
        eprintln!(
            "rope: viewers get a live picture that replaces itself and a history: {} rows of each plot per time unit and the rope's shape every {} time units (--history-rate); {text}",
            rates.series_per_unit,
            rope::run::config::trimmed_fixed(rates.shape_interval(), 3)
        );
        for logger in &mut loggers {
            logger.note_in_parameters(format!("**For viewers:** {text}."));
        }
    }
    if let Some(link) = output.viewer.clone() {
        watch_viewer(link, output.survives_viewer_loss, Arc::clone(&stop));
    }
    let (mut summary, strayed) = run_passes(args, &plans, &mut loggers, &stop)?;
    if let Some(reason) = lost_viewer(&output) {
        summary.recording_error = Some(format!(
            "{reason} (the run reached t = {:.3})",
            summary.steps as f64 * summary.dt
        ));
    }
    if let Some(path) = &args.summary {
        let json = serde_json::to_string_pretty(&summary).context("encoding the summary")?;
        std::fs::write(path, json)
            .with_context(|| format!("writing the summary to {}", path.display()))?;
    }
    if plans.len() == 1 && args.passes() == Some(1) {
        eprintln!("{}", summary.human());
    }
    energy_hint(strayed);
    if let Some(dropped) = output
        .live_dropped
        .as_ref()
        .map(|d| d.count())
        .filter(|&n| n > 0)
    {
        eprintln!(
            "rope: {dropped} messages of the live picture were not sent while its viewers were behind (the history and any file are whole)"
        );
    }
    serve_until_stopped(&output, &stop);
    drop(loggers); // closes the recordings: the file's footer, the last data to viewers
    drop(output);
    Ok(exit_code(&summary))
}

/// Says what was chosen for the user: the tolerance rule's choice, a default step, a default
/// method for an endless run, and the predicted cost of a run that takes more than a minute;
/// warns of a step past a method's limit and of a run the method is known not to last.
fn announce(args: &RunArgs, plans: &[Planned]) {
    let several = plans.len() > 1;
    for Planned {
        plan,
        choice,
        pilots,
        ..
    } in plans
    {
        let Some(choice) = choice else { continue };
        let scene = if several {
            format!(" ({})", plan.scene)
        } else {
            String::new()
        };
        use rope::run::pilot::Basis;
        let basis = match pilots.as_ref().map(|p| p.basis) {
            Some(Basis::Held) => "the scene's own error, measured by the pilot at this N",
            Some(Basis::OwnModel) => "the scene's own error model, from the pilots",
            Some(Basis::CommittedTighter) => {
                "the committed error model, here tighter than the pilots' own (measured at N ≤ 64)"
            }
            Some(Basis::Atlas) => {
                "the release atlas: the rods' worst error to t = 3 measured up to N = 566 from this angle's neighbours among 0°, 10°, …, 90°, times the margin the angles between them showed (`scripts/release-atlas.sh`)"
            }
            Some(Basis::Committed) | None => {
                "the committed error model, fitted to t = 3 over six scenes by `rope study --estimate-check`, no cheaper run found by the pilots that were worth their cost"
            }
        };
        let flew = |p: &&rope::run::pilot::Pilots| p.flown.iter().any(|f| f.flew());
        if let Some(pilots) = pilots.as_ref().filter(flew) {
            eprintln!("{}", pilot_lines(pilots, plan.duration));
        }
        eprintln!(
            "rope: tolerance {:e}{scene}: chose the {} method, N = {}, k = {}; predicted tip error at most {:.1e}, predicted cost {:.2e} CPU s with its frames and the estimate's shadow ({basis}; the live estimate will say if it holds)",
            args.tolerance.unwrap_or_default(),
            choice.method,
            choice.segments,
            step_text(choice.dt),
            choice.predicted_error,
            plan.cost.seconds
        );
    }
    for Planned { plan, .. } in plans {
        if plan.cost.seconds > cost::ANNOUNCE_SECONDS {
            eprintln!(
                "rope: {} is predicted to take about {} of CPU and {} of memory",
                plan.scene,
                cost::seconds_text(plan.cost.seconds),
                cost::bytes_text(plan.cost.bytes)
            );
        }
    }
    if let Some(Planned { plan, .. }) = plans.first() {
        let method = plan.method.descriptor();
        let limit = method.stability_limit(plan.segments);
        let others = plans.first().map_or(&[][..], |p| &p.others[..]);
        if !others.is_empty() {
            let steps: Vec<String> = std::iter::once(plan)
                .chain(others)
                .map(|p| format!("{} k = {:.3e}", p.method, p.dt))
                .collect();
            eprintln!(
                "rope: side by side at N = {}, each at {} brought down so that {} instants a time unit, shared by all, fall on its steps (the frames fall on them): {}",
                plan.segments,
                if args.dt.is_some() {
                    "--dt"
                } else {
                    "its default step"
                },
                plan.frame_grid.unwrap_or(plan.log_rate),
                steps.join(", ")
            );
        } else if args.tolerance.is_none() && args.dt.is_none() {
            eprintln!(
                "rope: --dt not given: using k = {:.3e} for the {} method at N = {} (estimated stability limit {limit:.3e}: {})",
                plan.dt, plan.method, plan.segments, method.past_limit
            );
        } else if plan.dt > limit && !method.refuses_unstable_step {
            eprintln!(
                "rope: k = {:e} is {:.1} times the {} method's estimated stability limit {limit:.3e} at N = {}; {}",
                plan.dt,
                plan.dt / limit,
                plan.method,
                plan.segments,
                method.past_limit
            );
        }
        for lane in std::iter::once(plan).chain(others) {
            warn_of_blow_up(lane, !others.is_empty());
        }
    }
    // (--tolerance with an endless run was refused before.)
    if args.lasting_default() {
        eprintln!(
            "rope: a run left running (endless, looping or served) uses the {} method: {} (the report's scheme blows up after tens of time units, the chain's energy drifts down, rattle's jumps at violent snaps; --method to choose another)",
            args.method(),
            MethodKind::DEFAULT_LASTING_BECAUSE
        );
    }
}

/// A step as the user reads it: in four significant digits, and as 1/m where it is the
/// reciprocal of a whole number that those digits do not give exactly (`6.41e-4 = 1/1560`).
fn step_text(dt: f64) -> String {
    let short = rope::run::config::short_step(dt);
    let whole = (1.0 / dt).round();
    match short.parse::<f64>() {
        Ok(v) if v != dt && (1.0 / whole - dt).abs() <= 1e-12 * dt => {
            format!("{short} = 1/{whole}")
        }
        _ => short,
    }
}

/// What the pilots of `--tolerance` measured, a line per method.
fn pilot_lines(pilots: &rope::run::pilot::Pilots, duration: f64) -> String {
    let seconds = pilots.seconds();
    let mut text = format!(
        "rope: tolerance pilots: to t = {}, {seconds:.2} s of CPU; the largest live tip estimate at each N flown:",
        duration.min(rope::run::pilot::WINDOW)
    );
    for p in &pilots.flown {
        let measured: Vec<String> = p
            .measured
            .iter()
            .map(|(n, e)| format!("{e:.1e} at N = {n}"))
            .collect();
        let measured = measured.join(", ");
        let what = match (&p.diverged, &p.model, p.held_at) {
            (Some(d), _, _) => format!("ruled out, a pilot diverged: {d}"),
            (None, _, None) if p.measured_by.is_some() => format!(
                "not flown: its {} are the {}'s, whose pilots measure their error",
                p.method.descriptor().discretization,
                p.measured_by.map_or("", MethodKind::name)
            ),
            (None, _, None) if !p.flew() => "not flown".to_owned(),
            (None, _, None) if p.measured.is_empty() && !p.shadow_lost.is_empty() => {
                let lost: Vec<String> = p
                    .shadow_lost
                    .iter()
                    .map(|(n, why)| format!("at N = {n}, {why}"))
                    .collect();
                format!(
                    "not measured: the method ran, but its error estimate's coarser run (the shadow at N/2) diverged ({})",
                    lost.join("; ")
                )
            }
            (None, _, Some(n)) => format!(
                "{measured} → holds the tolerance at N = {n} by its own estimate (×{} safety)",
                rope::run::pilot::SAFETY
            ),
            (None, Some(m), None) => {
                // Three significant digits, however small the constant.
                let constant = match m.constant >= 0.01 {
                    true => format!("{:.3}", m.constant),
                    false => format!("{:.2e}", m.constant),
                };
                format!(
                    "{measured} → error ≈ {constant} h^{:.2} (×{:.1} safety)",
                    m.order, m.safety
                )
            }
            (None, None, None) => format!("{measured} → no model fitted"),
        };
        text += &format!("\n  {}: {what}", p.method);
    }
    text
}

/// Warns of a run longer than its method is known to last (the blow-up map's earliest at
/// its N), suggesting the methods that last; side by side, says the others go on.
fn warn_of_blow_up(plan: &rope::run::RunPlan, side_by_side: bool) {
    let method = plan.method.descriptor();
    let Some(blow_up) = method.blow_up_at(plan.segments) else {
        return;
    };
    if plan.duration <= blow_up.earliest {
        return;
    }
    let seen = format!(
        "the {} method blows up in a long run at any step (from the release at 30° at N = {}, `rope study --blow-up 200` saw it diverge between t = {} and {})",
        plan.method, blow_up.segments, blow_up.earliest, blow_up.latest
    );
    if side_by_side {
        eprintln!(
            "rope: note: side by side, {} will most likely stop before t = {}: {seen}; the others go on",
            plan.method, plan.duration
        );
        return;
    }
    let stable: Vec<&str> = MethodKind::ALL
        .iter()
        .filter(|m| m.descriptor().blow_up.is_empty())
        .map(|m| m.name())
        .collect();
    eprintln!(
        "rope: warning: a run to t = {} will most likely stop early: {seen}; for a long run use --method {}",
        plan.duration,
        stable.join(" or ")
    );
}

/// The method whose energy strayed most, and by how much relative to |E_ref|, among the
/// runs of methods that do not keep it.
type Strayed = Option<(rope::methods::MethodKind, f64)>;

/// Once, after the runs: a method that let the energy stray by more than
/// [`ENERGY_HINT`] of |E_ref| is told which method keeps it.
fn energy_hint(strayed: Strayed) {
    let Some((method, deviation)) = strayed else {
        return;
    };
    let Some(keeper) = rope::methods::MethodKind::ALL
        .iter()
        .find(|m| m.descriptor().keeps_energy)
    else {
        return;
    };
    if deviation > ENERGY_HINT {
        eprintln!(
            "rope: the {method} method let the energy stray by up to {:.1} % of |E_ref|; the {keeper} method keeps it exactly (--method {keeper})",
            100.0 * deviation
        );
    }
}

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

/// A flag that Ctrl-C or SIGTERM sets; a second one leaves at once.
fn stop_on_interrupt() -> anyhow::Result<Arc<AtomicBool>> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(EXIT_INTERRUPTED)); // a second Ctrl-C: leave now
        }
        eprintln!("rope: interrupted, finishing the recording…");
    })
    .context("installing the Ctrl-C / SIGTERM handler")?;
    Ok(stop)
}

/// Runs the plans in turn, `--loop` times over, until one does not end well or `stop` is
/// set. Returns the last run's summary, and the method whose energy strayed most.
fn run_passes(
    args: &RunArgs,
    plans: &[Planned],
    logger: &mut Vec<RopeLogger>,
    stop: &AtomicBool,
) -> anyhow::Result<(Summary, Strayed)> {
    let several = plans.len() > 1 || args.passes() != Some(1);
    let mut last = None;
    let mut strayed: Strayed = None;
    let mut pass = 0;
    'passes: while args.passes().is_none_or(|passes| pass < passes) {
        pass += 1;
        for planned in plans {
            let plan = &planned.plan;
            let progress = Progress::new(plan.duration);
            let on_frame = |frame: &rope::run::Frame| {
                progress.at(frame.time);
                if frame.tolerance_exceeded {
                    progress.say(&tolerance_notice(plan, frame));
                }
            };
            let summary = if planned.others.is_empty() {
                rope::run::pipeline::run(plan, logger, stop, &on_frame)?
            } else {
                let lanes = rope::run::lanes::run(&planned.lanes(), logger, stop, &on_frame)?;
                side_by_side(lanes)?
            };
            progress.finish();
            let mut summary = summary;
            if args.lasting_default() {
                summary.method_chosen_because = Some(format!(
                    "{}, the default for a run left running (endless, looping or served): {}",
                    summary.method,
                    MethodKind::DEFAULT_LASTING_BECAUSE
                ));
            }
            if several {
                // Each run of several says all it has as it ends; the last is not repeated.
                eprintln!("{}", summary.human());
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
    Ok((last.context("no run was made")?, strayed))
}

/// The summary of methods side by side: the first one's fields, and each one's under
/// `methods` (its text says each one's lines, and how far each strayed).
fn side_by_side(lanes: Vec<Summary>) -> anyhow::Result<Summary> {
    let mut first = lanes.first().cloned().context("no method was run")?;
    first.methods = lanes;
    Ok(first)
}

/// What a run says, once, when its error estimate passes the tolerance.
fn tolerance_notice(plan: &rope::run::RunPlan, frame: &rope::run::Frame) -> String {
    format!(
        "rope: at t = {:.3} the estimated tip error {:.1e} passed the tolerance {:.1e} (N = {}); the run goes on; its summary says tolerance_met: false, and it exits with status 4",
        frame.time,
        frame.error_estimate.map_or(f64::NAN, |e| e.tip),
        plan.tolerance.unwrap_or(f64::NAN),
        plan.segments
    )
}

/// Why the viewer that was the only destination is gone, if it is: that says more than a
/// flush that failed for want of it (a lost link stays lost).
fn lost_viewer(output: &Output) -> Option<String> {
    match &output.viewer {
        Some(link) if !output.survives_viewer_loss => link.lost(),
        _ => None,
    }
}

/// A served recording stays up for late viewers after a finite run, until Ctrl-C.
fn serve_until_stopped(output: &Output, stop: &AtomicBool) {
    let Some(url) = &output.serving else { return };
    if stop.load(Ordering::SeqCst) {
        return;
    }
    eprintln!("rope: the run has ended; still serving it at {url} until Ctrl-C");
    while !stop.load(Ordering::SeqCst) {
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// How the last run ended, as the process's exit code.
fn exit_code(summary: &Summary) -> ExitCode {
    if let Some(err) = &summary.recording_error {
        eprintln!("rope: error: the recording is incomplete: {err}");
    }
    ExitCode::from(summary.verdict().exit_status())
}

/// Watches the viewer from a thread of its own (a viewer already gone, as one that refused
/// the connection, is reported at once, before the run). When it is gone: if a file or a
/// served endpoint keeps the recording, says so once and lets the run go on; otherwise stops
/// the run (the link keeps the reason, for the summary).
fn watch_viewer(link: ViewerLink, survives: bool, stop: Arc<AtomicBool>) {
    if viewer_gone(&link, survives, &stop) {
        return;
    }
    std::thread::spawn(move || {
        while !viewer_gone(&link, survives, &stop) {
            std::thread::sleep(Duration::from_millis(100));
        }
    });
}

/// Whether the viewer is gone; if it is, acts on it (see [`watch_viewer`]).
fn viewer_gone(link: &ViewerLink, survives: bool, stop: &AtomicBool) -> bool {
    let Some(reason) = link.lost() else {
        return false;
    };
    if survives {
        eprintln!("rope: warning: {reason}; the run goes on without it");
    } else {
        stop.store(true, Ordering::SeqCst);
    }
    true
}

/// `rope study`: the grid, the reference, the findings and charts; optionally a recording.
fn study(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    if let Some(duration) = args.long_run {
        return long_runs(args, duration);
    }
    if let Some(duration) = args.blow_up {
        return blow_up(args, duration);
    }
    if args.estimate_check {
        return estimate_check(args);
    }
    if let Some(size) = args.tolerance_check {
        return tolerance_check(args, size);
    }
    if let Some(dirs) = &args.merge {
        return merge(args, dirs);
    }
    let plan = match args.plan() {
        Ok(plan) => plan,
        Err(err) => return Ok(bad_input(&err)),
    };
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    if let Some(Err(err)) = args.save.as_deref().map(|p| check_writable_file("save", p)) {
        return Ok(bad_input(&err));
    }
    let spec = &plan.spec;
    if plan.cost.seconds > cost::ANNOUNCE_SECONDS {
        eprintln!(
            "rope study: predicted to take about {} of CPU ({} on {} threads) and {} of memory",
            cost::seconds_text(plan.cost.seconds),
            cost::seconds_text(plan.cost.seconds / rayon::current_num_threads() as f64),
            rayon::current_num_threads(),
            cost::bytes_text(plan.cost.bytes)
        );
    }
    let reference = match args
        .reference
        .as_deref()
        .map(|p| rope::cli::reference_file(p, &plan))
    {
        Some(Ok(file)) => Some(file),
        Some(Err(err)) => return Ok(bad_input(&err)),
        None => None,
    };
    if args.reference_only {
        let path = rope::study::execute_reference_only(spec, plan.reference_segments, &args.out)?;
        eprintln!(
            "rope study: wrote the reference to {}; give it to each shard with --reference",
            path.display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    let cells = match args.shard {
        Some(shard) => shard.cells(spec).len(),
        None => spec.cells().len(),
    } as u64;
    eprintln!(
        "rope study: {cells} runs ({} methods × {} N × {} k{}) on {} threads, reference at N = {}{}",
        spec.methods.len(),
        spec.segments.len(),
        spec.dts.len(),
        args.shard.map_or(String::new(), |s| format!(", shard {s}")),
        rayon::current_num_threads(),
        plan.reference_segments,
        if reference.is_some() { " (read)" } else { "" }
    );
    for (asked, run) in spec.moved_dts() {
        eprintln!(
            "rope study: k = {asked:e} runs at {run:.4e}, the largest step no larger that ends each run at t = {}",
            spec.duration
        );
    }
    let counter = Counter::new(cells, "rope study", "runs");
    let command = command_line();
    if let Some(shard) = args.shard {
        rope::study::execute_shard(
            spec,
            shard,
            reference,
            plan.reference_segments,
            &args.out,
            || counter.inc(),
        )?;
        counter.finish();
        eprintln!(
            "rope study: wrote shard {shard}'s study.csv and shard.json to {}; put the shards together with `rope study --merge DIR…`",
            args.out.display()
        );
        return Ok(ExitCode::SUCCESS);
    }
    let outcome = match reference {
        Some(file) => {
            rope::study::execute_with(spec, file.reference(), &args.out, &command, || {
                counter.inc()
            })?
        }
        None => rope::study::execute(spec, plan.reference_segments, &args.out, &command, || {
            counter.inc()
        })?,
    };
    counter.finish();
    if let Some(path) = &args.save {
        let rec = rerun::RecordingStreamBuilder::new("rope-study")
            .save(path)
            .with_context(|| format!("opening {}", path.display()))?;
        rope::study::record::log(&rec, &outcome).context("logging the study")?;
        rec.flush_blocking()
            .context("writing the study recording")?;
    }
    println!("{}", outcome.markdown);
    let findings = &outcome.findings;
    for r in &findings.at_target {
        if let Some(edge) = findings.edge(r) {
            eprintln!(
                "rope study: warning: {}'s cheapest run to a tip error of {:.0e} (N = {}, k = {:e}) is at the grid's edge, {}: a cheaper one may lie beyond it",
                r.method,
                rope::study::findings::TIP_TARGET,
                r.segments,
                r.dt,
                edge
            );
        }
    }
    eprintln!(
        "rope study: wrote study.csv, findings.md and the charts to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `rope study --long-run T`: each method from each release for T time units.
fn long_runs(args: &StudyArgs, duration: f64) -> anyhow::Result<ExitCode> {
    let plan = match args.long_run_plan(duration) {
        Ok(plan) => plan,
        Err(err) => return Ok(bad_input(&err)),
    };
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    let runs = plan.runs.len() as u64;
    eprintln!(
        "rope study: {runs} long runs of {duration} time units on {} threads, predicted {} of CPU",
        rayon::current_num_threads(),
        cost::seconds_text(plan.cost.seconds)
    );
    let counter = Counter::new(
        runs.saturating_mul(duration.ceil() as u64),
        "rope study",
        "time units",
    );
    let command = command_line();
    let markdown =
        rope::study::execute_long_runs(&plan.runs, duration, &args.out, &command, || {
            counter.inc()
        })?;
    counter.finish();
    println!("{markdown}");
    eprintln!(
        "rope study: wrote long_run.csv, long_run.md and the chart to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// The command line as typed, for the findings to cite.
fn command_line() -> String {
    std::env::args().collect::<Vec<_>>().join(" ")
}

/// `rope study --merge DIR…`: the shards of a study put together.
fn merge(args: &StudyArgs, dirs: &[std::path::PathBuf]) -> anyhow::Result<ExitCode> {
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    let command = command_line();
    let outcome = match rope::study::execute_merge(dirs, &args.out, &command) {
        Ok(outcome) => outcome,
        Err(err) => match err.downcast_ref::<rope::study::shard::MergeError>() {
            Some(merge) => return Ok(bad_input(merge)),
            None => return Err(err),
        },
    };
    println!("{}", outcome.markdown);
    eprintln!(
        "rope study: merged {} shards ({} runs) into study.csv, findings.md and the charts in {}",
        dirs.len(),
        outcome.rows.len(),
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `rope study --estimate-check`: the live error estimate against the truth.
fn estimate_check(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    let spec = rope::study::estimate_check::CheckSpec {
        methods: args.methods.clone(),
        ..Default::default()
    };
    let cells = spec.methods.len() * spec.scenes.len() * spec.segments.len();
    eprintln!(
        "rope study: {} references at N = {} and {cells} runs with their shadows, to t = {}, on {} threads",
        spec.scenes.len(),
        spec.reference_segments,
        spec.duration,
        rayon::current_num_threads()
    );
    let counter = Counter::new(
        (spec.scenes.len() + cells) as u64,
        "rope study",
        "references and runs",
    );
    let command = command_line();
    let markdown =
        rope::study::execute_estimate_check(&spec, &args.out, &command, || counter.inc())?;
    counter.finish();
    println!("{markdown}");
    eprintln!(
        "rope study: wrote estimate_check.md, estimate_check.csv and estimate_check.png to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `rope study --tolerance-check`: what `--tolerance` chooses, against the truth and the
/// cheapest run of a grid.
fn tolerance_check(args: &StudyArgs, size: CheckSize) -> anyhow::Result<ExitCode> {
    use rope::study::tolerance_check::{CheckSpec, grid_steps};
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    let spec = match size {
        CheckSize::Full => CheckSpec::default(),
        CheckSize::Quick => CheckSpec::quick(),
    };
    let grid_runs: usize = spec
        .grid
        .iter()
        .flat_map(|&n| MethodKind::ALL.map(|m| grid_steps(m, n).len()))
        .sum();
    let runs = spec.scenes.len() * (1 + grid_runs + spec.tolerances.len());
    eprintln!(
        "rope study: {} scenes, each a reference at N = {} (with N/2 and 2N; N doubled up to {} until it is fine enough), a grid of up to {} runs and a choice per EPS in {:?}, to t = {}",
        spec.scenes.len(),
        spec.reference_segments,
        spec.reference_segments_max,
        grid_runs,
        spec.tolerances,
        spec.duration
    );
    let counter = Counter::new(runs as u64, "rope study", "references, runs and choices");
    let markdown =
        rope::study::execute_tolerance_check(&spec, &args.out, &command_line(), || counter.inc())?;
    counter.finish();
    println!("{markdown}");
    eprintln!(
        "rope study: wrote tolerance_check.md and tolerance_check.svg/.png to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}

/// `rope study --blow-up T`: when the report's scheme blows up, and what grows first.
fn blow_up(args: &StudyArgs, duration: f64) -> anyhow::Result<ExitCode> {
    let scene = match args.blow_up_plan(duration) {
        Ok(scene) => scene,
        Err(err) => return Ok(bad_input(&err)),
    };
    if let Err(err) = writable_dir("out", &args.out) {
        return Ok(bad_input(&err));
    }
    let runs =
        (rope::study::blow_up::SEGMENTS.len() * rope::study::blow_up::FRACTIONS.len()) as u64;
    eprintln!(
        "rope study: {runs} runs of the {} scheme from the {scene}, each to its blow-up or t = {duration}",
        rope::methods::REPORT.method
    );
    let counter = Counter::new(runs, "rope study", "runs");
    let command = command_line();
    let markdown =
        rope::study::execute_blow_up(&scene, duration, &args.out, &command, || counter.inc())?;
    counter.finish();
    println!("{markdown}");
    eprintln!(
        "rope study: wrote blow_up.md, blow_up.csv and the charts to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
