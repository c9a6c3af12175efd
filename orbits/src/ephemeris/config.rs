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
    /// Cross-field checks that need no file access (PRN range, at least one PRN when the
    /// constellation is enabled, nav_file iff rinex).
    pub fn check(&self, max_prn: u8) -> Result<(), Invalid> {
        if self.enabled && self.prns.as_ref().is_some_and(Vec::is_empty) {
            return Err(Invalid::new(
                "prns",
                "[]",
                format!(
                    "must list at least one PRN in 1..={max_prn} (leave prns out for every \
                     satellite, or set enabled = false)"
                ),
            ));
        }
        if let Some(prns) = &self.prns {
            let mut seen = std::collections::BTreeSet::new();
            for &prn in prns {
                if prn == 0 || prn > max_prn {
                    return Err(Invalid::new(
                        "prns",
                        prn,
                        format!("each PRN must be in 1..={max_prn}"),
                    ));
                }
                if !seen.insert(prn) {
                    return Err(Invalid::new("prns", prn, "PRNs must not repeat"));
                }
            }
        }
        match (self.source, &self.nav_file) {
            (ConstellationSource::Rinex, None) => Err(Invalid::new(
                "nav_file",
                "(missing)",
                "required when source = \"rinex\"",
            )),
            (ConstellationSource::Embedded, Some(_)) => Err(Invalid::new(
                "source",
                "embedded",
                "must be \"rinex\" when nav_file is given (or remove nav_file)",
            )),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(
        source: ConstellationSource,
        nav: Option<&str>,
        prns: Option<Vec<u8>>,
    ) -> ConstellationConfig {
        ConstellationConfig {
            enabled: true,
            source,
            nav_file: nav.map(PathBuf::from),
            embedded_set: BeidouSet::Bds3,
            prns,
        }
    }

    #[test]
    fn accepts_valid_configs() {
        assert_eq!(
            cfg(ConstellationSource::Embedded, None, None).check(32),
            Ok(())
        );
        assert_eq!(
            cfg(
                ConstellationSource::Rinex,
                Some("brdc.n"),
                Some(vec![1, 32])
            )
            .check(32),
            Ok(())
        );
    }

    #[test]
    fn prn_range_and_uniqueness() {
        let e = cfg(ConstellationSource::Embedded, None, Some(vec![1, 33]))
            .check(32)
            .unwrap_err();
        assert_eq!((e.field.as_str(), e.value.as_str()), ("prns", "33"));
        let e = cfg(ConstellationSource::Embedded, None, Some(vec![0]))
            .check(32)
            .unwrap_err();
        assert_eq!(e.field, "prns");
        let e = cfg(ConstellationSource::Embedded, None, Some(vec![5, 6, 5]))
            .check(63)
            .unwrap_err();
        assert_eq!((e.field.as_str(), e.value.as_str()), ("prns", "5"));
    }

    #[test]
    fn nav_file_iff_rinex() {
        let e = cfg(ConstellationSource::Rinex, None, None)
            .check(32)
            .unwrap_err();
        assert_eq!(e.field, "nav_file");
        let e = cfg(ConstellationSource::Embedded, Some("x.rnx"), None)
            .check(32)
            .unwrap_err();
        assert_eq!((e.field.as_str(), e.value.as_str()), ("source", "embedded"));
    }
}
