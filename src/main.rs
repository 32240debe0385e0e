//! The `rope` command: parses the flags, hands the command to its service
//! ([`rope::service::run::run`] or [`rope::service::study::study`]), prints the error that
//! ended it, if one did, and maps the outcome to an exit code.

use clap::Parser as _;
use rope::cli::{Cli, Command};
use rope::service::{self, EXIT_BAD_INPUT, ServiceError, Session};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = Session::terminal()
        .map_err(ServiceError::from)
        .and_then(|session| match &cli.command {
            Command::Run(args) => service::run::run(args, &session).map(|o| o.exit_status),
            Command::Study(args) => service::study::study(args, &session).map(|v| v.exit_status()),
        });
    match result {
        Ok(status) => ExitCode::from(status),
        Err(ServiceError::BadInput(err)) => {
            eprintln!("rope: bad input: {err}");
            ExitCode::from(EXIT_BAD_INPUT)
        }
        Err(ServiceError::Failed(err)) => {
            eprintln!("rope: error: {err:#}");
            ExitCode::FAILURE
        }
    }
}
