//! The IMU grades, each with its source. Values a source leaves open are marked
//! `assumed` with the reason; none was changed after a run.

use super::config::{AccelSpec, GyroSpec, ImuConfig, ImuGrade, TriadErrors};

/// Paper 001's laser-gyro SINS (section 3.1): gyro drift stability 0.005 deg/h (1 sigma),
/// which its filter treats as a random constant; the accelerometer bias's exponent is lost
/// in the source (`5x10^? g`).
pub const NAVIGATION: (GyroSpec, AccelSpec) = (
    GyroSpec {
        bias_deg_h: 0.005,
        instability_deg_h: 0.0, // the paper's filter: a random constant
        instability_tau_s: 3600.0,
        arw_deg_rth: 0.002, // assumed: El-Sheimy & Youssef 2020 Table 1, navigation grade
        scale_factor_ppm: 5.0, // assumed: ring-laser gyros hold a few ppm
        misalignment_mrad: 0.02, // assumed: a calibrated navigation-grade cluster
        quantum_urad: 1.0,  // assumed: a ring-laser's counts are of order a micro-radian
    },
    AccelSpec {
        bias_ug: 50.0, // assumed: 5e-5 g, the digest's reading of the lost exponent
        instability_ug: 0.0,
        instability_tau_s: 3600.0,
        vrw_mps_rth: 0.003,     // assumed: a navigation-grade servo accelerometer
        scale_factor_ppm: 50.0, // assumed: the same class
        misalignment_mrad: 0.02,
        quantum_umps: 100.0, // assumed: 0.1 mm/s per count
    },
);

/// Tactical grade: gyro drift 1 deg/h and accelerometer bias 1 mg, the lower ends of El-Sheimy
/// & Youssef 2020 (Satellite Navigation 1:2) Table 1's tactical column (1-10 deg/h,
/// 1-5 mg).
pub const TACTICAL: (GyroSpec, AccelSpec) = (
    GyroSpec {
        bias_deg_h: 1.0,
        instability_deg_h: 0.5, // assumed: half the drift, over an hour
        instability_tau_s: 3600.0,
        arw_deg_rth: 0.1,        // assumed: a fibre-optic gyro of the class
        scale_factor_ppm: 300.0, // assumed
        misalignment_mrad: 0.5,  // assumed
        quantum_urad: 0.0,
    },
    AccelSpec {
        bias_ug: 1000.0,
        instability_ug: 50.0, // assumed
        instability_tau_s: 3600.0,
        vrw_mps_rth: 0.05,       // assumed
        scale_factor_ppm: 300.0, // assumed
        misalignment_mrad: 0.5,
        quantum_umps: 0.0,
    },
);

/// Consumer MEMS: gyro drift 0.1 deg/s (360 deg/h) and accelerometer bias 1000 micro-g, El-Sheimy
/// & Youssef 2020 Table 1's commercial column.
pub const CONSUMER: (GyroSpec, AccelSpec) = (
    GyroSpec {
        bias_deg_h: 360.0,
        instability_deg_h: 10.0, // assumed: a phone-class MEMS gyro's Allan minimum
        instability_tau_s: 300.0,
        arw_deg_rth: 0.5,         // assumed
        scale_factor_ppm: 3000.0, // assumed
        misalignment_mrad: 2.0,   // assumed
        quantum_urad: 0.0,
    },
    AccelSpec {
        bias_ug: 1000.0,
        instability_ug: 100.0, // assumed
        instability_tau_s: 300.0,
        vrw_mps_rth: 0.2,         // assumed
        scale_factor_ppm: 3000.0, // assumed
        misalignment_mrad: 2.0,
        quantum_umps: 0.0,
    },
);

/// The book's Table 3-1 SINS (1 sigma): gyro drift 0.5 deg/h as a first-order Markov
/// process of 1 h, gyro white 0.005 deg/h; accelerometer bias 5e-4 g of 0.5 h, white
/// 5e-6 g. The book gives the white terms without a bandwidth: taken as densities per
/// root hertz (assumed), so 0.005 deg/h/sqrt(Hz) = 0.005/60 deg/sqrt(h) and
/// 5e-6 g/sqrt(Hz) = 60 x 9.80665 x 5e-6 m/s/sqrt(h).
pub const BOOK_TABLE_3_1: (GyroSpec, AccelSpec) = (
    GyroSpec {
        bias_deg_h: 0.0,
        instability_deg_h: 0.5,
        instability_tau_s: 3600.0,
        arw_deg_rth: 0.005 / 60.0,
        scale_factor_ppm: 0.0,
        misalignment_mrad: 0.0,
        quantum_urad: 0.0,
    },
    AccelSpec {
        bias_ug: 0.0,
        instability_ug: 500.0,
        instability_tau_s: 1800.0,
        vrw_mps_rth: 60.0 * 9.806_65 * 5e-6,
        scale_factor_ppm: 0.0,
        misalignment_mrad: 0.0,
        quantum_umps: 0.0,
    },
);

impl ImuConfig {
    /// The gyros' and accelerometers' errors in SI units: the grade's preset, or
    /// `[imu.gyro]` and `[imu.accel]` for `grade = "custom"`.
    pub fn errors(&self) -> (TriadErrors, TriadErrors) {
        let (g, a) = match (self.grade, self.gyro, self.accel) {
            (ImuGrade::Custom, Some(g), Some(a)) => return (g.into(), a.into()),
            (ImuGrade::Ideal | ImuGrade::Custom, ..) => {
                return (TriadErrors::NONE, TriadErrors::NONE);
            }
            (ImuGrade::Navigation, ..) => NAVIGATION,
            (ImuGrade::Tactical, ..) => TACTICAL,
            (ImuGrade::Consumer, ..) => CONSUMER,
            (ImuGrade::BookTable31, ..) => BOOK_TABLE_3_1,
        };
        (g.into(), a.into())
    }
}
