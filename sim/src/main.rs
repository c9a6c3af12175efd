//! `skyforge`: GNSS constellation and LEO scenario simulator.

mod bad_input;
mod cli;
mod commands;
mod output;

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;

use bad_input::{EXIT_BAD_INPUT, is_bad_input};
/// The output directory of a command that writes one.
fn output_dir(args: &cli::Cli) -> Option<PathBuf> {
    match &args.command {
        cli::Command::Run { run }
        | cli::Command::Synth { run, .. }
        | cli::Command::Calibrate { run } => Some(run.out.clone()),
        cli::Command::Receive { args } => Some(args.out.clone()),
        cli::Command::Attitude { args } => Some(args.out.clone()),
        cli::Command::Od { args } => Some(args.out.clone()),
        cli::Command::Ins { args } => Some(args.out.clone()),
        cli::Command::Relnav { args } => Some(args.out.clone()),
        cli::Command::Jamming { args } => Some(args.out.clone()),
        cli::Command::Monitor {
            action:
                cli::MonitorAction::Run { args } | cli::MonitorAction::CalibrateFiles { args, .. },
        } => Some(args.out.clone()),
        cli::Command::Monitor {
            action: cli::MonitorAction::Calibrate { run, .. },
        } => Some(run.out.clone()),
        cli::Command::Validate {
            suite: cli::ValidateSuite::Thesis { out, .. },
        } => out.clone(),
        cli::Command::Validate {
            suite:
                cli::ValidateSuite::Obs { .. }
                | cli::ValidateSuite::Attitude { .. }
                | cli::ValidateSuite::Monitor { .. }
                | cli::ValidateSuite::Od { .. }
                | cli::ValidateSuite::Ins { .. }
                | cli::ValidateSuite::Interference { .. }
                | cli::ValidateSuite::Relnav { .. }
                | cli::ValidateSuite::Agree { .. },
        }
        | cli::Command::Scenarios { .. }
        | cli::Command::Report { .. }
        | cli::Command::Ambiguity { .. } => None,
        // A study keeps what it finished (its journal) to resume from.
        cli::Command::Study { .. } => None,
    }
}

fn main() -> ExitCode {
    let args = cli::Cli::parse();
    let out = output_dir(&args);
    match commands::dispatch(args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            if is_bad_input(&e) {
                ExitCode::from(EXIT_BAD_INPUT)
            } else {
                // A run that failed while writing (e.g. a full disk): outputs are staged and
                // the staging directory is removed on failure, so say where nothing went.
                if let Some(out) = out {
                    eprintln!(
                        "error: the output directory {} was not written; partial files were removed",
                        out.display()
                    );
                }
                ExitCode::FAILURE
            }
        }
    }
}
