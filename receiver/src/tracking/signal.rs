//! The signals a channel tracks: ranging code, chip rate, carrier, and the data
//! modulation each PRN carries.

use skyforge_orbits::constants::{F_BDS_B1I_HZ, F_GPS_L1_HZ};
use skyforge_signals::codes::bds_b1i;
use skyforge_signals::codes::gps_ca;

use super::TrackingError;

/// A tracked signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SignalKind {
    /// GPS L1 C/A (IS-GPS-200).
    GpsL1Ca,
    /// BeiDou B1I (BDS-SIS-ICD-B1I-3.0).
    BdsB1I,
}

/// How navigation data (and any secondary code) modulate the ranging code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DataModulation {
    /// GPS LNAV: 50 bit/s, bit edges on code epochs, 20 code periods per bit
    /// (IS-GPS-200 §3.3.2.4).
    GpsLnav,
    /// BeiDou D1 (MEO/IGSO): 50 bit/s, each bit spread by the 20-chip Neumann-Hoffman code
    /// (BDS-SIS-ICD-B1I-3.0 §5.2.1).
    BdsD1,
    /// BeiDou D2 (GEO, PRN 1-5 and 59-63): 500 bit/s, 2 code periods per bit, no secondary
    /// code (BDS-SIS-ICD-B1I-3.0 §5.3).
    BdsD2,
}

impl DataModulation {
    /// Code periods per data bit.
    pub fn periods_per_bit(self) -> u32 {
        match self {
            DataModulation::GpsLnav | DataModulation::BdsD1 => 20,
            DataModulation::BdsD2 => 2,
        }
    }
}

impl SignalKind {
    /// Short name.
    pub fn name(self) -> &'static str {
        match self {
            SignalKind::GpsL1Ca => "GPS L1 C/A",
            SignalKind::BdsB1I => "BDS B1I",
        }
    }

    /// Carrier frequency (Hz).
    pub fn carrier_hz(self) -> f64 {
        match self {
            SignalKind::GpsL1Ca => F_GPS_L1_HZ,
            SignalKind::BdsB1I => F_BDS_B1I_HZ,
        }
    }

    /// Nominal chip rate (chips/s).
    pub fn chip_rate_hz(self) -> f64 {
        match self {
            SignalKind::GpsL1Ca => gps_ca::GPS_CA_CHIP_RATE_HZ,
            SignalKind::BdsB1I => bds_b1i::BDS_B1I_CHIP_RATE_HZ,
        }
    }

    /// Code length (chips); one period is 1 ms for both signals.
    pub fn code_length(self) -> usize {
        match self {
            SignalKind::GpsL1Ca => gps_ca::GPS_CA_CODE_LENGTH,
            SignalKind::BdsB1I => bds_b1i::BDS_B1I_CODE_LENGTH,
        }
    }

    /// Nominal code period (s).
    pub fn code_period_s(self) -> f64 {
        self.code_length() as f64 / self.chip_rate_hz()
    }

    /// The ranging code of `prn` as signal levels (+1/-1).
    pub fn code(self, prn: u8) -> Result<Vec<i8>, TrackingError> {
        let code = match self {
            SignalKind::GpsL1Ca => gps_ca::gps_ca(prn).map(|c| c.to_vec()),
            SignalKind::BdsB1I => bds_b1i::bds_b1i(prn),
        };
        code.ok_or(TrackingError::UnknownPrn {
            signal: self.name(),
            prn,
        })
    }

    /// The data modulation of `prn`: BeiDou GEO satellites (PRN 1-5 and 59-63) broadcast
    /// D2, the others D1 (BDS-SIS-ICD-B1I-3.0 §5.1).
    pub fn data_modulation(self, prn: u8) -> DataModulation {
        match self {
            SignalKind::GpsL1Ca => DataModulation::GpsLnav,
            SignalKind::BdsB1I if prn <= 5 || prn >= 59 => DataModulation::BdsD2,
            SignalKind::BdsB1I => DataModulation::BdsD1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_periods_are_one_millisecond() {
        for s in [SignalKind::GpsL1Ca, SignalKind::BdsB1I] {
            assert!((s.code_period_s() - 1e-3).abs() < 1e-15);
            assert_eq!(s.code(1).unwrap().len(), s.code_length());
        }
        assert!(SignalKind::GpsL1Ca.code(0).is_err());
        assert!(SignalKind::BdsB1I.code(64).is_err());
    }

    #[test]
    fn geo_prns_carry_d2() {
        let s = SignalKind::BdsB1I;
        for prn in [1, 5, 59, 63] {
            assert_eq!(s.data_modulation(prn), DataModulation::BdsD2);
        }
        for prn in [6, 19, 58] {
            assert_eq!(s.data_modulation(prn), DataModulation::BdsD1);
        }
        assert_eq!(DataModulation::BdsD2.periods_per_bit(), 2);
    }
}
