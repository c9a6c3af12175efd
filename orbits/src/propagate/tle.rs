//! Initial state from a TLE through SGP4 (the `sgp4` crate, Vallado's 2006 revision of
//! the reference implementation), in its AFSPC compatibility mode: WGS-72 constants, as the
//! element sets are fitted with, and the mode that reproduces the published verification
//! output (`tcppver.out`) exactly. (The crate's default WGS-84 mode differs by ~20 m.)
//!
//! The TLE is propagated from its epoch to the scenario start; SGP4's output frame, TEME
//! (true equator, mean equinox of date), is taken as the scenario ECI frame. TEME and the
//! true-of-date frame differ by a rotation about Z by the equation of the equinoxes
//! (< 1.2 arcsec, i.e. < 40 m along track at LEO radius); that and precession-nutation
//! towards J2000 (the frame the Earth-rotation-only ECI <-> ECEF transformation stands for)
//! are neglected, consistent with that transformation's own documented simplification.

use super::PropagateError;
use super::config::TleConfig;
use crate::Vec3;
use crate::check::Invalid;
use hifitime::{Duration, Epoch};

/// The parsed TLE, its SGP4 constants and its epoch.
#[derive(Debug, Clone)]
pub struct Tle {
    constants: sgp4::Constants,
    epoch: Epoch,
}

impl Tle {
    /// Parse the two lines and initialise SGP4. Errors carry the `sgp4` message.
    pub fn parse(cfg: &TleConfig) -> Result<Self, PropagateError> {
        let elements = sgp4::Elements::from_tle(
            None,
            cfg.line1.trim().as_bytes(),
            cfg.line2.trim().as_bytes(),
        )
        .map_err(|e| PropagateError::Tle(e.to_string()))?;
        let constants = sgp4::Constants::from_elements_afspc_compatibility_mode(&elements)
            .map_err(|e| PropagateError::Tle(e.to_string()))?;
        // The TLE epoch is UTC; chrono's Unix time stamp does not count leap seconds,
        // exactly like hifitime's Unix-time constructor.
        let unix = elements.datetime.and_utc();
        let nanos = i128::from(unix.timestamp()) * 1_000_000_000
            + i128::from(unix.timestamp_subsec_nanos());
        let epoch = Epoch::from_unix_duration(Duration::from_total_nanoseconds(nanos));
        Ok(Self { constants, epoch })
    }

    /// The TLE epoch (UTC).
    #[cfg(test)]
    pub fn epoch(&self) -> Epoch {
        self.epoch
    }

    /// TEME position (m) and velocity (m/s) at `epoch` (elapsed SI time since the TLE
    /// epoch, leap seconds included).
    pub fn state_teme(&self, epoch: Epoch) -> Result<(Vec3, Vec3), PropagateError> {
        let minutes = (epoch - self.epoch).to_seconds() / 60.0;
        let prediction = self
            .constants
            .propagate_afspc_compatibility_mode(sgp4::MinutesSinceEpoch(minutes))
            .map_err(|e| PropagateError::Tle(e.to_string()))?;
        let r = Vec3::from(prediction.position) * 1e3;
        let v = Vec3::from(prediction.velocity) * 1e3;
        Ok((r, v))
    }
}

impl TleConfig {
    /// The TLE parses: the scenario check of `[platform.tle]`.
    pub(crate) fn check(&self) -> Result<(), Invalid> {
        match Tle::parse(self) {
            Ok(_) => Ok(()),
            Err(err) => {
                let msg = err.to_string();
                let (field, value) = if msg.contains("line 2") {
                    ("line2", self.line2.as_str())
                } else if msg.contains("line 1") {
                    ("line1", self.line1.as_str())
                } else {
                    ("", "")
                };
                let value = if field.is_empty() {
                    format!("{:?} / {:?}", self.line1, self.line2)
                } else {
                    format!("{value:?}")
                };
                Err(Invalid::new(
                    field,
                    value,
                    format!("must be a valid two-line element set ({msg})"),
                ))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::GM_GPS;
    use crate::propagate::elements::KeplerianElements;

    fn cfg(line1: &str, line2: &str) -> TleConfig {
        TleConfig {
            line1: line1.to_string(),
            line2: line2.to_string(),
        }
    }

    /// Vallado et al., "Revisiting Spacetrack Report #3", AIAA 2006-6753, verification
    /// satellite 00005 (file tcppver.out): states at 0 and 360 min after the epoch.
    #[test]
    fn vallado_verification_satellite_00005() {
        let tle = Tle::parse(&cfg(
            "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753",
            "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667",
        ))
        .unwrap();
        // Epoch 2000 day 179.78495062 = 2000-06-27 18:50:19.733568 UTC.
        let expected_epoch = Epoch::from_gregorian_utc(2000, 6, 27, 18, 50, 19, 733_568_000);
        assert!(((tle.epoch() - expected_epoch).to_seconds()).abs() < 1e-6);
        let cases = [
            (
                0.0,
                [7022.46529266, -1400.08296755, 0.03995155],
                [1.893841015, 6.405893759, 4.534807250],
            ),
            (
                360.0,
                [-7154.03120202, -3783.17682504, -3536.19412294],
                [4.741887409, -4.151817765, -2.093935425],
            ),
        ];
        for (minutes, r_km, v_kms) in cases {
            let epoch = expected_epoch + Duration::from_seconds(minutes * 60.0);
            let (r, v) = tle.state_teme(epoch).unwrap();
            assert!(
                (r - Vec3::from(r_km) * 1e3).norm() < 0.1,
                "{minutes} min: {r}"
            );
            assert!(
                (v - Vec3::from(v_kms) * 1e3).norm() < 1e-4,
                "{minutes} min: {v}"
            );
        }
    }

    #[test]
    fn iss_state_agrees_with_mean_motion() {
        // ISS (ZARYA) TLE of 2020-07-12 (the sgp4 crate's example): 15.49507896 rev/day,
        // e = 0.0001413. The osculating semi-major axis differs from the mean one by the
        // J2 short-period terms, at most ~ 1.5 J2 R^2 / a ~ 10 km.
        let tle = Tle::parse(&cfg(
            "1 25544U 98067A   20194.88612269 -.00002218  00000-0 -31515-4 0  9992",
            "2 25544  51.6461 221.2784 0001413  89.1723 280.4612 15.49507896236008",
        ))
        .unwrap();
        let n_rad_s = 15.495_078_96 * std::f64::consts::TAU / 86_400.0;
        let a_mean_m = (GM_GPS / (n_rad_s * n_rad_s)).cbrt();
        for hours in [0.0, 5.0, 24.0] {
            let epoch = tle.epoch() + Duration::from_seconds(hours * 3600.0);
            let (r, v) = tle.state_teme(epoch).unwrap();
            let el = KeplerianElements::from_cartesian(&r, &v, GM_GPS);
            assert!(
                (el.a_m - a_mean_m).abs() < 12e3,
                "a {} vs {}",
                el.a_m,
                a_mean_m
            );
            assert!((r.norm() - a_mean_m).abs() < 15e3, "|r| {}", r.norm());
            let period_rel = el.period_s(GM_GPS) * n_rad_s / std::f64::consts::TAU - 1.0;
            assert!(period_rel.abs() < 3e-3, "period off by {period_rel}");
            assert!((el.i_rad.to_degrees() - 51.6461).abs() < 0.1);
        }
    }

    #[test]
    fn bad_checksum_is_a_tle_error_with_the_sgp4_message() {
        let err = Tle::parse(&cfg(
            "1 25544U 98067A   20194.88612269 -.00002218  00000-0 -31515-4 0  9993",
            "2 25544  51.6461 221.2784 0001413  89.1723 280.4612 15.49507896236008",
        ))
        .unwrap_err();
        match err {
            PropagateError::Tle(msg) => assert!(msg.contains("checksum"), "{msg}"),
            other => panic!("unexpected {other:?}"),
        }
    }
}
