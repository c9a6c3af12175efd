//! A study's results on disk (docs/study.md), one home for the format: the journal a
//! shard appends each finished run to ([`Journal`]), the shard's HDF5 file, the merged
//! `study.h5` with the per-point summaries, their readers, and the names of their groups,
//! datasets and attributes, once.

mod journal;
mod study_h5;

pub use journal::Journal;
pub use study_h5::{
    MergedFile, ShardFile, read_shard, shard_study_text, write_merged, write_shard,
};

use super::Shard;
use std::path::{Path, PathBuf};

/// The `format` attribute of a study file.
const FORMAT: &str = "skyforge-study 1";
/// Root attributes: the format, and the study file's text.
const FORMAT_ATTR: &str = "format";
const STUDY_TOML_ATTR: &str = "study_toml";
/// Group of one dataset per run column (`run`, `point`, `seed`, one per metric).
const RUNS_GROUP: &str = "runs";
const RUN: &str = "run";
/// Group of one group per metric, each with one dataset per statistic over the points.
const SUMMARY_GROUP: &str = "summary";
/// Summary statistics the report draws.
pub const MEAN: &str = "mean";
pub const MEAN_CI_LOW: &str = "mean_ci_low";
pub const MEAN_CI_HIGH: &str = "mean_ci_high";
pub const P95: &str = "p95";

/// Why a study's files could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// The file is not this study's (the user's input: another `--out`, another file).
    #[error("{0}")]
    NotThisStudy(String),
    /// Another process is making the shard (the user's input: a second run of it).
    #[error("{0}")]
    Busy(String),
    /// Reading or writing failed.
    #[error("{0}")]
    Io(String),
}

/// `cannot <verb> <path>: <error>`.
fn io(verb: &str, path: &Path, e: std::io::Error) -> ResultsError {
    ResultsError::Io(format!("cannot {verb} {}: {e}", path.display()))
}

/// The shard file's path in `dir`.
pub fn shard_path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("{}.h5", shard.tag()))
}
