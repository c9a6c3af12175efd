//! Stages that run at every observation epoch, after the observables, in the stage idiom:
//! the trait [`EpochStage`] and [`build`], which maps `[stages] epoch`
//! ([`EpochStageKind`], in `pipeline::config`) to an implementation, one per file. Today
//! one: single-point PVT per antenna (`pvt_stage.rs`). The attitude chain consumes the
//! same epochs beside the receiver's files (`skyforge receive --geometry`, an epoch sink).

mod pvt_stage;

use super::AntennaFix;
use super::config::{EpochStageKind, ReceiverConfig};
use super::navdata::NavData;
use crate::observables::Observation;
use pvt_stage::PvtStage;
use skyforge_orbits::Vec3;

/// An antenna's latest fix, for assisting its searches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LastFix {
    /// Receiver time of the fix (s since the origin).
    pub t_s: f64,
    pub r_ecef_m: Vec3,
    /// Zero when no velocity was solved.
    pub v_ecef_mps: Vec3,
}

/// What an epoch stage is given at one epoch.
pub(crate) struct EpochInput<'a> {
    /// Receiver time of the epoch (s since the origin).
    pub(crate) t_s: f64,
    /// Every antenna's observations.
    pub(crate) observations: &'a [Observation],
    /// The navigation data decoded or given so far.
    pub(crate) nav: &'a NavData,
}

/// A stage run at every epoch.
pub(crate) trait EpochStage: Send {
    /// One result per antenna, in antenna order.
    fn epoch(&mut self, input: &EpochInput<'_>) -> Vec<AntennaFix>;
    /// The latest fix of `antenna`, if the stage has one.
    fn last_fix(&self, antenna: usize) -> Option<LastFix>;
}

/// The configured epoch stage for `antennas` antennas.
pub(crate) fn build(config: &ReceiverConfig, antennas: usize) -> Box<dyn EpochStage> {
    match config.epoch_stage {
        EpochStageKind::Pvt => Box::new(PvtStage::new(config.pvt.clone(), antennas)),
    }
}
