//! The whole receiver on a stream of sample blocks: acquisition (cold or assisted), one
//! tracking channel per antenna x satellite, navigation decoding, observables on a common
//! receive time and a PVT fix per antenna at every observation epoch.

mod channel;
mod config;
mod epoch_stage;
#[cfg(any(test, feature = "test-support"))]
pub mod fixtures;
mod navdata;
mod receiver;
mod timing;

pub use config::{
    AcquisitionFile, AcquisitionMethod, AcquisitionSettings, ApproximateState, AssistFile,
    EpochStageKind, ObservablesFile, PvtFile, ReceiverConfig, ReceiverFile, StagesFile,
    assistance_toml,
};
pub use epoch_stage::LastFix;
pub use receiver::{BandInput, PipelineError, Receiver, ReceiverSetup, ReceiverSummary};

use crate::observables::Observation;
use hifitime::Epoch;
use skyforge_gnss::observation::ObsRecord;
use skyforge_navigation::pvt::{Fix, PvtError, VelocityFix};

/// The fix of one antenna at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct AntennaFix {
    /// Index of the antenna (order of the input files).
    pub antenna: usize,
    /// Position and clock, or why there is none.
    pub fix: Result<Fix, PvtError>,
    /// Velocity and clock drift from Doppler when the position fix exists.
    pub velocity: Option<VelocityFix>,
}

/// What the receiver produced at one observation epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct EpochReport {
    /// The epoch's (fractional) sample index on the common sample clock.
    pub sample_index: f64,
    /// Receiver time of the epoch (GPST, the receiver's own clock: the recording's start
    /// time plus samples / rate, re-anchored to GPS time by a fix that finds it more than
    /// 0.5 us off, so GPS time within a microsecond after the first fix; the fix's clock
    /// bias says how far off it is).
    pub t_rx: Epoch,
    /// Observations of every antenna and satellite tracked at the epoch.
    pub observations: Vec<Observation>,
    /// One entry per antenna.
    pub fixes: Vec<AntennaFix>,
}

impl EpochReport {
    /// Antenna `antenna`'s observations as records, ordered by satellite (a RINEX epoch's
    /// content).
    pub fn records(&self, antenna: usize) -> Vec<ObsRecord> {
        let mut records: Vec<ObsRecord> = self
            .observations
            .iter()
            .filter(|o| o.antenna == antenna)
            .map(Observation::record)
            .collect();
        records.sort_by_key(|r| r.sat);
        records
    }
}
