//! Rotation-vector helpers: the exact direction-cosine matrix of a rotation vector, the
//! interval-mean matrix that carries a specific-force increment, and re-orthonormalisation.

use skyforge_orbits::{Mat3, Vec3};

/// Below this angle (rad) the trigonometric coefficients use their Taylor series: the
/// closed forms lose digits to cancellation and the series truncated after the fourth
/// order is then exact to below 1e-16.
const SERIES_BELOW_RAD: f64 = 1e-2;

/// `sin(a)/a`, `(1 - cos a)/a^2` and `(a - sin a)/a^3` of the angle `a = |phi|`.
fn coefficients(a: f64) -> (f64, f64, f64) {
    if a < SERIES_BELOW_RAD {
        let a2 = a * a;
        let a4 = a2 * a2;
        (
            1.0 - a2 / 6.0 + a4 / 120.0,
            0.5 - a2 / 24.0 + a4 / 720.0,
            1.0 / 6.0 - a2 / 120.0 + a4 / 5040.0,
        )
    } else {
        let (s, c) = a.sin_cos();
        (s / a, (1.0 - c) / (a * a), (a - s) / (a * a * a))
    }
}

/// Rodrigues' formula (Groves 2013 sec. 5.5.1; Savage 1998 part 1, the direction-cosine
/// matrix of a rotation vector): `C = I + sin(a)/a [phi x] + (1 - cos a)/a^2 [phi x]^2`,
/// exact for any angle. Maps vectors of the rotated frame to the original frame.
pub(crate) fn rodrigues(phi: &Vec3) -> Mat3 {
    let (s, c, _) = coefficients(phi.norm());
    let k = phi.cross_matrix();
    Mat3::identity() + k * s + k * k * c
}

/// The mean over an interval of the rotation `C(t)` turning at a constant rate through
/// `alpha` (Groves 2013 sec. 5.5.2, the specific-force frame transformation):
/// `A = I + (1 - cos a)/a^2 [alpha x] + (a - sin a)/a^3 [alpha x]^2`, so that a constant
/// specific force's increment in the start frame is `A dv`. To first order
/// `A dv = dv + dv_rot` with Savage's rotation compensation `dv_rot = (1/2) alpha x dv`
/// (Savage 1998 part 2).
pub(crate) fn interval_mean(alpha: &Vec3) -> Mat3 {
    let (_, c, d) = coefficients(alpha.norm());
    let k = alpha.cross_matrix();
    Mat3::identity() + k * c + k * k * d
}

/// One step of the polar-decomposition iteration `C <- C (3 I - C^T C) / 2`: removes the
/// non-orthogonality of `c` to second order (rounding leaves it at ~1e-16 per update).
pub(crate) fn orthonormalise(c: &Mat3) -> Mat3 {
    c * (Mat3::identity() * 3.0 - c.transpose() * c) * 0.5
}

/// The small rotation vector `e` with `a b^T = I + [e x]` to first order: the attitude
/// difference of two direction-cosine matrices `a` and `b` (the vector part of the skew
/// half of `a b^T`, accurate for angles well under a degree).
pub fn attitude_difference(a: &Mat3, b: &Mat3) -> Vec3 {
    let d = a * b.transpose();
    Vec3::new(
        d[(2, 1)] - d[(1, 2)],
        d[(0, 2)] - d[(2, 0)],
        d[(1, 0)] - d[(0, 1)],
    ) * 0.5
}
