//! `rope study` as a service: a grid of runs against a reference, or one of the studies
//! beside it (`--long-run`, `--blow-up`, `--estimate-check`, `--tolerance-check`, `--merge`),
//! its files written to `--out`. What it says goes to the
//! [`Listener`](super::notices::Listener) of its [`Session`]: the findings as a report, the
//! rest as notices.

use super::notices::{Notice, Topic};
use super::{ServiceError, Session};
use crate::cli::{CheckSize, StudyArgs, check_writable_file, writable_dir};
use crate::methods::MethodKind;
use crate::run::Verdict;
use crate::run::cost;
use crate::run::progress::Counter;
use crate::study::{Progress, Stopped};
use anyhow::Context as _;
use std::sync::atomic::Ordering;

/// A line of what the study does, or wrote.
fn say(session: &Session, text: String) {
    session.listener.tell(Notice::new(Topic::Study, text));
}

/// What the study wrote, and where.
fn wrote(session: &Session, what: &str, out: &std::path::Path) {
    say(
        session,
        format!("rope study: wrote {what} to {}", out.display()),
    );
}

/// The study's findings, the report the terminal prints on stdout.
fn report(session: &Session, markdown: String) {
    session.listener.tell(Notice::new(Topic::Report, markdown));
}

/// A study's progress as the session sees it: each piece done counted on `counter`, and the
/// session's stop flag (Ctrl-C or SIGTERM) heard before each run.
struct Watched<'a> {
    counter: &'a Counter,
    session: &'a Session,
}

impl Progress for Watched<'_> {
    fn done(&self) {
        self.counter.inc();
    }

    fn stopped(&self) -> bool {
        self.session.stop.load(Ordering::SeqCst)
    }
}

/// Runs `work` watched: `total` pieces called `what` counted on a bar (or a line every tenth
/// off a terminal), the session's stop flag heard; the bar goes when `work` returns, however
/// it ends.
fn watched<T>(
    session: &Session,
    total: u64,
    what: &'static str,
    work: impl FnOnce(&Watched<'_>) -> T,
) -> T {
    let counter = Counter::new(total, "rope study", what);
    let ended = work(&Watched {
        counter: &counter,
        session,
    });
    counter.finish();
    ended
}

/// `rope study`: the grid, the reference, the findings and charts; optionally a recording.
/// Stopped (Ctrl-C or SIGTERM), it starts no more runs, lets those under way finish, writes
/// nothing and ends [`Verdict::Interrupted`]; otherwise [`Verdict::Ok`].
pub fn study(args: &StudyArgs, session: &Session) -> Result<Verdict, ServiceError> {
    match dispatch(args, session) {
        Ok(()) => Ok(Verdict::Ok),
        Err(ServiceError::Failed(err)) if err.downcast_ref::<Stopped>().is_some() => {
            // The check's references are the runs a folder of kept runs keeps.
            let cache = std::env::var_os(crate::study::run_cache::ENV)
                .filter(|dir| !dir.is_empty() && args.tolerance_check.is_some());
            let kept = match cache {
                Some(dir) => format!(
                    "; the reference runs it finished are kept in {} and will be read back",
                    std::path::Path::new(&dir).display()
                ),
                None => String::new(),
            };
            say(
                session,
                format!(
                    "rope study: stopped before its last run; nothing was written to {}{kept}",
                    args.out.display()
                ),
            );
            Ok(Verdict::Interrupted)
        }
        Err(err) => Err(err),
    }
}

/// The study `args` asks for, to its end or its first error.
fn dispatch(args: &StudyArgs, session: &Session) -> Result<(), ServiceError> {
    if let Some(duration) = args.long_run {
        return long_runs(session, args, duration);
    }
    if let Some(duration) = args.blow_up {
        return blow_up(session, args, duration);
    }
    if args.estimate_check {
        return estimate_check(session, args);
    }
    if let Some(size) = args.tolerance_check {
        return tolerance_check(session, args, size);
    }
    if let Some(dirs) = &args.merge {
        return merge(session, args, dirs);
    }
    let plan = args.plan()?;
    writable_dir("out", &args.out)?;
    if let Some(path) = args.save.as_deref() {
        check_writable_file("save", path)?;
    }
    let spec = &plan.spec;
    // What `rope run` warns of a fold, the study warns of its grid.
    for notice in [
        super::notices::coarse_bends(spec.scene, &spec.segments),
        super::notices::wide_gap(spec.scene),
    ]
    .into_iter()
    .flatten()
    {
        session.listener.tell(notice);
    }
    if plan.cost.seconds > cost::ANNOUNCE_SECONDS {
        say(
            session,
            format!(
                "rope study: predicted to take about {} of CPU ({} on {} threads) and {} of memory",
                cost::seconds_text(plan.cost.seconds),
                cost::seconds_text(plan.cost.seconds / rayon::current_num_threads() as f64),
                rayon::current_num_threads(),
                cost::bytes_text(plan.cost.bytes)
            ),
        );
    }
    let reference = args
        .reference
        .as_deref()
        .map(|p| crate::cli::reference_file(p, &plan))
        .transpose()?;
    if args.reference_only {
        let path = watched(session, 1, "references", |progress| {
            crate::study::execute_reference_only(spec, plan.reference_segments, &args.out, progress)
        })?;
        say(
            session,
            format!(
                "rope study: wrote the reference to {}; give it to each shard with --reference",
                path.display()
            ),
        );
        return Ok(());
    }
    let cells = match args.shard {
        Some(shard) => shard.cells(spec).len(),
        None => spec.cells().len(),
    } as u64;
    say(
        session,
        format!(
            "rope study: {cells} runs ({} methods × {} N × {} k{}) on {} threads, reference at N = {}{}",
            spec.methods.len(),
            spec.segments.len(),
            spec.dts.len(),
            args.shard.map_or(String::new(), |s| format!(", shard {s}")),
            rayon::current_num_threads(),
            plan.reference_segments,
            if reference.is_some() { " (read)" } else { "" }
        ),
    );
    for (asked, run) in spec.moved_dts() {
        say(
            session,
            format!(
                "rope study: k = {asked:e} runs at {run:.4e}, the largest step no larger that ends each run at t = {}",
                spec.duration
            ),
        );
    }
    let command = &session.command;
    if let Some(shard) = args.shard {
        watched(session, cells, "runs", |progress| {
            crate::study::execute_shard(
                spec,
                shard,
                reference,
                plan.reference_segments,
                &args.out,
                progress,
            )
        })?;
        say(
            session,
            format!(
                "rope study: wrote shard {shard}'s study.csv and shard.json to {}; put the shards together with `rope study --merge DIR…`",
                args.out.display()
            ),
        );
        return Ok(());
    }
    let outcome = watched(session, cells, "runs", |progress| match reference {
        Some(file) => {
            crate::study::execute_with(spec, file.reference(), &args.out, command, progress)
        }
        None => crate::study::execute(spec, plan.reference_segments, &args.out, command, progress),
    })?;
    if let Some(path) = &args.save {
        let rec = rerun::RecordingStreamBuilder::new("rope-study")
            .save(path)
            .with_context(|| format!("opening {}", path.display()))?;
        crate::study::record::log(&rec, &outcome).context("logging the study")?;
        rec.flush_blocking()
            .context("writing the study recording")?;
    }
    report(session, outcome.markdown);
    let findings = &outcome.findings;
    for r in &findings.at_target {
        if let Some(edge) = findings.edge(r) {
            session.listener.tell(Notice::new(Topic::StudyWarning, format!(
                "rope study: warning: {}'s cheapest run to a tip error of {:.0e} (N = {}, k = {:e}) is at the grid's edge, {}: a cheaper one may lie beyond it",
                r.method,
                crate::study::findings::TIP_TARGET,
                r.segments,
                r.dt,
                edge
            )));
        }
    }
    wrote(session, "study.csv, findings.md and the charts", &args.out);
    Ok(())
}

/// `rope study --long-run T`: each method from each release for T time units.
fn long_runs(session: &Session, args: &StudyArgs, duration: f64) -> Result<(), ServiceError> {
    let plan = args.long_run_plan(duration)?;
    writable_dir("out", &args.out)?;
    let runs = plan.runs.len() as u64;
    say(
        session,
        format!(
            "rope study: {runs} long runs of {duration} time units on {} threads, predicted {} of CPU",
            rayon::current_num_threads(),
            cost::seconds_text(plan.cost.seconds)
        ),
    );
    let units = runs.saturating_mul(duration.ceil() as u64);
    let markdown = watched(session, units, "time units", |progress| {
        crate::study::execute_long_runs(&plan.runs, duration, &args.out, &session.command, progress)
    })?;
    report(session, markdown);
    wrote(
        session,
        "long_run.csv, long_run.md and the chart",
        &args.out,
    );
    Ok(())
}

/// `rope study --merge DIR…`: the shards of a study put together.
fn merge(
    session: &Session,
    args: &StudyArgs,
    dirs: &[std::path::PathBuf],
) -> Result<(), ServiceError> {
    writable_dir("out", &args.out)?;
    let command = &session.command;
    let outcome = match crate::study::execute_merge(dirs, &args.out, command) {
        Ok(outcome) => outcome,
        Err(err) => match err.downcast_ref::<crate::study::shard::MergeError>() {
            Some(merge) => return Err(ServiceError::bad_input(merge)),
            None => return Err(err.into()),
        },
    };
    report(session, outcome.markdown);
    say(
        session,
        format!(
            "rope study: merged {} shards ({} runs) into study.csv, findings.md and the charts in {}",
            dirs.len(),
            outcome.rows.len(),
            args.out.display()
        ),
    );
    Ok(())
}

/// `rope study --estimate-check`: the live error estimate against the truth.
fn estimate_check(session: &Session, args: &StudyArgs) -> Result<(), ServiceError> {
    writable_dir("out", &args.out)?;
    let spec = crate::study::estimate_check::CheckSpec {
        methods: args.methods.clone(),
        ..Default::default()
    };
    let cells = spec.methods.len() * spec.scenes.len() * spec.segments.len();
    say(
        session,
        format!(
            "rope study: {} references at N = {} and {cells} runs with their shadows, to t = {}, on {} threads",
            spec.scenes.len(),
            spec.reference_segments,
            spec.duration,
            rayon::current_num_threads()
        ),
    );
    let pieces = (spec.scenes.len() + cells) as u64;
    let markdown = watched(session, pieces, "references and runs", |progress| {
        crate::study::execute_estimate_check(&spec, &args.out, &session.command, progress)
    })?;
    report(session, markdown);
    wrote(
        session,
        "estimate_check.md, estimate_check.csv and estimate_check.png",
        &args.out,
    );
    Ok(())
}

/// `rope study --tolerance-check`: what `--tolerance` chooses, against the truth and the
/// cheapest run of a grid.
fn tolerance_check(
    session: &Session,
    args: &StudyArgs,
    size: CheckSize,
) -> Result<(), ServiceError> {
    use crate::study::tolerance_check::{CheckSpec, grid_steps};
    writable_dir("out", &args.out)?;
    let spec = match size {
        CheckSize::Full => CheckSpec::default(),
        CheckSize::Quick => CheckSpec::quick(),
        CheckSize::Unseen => CheckSpec::unseen(),
        CheckSize::Modes => CheckSpec::modes(),
    };
    let grid_runs: usize = spec
        .grid
        .iter()
        .chain(&spec.grid_beyond)
        .flat_map(|&n| MethodKind::ALL.map(|m| grid_steps(m, n).len()))
        .sum();
    let read =
        crate::study::read_reference::read_all(&args.references, &spec.scenes, spec.duration)?;
    let (mut read_for, mut too_coarse) = (Vec::new(), Vec::new());
    let judges_all = crate::study::tolerance_check::REFERENCE_MARGIN * spec.smallest_tolerance();
    for scene in &spec.scenes {
        if let Some(r) = crate::study::tolerance_check::best_read(&read, scene) {
            read_for.push(format!("{scene} (from {})", r.source.display()));
            if r.own_error > judges_all {
                too_coarse.push(format!("{scene} (errs by {:.1e})", r.own_error));
            }
        }
    }
    if !args.references.is_empty() {
        let list = |v: &[String]| match v.is_empty() {
            true => "none".to_owned(),
            false => v.join(", "),
        };
        say(
            session,
            format!(
                "rope study: references read: {}; of these, too coarse to judge {:.0e} (its cells skipped): {}",
                list(&read_for),
                spec.smallest_tolerance(),
                list(&too_coarse)
            ),
        );
    }
    let runs = spec.scenes.len() * (1 + grid_runs + spec.tolerances.len());
    say(
        session,
        format!(
            "rope study: {} scenes, each a reference ({} read) at N = {} (with N/2 and 2N; N doubled up to {} until it is fine enough, and on up to {} where it can get there), a grid of up to {} runs and a choice per EPS in {:?}, to t = {}",
            spec.scenes.len(),
            read_for.len(),
            spec.reference_segments,
            spec.reference_segments_max,
            spec.reference_segments_reach,
            grid_runs,
            spec.tolerances,
            spec.duration
        ),
    );
    let markdown = watched(
        session,
        runs as u64,
        "references, runs and choices",
        |progress| {
            crate::study::execute_tolerance_check(
                &spec,
                &read,
                &args.out,
                &session.command,
                progress,
            )
        },
    )?;
    report(session, markdown);
    wrote(
        session,
        "tolerance_check.md, tolerance_check.csv, references.csv and tolerance_check.svg/.png",
        &args.out,
    );
    Ok(())
}

/// `rope study --blow-up T`: when the report's scheme blows up, and what grows first.
fn blow_up(session: &Session, args: &StudyArgs, duration: f64) -> Result<(), ServiceError> {
    let scene = args.blow_up_plan(duration)?;
    writable_dir("out", &args.out)?;
    let runs =
        (crate::study::blow_up::SEGMENTS.len() * crate::study::blow_up::FRACTIONS.len()) as u64;
    say(
        session,
        format!(
            "rope study: {runs} runs of the {} scheme from the {scene}, each to its blow-up or t = {duration}",
            crate::methods::REPORT.method
        ),
    );
    let markdown = watched(session, runs, "runs", |progress| {
        crate::study::execute_blow_up(&scene, duration, &args.out, &session.command, progress)
    })?;
    report(session, markdown);
    wrote(session, "blow_up.md, blow_up.csv and the charts", &args.out);
    Ok(())
}
