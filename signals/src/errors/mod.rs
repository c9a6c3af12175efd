//! Error models: receiver oscillator, ionosphere, troposphere, link budget, multipath,
//! satellite orbit and clock, fault events.

pub(crate) mod clock;
pub(crate) mod events;
pub(crate) mod ionosphere;
pub(crate) mod link_budget;
pub(crate) mod multipath;
pub(crate) mod satellite;
pub(crate) mod seed;
pub(crate) mod troposphere;

pub use clock::{
    ClockModel, ClockSample, OffsetPoint, OscillatorConfig, OscillatorPreset, PowerLaw,
    RelativisticOffset, overlapping_adev, overlapping_avar, predicted_adev, predicted_avar,
};
pub use events::{EventConfig, EventKind, EventSchedule};
pub use ionosphere::{
    IonoConfig, IonoModel, KlobucharCoeffs, bds_klobuchar_b1i_s, gps_klobuchar_l1_s,
    remaining_fraction, scale_to_frequency,
};
pub use multipath::{MultipathConfig, TapConfig};
pub use satellite::{
    BOOK_SA, DrawnTrack, PreciseOrbit, SatelliteErrorConfig, SatelliteErrors, SatelliteModel,
    SatelliteProcesses, SatelliteTrack, SmoothGaussMarkov, W_R, modern, precise_orbits, sisre_m,
    w_ac_squared,
};
pub use seed::{Stream, stream_rng, vehicle_seed};
pub use troposphere::{
    TROPOSPHERE_CEILING_M, TropoConfig, TropoModel, chao_mapping, saastamoinen_zenith_m,
    standard_atmosphere,
};

pub use link_budget::default_gps_eirp_dbw;

use serde::Deserialize;

/// `[errors]`: error sources applied to the synthesised signal.
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorsConfig {
    /// `[errors.ionosphere]` (default: Klobuchar with the default coefficient sets).
    #[serde(default)]
    pub ionosphere: IonoConfig,
    /// `[errors.troposphere]` (default: Saastamoinen with the standard atmosphere; only
    /// receivers below the tropopause ceiling see it).
    #[serde(default)]
    pub troposphere: TropoConfig,
    /// `[errors.receiver_clock]`: the receiver oscillator (absent: an ideal clock).
    #[serde(default)]
    pub receiver_clock: Option<OscillatorConfig>,
    /// `[errors.multipath]`: reflected paths (absent: none).
    #[serde(default)]
    pub multipath: MultipathConfig,
    /// `[errors.satellite]`: true orbits and clocks off the broadcast ones (absent: the
    /// signals follow the broadcast ephemerides exactly).
    #[serde(default)]
    pub satellite: Option<SatelliteErrorConfig>,
    /// `[[errors.events]]`: faults for robustness tests.
    #[serde(default)]
    pub events: Vec<EventConfig>,
}
