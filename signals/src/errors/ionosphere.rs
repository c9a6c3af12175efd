//! Ionospheric group delay: the broadcast Klobuchar models of GPS and BeiDou, frequency
//! scaling, and the reduction for a receiver above part of the ionosphere.
//!
//! Sign convention (metres): the ionosphere delays the code and advances the carrier by
//! the same first-order amount, so a pseudorange gains `+d` and a carrier-phase range
//! (`lambda * phi`) gains `-d` ([`IonoDelay`]; Yuan 2000 eqs. 5-20/5-21).
//!
//! Receiver height (Yuan 2000 section 5.4.1, L5309 and L5360 of the source text): the
//! Klobuchar value is computed as for a ground user under the receiver (same elevation and
//! azimuth, the book's method 1) and multiplied by the fraction of the ionospheric error
//! that lies above the receiver, [`remaining_fraction`]: piecewise linear through the
//! book's figures, 1 at or below 100 km (the book puts the neutral atmosphere below
//! 100 km), 0.4 at 350 km ("60 % of the error is below 350 km"), 0.3 at 400 km, 0.1 at
//! 500 km, 0 from 700 km ("the ionospheric delay is essentially below 700 km").
//! `leo_scale` replaces that profile by a constant for receivers above 100 km.
//! Elevations below 0 (seen from orbit) are evaluated at 0: the models do not describe
//! limb paths.

use skyforge_orbits::check::{Allowed, Invalid};
use skyforge_orbits::constants::{C_MPS, F_BDS_B1I_HZ, F_GPS_L1_HZ};
use skyforge_orbits::ephemeris::System;
use skyforge_orbits::frames::Geodetic;

pub use skyforge_orbits::ephemeris::{KlobucharCoeffs, bds_klobuchar_b1i_s, gps_klobuchar_l1_s};

/// Height below which the whole ionosphere is above the receiver (m).
pub const FULL_IONOSPHERE_BELOW_M: f64 = 100e3;
/// (height m, fraction of the ground delay above it): Yuan 2000 section 5.4.1.
const HEIGHT_PROFILE: [(f64, f64); 5] = [
    (FULL_IONOSPHERE_BELOW_M, 1.0),
    (350e3, 0.4),
    (400e3, 0.3),
    (500e3, 0.1),
    (700e3, 0.0),
];

/// Default GPS set: `ION ALPHA` / `ION BETA` of the IGS broadcast file `brdc0010.22n`
/// (2022-01-01).
pub const GPS_DEFAULT_COEFFS: KlobucharCoeffs = KlobucharCoeffs {
    alpha: [0.1211e-7, -0.7451e-8, -0.5960e-7, 0.1192e-6],
    beta: [0.1167e6, -0.2458e6, -0.6554e5, 0.1114e7],
};

/// Default BeiDou set: `ION C05 D1D2` of 2023-03-12 00:00 BDT in the DLR broadcast file
/// `BRD400DLR_S_20230710000_01D_MN.rnx`.
pub const BDS_DEFAULT_COEFFS: KlobucharCoeffs = KlobucharCoeffs {
    alpha: [
        4.190951585770e-8,
        4.395842552185e-7,
        -2.861022949219e-6,
        3.576278686523e-6,
    ],
    beta: [8.3968e4, 9.99424e5, -7.798784e6, 8.323072e6],
};

/// First-order scaling of an ionospheric delay from `f_ref_hz` to `f_hz`: `(f_ref/f)^2`.
pub fn scale_to_frequency(delay_at_ref: f64, f_ref_hz: f64, f_hz: f64) -> f64 {
    delay_at_ref * (f_ref_hz / f_hz).powi(2)
}

/// Fraction of the ground ionospheric delay that lies above a receiver at `height_m`
/// (module docs; Yuan 2000 section 5.4.1).
pub fn remaining_fraction(height_m: f64) -> f64 {
    let (h_first, f_first) = HEIGHT_PROFILE[0];
    if height_m <= h_first {
        return f_first;
    }
    for pair in HEIGHT_PROFILE.windows(2) {
        let ((h0, f0), (h1, f1)) = (pair[0], pair[1]);
        if height_m <= h1 {
            return f0 + (f1 - f0) * (height_m - h0) / (h1 - h0);
        }
    }
    0.0
}

/// The ionospheric effect on one signal (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IonoDelay {
    /// Added to the pseudorange (group delay, >= 0).
    pub code_m: f64,
    /// Added to the carrier-phase range: `-code_m` (phase advance).
    pub carrier_m: f64,
}

/// Ionosphere model choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IonoModel {
    /// GPS satellites: IS-GPS-200 Klobuchar; BeiDou satellites: the BDS variant.
    Klobuchar,
    Off,
}

/// `[errors.ionosphere]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IonoConfig {
    pub model: IonoModel,
    /// Constant fraction of the ground delay for a receiver above 100 km, replacing the
    /// height profile (in [0, 1]).
    #[serde(default)]
    pub leo_scale: Option<f64>,
    /// Factor on the delay the model gives (a storm: 3 triples it), while the broadcast
    /// coefficients stay those of `gps` and `bds`, so a single-frequency user's model
    /// misses the difference and a dual-frequency user removes it (default 1).
    #[serde(default = "unit_scale")]
    pub scale: f64,
    /// GPS coefficients (default [`GPS_DEFAULT_COEFFS`]).
    #[serde(default = "gps_default")]
    pub gps: KlobucharCoeffs,
    /// BeiDou coefficients (default [`BDS_DEFAULT_COEFFS`]).
    #[serde(default = "bds_default")]
    pub bds: KlobucharCoeffs,
}

fn unit_scale() -> f64 {
    1.0
}
fn gps_default() -> KlobucharCoeffs {
    GPS_DEFAULT_COEFFS
}
fn bds_default() -> KlobucharCoeffs {
    BDS_DEFAULT_COEFFS
}

impl Default for IonoConfig {
    /// Klobuchar with the default coefficient sets and the height profile.
    fn default() -> Self {
        Self {
            model: IonoModel::Klobuchar,
            leo_scale: None,
            scale: 1.0,
            gps: GPS_DEFAULT_COEFFS,
            bds: BDS_DEFAULT_COEFFS,
        }
    }
}

/// assumed: ten times the model's delay is beyond the strongest storms' (a Klobuchar day
/// peaks near 30 m on L1; storms have reached about 100 m).
const STORM_SCALE: Allowed = Allowed::closed(0.0, 10.0, "");

/// The largest magnitudes of the Klobuchar coefficients (alpha_0..3 in s, s/semicircle^n;
/// beta_0..3 in s, s/semicircle^n): 8-bit two's complement fields, 128 times their scale
/// factors 2^-30, 2^-27, 2^-24, 2^-24 and 2^11, 2^14, 2^16, 2^16 (IS-GPS-200 section
/// 20.3.3.5.1, Table 20-X; the BeiDou D1/D2 fields have the same, BDS-SIS-ICD-B1I
/// section 5.2.4.7).
pub const COEFFICIENT_RANGE: ([f64; 4], [f64; 4]) = (
    [
        128.0 / 1_073_741_824.0,
        128.0 / 134_217_728.0,
        128.0 / 16_777_216.0,
        128.0 / 16_777_216.0,
    ],
    [
        128.0 * 2048.0,
        128.0 * 16_384.0,
        128.0 * 65_536.0,
        128.0 * 65_536.0,
    ],
);

impl IonoConfig {
    /// Checks: `leo_scale` in [0, 1]; `scale` in [0, 10]; every coefficient within what the navigation
    /// message can broadcast ([`COEFFICIENT_RANGE`]: SkyForge writes them into its
    /// navigation files and messages).
    pub fn check(&self) -> Result<(), Invalid> {
        if let Some(s) = self.leo_scale
            && !(0.0..=1.0).contains(&s)
        {
            return Err(Invalid::new("leo_scale", s, "must be in [0, 1]"));
        }
        STORM_SCALE.check("scale", self.scale)?;
        for (name, set) in [("gps", &self.gps), ("bds", &self.bds)] {
            for (part, values, ranges) in [
                ("alpha", &set.alpha, &COEFFICIENT_RANGE.0),
                ("beta", &set.beta, &COEFFICIENT_RANGE.1),
            ] {
                for (i, (&v, &limit)) in values.iter().zip(ranges).enumerate() {
                    Allowed::closed(-limit, limit, "").check(&format!("{name}.{part}[{i}]"), v)?;
                }
            }
        }
        Ok(())
    }

    /// Fraction of the ground delay applied to a receiver at `height_m`.
    pub fn height_factor(&self, height_m: f64) -> f64 {
        match self.leo_scale {
            Some(s) if height_m > FULL_IONOSPHERE_BELOW_M => s,
            _ => remaining_fraction(height_m),
        }
    }

    /// Delay of a signal at `carrier_hz` from a `system` satellite seen at `az_rad`,
    /// `el_rad` from `rx`, at `t_system_s` (the system's own time scale, seconds from any
    /// of its midnights).
    pub fn delay(
        &self,
        system: System,
        rx: &Geodetic,
        az_rad: f64,
        el_rad: f64,
        t_system_s: f64,
        carrier_hz: f64,
    ) -> IonoDelay {
        let code_m = match self.model {
            IonoModel::Off => 0.0,
            IonoModel::Klobuchar => {
                let (delay_s, f_ref_hz) = match system {
                    // Galileo's own model (NeQuick-G) is not simulated: its signals take the
                    // GPS coefficients' delay, scaled to their carrier (GST's seconds of
                    // day are GPST's).
                    System::Gps | System::Galileo => (
                        gps_klobuchar_l1_s(
                            &self.gps, rx.lat_rad, rx.lon_rad, az_rad, el_rad, t_system_s,
                        ),
                        F_GPS_L1_HZ,
                    ),
                    System::Beidou => (
                        bds_klobuchar_b1i_s(
                            &self.bds, rx.lat_rad, rx.lon_rad, az_rad, el_rad, t_system_s,
                        ),
                        F_BDS_B1I_HZ,
                    ),
                };
                scale_to_frequency(delay_s * C_MPS, f_ref_hz, carrier_hz)
                    * self.height_factor(rx.h_m)
                    * self.scale
            }
        };
        IonoDelay {
            code_m,
            carrier_m: -code_m,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue #33 (14): an alpha of 1e30 passed "finite" and failed later with exit 1.
    #[test]
    fn coefficients_beyond_what_is_broadcast_are_refused() {
        IonoConfig::default().check().unwrap();
        let mut c = IonoConfig::default();
        c.gps.alpha[0] = 1e30;
        let e = c.check().unwrap_err();
        assert_eq!(e.field, "gps.alpha[0]", "{e}");
        let mut c = IonoConfig::default();
        c.bds.beta[3] = -9.0e6;
        assert_eq!(c.check().unwrap_err().field, "bds.beta[3]");
        c.bds.beta[3] = -8.3e6;
        c.check().unwrap();
    }
}
