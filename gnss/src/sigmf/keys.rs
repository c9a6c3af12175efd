//! Every name SkyForge writes or reads in a `.sigmf-meta` document: the SigMF 1.0 `core`
//! namespace's and those of SkyForge's own `skyforge` extension.

/// Top-level object of the fields that hold for the whole recording.
pub const GLOBAL: &str = "global";
/// Top-level array of capture segments.
pub const CAPTURES: &str = "captures";
/// Top-level array of annotations.
pub const ANNOTATIONS: &str = "annotations";

/// Global: the sample container (`ci8`, `ci16_le`, `cf32_le`, `ri8`).
pub const DATATYPE: &str = "core:datatype";
/// Global: samples per second.
pub const SAMPLE_RATE: &str = "core:sample_rate";
/// Global: the SigMF version the document follows.
pub const VERSION: &str = "core:version";
/// Global: interleaved channels in the data file.
pub const NUM_CHANNELS: &str = "core:num_channels";
/// Global: what the recording is, for people.
pub const DESCRIPTION: &str = "core:description";
/// Global: the program that wrote the recording.
pub const RECORDER: &str = "core:recorder";
/// Global: the extensions the document uses.
pub const EXTENSIONS: &str = "core:extensions";
/// Global: non-sample bytes at the end of the data file.
pub const TRAILING_BYTES: &str = "core:trailing_bytes";

/// An extension's name (in [`EXTENSIONS`]).
pub const EXTENSION_NAME: &str = "name";
/// An extension's version (in [`EXTENSIONS`]).
pub const EXTENSION_VERSION: &str = "version";
/// Whether a reader may ignore an extension (in [`EXTENSIONS`]).
pub const EXTENSION_OPTIONAL: &str = "optional";

/// Capture: index of the segment's first sample in the data file.
pub const SAMPLE_START: &str = "core:sample_start";
/// Capture: index of the segment's first sample in the recorder's sample stream.
pub const GLOBAL_INDEX: &str = "core:global_index";
/// Capture: centre frequency (Hz).
pub const FREQUENCY: &str = "core:frequency";
/// Capture: ISO-8601 UTC time of the segment's first sample.
pub const DATETIME: &str = "core:datetime";
/// Capture: non-sample bytes before the segment's samples.
pub const HEADER_BYTES: &str = "core:header_bytes";

/// The name of SkyForge's extension, the namespace of the keys below.
pub const SKYFORGE: &str = "skyforge";
/// Global: the scenario synthesised.
pub const SCENARIO: &str = "skyforge:scenario";
/// Global: the synthesis's random seed.
pub const SEED: &str = "skyforge:seed";
/// Global: the vehicle whose antenna it is, in a scenario of several (`[[vehicles]]`):
/// with [`SCENARIO`] and [`SEED`] what reproduces the recording (the vehicle's receiver
/// streams are keyed by its name).
pub const VEHICLE: &str = "skyforge:vehicle";
/// Global: the antenna recorded.
pub const ANTENNA: &str = "skyforge:antenna";
/// Global: the antenna's nominal position in the body frame (m).
pub const ANTENNA_POSITION_BODY_M: &str = "skyforge:antenna_position_body_m";
/// Global: the intermediate frequency of the signal within the recording (Hz).
pub const IF_HZ: &str = "skyforge:if_hz";
/// Global: the signals a recording of one band carries, by tag (`["gps-l1ca",
/// "gal-e1"]`); written where it carries several (a recording of one signal names it by
/// its carrier).
pub const SIGNALS: &str = "skyforge:signals";
