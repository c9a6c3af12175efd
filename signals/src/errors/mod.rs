//! Error models: receiver oscillator, ionosphere, troposphere, link budget, multipath,
//! fault events.

pub mod clock;
pub mod events;
pub mod ionosphere;
pub(crate) mod link_budget;
pub mod multipath;
pub mod seed;
pub mod troposphere;

pub use link_budget::default_gps_eirp_dbw;

use clock::OscillatorConfig;
use events::EventConfig;
use ionosphere::IonoConfig;
use multipath::MultipathConfig;
use serde::Deserialize;
use troposphere::TropoConfig;

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
    /// `[[errors.events]]`: faults for robustness tests.
    #[serde(default)]
    pub events: Vec<EventConfig>,
}
