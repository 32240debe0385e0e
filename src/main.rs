//! The `rope` command: parses the flags, opens the Rerun recording, and hands off to
//! [`rope::app::run`].

use anyhow::Context as _;
use clap::Parser as _;
use rope::cli::{Cli, Command, RunArgs, StudyArgs};
use rope::summary::Status;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Exit codes: 2 is bad input (as clap's own errors), 3 a diverged run, 130 an interrupted one,
/// 1 anything else (among it a recording that could not be completed).
const EXIT_BAD_INPUT: u8 = 2;
const EXIT_DIVERGED: u8 = 3;
const EXIT_INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Run(args) => run(args),
        Command::Study(args) => study(args),
    };
    match result {
        Ok(code) => code,
        Err(err) => {
            eprintln!("rope: error: {err:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &RunArgs) -> anyhow::Result<ExitCode> {
    let runs = match args.configs() {
        Ok(runs) => runs,
        Err(err) => {
            eprintln!("rope: bad input: {err}");
            return Ok(ExitCode::from(EXIT_BAD_INPUT));
        }
    };
    let Some((first, _)) = runs.first() else {
        anyhow::bail!("no scene to run");
    };
    match (args.tolerance, args.dt) {
        (Some(eps), _) => {
            for (config, choice) in runs.iter().filter_map(|(c, ch)| Some((c, ch.as_ref()?))) {
                let scene = if runs.len() > 1 {
                    format!(" ({:?})", config.scene)
                } else {
                    String::new()
                };
                eprintln!(
                    "rope: tolerance {eps:e}{scene}: chose the {} method, N = {}, k = {:e}; predicted tip error {:.1e}, predicted cost {:.2e} CPU s (error model fitted by `rope study` on the 30° release)",
                    choice.method,
                    choice.segments,
                    choice.dt,
                    choice.predicted_error,
                    choice.predicted_seconds
                );
            }
        }
        (None, None) => eprintln!(
            "rope: --dt not given: using k = {:.3e} for the {} method at N = {} (estimated stability limit {:.3e})",
            first.dt,
            first.method,
            first.segments,
            first.method.stability_limit(first.segments)
        ),
        (None, Some(_)) => {}
    }
    // (--tolerance with an endless run was refused above.)
    if args.method.is_none() && args.duration.is_infinite() {
        eprintln!(
            "rope: an endless run uses the chain method: the seed scheme diverges after some tens of time units at any time step (--method seed to watch it)"
        );
    }
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(EXIT_INTERRUPTED)); // a second Ctrl-C: leave now
        }
        eprintln!("rope: interrupted, finishing the recording…");
    })
    .context("installing the Ctrl-C / SIGTERM handler")?;

    let output = args
        .output
        .open("rope", rope::logger::blueprint())
        .context("opening the Rerun recording")?;
    if let Some(url) = &output.serving {
        eprintln!(
            "rope: serving at {url}: any number of viewers can join, at any time, with `rerun --connect {url}`, and get the history first; memory is kept within {} by dropping the oldest",
            args.output.server_memory_limit
        );
    }
    if let Some(link) = output.viewer.clone() {
        watch_viewer(link, output.survives_viewer_loss, Arc::clone(&stop));
    }
    let mut logger =
        rope::logger::RopeLogger::new(output.rec).context("logging the recording's styling")?;

    let several = runs.len() > 1 || args.passes() != Some(1);
    let mut last = None;
    let mut pass = 0;
    'passes: while args.passes().is_none_or(|passes| pass < passes) {
        pass += 1;
        for (config, _) in &runs {
            let progress = rope::progress::Progress::new(config.duration);
            let summary = rope::app::run(config, Some(&mut logger), &stop, &|t| progress.at(t))?;
            progress.finish();
            let ended = summary.status != Status::Ok || summary.recording_error.is_some();
            if several {
                let line = summary.human();
                eprintln!("{}", line.lines().next().unwrap_or_default());
            }
            last = Some(summary);
            if ended || stop.load(Ordering::SeqCst) {
                break 'passes;
            }
        }
    }
    let Some(mut summary) = last else {
        anyhow::bail!("no run was made");
    };
    // A viewer that was the only destination and is gone (a lost link stays lost) says more
    // than a flush that failed for want of it.
    let lost = match &output.viewer {
        Some(link) if !output.survives_viewer_loss => link.lost(),
        _ => None,
    };
    if let Some(reason) = lost {
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
    eprintln!("{}", summary.human());
    if let Some(url) = &output.serving
        && !stop.load(Ordering::SeqCst)
    {
        eprintln!("rope: the run has ended; still serving it at {url} until Ctrl-C");
        while !stop.load(Ordering::SeqCst) {
            std::thread::sleep(Duration::from_millis(50));
        }
    }
    drop(logger); // closes the recording: the file's footer, the last data to viewers
    if let Some(err) = &summary.recording_error {
        eprintln!("rope: error: the recording is incomplete: {err}");
        return Ok(ExitCode::FAILURE);
    }
    Ok(match summary.status {
        Status::Ok => ExitCode::SUCCESS,
        Status::Diverged => ExitCode::from(EXIT_DIVERGED),
        Status::Interrupted => ExitCode::from(EXIT_INTERRUPTED),
    })
}

/// Watches the viewer from a thread of its own. When it is gone: if a file or a served
/// endpoint keeps the recording, says so once and lets the run go on; otherwise stops the
/// run (the link keeps the reason, for the summary).
fn watch_viewer(link: rope::viewer_link::ViewerLink, survives: bool, stop: Arc<AtomicBool>) {
    std::thread::spawn(move || {
        loop {
            std::thread::sleep(Duration::from_millis(100));
            if let Some(reason) = link.lost() {
                if survives {
                    eprintln!("rope: warning: {reason}; the run goes on without it");
                } else {
                    stop.store(true, Ordering::SeqCst);
                }
                return;
            }
        }
    });
}

fn study(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    use rope::study;
    let dts = args.dts();
    let bad = |what: String| -> anyhow::Result<ExitCode> {
        eprintln!("rope: bad input: {what}");
        Ok(ExitCode::from(EXIT_BAD_INPUT))
    };
    let scene = match args.scene.scene() {
        Ok(scene) => scene,
        Err(err) => return bad(err),
    };
    if let Err(err) = scene.validate() {
        return bad(err.to_string());
    }
    if !(args.duration.is_finite() && args.duration > 0.0) {
        return bad(format!(
            "duration = {}: must be a finite number of time units > 0",
            args.duration
        ));
    }
    if let Some(dt) = dts.iter().find(|dt| !(dt.is_finite() && **dt > 0.0)) {
        return bad(format!("dts: {dt} is not a positive, finite time step"));
    }
    if let Some(n) = args.segments.iter().find(|n| **n < 2) {
        return bad(format!(
            "segments: {n} is too few (at least 2; the seed method needs 4)"
        ));
    }
    let finest = args.segments.iter().copied().max().unwrap_or(100);
    let reference_segments = args.reference_segments.unwrap_or(2 * finest);
    if reference_segments < 4 || !reference_segments.is_multiple_of(2) {
        return bad(format!(
            "reference-segments = {reference_segments}: must be an even number ≥ 4"
        ));
    }
    let spec = study::Spec {
        scene,
        duration: args.duration,
        methods: args.methods.clone(),
        segments: args.segments.clone(),
        dts,
    };
    let cells = (spec.methods.len() * spec.segments.len() * spec.dts.len()) as u64;
    eprintln!(
        "rope study: {cells} runs ({} methods × {} N × {} k) on {} threads, reference at N = {reference_segments}",
        spec.methods.len(),
        spec.segments.len(),
        spec.dts.len(),
        rayon::current_num_threads()
    );
    let bar = indicatif::ProgressBar::new(cells).with_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} runs, {elapsed} elapsed, ~{eta} left",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    // Off a terminal (CI logs, pipes) the bar is hidden: print a line every tenth instead.
    let plain = !std::io::IsTerminal::is_terminal(&std::io::stderr());
    let started = std::time::Instant::now();
    let progress = || {
        bar.inc(1);
        let done = bar.position();
        if plain && (done * 10 / cells.max(1) != (done - 1) * 10 / cells.max(1) || done == cells) {
            eprintln!(
                "rope study: {done}/{cells} runs done, {:.0} s",
                started.elapsed().as_secs_f64()
            );
        }
    };
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let outcome = study::execute(&spec, reference_segments, &args.out, &command, progress)?;
    bar.finish_and_clear();
    if let Some(path) = &args.save {
        let rec = rerun::RecordingStreamBuilder::new("rope-study")
            .save(path)
            .with_context(|| format!("opening {}", path.display()))?;
        study::record::log(&rec, &outcome).context("logging the study")?;
        rec.flush_blocking()
            .context("writing the study recording")?;
    }
    println!("{}", outcome.markdown);
    eprintln!(
        "rope study: wrote study.csv, findings.md and the charts to {}",
        args.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
