//! What baselines can tell about the antenna geometry, and what they cannot.
//!
//! The baselines of an epoch are `B = R(xi) B'_0`. For any rotation `Q`,
//! `R(xi) B'_0 = (R(xi) Q^T) (Q B'_0)`: a geometry turned by `Q` in the body frame and an
//! attitude turned back by `Q^T` give the same baselines at every epoch. Baselines alone
//! therefore fix the *shape* of the antenna geometry (the baselines' lengths and the
//! angles between them: the [`Invariants`]) and leave its orientation in the body frame
//! to whatever else is known (a star tracker, or the nominal geometry). Thesis section 4.3
//! estimates all six offsets of two baselines; three of them (a small rotation) are this
//! orientation.
//!
//! [`align`] keeps the estimated shape and takes the orientation from the nominal
//! geometry: the rotation `Q` that brings the estimated baselines closest to the nominal
//! ones (Wahba's problem, [`crate::attitude::wahba::wahba_svd`]).

use crate::attitude::AttitudeError;
use crate::attitude::wahba::wahba_svd;
use nalgebra::Vector3;
#[cfg(test)]
use nalgebra::{Matrix3, SMatrix};
use skyforge_orbits::{Mat3, Vec3};

/// The shape of two baselines: their lengths and their dot product (m, m, m^2), which no
/// rotation changes.
pub type Invariants = Vector3<f64>;

/// The [`Invariants`] of two baselines.
pub fn invariants(b: &[Vec3; 2]) -> Invariants {
    Vector3::new(b[0].norm(), b[1].norm(), b[0].dot(&b[1]))
}

/// `d invariants / d (b1, b2)` (3 x 6, order `x1, y1, z1, x2, y2, z2`).
#[cfg(test)]
pub fn invariants_jacobian(b: &[Vec3; 2]) -> SMatrix<f64, 3, 6> {
    let mut j = SMatrix::<f64, 3, 6>::zeros();
    for a in 0..3 {
        j[(0, a)] = b[0][a] / b[0].norm();
        j[(1, 3 + a)] = b[1][a] / b[1].norm();
        j[(2, a)] = b[1][a];
        j[(2, 3 + a)] = b[0][a];
    }
    j
}

/// The covariance of the [`Invariants`] of `b` from the covariance `p` of its six
/// components (first order).
#[cfg(test)]
pub fn invariants_covariance(b: &[Vec3; 2], p: &SMatrix<f64, 6, 6>) -> Matrix3<f64> {
    let j = invariants_jacobian(b);
    j * p * j.transpose()
}

/// `e^T P^-1 e` for the invariants of `estimate` against those of `truth`, `P` their
/// covariance from `p` (the estimate's six components): chi-square with 3 degrees of
/// freedom when the estimate and its covariance agree. `None` if that covariance is not
/// positive definite.
#[cfg(test)]
pub fn shape_nees(estimate: &[Vec3; 2], p: &SMatrix<f64, 6, 6>, truth: &[Vec3; 2]) -> Option<f64> {
    let e = invariants(estimate) - invariants(truth);
    let c = invariants_covariance(estimate, p).cholesky()?;
    Some(e.dot(&c.solve(&e)))
}

/// An estimated geometry turned to the nominal orientation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aligned {
    /// `Q b'_k`: the estimated baselines turned by `Q` (m).
    pub baselines: [Vec3; 2],
    /// The rotation `Q` taken out (body frame).
    pub rotation: Mat3,
    /// Its angle (rad).
    pub angle_rad: f64,
}

/// Turn `estimate` by the rotation that brings it closest to `nominal` (equal weights).
pub fn align(estimate: &[Vec3; 2], nominal: &[Vec3; 2]) -> Result<Aligned, AttitudeError> {
    let pairs: Vec<(Vec3, Vec3, f64)> = estimate
        .iter()
        .zip(nominal)
        .map(|(e, n)| (*e, *n, 1.0))
        .collect();
    let q = wahba_svd(&pairs)?;
    let cos = ((q.trace() - 1.0) / 2.0).clamp(-1.0, 1.0);
    Ok(Aligned {
        baselines: estimate.map(|b| q * b),
        rotation: q,
        angle_rad: cos.acos(),
    })
}

/// A small rotation about `axis` by `angle` (Rodrigues), for tests and callers that
/// build rotated geometries.
#[cfg(test)]
pub fn rotation(axis: &Vec3, angle_rad: f64) -> Mat3 {
    nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(*axis), angle_rad)
        .into_inner()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn thesis() -> ([Vec3; 2], [Vec3; 2]) {
        (
            [Vec3::new(0.99, -0.02, -0.03), Vec3::new(0.03, 1.02, 0.01)],
            [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)],
        )
    }

    #[test]
    fn a_rotation_changes_no_invariant_and_align_takes_it_out() {
        let (nominal, truth) = thesis();
        let q = rotation(&Vec3::new(0.3, -0.5, 0.8), 0.03);
        let turned = truth.map(|b| q * b);
        assert!((invariants(&turned) - invariants(&truth)).amax() < 1e-15);
        let a = align(&turned, &nominal).unwrap();
        let b = align(&truth, &nominal).unwrap();
        for k in 0..2 {
            assert!((a.baselines[k] - b.baselines[k]).amax() < 1e-12);
        }
        // Aligning the nominal geometry to itself turns nothing.
        assert!(align(&nominal, &nominal).unwrap().angle_rad < 1e-12);
    }

    #[test]
    fn jacobian_matches_finite_differences() {
        let (_, truth) = thesis();
        let j = invariants_jacobian(&truth);
        let h = 1e-7;
        for c in 0..6 {
            let mut b = truth;
            b[c / 3][c % 3] += h;
            let d = (invariants(&b) - invariants(&truth)) / h;
            for r in 0..3 {
                assert!((d[r] - j[(r, c)]).abs() < 1e-6, "row {r} column {c}");
            }
        }
    }

    #[test]
    fn nees_of_an_exact_estimate_is_zero_and_grows_with_a_length_error() {
        let (_, truth) = thesis();
        let p = SMatrix::<f64, 6, 6>::identity() * 1e-6;
        assert!(shape_nees(&truth, &p, &truth).unwrap() < 1e-20);
        let mut longer = truth;
        longer[0].x += 2e-3;
        // One length 2 mm off with 1 mm sigmas: about (2 / 1)^2.
        let nees = shape_nees(&longer, &p, &truth).unwrap();
        assert!((3.0..6.0).contains(&nees), "{nees}");
    }
}
