//! The measurement model's derivatives, thesis eqs. 2.5-8 and 2.5-10.

use super::{BodyGeometry, YawPitchRoll};
use nalgebra::{DMatrix, SMatrix};

/// Thesis eq. 2.5-10: `J(xi) = d vec(R(xi)) / d xi` (9 x 3). Rows are `vec(R)` in column
/// order (R11, R21, R31, R12, ..., R33), columns yaw, pitch, roll; `R(xi)` is
/// [`YawPitchRoll::c_body_ref`] (eq. 2.5-6).
pub fn vec_r_jacobian(xi: &YawPitchRoll) -> SMatrix<f64, 9, 3> {
    let (sy, cy) = xi.yaw_rad.sin_cos();
    let (sp, cp) = xi.pitch_rad.sin_cos();
    let (sr, cr) = xi.roll_rad.sin_cos();
    SMatrix::<f64, 9, 3>::from_row_slice(&[
        // R11 = cy cp
        -sy * cp,
        -cy * sp,
        0.0,
        // R21 = sy cp
        cy * cp,
        -sy * sp,
        0.0,
        // R31 = -sp
        0.0,
        -cp,
        0.0,
        // R12 = cy sp sr - sy cr
        -sy * sp * sr - cy * cr,
        cy * cp * sr,
        cy * sp * cr + sy * sr,
        // R22 = sy sp sr + cy cr
        cy * sp * sr - sy * cr,
        sy * cp * sr,
        sy * sp * cr - cy * sr,
        // R32 = cp sr
        0.0,
        -sp * sr,
        cp * cr,
        // R13 = cy sp cr + sy sr
        -sy * sp * cr + cy * sr,
        cy * cp * cr,
        -cy * sp * sr + sy * cr,
        // R23 = sy sp cr - cy sr
        cy * sp * cr + sy * sr,
        sy * cp * cr,
        -sy * sp * sr - cy * cr,
        // R33 = cp cr
        0.0,
        -sp * cr,
        -cp * sr,
    ])
}

/// Thesis eq. 2.5-8: `h = B_0^T (x) I_3` (3m x 9), so that `vec(R B_0) = h vec(R)`.
pub fn h_matrix(geometry: &BodyGeometry) -> DMatrix<f64> {
    let m = geometry.len();
    let mut b0_t = DMatrix::<f64>::zeros(m, 3);
    for (i, b) in geometry.baselines().iter().enumerate() {
        b0_t.row_mut(i).copy_from(&b.transpose());
    }
    b0_t.kronecker(&DMatrix::<f64>::identity(3, 3))
}

/// `H = h J(xi)` (3m x 3): the derivative of the predicted baselines `vec(R(xi) B_0)`
/// with respect to the angles (eq. 2.5-9).
pub fn design_matrix(geometry: &BodyGeometry, xi: &YawPitchRoll) -> DMatrix<f64> {
    let j = vec_r_jacobian(xi);
    let j = DMatrix::from_column_slice(9, 3, j.as_slice());
    h_matrix(geometry) * j
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::Vec3;

    fn vec_r(xi: &YawPitchRoll) -> [f64; 9] {
        let r = xi.c_body_ref();
        let mut out = [0.0; 9];
        out.copy_from_slice(r.as_slice()); // nalgebra is column-major: vec()
        out
    }

    #[test]
    fn jacobian_matches_central_differences() {
        let xi = YawPitchRoll::new(2.5, -0.6, -1.2);
        let j = vec_r_jacobian(&xi);
        let d = 1e-6;
        for k in 0..3 {
            let mut plus = [xi.yaw_rad, xi.pitch_rad, xi.roll_rad];
            let mut minus = plus;
            plus[k] += d;
            minus[k] -= d;
            let (p, m) = (
                vec_r(&YawPitchRoll::new(plus[0], plus[1], plus[2])),
                vec_r(&YawPitchRoll::new(minus[0], minus[1], minus[2])),
            );
            for row in 0..9 {
                let fd = (p[row] - m[row]) / (2.0 * d);
                assert!((fd - j[(row, k)]).abs() < 1e-9, "row {row} col {k}");
            }
        }
    }

    #[test]
    fn h_maps_vec_r_to_the_rotated_baselines() {
        let g = BodyGeometry::new(&[Vec3::new(1.0, 0.2, -0.1), Vec3::new(0.0, 0.9, 0.3)]).unwrap();
        let xi = YawPitchRoll::new(0.3, 0.2, -0.4);
        let vr = nalgebra::DVector::from_column_slice(xi.c_body_ref().as_slice());
        assert!((h_matrix(&g) * vr - g.predict(&xi)).amax() < 1e-15);
    }
}
