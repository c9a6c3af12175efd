//! RINEX 3 observation codes (band and attribute, RINEX 3.04 tables 4 and 9) of each
//! signal: what the writer names it and what the reader takes for it. A signal that
//! several trackings measure (GPS L2: P(Y) semi-codeless or L2C) has several codes; a file
//! may carry more than one of them, and the reader then takes one code per signal for the
//! whole file, the first of this table's list the file has, so that every satellite's
//! observation of the signal comes from the same tracking.

use crate::signal::Signal;

/// The codes of `signal`, preferred first; the first is what SkyForge writes (for GPS and
/// BeiDou each system's reference signal for the phase, RINEX 3.04 table A23, so no phase
/// shift applies; for Galileo the pilot, 1C and 5Q, as pilot-tracking receivers write; BeiDou B2a and B1C likewise their pilots, 5P and 1P). BeiDou B1I is also `1I` in files before RINEX 3.03 ([`codes_in_version`]), where band 1 is never B1C.
pub fn codes(signal: Signal) -> &'static [&'static str] {
    match signal {
        Signal::GpsL1Ca => &["1C"],
        // P(Y) (what RINEX 2's `P2`/`L2` of a geodetic receiver are), then L2C.
        Signal::GpsL2 => &["2W", "2P", "2X", "2L", "2S"],
        Signal::GpsL5 => &["5I", "5X", "5Q"],
        Signal::BdsB1I => &["2I"],
        Signal::BdsB2I => &["7I"],
        Signal::BdsB3I => &["6I"],
        // Pilot tracking (E1-C, E5a-Q), then data + pilot, then data alone.
        Signal::GalE1 => &["1C", "1X", "1B"],
        Signal::GalE5a => &["5Q", "5X", "5I"],
        // B2a pilot (B2a_p), then data + pilot, then data (RINEX 3.04 table 9 band 5).
        Signal::BdsB2a => &["5P", "5X", "5D"],
        // B1C pilot, then data + pilot, then data (RINEX 3.04 table 9 band 1, from 3.03 on).
        Signal::BdsB1C => &["1P", "1X", "1D"],
    }
}

/// The code SkyForge writes for `signal`.
pub fn written_code(signal: Signal) -> &'static str {
    codes(signal)[0]
}

/// The signal `band_attribute` (e.g. `2W`) names for a satellite of `signal`'s system in a
/// file of RINEX version `major.minor`, with its rank in [`codes`] (0: preferred). RINEX
/// 3.02 names B1I band 1 (`1I`); 3.03 renamed it band 2 and gave band 1 to B1C.
pub fn classify(
    system: skyforge_orbits::ephemeris::System,
    band_attribute: &str,
    major: u8,
    minor: u8,
) -> Option<(Signal, usize)> {
    if system == skyforge_orbits::ephemeris::System::Beidou
        && band_attribute.starts_with('1')
        && (major, minor) < (3, 3)
    {
        // Before 3.03 band 1 is B1I (1I, 1Q, 1X): never B1C.
        return (band_attribute == "1I").then_some((Signal::BdsB1I, 0));
    }
    Signal::ALL
        .into_iter()
        .filter(|s| s.system() == system)
        .find_map(|s| {
            codes(s)
                .iter()
                .position(|c| *c == band_attribute)
                .map(|rank| (s, rank))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::ephemeris::System;

    /// Every code names one signal of one system, and the written code reads back as its
    /// signal at rank 0.
    #[test]
    fn codes_are_unique_and_written_codes_read_back() {
        for s in Signal::ALL {
            assert_eq!(
                classify(s.system(), written_code(s), 3, 4),
                Some((s, 0)),
                "{s}"
            );
            for t in Signal::ALL
                .into_iter()
                .filter(|t| *t != s && t.system() == s.system())
            {
                assert!(codes(s).iter().all(|c| !codes(t).contains(c)), "{s} {t}");
            }
        }
        assert_eq!(classify(System::Gps, "2L", 3, 4), Some((Signal::GpsL2, 3)));
        assert_eq!(
            classify(System::Beidou, "1I", 3, 2),
            Some((Signal::BdsB1I, 0))
        );
        assert_eq!(classify(System::Beidou, "1I", 3, 4), None);
        assert_eq!(classify(System::Gps, "7I", 3, 4), None);
        // B1C's band 1 from RINEX 3.03 on; before it band 1 was B1I's.
        assert_eq!(
            classify(System::Beidou, "1D", 3, 4),
            Some((Signal::BdsB1C, 2))
        );
        assert_eq!(classify(System::Beidou, "1X", 3, 2), None);
    }
}
