//! Coarse (analytic) alignment of a stationary IMU: levelling from the specific force and
//! gyrocompassing from the Earth's rate (Groves 2013 sec. 5.6.2; Titterton & Weston 2004
//! ch. 10), and the heading error a gyro bias leaves in it.

use super::checks::check_values;
use super::error::InsError;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::frames::Geodetic;
use skyforge_orbits::gravity::{earth_rate_ecef, normal_gravity_ecef};
use skyforge_orbits::{Mat3, Vec3};

/// The smallest sine of the angle between the specific force and the Earth's rate that
/// still defines north (about 0.06 deg from a pole).
const MIN_SIN_ANGLE: f64 = 1e-3;

/// Mean specific force and angular rate over a stationary period, body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticMeans {
    /// Mean specific force (m/s^2).
    pub f_body_mps2: Vec3,
    /// Mean angular rate relative to inertial space (rad/s).
    pub w_body_rps: Vec3,
    /// Length of the period (s).
    pub duration_s: f64,
}

/// The means of `increments` (sums of the increments over the sum of the intervals).
/// Each increment is checked; their order is not (a stationary sum does not depend on it).
pub fn static_means(increments: &[ImuIncrement]) -> Result<StaticMeans, InsError> {
    if increments.is_empty() {
        return Err(InsError::Empty);
    }
    let (mut dv, mut dtheta, mut duration_s) = (Vec3::zeros(), Vec3::zeros(), 0.0);
    for inc in increments {
        check_values(inc)?;
        dv += inc.dv_mps;
        dtheta += inc.dtheta_rad;
        duration_s += inc.dt_s;
    }
    Ok(StaticMeans {
        f_body_mps2: dv / duration_s,
        w_body_rps: dtheta / duration_s,
        duration_s,
    })
}

/// The body-to-ECEF attitude of a stationary IMU at `position` from its mean specific
/// force `mean_f_body` (m/s^2) and mean angular rate `mean_w_body` (rad/s).
///
/// The TRIAD form of levelling and gyrocompassing (Groves 2013 sec. 5.6.2; Titterton &
/// Weston 2004 ch. 10): the specific force at rest is minus normal gravity and fixes the
/// vertical exactly; the Earth's rate, made orthogonal to it, fixes north. With
/// orthonormal triads `T = [u, (u x w)/|u x w|, u x (u x w)/|u x w|]`, `u = f/|f|`, built
/// alike from the measurements and from the ECEF references,
/// `C_b^e = T_e T_b^T`. A gyro bias `b_E` along east turns the heading by
/// `-b_E / (w_ie cos L)` ([`heading_error_from_east_gyro_bias_rad`]); an accelerometer
/// bias tilts the level by `b / g`.
pub fn coarse_alignment(
    mean_f_body: &Vec3,
    mean_w_body: &Vec3,
    position: &Geodetic,
) -> Result<Mat3, InsError> {
    let t_body = triad(mean_f_body, mean_w_body)?;
    let t_ecef = triad(&-normal_gravity_ecef(position), &earth_rate_ecef())?;
    Ok(t_ecef * t_body.transpose())
}

/// The orthonormal triad (columns) of a primary vector `f` and a secondary vector `w`.
fn triad(f: &Vec3, w: &Vec3) -> Result<Mat3, InsError> {
    let (nf, nw) = (f.norm(), w.norm());
    if !(nf.is_finite() && nw.is_finite()) || nf == 0.0 || nw == 0.0 {
        return Err(InsError::Degenerate(
            "zero or non-finite specific force or rate",
        ));
    }
    let u = f / nf;
    let cross = u.cross(w);
    if cross.norm() < MIN_SIN_ANGLE * nw {
        return Err(InsError::Degenerate(
            "specific force parallel to the Earth's rate",
        ));
    }
    let e = cross.normalize();
    Ok(Mat3::from_columns(&[u, e, u.cross(&e)]))
}

/// The heading error (rad, computed minus true) that an
/// uncompensated gyro bias `east_bias_rps` along local east leaves in gyrocompassing at
/// `position`: `-b_E / (w_ie cos L)` (Groves 2013 sec. 5.6.2; Titterton & Weston 2004
/// ch. 10). Fine alignment cannot remove it: at rest the bias and the heading error are
/// indistinguishable.
pub fn heading_error_from_east_gyro_bias_rad(east_bias_rps: f64, position: &Geodetic) -> f64 {
    -east_bias_rps / (OMEGA_E_GPS * position.lat_rad.cos())
}
