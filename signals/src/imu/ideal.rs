//! What an error-free strapdown IMU senses on a platform whose motion is known exactly
//! ([`Kinematics`]): the angular rate of the body relative to inertial space and the
//! specific force, in body axes, and their integrals over a sampling interval.

use skyforge_orbits::Vec3;
use skyforge_orbits::gravity::earth_rate_ecef;
use skyforge_orbits::platform::Kinematics;

/// The body's angular rate relative to inertial space (rad/s) and the specific force
/// (m/s^2), body axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensed {
    pub omega_ib_body_rps: Vec3,
    pub f_body_mps2: Vec3,
}

/// Groves (2013) eqs. 2.48 and 5.34 rearranged: `w_ib^b = w_eb^b + C_e^b w_ie^e`, and
/// `f^b = C_e^b (a^e + 2 w_ie x v^e - g^e)`, where `g` is the gravity acting at the
/// platform (gravitation plus the centrifugal term `-w_ie x (w_ie x r)`: normal gravity
/// near the surface, the propagator's in orbit), so the centripetal acceleration of the
/// rotating frame cancels between the two.
pub fn sensed(k: &Kinematics) -> Sensed {
    let w_ie = earth_rate_ecef();
    let c_ecef_body = k.c_body_ecef.transpose();
    let g = k.gravity_ecef_mps2;
    Sensed {
        omega_ib_body_rps: k.omega_eb_body_rps + c_ecef_body * w_ie,
        f_body_mps2: c_ecef_body * (k.a_ecef_mps2 + 2.0 * w_ie.cross(&k.v_ecef_mps) - g),
    }
}

/// Nodes (on [-1, 1]) and weights of the 3-point Gauss-Legendre rule, exact for
/// polynomials up to degree 5 (Abramowitz & Stegun Table 25.4).
const GAUSS_3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// The error-free increments over `(t0_s, t0_s + dt_s]`: the integrals of the angular
/// rate (rad) and of the specific force (m/s) by 3-point Gauss-Legendre quadrature on
/// `kinematics`. `None` where the platform has no kinematics at a node.
pub fn increments(
    kinematics: &impl Fn(f64) -> Option<Kinematics>,
    t0_s: f64,
    dt_s: f64,
) -> Option<(Vec3, Vec3)> {
    let half = dt_s / 2.0;
    let mut dtheta = Vec3::zeros();
    let mut dv = Vec3::zeros();
    for (x, w) in GAUSS_3 {
        let s = sensed(&kinematics(t0_s + half * (1.0 + x))?);
        dtheta += w * half * s.omega_ib_body_rps;
        dv += w * half * s.f_body_mps2;
    }
    Some((dtheta, dv))
}
