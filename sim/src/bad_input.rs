//! Errors that are the user's input: reported with exit code 2, whatever command met them.

use skyforge_studies::study::results::ResultsError;

/// Exit code for bad user input (scenario errors, existing output without `--force`).
pub const EXIT_BAD_INPUT: u8 = 2;

/// An error that is the user's input, reported with exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadInput(pub String);

/// Whether `e` is the user's input: a [`BadInput`], a scenario the checks refused, a
/// study file that is not the study's, or a shard another process is making.
pub fn is_bad_input(e: &anyhow::Error) -> bool {
    e.downcast_ref::<BadInput>().is_some()
        || e.downcast_ref::<skyforge_scenarios::ScenarioError>()
            .is_some()
        || matches!(
            e.downcast_ref::<ResultsError>(),
            Some(ResultsError::NotThisStudy(_) | ResultsError::Busy(_))
        )
}
