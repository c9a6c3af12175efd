//! Studies: Monte Carlo runs of one base scenario over a grid of parameter values and
//! seeds, each run measured against its own truth, split into shards that merge into the
//! same result whatever the layout (docs/study.md). `skyforge study` drives them and
//! writes their files.

pub(crate) mod file;
pub(crate) mod metrics;
pub(crate) mod plan;
pub mod results;
pub(crate) mod summary;

pub use file::{Parameter, Study, StudyError};
pub use metrics::Metric;
pub use plan::{RunResult, Shard, run_seed};
pub use summary::MetricSummary;

/// The merged file `study run` writes for a whole study and `study merge` by default.
pub const MERGED_FILE: &str = "study.h5";
