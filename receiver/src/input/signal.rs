//! The signal bands a recording can hold, identified by their carrier frequency.

use super::error::InputError;
use skyforge_orbits::constants::{F_BDS_B1I_HZ, F_GPS_L1_HZ};
use std::str::FromStr;

/// A signal the receiver processes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SignalBand {
    /// GPS L1 C/A.
    GpsL1Ca,
    /// BeiDou B1I.
    BdsB1I,
}

/// Largest difference (Hz) between a recording's stated carrier (centre + IF) and a
/// signal's nominal carrier for the two to be taken as the same.
pub const CARRIER_MATCH_TOLERANCE_HZ: f64 = 1e3;

impl SignalBand {
    /// Every signal.
    pub const ALL: [SignalBand; 2] = [SignalBand::GpsL1Ca, SignalBand::BdsB1I];

    /// Nominal carrier frequency (Hz): IS-GPS-200 §3.3.1.1 (L1 = 154 x 10.23 MHz =
    /// 1575.42 MHz); BDS-SIS-ICD-B1I-3.0 §4.2.1 (B1I nominal carrier 1561.098 MHz).
    pub fn carrier_hz(self) -> f64 {
        match self {
            SignalBand::GpsL1Ca => F_GPS_L1_HZ,
            SignalBand::BdsB1I => F_BDS_B1I_HZ,
        }
    }

    /// Command-line and file-name tag (`gps-l1ca`, `bds-b1i`), as in SkyForge's
    /// `<antenna>.<tag>.sigmf-meta` file names.
    pub fn tag(self) -> &'static str {
        match self {
            SignalBand::GpsL1Ca => "gps-l1ca",
            SignalBand::BdsB1I => "bds-b1i",
        }
    }

    /// The signal whose carrier is within [`CARRIER_MATCH_TOLERANCE_HZ`] of `carrier_hz`.
    pub fn from_carrier_hz(carrier_hz: f64) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|s| (s.carrier_hz() - carrier_hz).abs() <= CARRIER_MATCH_TOLERANCE_HZ)
    }

    /// The only signal whose carrier lies inside the band recorded about `centre_hz`
    /// (complex: `|carrier - centre| < fs / 2`), or `None` when none or several do.
    pub fn in_band(centre_hz: f64, sample_rate_hz: f64) -> Option<Self> {
        let mut inside = Self::ALL
            .into_iter()
            .filter(|s| (s.carrier_hz() - centre_hz).abs() < sample_rate_hz / 2.0);
        match (inside.next(), inside.next()) {
            (Some(s), None) => Some(s),
            _ => None,
        }
    }

    /// The signal named by a `.<tag>` component of a file name
    /// (`ant1.gps-l1ca.sigmf-meta`).
    pub fn from_file_name(name: &str) -> Option<Self> {
        Self::ALL
            .into_iter()
            .find(|s| name.split('.').any(|part| part == s.tag()))
    }
}

impl std::fmt::Display for SignalBand {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.tag())
    }
}

impl FromStr for SignalBand {
    type Err = InputError;
    /// A command-line `--signal` value.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|b| b.tag().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| InputError::InvalidParameter {
                name: "--signal",
                value: s.to_owned(),
                allowed: "gps-l1ca or bds-b1i".to_owned(),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn carriers_are_the_icd_multiples_of_the_fundamental() {
        // GPS: 154 f0 with f0 = 10.23 MHz; BeiDou B1I: 1526 x 1.023 MHz.
        assert_eq!(SignalBand::GpsL1Ca.carrier_hz(), 154.0 * 10.23e6);
        assert!((SignalBand::BdsB1I.carrier_hz() - 1526.0 * 1.023e6).abs() < 1e-3);
    }

    #[test]
    fn identified_by_carrier_band_and_file_name() {
        assert_eq!(
            SignalBand::from_carrier_hz(1575.42e6 - 400.0),
            Some(SignalBand::GpsL1Ca)
        );
        assert_eq!(SignalBand::from_carrier_hz(1575.0e6), None);
        assert_eq!(
            SignalBand::in_band(1561.098e6 - 1.0e6, 4e6),
            Some(SignalBand::BdsB1I)
        );
        assert_eq!(SignalBand::in_band(1568.0e6, 40e6), None);
        assert_eq!(
            SignalBand::from_file_name("ant2.bds-b1i.sigmf-meta"),
            Some(SignalBand::BdsB1I)
        );
        assert_eq!(SignalBand::from_file_name("ant2.sigmf-meta"), None);
    }

    #[test]
    fn parses_the_cli_values() {
        assert_eq!(
            "GPS-L1CA".parse::<SignalBand>().unwrap(),
            SignalBand::GpsL1Ca
        );
        let e = "gal-e1".parse::<SignalBand>().unwrap_err().to_string();
        assert_eq!(
            e,
            "invalid --signal \"gal-e1\": allowed: gps-l1ca or bds-b1i"
        );
    }
}
