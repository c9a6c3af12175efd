//! What the RINEX observation readers (versions 2 and 3) share: their error, and the
//! quantity an observation code names.

use std::path::PathBuf;

/// Which quantity an observation code holds (RINEX 3 and 2 alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Code,
    Phase,
    Doppler,
    Strength,
}

/// Why an observation file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ObsReadError {
    /// The file could not be read or parsed as RINEX.
    #[error("{path}: {message}")]
    Read { path: PathBuf, message: String },
    /// The file is not well formed at `line` (1-based; 0 when the whole file is at fault).
    #[error("{path}:{line}: {message}")]
    Syntax {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// The file is RINEX but not an observation file.
    #[error("{0}: not a RINEX observation file")]
    NotObservation(PathBuf),
}
