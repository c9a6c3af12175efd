//! Reading sample files: SkyForge SigMF recordings and raw files of other sources, several antennas on one sample clock.
//!
//! Use: describe each antenna's file with [`Recording::open`] (SigMF metadata, or raw-file
//! [`InputParams`] from the command line, e.g. gps-sdr-sim's 8- or 16-bit I/Q at 2.6 Msps
//! is raw `ci8`/`ci16`), open them together with [`BlockReader::open`] (which checks that
//! they can share one sample clock and reports what it found in an [`InputReport`]), then
//! call [`BlockReader::read_block`] with the buffers of [`BlockReader::buffers`] until it
//! returns `None`. Samples arrive as complex f32 at the full scale documented in
//! [`format`]; real IF input is mixed to complex baseband ([`if_mixer`]).

pub(crate) mod error;
pub(crate) mod format;
pub(crate) mod if_mixer;
pub(crate) mod reader;
pub(crate) mod recording;
pub(crate) mod stream;

pub use error::{Finding, InputError};
pub use format::{SampleFormat, decode_cf32, decode_ci8, decode_ci16, decode_ri8, parse_format};
pub use if_mixer::IfMixer;
pub use reader::{AntennaInput, Block, BlockReader, InputReport};
pub use recording::{InputParams, Recording};
pub use stream::{FeedError, SampleFeed, StreamReader, sample_stream};
