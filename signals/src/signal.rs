//! Signal identifiers that carry through truth, samples and observables.

use skyforge_orbits::constants::{F_BDS_B1I_HZ, F_GPS_L1_HZ};
use skyforge_orbits::ephemeris::{SatId, System};

/// A GNSS signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum SignalId {
    GpsL1Ca,
    BdsB1I,
}

impl SignalId {
    /// Carrier frequency (Hz).
    pub fn carrier_hz(self) -> f64 {
        match self {
            SignalId::GpsL1Ca => F_GPS_L1_HZ,
            SignalId::BdsB1I => F_BDS_B1I_HZ,
        }
    }
    /// The signal SkyForge generates for a satellite.
    pub fn primary_for(sat: SatId) -> Self {
        match sat.system {
            System::Gps => SignalId::GpsL1Ca,
            System::Beidou => SignalId::BdsB1I,
        }
    }
    /// Short name, as in file names and HDF5 attributes.
    pub fn name(self) -> &'static str {
        match self {
            SignalId::GpsL1Ca => "GPS L1 C/A",
            SignalId::BdsB1I => "BDS B1I",
        }
    }
}
