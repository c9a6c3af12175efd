//! The 15-state error model of an ECEF-frame INS (Groves 2013 sec. 14.2.3): position,
//! velocity and attitude errors and the residual accelerometer and gyro biases, their
//! dynamics and process noise.
//!
//! Definitions (computed minus true, Groves sec. 14.1): `dr = r^ - r`, `dv = v^ - v`,
//! the attitude error `psi` with `C^ = (I + [psi x]) C` (C body-to-ECEF), and the bias
//! errors `db = b - b^` that the INS's corrected increments still carry.

use super::config::ImuNoise;
use nalgebra::{SMatrix, SVector};
use skyforge_orbits::constants::GM_GPS;
use skyforge_orbits::gravity::earth_rate_ecef;
use skyforge_orbits::{Mat3, Vec3};

/// Number of error states.
pub const STATES: usize = 15;
/// A square matrix of the error state.
pub(crate) type Mat15 = SMatrix<f64, STATES, STATES>;
/// An error-state vector.
pub(crate) type Vec15 = SVector<f64, STATES>;

/// First index of each block.
pub(crate) const POS: usize = 0;
pub(crate) const VEL: usize = 3;
pub(crate) const ATT: usize = 6;
pub(crate) const ACC: usize = 9;
pub(crate) const GYR: usize = 12;

/// `[a x]`.
pub(crate) fn skew(a: &Vec3) -> Mat3 {
    a.cross_matrix()
}

/// The gradient of gravity plus the centrifugal acceleration: point-mass
/// `-(mu / r^3) (I - 3 u u^T)` (Groves eq. 14.49 keeps only its radial term) minus
/// `[w_ie x]^2`.
fn gravity_gradient(r: &Vec3) -> Mat3 {
    let n = r.norm();
    let u = r / n;
    let w = skew(&earth_rate_ecef());
    -(GM_GPS / n.powi(3)) * (Mat3::identity() - 3.0 * u * u.transpose()) - w * w
}

/// Groves 2013 eqs. 14.48-14.50, 14.63 (ECEF): the error dynamics `x' = F x` at
/// position `r`, attitude `c` (body-to-ECEF) and specific force `f_body`, with the biases
/// first-order Gauss-Markov processes (or constants).
fn system_matrix(r: &Vec3, c: &Mat3, f_body: &Vec3, noise: &ImuNoise) -> Mat15 {
    let mut f = Mat15::zeros();
    let omega = skew(&earth_rate_ecef());
    let mut set =
        |row: usize, col: usize, m: Mat3| f.fixed_view_mut::<3, 3>(row, col).copy_from(&m);
    set(POS, VEL, Mat3::identity());
    set(VEL, POS, gravity_gradient(r));
    set(VEL, VEL, -2.0 * omega);
    set(VEL, ATT, -skew(&(c * f_body)));
    set(VEL, ACC, *c);
    set(ATT, ATT, -omega);
    set(ATT, GYR, *c);
    let decay = |tau: Option<f64>| Mat3::identity() * tau.map_or(0.0, |t| -1.0 / t);
    set(ACC, ACC, decay(noise.accel_bias_tau_s));
    set(GYR, GYR, decay(noise.gyro_bias_tau_s));
    f
}

/// The transition matrix over `dt` (second-order series of `exp(F dt)`, Groves eq.
/// 14.72) and the process noise (Groves eq. 14.82, first order): the random walks on
/// velocity and attitude, the bias processes' driving noise `2 sigma^2 / tau`.
pub(crate) fn transition(
    r: &Vec3,
    c: &Mat3,
    f_body: &Vec3,
    noise: &ImuNoise,
    dt: f64,
) -> (Mat15, Vec15) {
    let fdt = system_matrix(r, c, f_body, noise) * dt;
    let phi = Mat15::identity() + fdt + fdt * fdt * 0.5;
    let driving = |sigma: f64, tau: Option<f64>| tau.map_or(0.0, |t| 2.0 * sigma * sigma / t);
    let mut q = Vec15::zeros();
    let blocks = [
        (VEL, noise.accel_vrw.powi(2)),
        (ATT, noise.gyro_arw.powi(2)),
        (ACC, driving(noise.accel_bias, noise.accel_bias_tau_s)),
        (GYR, driving(noise.gyro_bias, noise.gyro_bias_tau_s)),
    ];
    for (start, density) in blocks {
        for k in start..start + 3 {
            q[k] = density * dt;
        }
    }
    (phi, q)
}
