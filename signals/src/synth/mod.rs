//! IF/baseband synthesis: the signal configuration, transmitters (code + data), per-channel
//! mixing, thermal noise, front-end quantisation, the per-antenna renderer, the sample-file
//! formats with their SigMF metadata, and the streaming session that drives them.

pub(crate) mod budget;
pub(crate) mod config;
pub mod constellation;
pub(crate) mod filter;
pub mod gnss_sdr;
pub(crate) mod jamming;
pub mod link;
pub(crate) mod link_terms;
pub(crate) mod mix;
pub(crate) mod noise;
pub(crate) mod quantise;
pub mod render;
pub(crate) mod session;
pub(crate) mod sigmf;
pub(crate) mod transmitter;

pub use config::{BLOCK_S, RecordingLayout, SignalConfig};
pub use filter::{BandFilter, FilterConfig};
pub use link_terms::{AntennaEpoch, LinkTerms};
pub use mix::{ChannelBlock, Chips, MixScratch, mix_into};
pub use session::{
    Discard, GEOMETRY_STEP_S, ObservationSink, RunInfo, SampleSink, SinkError, Sinks, SynthError,
    SynthReport, SynthSession, SynthWorld, TruthSink,
};
pub use sigmf::{SigmfRecordings, recording_name};

pub use budget::Budget;
pub use noise::ThermalNoise;
pub use quantise::Quantiser;
pub use transmitter::Transmitter;
