//! Baselines and their covariance from ECEF to the reference frame, thesis eqs. 2.4-66 and
//! 2.4-67:
//!
//! `vec(B_ref) = (I_m (x) F) vec(B_ecef)`, `Q_ref = (I_m (x) F) Q_ecef (I_m (x) F)^T`,
//!
//! with `F` the ECEF -> reference rotation: `F = c_ecef_ned` at the reference antenna's
//! geodetic position for NED (section 2.5.1, `F = F1`), or `R_oe F1` for the orbital frame.

use super::{AttitudeError, NedBaselines, check_covariance};
use nalgebra::DMatrix;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::{Mat3, Vec3};

/// Eqs. 2.4-66, 2.4-67 with any rotation `f` (ECEF -> reference frame): baselines
/// `b_ecef_m` (m) and their covariance `q_ecef_m2` (3m x 3m, `vec()` order) in the
/// reference frame.
pub fn baselines_to_frame(
    b_ecef_m: &[Vec3],
    q_ecef_m2: &DMatrix<f64>,
    f: &Mat3,
) -> Result<NedBaselines, AttitudeError> {
    let m = b_ecef_m.len();
    check_covariance(q_ecef_m2, 3 * m, "Q_BB (ECEF)")?;
    if !f.iter().all(|v| v.is_finite()) {
        return Err(AttitudeError::Measurement(format!(
            "frame rotation F is not finite: {f:?}"
        )));
    }
    let i_kron_f = DMatrix::<f64>::identity(m, m).kronecker(f);
    let b: Vec<Vec3> = b_ecef_m.iter().map(|b| f * b).collect();
    let q = &i_kron_f * q_ecef_m2 * i_kron_f.transpose();
    // Symmetrise the rounding of the product.
    let q = 0.5 * (&q + q.transpose());
    NedBaselines::new(&b, q)
}

/// Eqs. 2.4-66, 2.4-67 with `F = c_ecef_ned` at the geodetic position of the reference
/// antenna `r_ref_ecef_m` (ECEF, m).
pub fn ned_baselines_from_ecef(
    b_ecef_m: &[Vec3],
    q_ecef_m2: &DMatrix<f64>,
    r_ref_ecef_m: &Vec3,
) -> Result<NedBaselines, AttitudeError> {
    baselines_to_frame(b_ecef_m, q_ecef_m2, &ned_frame(r_ref_ecef_m)?)
}

/// `F = c_ecef_ned` at the geodetic position of the reference antenna `r_ref_ecef_m`
/// (ECEF, m).
pub fn ned_frame(r_ref_ecef_m: &Vec3) -> Result<Mat3, AttitudeError> {
    if !r_ref_ecef_m.iter().all(|v| v.is_finite()) || r_ref_ecef_m.norm() < 1.0 {
        return Err(AttitudeError::Measurement(format!(
            "reference antenna position {r_ref_ecef_m:?} m has no geodetic latitude/longitude"
        )));
    }
    let g = ecef_to_geodetic(r_ref_ecef_m);
    Ok(c_ecef_ned(g.lat_rad, g.lon_rad))
}
