//! `skyforge`: GNSS constellation and LEO scenario simulator.

mod cli;
mod commands;
mod output;

use clap::Parser;
use std::process::ExitCode;

/// Exit code for bad user input (scenario errors, existing output without `--force`).
const EXIT_BAD_INPUT: u8 = 2;

/// An error that is the user's input, reported with exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadInput(String);

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    match commands::dispatch(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if e.downcast_ref::<BadInput>().is_some()
                || e.downcast_ref::<skyforge_scenarios::ScenarioError>()
                    .is_some()
            {
                ExitCode::from(EXIT_BAD_INPUT)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}
