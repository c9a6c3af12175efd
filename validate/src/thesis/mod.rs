//! The thesis acceptance tables (`../shared/reference/THESIS_TARGETS.md`): each module runs
//! the bundled scenarios of its table and returns one [`Row`](crate::report::Row) per
//! printed number.

pub mod attitude_noise;
pub mod attitude_realtime;
mod attitude_runs;
pub mod fast_sync;
pub mod geometry_offsets;
mod geometry_run;
pub mod loop_budget;
pub mod pmf_fft;
pub mod reverse_filter;
pub mod visibility;
pub mod zero_baseline;

use crate::integrity::raim;
use crate::report::Row;
use std::path::PathBuf;

/// Table identifiers `validate thesis --only` accepts, in run order.
pub const TABLES: &[&str] = &[
    "V-1.2.1", "T-1.2-2", "T-1.2-3", "T-3.2", "T-3.3-R", "T-3.3-S", "T-4.3", "T-5.4-2", "T-5.4-3",
    "T-5.4-4", "T-5.4-5", "T-5.5", "P2-4.2", "P2-PD", "B-5.2-1", "B-5.2-2",
];

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

/// Whether `--only id` selects `table`: the same identifier, or a group of it (`T-1.2`
/// selects `T-1.2-2` and `T-1.2-3`), ignoring case.
fn selects(id: &str, table: &str) -> bool {
    let (id, table) = (id.to_ascii_uppercase(), table.to_ascii_uppercase());
    table == id
        || table
            .strip_prefix(&id)
            .is_some_and(|rest| rest.starts_with('-'))
}

/// Whether `--only id` selects any table.
pub fn known(id: &str) -> bool {
    TABLES.iter().any(|t| selects(id, t))
}

/// Run the selected tables and return their rows; `starting` is told each table's ID
/// before it runs (for progress output).
pub fn run(opts: &Options, mut starting: impl FnMut(&str)) -> Result<Vec<Row>, ValidateError> {
    for id in &opts.only {
        if !known(id) {
            return Err(ValidateError::UnknownTable {
                id: id.clone(),
                known: TABLES.join(", "),
            });
        }
    }
    let wanted = |t: &str| opts.only.is_empty() || opts.only.iter().any(|id| selects(id, t));
    let mut rows = Vec::new();
    if wanted("V-1.2.1") {
        starting("V-1.2.1");
        rows.extend(visibility::rows(opts.data_dir.as_deref())?);
    }
    let (noise, offsets) = (
        wanted(attitude_noise::TABLE_NOISE),
        wanted(attitude_noise::TABLE_OFFSETS),
    );
    if noise || offsets {
        starting(if noise {
            attitude_noise::TABLE_NOISE
        } else {
            attitude_noise::TABLE_OFFSETS
        });
        rows.extend(attitude_noise::rows(noise, offsets)?);
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
    if wanted(geometry_offsets::TABLE) {
        starting(geometry_offsets::TABLE);
        rows.extend(geometry_offsets::rows()?);
    }
    if wanted(zero_baseline::TABLE) {
        starting(zero_baseline::TABLE);
        rows.extend(zero_baseline::rows_from_chain()?);
    }
    let realtime: Vec<&str> = attitude_realtime::TABLES
        .into_iter()
        .filter(|t| wanted(t))
        .collect();
    if let Some(first) = realtime.first() {
        starting(first);
        let all = attitude_realtime::rows()?;
        rows.extend(
            all.into_iter()
                .filter(|r| realtime.contains(&r.table.as_str())),
        );
    }
    if wanted(reverse_filter::TABLE) {
        starting(reverse_filter::TABLE);
        rows.extend(reverse_filter::rows()?);
    }
    let (patterns, curves) = (
        wanted(crate::integrity::patterns::TABLE),
        wanted(crate::integrity::detection::TABLE),
    );
    if patterns || curves {
        starting(if patterns { "P2-4.2" } else { "P2-PD" });
        rows.extend(
            crate::integrity::rows(
                crate::integrity::patterns::SEEDS,
                crate::integrity::detection::SEEDS,
                patterns,
                curves,
            )
            .map_err(ValidateError::Pipeline)?,
        );
    }
    let (mops, leo) = (wanted(raim::TABLE_MOPS), wanted(raim::TABLE_LEO));
    if mops || leo {
        starting(if mops {
            raim::TABLE_MOPS
        } else {
            raim::TABLE_LEO
        });
        rows.extend(raim::rows(mops, leo, raim::RUNS)?);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::selects;

    #[test]
    fn only_selects_a_table_or_its_group() {
        assert!(selects("t-1.2-2", "T-1.2-2"));
        assert!(selects("T-1.2", "T-1.2-3"));
        assert!(selects("T-5.4", "T-5.4-2"));
        assert!(!selects("T-5.4-2", "T-5.4-3"));
        assert!(!selects("T-1", "T-1.2-2"));
        assert!(!selects("T-3.3", "T-3.2"));
        assert!(!selects("T-3.3-", "T-3.3-R"));
        assert!(selects("T-5.5", "T-5.5"));
        assert!(!selects("T-5.5", "T-5.4-5"));
    }
}
