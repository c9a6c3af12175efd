//! Acquisition: parallel code-phase search (PCPS) and the PMF-FFT of thesis section 3.3.1.
//!
//! - [`pcps`]: FFT circular correlation over a Doppler grid, coherent and non-coherent
//!   integration, a CFAR decision ([`cfar`]), optional bit-transition-safe windows.
//! - [`pmf_fft`]: partial matched filters + FFT with the fine Doppler estimator of thesis
//!   eq. 3.3-13/3.3-14, and its noise theory (eq. 3.3-45..3.3-55) in [`pmf_fft::theory`].
//! - [`replica`]: ranging-code replicas at any sample rate and the carrier wipe-off.

pub mod cfar;
pub mod pcps;
pub mod pmf_fft;
pub mod replica;

/// The complex `f32` sample type the acquisition functions take.
pub use num_complex::Complex32;

use skyforge_signals::codes::bds_b1i;
use skyforge_signals::codes::gps_ca;

/// Why an acquisition could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AcquisitionError {
    #[error("PRN {prn} has no {signal} ranging code (allowed: 1..={max})")]
    UnknownPrn { signal: Signal, prn: u8, max: u8 },
    #[error("{name} = {value} is not allowed: {allowed}")]
    BadParameter {
        name: &'static str,
        value: f64,
        allowed: &'static str,
    },
    #[error("the search needs {needed} samples but only {got} were given")]
    TooFewSamples { needed: usize, got: usize },
}

/// The signals the bundled receiver acquires.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Signal {
    /// GPS L1 C/A: 1023 chips at 1.023 Mchip/s (IS-GPS-200 §3.3.2.3).
    GpsL1Ca,
    /// BeiDou B1I: 2046 chips at 2.046 Mchip/s (BDS-SIS-ICD-B1I §4.3).
    BdsB1I,
}

impl std::fmt::Display for Signal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Signal::GpsL1Ca => "GPS L1 C/A",
            Signal::BdsB1I => "BeiDou B1I",
        })
    }
}

impl Signal {
    /// Chipping rate (chip/s).
    pub fn chip_rate_hz(self) -> f64 {
        match self {
            Signal::GpsL1Ca => gps_ca::GPS_CA_CHIP_RATE_HZ,
            Signal::BdsB1I => bds_b1i::BDS_B1I_CHIP_RATE_HZ,
        }
    }

    /// Chips per code period.
    pub fn code_length(self) -> usize {
        match self {
            Signal::GpsL1Ca => gps_ca::GPS_CA_CODE_LENGTH,
            Signal::BdsB1I => bds_b1i::BDS_B1I_CODE_LENGTH,
        }
    }

    /// Code period (s): 1 ms for both signals.
    pub fn code_period_s(self) -> f64 {
        self.code_length() as f64 / self.chip_rate_hz()
    }

    /// One code period of `prn` as signal levels (+1/-1), chip 0 first.
    pub fn code(self, prn: u8) -> Result<Vec<i8>, AcquisitionError> {
        let (code, max) = match self {
            Signal::GpsL1Ca => (gps_ca::gps_ca(prn).map(Vec::from), gps_ca::GPS_CA_PRN_MAX),
            Signal::BdsB1I => (bds_b1i::bds_b1i(prn), bds_b1i::BDS_B1I_PRN_MAX),
        };
        code.ok_or(AcquisitionError::UnknownPrn {
            signal: self,
            prn,
            max,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn code_lengths_and_periods_follow_the_icds() {
        assert_eq!(Signal::GpsL1Ca.code(1).unwrap().len(), 1023);
        assert_eq!(Signal::BdsB1I.code(1).unwrap().len(), 2046);
        assert!((Signal::GpsL1Ca.code_period_s() - 1e-3).abs() < 1e-15);
        assert!((Signal::BdsB1I.code_period_s() - 1e-3).abs() < 1e-15);
        assert!(matches!(
            Signal::GpsL1Ca.code(0),
            Err(AcquisitionError::UnknownPrn { prn: 0, .. })
        ));
    }
}
