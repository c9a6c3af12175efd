//! The thesis acceptance tables (`../shared/reference/THESIS_TARGETS.md`): each module runs
//! the bundled scenarios of its table and returns one [`Row`](crate::report::Row) per
//! printed number.

pub mod fast_sync;
mod geometry_run;
pub mod loop_budget;
pub mod pmf_fft;
pub mod visibility;
pub mod zero_baseline;

use crate::report::Row;
use std::path::PathBuf;

/// Table identifiers `validate thesis --only` accepts, in run order.
pub const TABLES: &[&str] = &["V-1.2.1", "T-3.2", "T-3.3-R", "T-3.3-S", "T-5.4-2"];

/// Why a validation could not run.
#[derive(Debug, thiserror::Error)]
pub enum ValidateError {
    #[error("bundled scenario: {0}")]
    Scenario(Box<skyforge_scenarios::ScenarioError>),
    #[error("geometry: {0}")]
    Geometry(String),
    #[error("acquisition: {0}")]
    Acquisition(#[from] skyforge_receiver::acquisition::AcquisitionError),
    #[error("tracking: {0}")]
    Tracking(#[from] skyforge_receiver::tracking::TrackingError),
    #[error("observations: {0}")]
    Observations(#[from] crate::observables::ObsError),
    #[error("{0}")]
    Pipeline(String),
    #[error("unknown table {id:?}; known tables: {known}")]
    UnknownTable { id: String, known: String },
}

impl From<skyforge_scenarios::ScenarioError> for ValidateError {
    fn from(e: skyforge_scenarios::ScenarioError) -> Self {
        ValidateError::Scenario(Box::new(e))
    }
}

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Table IDs to run (empty: all).
    pub only: Vec<String>,
    /// The real-data folder (`SKYFORGE_DATA`); tables add real-data rows when it exists.
    pub data_dir: Option<PathBuf>,
}

/// Run the selected tables and return their rows; `starting` is told each table's ID
/// before it runs (for progress output).
pub fn run(opts: &Options, mut starting: impl FnMut(&str)) -> Result<Vec<Row>, ValidateError> {
    for id in &opts.only {
        if !TABLES.iter().any(|t| t.eq_ignore_ascii_case(id)) {
            return Err(ValidateError::UnknownTable {
                id: id.clone(),
                known: TABLES.join(", "),
            });
        }
    }
    let wanted =
        |t: &str| opts.only.is_empty() || opts.only.iter().any(|id| id.eq_ignore_ascii_case(t));
    let mut rows = Vec::new();
    if wanted("V-1.2.1") {
        starting("V-1.2.1");
        rows.extend(visibility::rows(opts.data_dir.as_deref())?);
    }
    if wanted("T-3.2") {
        starting("T-3.2");
        rows.extend(loop_budget::rows()?);
    }
    if wanted("T-3.3-R") {
        starting("T-3.3-R");
        rows.extend(pmf_fft::rows()?);
    }
    if wanted("T-3.3-S") {
        starting("T-3.3-S");
        rows.extend(fast_sync::rows()?);
    }
    if wanted(zero_baseline::TABLE) {
        starting(zero_baseline::TABLE);
        rows.extend(zero_baseline::rows_from_chain()?);
    }
    Ok(rows)
}
