//! Scenario configuration of one constellation.

use crate::check::Invalid;
use std::path::PathBuf;

/// Where a constellation's orbits come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ConstellationSource {
    /// The embedded nominal constellation (GPS: nominal slots; BeiDou: see `embedded_set`).
    #[default]
    Embedded,
    /// A RINEX 2/3/4 navigation file given in `nav_file`.
    Rinex,
}

/// Which embedded BeiDou constellation to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum BeidouSet {
    /// BDS-3: 24 MEO (Walker 24/3/1), 3 IGSO, 3 GEO.
    #[default]
    Bds3,
    /// BDS-2: 5 GEO, 7 IGSO, 3 MEO (the 2018 operational set).
    Bds2,
}

/// `[gnss.gps]` / `[gnss.beidou]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstellationConfig {
    /// Include this constellation.
    #[serde(default = "yes")]
    pub enabled: bool,
    #[serde(default)]
    pub source: ConstellationSource,
    /// RINEX navigation file (plain or `.gz`), relative paths from the scenario file.
    #[serde(default)]
    pub nav_file: Option<PathBuf>,
    /// Embedded BeiDou set (ignored for GPS).
    #[serde(default)]
    pub embedded_set: BeidouSet,
    /// Only these PRNs (default: all available).
    #[serde(default)]
    pub prns: Option<Vec<u8>>,
}

fn yes() -> bool {
    true
}

impl ConstellationConfig {
    /// Cross-field checks that need no file access (PRN range, nav_file iff rinex).
    pub fn check(&self, max_prn: u8) -> Result<(), Invalid> {
        todo!("{max_prn}")
    }
}
