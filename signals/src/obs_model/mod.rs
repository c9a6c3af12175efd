//! The observation-level path (DESIGN.md "obs_model"): per-antenna observables drawn from
//! the synthesiser's own link truth (the same geometry, clocks, ionosphere, troposphere,
//! antenna phase centres, lever arms, multipath and fault events) plus tracking noise,
//! without rendering samples. For long and Monte Carlo runs; the signal level stays the
//! reference.
//!
//! Noise comes from one of three models ([`ObsNoise`]): the loop thermal-noise formulas at
//! each link's C/N0 scaled by factors measured in a signal-level calibration run
//! (`skyforge calibrate`), the elevation model of thesis eqs. 2.4-9/2.4-10, or constant
//! standard deviations (what thesis table 1.2-2 prescribes).

pub(crate) mod calibration;
pub(crate) mod config;
pub(crate) mod model;

pub use calibration::{Calibration, LoopNoise, SignalCalibration};
pub use config::{Level, ObsNoise, ObsNoiseConfig, ObservationConfig};
pub use model::ObservationModel;
