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
    /// Galileo only: GST - GPST (ns) at the start's whole hour, which the satellites keep
    /// and broadcast (A0G); default 0.
    #[serde(default)]
    pub gst_gps_ns: f64,
    /// Galileo only: GST - GPST's rate (ns per day, A1G); default 0.
    #[serde(default)]
    pub gst_gps_drift_ns_per_day: f64,
}

/// Largest |GST - GPST| the broadcast carries either way: A0G's 16 bits at 2^-35 s,
/// 2^15 - 1 LSBs (ns).
pub const GST_GPS_MAX_NS: f64 = 32_767.0 * 1e9 / 34_359_738_368.0;
/// Largest |rate| A1G's 12 bits at 2^-51 s/s carry either way, 2^11 - 1 LSBs (ns per day).
pub const GST_GPS_DRIFT_MAX_NS_PER_DAY: f64 = 2_047.0 * 86_400.0 * 1e9 / 2_251_799_813_685_248.0;

fn yes() -> bool {
    true
}

impl ConstellationConfig {
    /// The GST - GPST offset this table sets, referred to `origin` (zero unless set).
    pub fn gst_gps(&self, origin: &crate::time::TimeOrigin) -> crate::time::GstGpsOffset {
        crate::time::GstGpsOffset::at_origin(
            self.gst_gps_ns * 1e-9,
            self.gst_gps_drift_ns_per_day * 1e-9 / 86_400.0,
            origin,
        )
    }

    /// The GST - GPST fields: finite and within what the broadcast carries; set only on
    /// Galileo's table (`galileo`).
    pub fn check_gst_gps(&self, galileo: bool) -> Result<(), Invalid> {
        for (field, value, max, unit) in [
            ("gst_gps_ns", self.gst_gps_ns, GST_GPS_MAX_NS, "ns"),
            (
                "gst_gps_drift_ns_per_day",
                self.gst_gps_drift_ns_per_day,
                GST_GPS_DRIFT_MAX_NS_PER_DAY,
                "ns per day",
            ),
        ] {
            if !galileo && value != 0.0 {
                return Err(Invalid::new(
                    field,
                    value,
                    "only [gnss.galileo] has a GST - GPST offset",
                ));
            }
            if !(value.is_finite() && value.abs() < max) {
                return Err(Invalid::new(
                    field,
                    value,
                    format!(
                        "must be finite and within +-{max:.3} {unit} (what the broadcast carries)"
                    ),
                ));
            }
        }
        Ok(())
    }

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
            gst_gps_ns: 0.0,
            gst_gps_drift_ns_per_day: 0.0,
        }
    }

    #[test]
    fn gst_gps_is_galileos_and_within_what_the_broadcast_carries() {
        let base = cfg(ConstellationSource::Embedded, None, None);
        let with = |ns: f64, drift: f64| ConstellationConfig {
            gst_gps_ns: ns,
            gst_gps_drift_ns_per_day: drift,
            ..base.clone()
        };
        assert_eq!(with(100.0, -5.0).check_gst_gps(true), Ok(()));
        assert_eq!(base.check_gst_gps(false), Ok(()));
        assert_eq!(
            with(100.0, 0.0).check_gst_gps(false).unwrap_err().field,
            "gst_gps_ns"
        );
        assert_eq!(with(-953.6, 78.5).check_gst_gps(true), Ok(()));
        assert_eq!(
            with(953.7, 0.0).check_gst_gps(true).unwrap_err().field,
            "gst_gps_ns"
        );
        assert_eq!(
            with(f64::NAN, 0.0).check_gst_gps(true).unwrap_err().field,
            "gst_gps_ns"
        );
        let e = with(0.0, 78.6).check_gst_gps(true).unwrap_err();
        assert_eq!(e.field, "gst_gps_drift_ns_per_day");
        // (2^15 - 1) x 2^-35 s = 953.645 ns; (2^11 - 1) x 2^-51 s/s x 86 400 s = 78.542 ns.
        assert!((GST_GPS_MAX_NS - 953.645).abs() < 1e-3);
        assert!((GST_GPS_DRIFT_MAX_NS_PER_DAY - 78.542).abs() < 1e-3);
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
