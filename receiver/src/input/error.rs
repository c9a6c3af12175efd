//! What can be wrong with sample input: errors that stop reading ([`InputError`]) and
//! findings that reading works around and reports ([`Finding`]).

use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::sigmf::MetaError;
use std::path::{Path, PathBuf};

/// The SigMF datatypes (and command-line spellings) this reader accepts, for messages.
pub const ALLOWED_DATATYPES: &str =
    "ci8, ci16_le (or ci16), cf32_le (or cf32), ri8 (all little-endian)";

/// Reading cannot go on.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// A file does not exist.
    #[error("{}: no such file", .path.display())]
    Missing { path: PathBuf },
    /// A file exists but cannot be read.
    #[error("{}: cannot read: {source}", .path.display())]
    Unreadable {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A metadata file is not a JSON document of the SigMF shape.
    #[error("{}: not SigMF metadata: {detail}", .path.display())]
    NotSigmf { path: PathBuf, detail: String },
    /// Metadata lacks a field the receiver needs.
    #[error("{}: the metadata has no {field} (required: {why})", .path.display())]
    MissingField {
        path: PathBuf,
        field: String,
        why: &'static str,
    },
    /// A metadata field has a value the receiver cannot use.
    #[error("{}: {field} is {found}; expected {expected}", .path.display())]
    BadField {
        path: PathBuf,
        field: String,
        found: String,
        expected: String,
    },
    /// A datatype this reader does not decode.
    #[error(
        "{origin}: unknown sample datatype {found:?}; allowed: {allowed}",
        allowed = ALLOWED_DATATYPES
    )]
    UnknownDatatype { origin: String, found: String },
    /// A parameter (command line or API) out of range.
    #[error("invalid {name} {value:?}: allowed: {allowed}")]
    InvalidParameter {
        name: &'static str,
        value: String,
        allowed: String,
    },
    /// A file that is neither SigMF nor described by raw-file parameters.
    #[error(
        "{}: not a .sigmf-meta/.sigmf-data recording; a raw sample file needs --format and --fs (and --if, --signal)",
        .path.display()
    )]
    RawParametersNeeded { path: PathBuf },
    /// Nothing to read.
    #[error("no sample files given")]
    NoRecordings,
    /// Two antennas' recordings were taken at different sample rates.
    #[error(
        "antenna {antenna} ({}) is sampled at {rate_hz} Hz but antenna {reference} at {reference_rate_hz} Hz: all antennas must share one sample clock",
        .path.display()
    )]
    RateMismatch {
        antenna: String,
        path: PathBuf,
        rate_hz: f64,
        reference: String,
        reference_rate_hz: f64,
    },
    /// Two antennas' recordings use different containers.
    #[error(
        "antenna {antenna} ({}) holds {format} samples but antenna {reference} holds {reference_format}: all antennas must use one datatype",
        .path.display()
    )]
    FormatMismatch {
        antenna: String,
        path: PathBuf,
        format: SampleFormat,
        reference: String,
        reference_format: SampleFormat,
    },
    /// Two antennas' complex recordings put the signal at different IFs.
    #[error(
        "antenna {antenna} ({}) has the signal at IF {if_hz} Hz but antenna {reference} at {reference_if_hz} Hz: complex recordings processed together must share one IF",
        .path.display()
    )]
    IfMismatch {
        antenna: String,
        path: PathBuf,
        if_hz: f64,
        reference: String,
        reference_if_hz: f64,
    },
    /// Two antennas' recordings hold different signals.
    #[error(
        "antenna {antenna} ({}) records {signal} but antenna {reference} records {reference_signal}: process one band per run",
        .path.display()
    )]
    SignalMismatch {
        antenna: String,
        path: PathBuf,
        signal: String,
        reference: String,
        reference_signal: String,
    },
    /// The file length is not a whole number of samples: a truncated or corrupted file.
    #[error(
        "{} (antenna {antenna}): {sample_bytes} bytes of samples{} are not a whole number of {format} samples ({bytes_per_sample} bytes each): {leftover_bytes} byte(s) after the last whole sample (a truncated or corrupted file)",
        .path.display(),
        if .file_bytes == .sample_bytes { String::new() } else { format!(" (a {file_bytes}-byte file less its header and trailing bytes)") }
    )]
    PartialSample {
        antenna: String,
        path: PathBuf,
        format: SampleFormat,
        file_bytes: u64,
        sample_bytes: u64,
        leftover_bytes: u64,
        bytes_per_sample: usize,
    },
    /// The files have no sample in common.
    #[error("no samples to process: {reason}")]
    NoCommonSamples { reason: String },
    /// A file ended before the length it had when it was opened.
    #[error(
        "{}: ended in the block starting at sample {at} of the {expected} to be read (the file shrank while being read)",
        .path.display()
    )]
    ShrankWhileReading {
        path: PathBuf,
        at: u64,
        expected: u64,
    },
    /// The caller passed the wrong number of block buffers.
    #[error("{given} block buffers given for {antennas} antennas")]
    BufferCount { given: usize, antennas: usize },
}

impl InputError {
    /// The error for an I/O failure on `path`: [`InputError::Missing`] when it does not
    /// exist, [`InputError::Unreadable`] otherwise.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        let path = path.into();
        if source.kind() == std::io::ErrorKind::NotFound {
            InputError::Missing { path }
        } else {
            InputError::Unreadable { path, source }
        }
    }

    /// The error for what is wrong with the SigMF metadata file `meta_path`.
    pub fn meta(meta_path: &Path, error: MetaError) -> Self {
        let path = meta_path.to_owned();
        match error {
            MetaError::NotSigmf { detail } => InputError::NotSigmf { path, detail },
            MetaError::BadField {
                field,
                found,
                expected,
            } => InputError::BadField {
                path,
                field,
                found,
                expected,
            },
            MetaError::UnknownDatatype { found } => InputError::UnknownDatatype {
                origin: meta_path.display().to_string(),
                found,
            },
        }
    }
}

/// Something wrong or notable in the input that reading works around; reported in
/// [`super::InputReport::findings`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Finding {
    /// One antenna's file ends before another's.
    #[error(
        "antenna {antenna} ({}) is {missing_samples} samples ({missing_s} s) shorter than antenna {longest}'s file: only the {common_samples} samples all files share are processed",
        .path.display()
    )]
    Shorter {
        antenna: String,
        path: PathBuf,
        missing_samples: u64,
        missing_s: f64,
        longest: String,
        common_samples: u64,
    },
    /// A file started earlier than the others; its first samples are skipped.
    #[error(
        "antenna {antenna} ({}) starts {skipped_samples} samples ({skipped_s} s) before the latest-starting file: its first {skipped_samples} samples are skipped to align the antennas",
        .path.display()
    )]
    StartAligned {
        antenna: String,
        path: PathBuf,
        skipped_samples: u64,
        skipped_s: f64,
    },
    /// Start times differ by a non-whole number of samples.
    #[error(
        "antenna {antenna}'s start time lies {offset_samples} samples after the earliest one, not a whole number: rounded to {rounded} (the metadata time stamps are coarser than a sample, or the clocks differ)"
    )]
    FractionalStart {
        antenna: String,
        offset_samples: f64,
        rounded: u64,
    },
    /// Some recordings say when they start and others do not.
    #[error(
        "antennas {antennas} give no start time or global sample index: all files are assumed to start at the same sample"
    )]
    StartUnknown { antennas: String },
    /// A recording with several capture segments.
    #[error(
        "{} has {count} capture segments: the first one's frequency and time are used, the samples are read as one stream",
        .path.display()
    )]
    SeveralCaptures { path: PathBuf, count: usize },
    /// A recording of several signals holds one the bundled receiver does not receive.
    #[error(
        "{} also holds {signal}, which the bundled receiver does not receive: it is read for the other signals",
        .path.display()
    )]
    SignalNotReceived { path: PathBuf, signal: String },
    /// A command-line value replaced a different metadata value.
    #[error("{}: {field} {given} from the command line replaces {metadata} of the metadata", .path.display())]
    Overridden {
        path: PathBuf,
        field: String,
        metadata: String,
        given: String,
    },
}
