//! The `rope` command: parses the flags, opens the Rerun recording, and hands off to
//! [`rope::app::run`].

use anyhow::Context as _;
use clap::Parser as _;
use rope::cli::{Cli, Command, RunArgs};
use rope::summary::Status;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit codes: 2 is bad input (as clap's own errors), 3 a diverged run, 130 an interrupted one.
const EXIT_BAD_INPUT: u8 = 2;
const EXIT_DIVERGED: u8 = 3;
const EXIT_INTERRUPTED: u8 = 130;

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Run(args) => match run(&args) {
            Ok(code) => code,
            Err(err) => {
                eprintln!("rope: error: {err:#}");
                ExitCode::FAILURE
            }
        },
    }
}

fn run(args: &RunArgs) -> anyhow::Result<ExitCode> {
    let config = match args.config() {
        Ok(config) => config,
        Err(err) => {
            eprintln!("rope: bad input: {err}");
            return Ok(ExitCode::from(EXIT_BAD_INPUT));
        }
    };
    if args.dt.is_none() {
        eprintln!(
            "rope: --dt not given: using k = {:.3e} for the {} method at N = {} (estimated stability limit {:.3e})",
            config.dt,
            config.method,
            config.segments,
            config.method.stability_limit(config.segments)
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

    let (rec, _serve_guard) = args
        .rerun
        .init_with_blueprint("rope", rope::logger::blueprint())
        .map_err(explain_viewer_error)?;
    let summary = rope::app::run(&config, Some(rec), &stop)?;

    if let Some(path) = &args.summary {
        let json = serde_json::to_string_pretty(&summary).context("encoding the summary")?;
        std::fs::write(path, json)
            .with_context(|| format!("writing the summary to {}", path.display()))?;
    }
    eprintln!("{}", summary.human());
    Ok(match summary.status {
        Status::Ok => ExitCode::SUCCESS,
        Status::Diverged => ExitCode::from(EXIT_DIVERGED),
        Status::Interrupted => ExitCode::from(EXIT_INTERRUPTED),
    })
}

/// Adds what to do when the viewer cannot be spawned because it is not installed.
fn explain_viewer_error(err: anyhow::Error) -> anyhow::Error {
    let missing = matches!(
        err.downcast_ref::<rerun::RecordingStreamError>(),
        Some(rerun::RecordingStreamError::SpawnViewer(
            rerun::SpawnError::ExecutableNotFoundInPath { .. }
        ))
    );
    if missing {
        err.context(
            "the Rerun viewer is not installed: install it with `pip install rerun-sdk==0.36.3`, or save the recording with --save FILE.rrd and open it later",
        )
    } else {
        err.context("opening the Rerun recording")
    }
}
