//! The rotation helpers against nalgebra's rotations and brute-force quadrature.

use super::truth::gauss_legendre3;
use crate::ins::rotation::{interval_mean, orthonormalise, rodrigues};
use nalgebra::Rotation3;
use skyforge_orbits::{Mat3, Vec3};

/// Rodrigues' matrix equals nalgebra's rotation of the same scaled axis, for angles on
/// both sides of the series threshold.
#[test]
fn rodrigues_matches_nalgebra() {
    for scale in [0.0, 1e-9, 1e-4, 9e-3, 1.1e-2, 0.3, 3.0] {
        let phi = Vec3::new(0.3, -0.5, 0.8).normalize() * scale;
        let diff = (rodrigues(&phi) - Rotation3::new(phi).into_inner()).norm();
        assert!(diff < 1e-15, "angle {scale}: {diff:e}");
    }
}

/// `A(alpha)` is the mean of `Rod(alpha t / T)` over the interval: checked by 100
/// Gauss-Legendre panels.
#[test]
fn interval_mean_is_the_mean_rotation() {
    for scale in [1e-5, 5e-3, 0.02, 0.7] {
        let alpha = Vec3::new(-0.2, 0.9, 0.4).normalize() * scale;
        let x = Vec3::new(1.0, -2.0, 0.5);
        let panels = 100;
        let mean = (0..panels)
            .map(|k| {
                let (a, b) = (k as f64 / panels as f64, (k + 1) as f64 / panels as f64);
                gauss_legendre3(|s| rodrigues(&(alpha * s)) * x, a, b)
            })
            .fold(Vec3::zeros(), |acc, v| acc + v);
        let diff = (interval_mean(&alpha) * x - mean).norm();
        assert!(diff < 1e-14, "angle {scale}: {diff:e}");
    }
}

/// One normalisation step takes a matrix 1e-6 off orthonormal to within 1e-10 (the step
/// leaves the square of the departure, a few 1e-12).
#[test]
fn orthonormalise_restores_orthogonality() {
    let c = Rotation3::new(Vec3::new(0.4, 0.1, -1.2)).into_inner()
        + Mat3::new(1.0, -2.0, 0.5, 0.3, 0.7, -0.9, 0.2, 0.1, 0.4) * 1e-6;
    let c1 = orthonormalise(&c);
    let off = (c1.transpose() * c1 - Mat3::identity()).norm();
    assert!(off < 1e-10, "{off:e}");
    assert!((c1 - c).norm() < 1e-5);
}
