//! One module per subcommand.

mod run;
mod scenarios;
pub(crate) mod synth;
mod validate;

use crate::cli::{Cli, Command, ScenariosAction, ValidateSuite};

/// Run the parsed command line.
pub fn dispatch(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Run {
            scenario,
            out,
            seed,
            force,
        } => run::run(&scenario, &out, seed, force),
        Command::Synth {
            scenario,
            out,
            seed,
            force,
            chunk_epochs,
        } => synth::synth(&scenario, &out, seed, force, chunk_epochs as usize),
        Command::Scenarios {
            action: ScenariosAction::List,
        } => scenarios::list(),
        Command::Scenarios {
            action: ScenariosAction::Show { name },
        } => scenarios::show(&name),
        Command::Validate {
            suite:
                ValidateSuite::Thesis {
                    only,
                    out,
                    force,
                    data,
                },
        } => validate::thesis(only, out.as_deref(), force, data),
        Command::Validate {
            suite:
                ValidateSuite::Obs {
                    truth,
                    estimate,
                    json,
                    tag_offset_s,
                },
        } => validate::obs(&truth, &estimate, json.as_deref(), tag_offset_s),
    }
}
