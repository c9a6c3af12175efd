//! The observation vocabulary: one record per satellite, signal and epoch ([`ObsRecord`]),
//! whoever measured it (the bundled receiver, the synthesiser's truth, another receiver's
//! RINEX), and the one RINEX 3.04 observation writer and reader.

pub(crate) mod as_written;
pub(crate) mod noise;
mod read_error;
pub(crate) mod record;
pub mod rinex2_read;
mod rinex3_scan;
pub(crate) mod rinex_codes;
pub mod rinex_read;
pub(crate) mod rinex_write;

pub use rinex_write::{Calendar, ObsHeader, ObsWriter, RECEIVER_TYPE, calendar_gpst};

pub use as_written::epoch_as_written;

pub use noise::{
    ElevationNoise, NOISE_SIGMA0_M, WEIGHT_SIGMA0_M, dll_thermal_chips, pll_thermal_cycles,
};
pub use read_error::ObsReadError;
pub use read_error::{DOPPLER_MAX_HZ, PHASE_MAX_CYCLES, PSEUDORANGE_RANGE_M};
pub use record::{Dropped, LLI_HALF_CYCLE, LLI_LOSS_OF_LOCK, ObsEpoch, ObsFile, ObsRecord};
pub use rinex_read::{parse_obs_text, read_obs_file};
