//! SigMF 1.0 recordings (a `.sigmf-data` sample file and its `.sigmf-meta` JSON metadata),
//! as SkyForge writes and reads them: the key names ([`keys`]), the metadata the simulator
//! writes ([`RecordingMeta`]), the fields a reader takes from a metadata document
//! ([`ParsedMeta`]), and `core:datetime` times ([`datetime`]). The simulator's sample sink
//! (`skyforge_signals` `synth::sigmf`) writes the files; the receiver's `input::recording`
//! reads them.

pub(crate) mod datetime;
pub mod keys;
mod read;
mod write;

pub use read::{Capture, MetaError, ParsedMeta, parse_json};
pub use write::{RECORDER, RecordingMeta};

#[cfg(test)]
mod tests;

pub use datetime::format_utc;
