//! The IMU's displacement from the antenna's: paper 001 eq. (3),
//! `Delta r_ant = Delta r_imu + (C_b^e(t2) - C_b^e(t1)) l_b`.
//!
//! `C_b^e` is SkyForge's `c_body_ecef` (`navigation::ins::InsState`: body components to
//! ECEF components, `x_ecef = c_body_ecef x_body`, Groves' `C_b^e`) and `l_b` the lever
//! arm from the IMU to the antenna's phase centre in body axes (m).
//!
//! The differences are built at the antenna: [`time_differences_imu`] turns the IMU's
//! positions and attitudes into the antenna's (`r_ant = r_imu + C_b^e l_b`) and
//! linearises there. With both attitudes known the lever-arm term is exact, so the
//! correction a solution makes to the antenna at `t2` is the correction to the IMU:
//! `r_imu(t2) = r_imu_hat(t2) + delta_r` ([`LeverArm::imu`] of the solved antenna).
//!
//! The alternative, differences linearised at the IMU's own positions, needs
//! `e_i(t2) . C_b^e(t2) l_b - e_i(t1) . C_b^e(t1) l_b` added to each `z_i`; with one line
//! of sight for both epochs, `e_i . (C_b^e(t2) - C_b^e(t1)) l_b` as in paper 001 eq. (6)
//! ([`LeverArm::displacement_term_m`]), it errs by `(e_i(t2) - e_i(t1)) . C_b^e(t1) l_b`:
//! about 0.15 mm per metre of lever arm per second of gap for a GPS satellite, whose line
//! of sight turns at about 1.5e-4 rad/s. Building at the antenna is exact (to the
//! `|l_b|^2 / rho` of the range's curvature, 5e-8 m).

use super::config::TdcpConfig;
use super::error::TdcpError;
use super::single_difference::{TdcpEpoch, time_differences};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::{Mat3, Vec3};

/// The IMU-to-antenna lever arm in body axes (front-right-down for SkyForge's INS), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeverArm {
    /// IMU -> antenna phase centre, body axes (m).
    pub body_m: Vec3,
}

/// Where the IMU is and how the body is turned at one epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuPose {
    /// The IMU (ECEF, m).
    pub r_ecef_m: Vec3,
    /// Body-to-ECEF attitude, `x_ecef = c_body_ecef x_body`.
    pub c_body_ecef: Mat3,
}

impl LeverArm {
    /// The antenna of the IMU at `pose`: `r_imu + C_b^e l_b`.
    pub fn antenna(&self, pose: &ImuPose) -> Vec3 {
        pose.r_ecef_m + pose.c_body_ecef * self.body_m
    }

    /// The IMU under the antenna at `r_antenna_m` with attitude `c_body_ecef`.
    pub fn imu(&self, r_antenna_m: Vec3, c_body_ecef: &Mat3) -> Vec3 {
        r_antenna_m - c_body_ecef * self.body_m
    }

    /// `(C_b^e(t2) - C_b^e(t1)) l_b`: the antenna's displacement beyond the IMU's (m).
    pub fn displacement_term_m(&self, c1_body_ecef: &Mat3, c2_body_ecef: &Mat3) -> Vec3 {
        (c2_body_ecef - c1_body_ecef) * self.body_m
    }
}

/// [`time_differences`] of the antenna `lever` from the IMU at `imu.0` (known) and
/// `imu.1` (a priori at `t2`, attitude known): the differences are those of the antenna;
/// a solution's `delta_r` is the IMU's correction too (module docs).
pub fn time_differences_imu(
    (prev, cur): (&ObsEpoch, &ObsEpoch),
    imu: (&ImuPose, &ImuPose),
    lever: &LeverArm,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    config: &TdcpConfig,
) -> Result<TdcpEpoch, TdcpError> {
    if !lever.body_m.iter().all(|x| x.is_finite()) {
        return Err(TdcpError::NonFinite { what: "lever arm" });
    }
    let (r1, r2_hat) = (lever.antenna(imu.0), lever.antenna(imu.1));
    time_differences(prev, cur, r1, r2_hat, store, origin, config)
}
