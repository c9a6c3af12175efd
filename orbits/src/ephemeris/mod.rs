//! GNSS satellites and their broadcast ephemerides: identifiers, the GPS LNAV, BeiDou D1/D2
//! and Galileo I/NAV and F/NAV user algorithms, RINEX 2/3/4 navigation files, SP3 precise orbits, ephemeris
//! selection, and the embedded default constellations.

pub(crate) mod broadcast;
pub(crate) mod config;
pub(crate) mod klobuchar;
pub(crate) mod nav_text;
pub mod nominal;
pub mod rinex_nav;
pub mod rinex_nav_iono;
pub(crate) mod rinex_nav_write;
pub(crate) mod sat_id;
pub(crate) mod sp3;
pub(crate) mod store;

pub use config::{BeidouSet, ConstellationConfig, ConstellationSource};
pub use klobuchar::{KlobucharCoeffs, bds_klobuchar_b1i_s, gps_klobuchar_l1_s};

pub use rinex_nav_write::{NavHeader, TimeSystemCorr, write_nav};
pub use sp3::{
    Sp3Header, Sp3Record, Sp3Series, Sp3State, parse_sp3_vehicle, read_sp3, read_sp3_vehicle,
    write_sp3,
};

pub use broadcast::{
    BoundEphemeris, BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements,
    NavMessage, OrbitClass,
};
pub use sat_id::{SatId, System};
pub use store::EphemerisStore;

/// Error reading or using navigation data.
#[derive(Debug, thiserror::Error)]
pub enum NavError {
    /// The file could not be opened or read.
    #[error("cannot read {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    /// The file content is malformed.
    #[error("{path}:{line}: {message}")]
    Format {
        path: String,
        line: usize,
        message: String,
    },
    /// No usable (healthy, in-fit) ephemeris for a satellite at the requested time.
    #[error("no ephemeris for {sat} at {epoch} in {source_name}")]
    NoEphemeris {
        sat: String,
        epoch: String,
        source_name: String,
    },
}
