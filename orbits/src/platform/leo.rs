//! A LEO platform's state: the propagator's ECI state in ECEF, with an Earth-pointing
//! attitude.
//!
//! The attitude chain (thesis section 2.5.1, with this crate's `c_from_to` naming):
//!
//! ```text
//! c_body_ecef = c_eci_ecef(t) * c_orbital_eci(r_eci, v_eci) * c_body_orbital
//! ```
//!
//! * `c_body_orbital = R(xi)` of thesis eq. 2.5-6 with the profile's yaw/pitch/roll;
//! * `c_orbital_eci` = `R_oi^T` of thesis eq. 2.5-2, built from the *inertial* position
//!   and velocity (Xo along the inertial flight direction, Zo to the Earth centre);
//! * `c_eci_ecef` = Earth rotation ([`EarthRotation`]).
//!
//! With zero attitude the body axes are the orbital axes: Zb points to the Earth centre and
//! Xb along the inertial flight direction (exactly along `v_eci` for a circular orbit).
//!
//! The kinematics an IMU needs ([`leo_kinematics`]): the propagator's ECI acceleration
//! (its force model at the interpolated state) in ECEF, `a_e = C a_i - 2 w x v_e - w x (w
//! x r_e)`, the gravity acting, `C g_i - w x (w x r_e)` (so the specific force is the
//! drag: a free-falling body's accelerometers read the non-gravitational forces alone),
//! and the body's angular rate relative to the Earth from the attitude chain's central
//! difference over [`RATE_STEP_S`], `[w_eb x] = C^T dC/dt`.

use super::{Kinematics, PlatformState};
use crate::Vec3;
use crate::frames::earth_rotation::EarthRotation;
use crate::frames::euler::YawPitchRoll;
use crate::frames::orbital::c_orbital_eci;
use crate::propagate::leo::DenseTrajectory;

/// The platform state of a LEO at ECI position `r_eci_m` and velocity `v_eci_mps` at
/// `t_s`, with `attitude` relative to its orbital frame.
pub(crate) fn leo_state(
    earth: &EarthRotation,
    t_s: f64,
    r_eci_m: &Vec3,
    v_eci_mps: &Vec3,
    attitude: YawPitchRoll,
) -> PlatformState {
    let (r_ecef_m, v_ecef_mps) = earth.eci_to_ecef(t_s, r_eci_m, v_eci_mps);
    let c_body_ecef =
        earth.c_eci_ecef(t_s) * c_orbital_eci(r_eci_m, v_eci_mps) * attitude.c_body_ref();
    PlatformState {
        r_ecef_m,
        v_ecef_mps,
        c_body_ecef,
        attitude,
    }
}

/// The step of the central difference that gives a LEO body's angular rate (s): its
/// truncation, `h^2 / 6` times the rate's second derivative (`n^3`, 1e-9 rad/s^3 at the
/// orbit rate: 1e-14 rad/s), and the rounding of the attitude matrix (1e-16 / h: 1e-14
/// rad/s) both far below any gyro's resolution.
const RATE_STEP_S: f64 = 0.01;

/// The kinematics at `t_s` of the LEO of `dense` with `attitude(t)` relative to its
/// orbital frame.
pub(crate) fn leo_kinematics(
    dense: &DenseTrajectory,
    earth: &EarthRotation,
    t_s: f64,
    attitude: &dyn Fn(f64) -> YawPitchRoll,
) -> Kinematics {
    let (r_i, v_i, a_i) = dense.state_eci(t_s);
    let now = leo_state(earth, t_s, &r_i, &v_i, attitude(t_s));
    let c_body_ecef = |t: f64| {
        let (r, v) = dense.position_velocity_eci(t);
        leo_state(earth, t, &r, &v, attitude(t)).c_body_ecef
    };
    let h = RATE_STEP_S;
    let dc = (c_body_ecef(t_s + h) - c_body_ecef(t_s - h)) / (2.0 * h);
    let skew = now.c_body_ecef.transpose() * dc;
    let omega_eb = Vec3::new(
        skew[(2, 1)] - skew[(1, 2)],
        skew[(0, 2)] - skew[(2, 0)],
        skew[(1, 0)] - skew[(0, 1)],
    ) / 2.0;
    let w = earth.omega_rad_s();
    let c = earth.c_eci_ecef(t_s);
    let (r_e, v_e) = (now.r_ecef_m, now.v_ecef_mps);
    let centrifugal = -w.cross(&w.cross(&r_e));
    Kinematics {
        r_ecef_m: r_e,
        v_ecef_mps: v_e,
        a_ecef_mps2: c * a_i - 2.0 * w.cross(&v_e) + centrifugal,
        c_body_ecef: now.c_body_ecef,
        omega_eb_body_rps: omega_eb,
        gravity_ecef_mps2: c * dense.gravity_eci(&r_i) + centrifugal,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Mat3;
    use crate::constants::GM_GPS;
    use hifitime::Epoch;
    use std::f64::consts::FRAC_PI_2;

    /// Circular orbit of radius `a`, inclination `inc`, RAAN `raan` (analytic).
    fn circular(t: f64, a: f64, inc: f64, raan: f64) -> (Vec3, Vec3) {
        let n = (GM_GPS / (a * a * a)).sqrt();
        let (s, c) = (n * t).sin_cos();
        let rot = nalgebra::Rotation3::from_axis_angle(&Vec3::z_axis(), raan)
            * nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), inc);
        (
            rot * Vec3::new(a * c, a * s, 0.0),
            rot * Vec3::new(-a * n * s, a * n * c, 0.0),
        )
    }

    fn earth() -> EarthRotation {
        EarthRotation::at_origin(Epoch::from_gregorian_utc_hms(2023, 3, 12, 0, 0, 0))
    }

    #[test]
    fn zero_attitude_points_zb_to_the_centre_and_xb_along_flight() {
        let e = earth();
        for t in [0.0, 700.0, 3000.0] {
            let (r, v) = circular(t, 6_878_137.0, 97.4f64.to_radians(), 1.0);
            let st = leo_state(&e, t, &r, &v, YawPitchRoll::default());
            let c = st.c_body_ecef;
            assert!((c * c.transpose() - Mat3::identity()).norm() < 1e-14);
            // Zb to the Earth centre, in ECEF.
            assert!((c * Vec3::z() + st.r_ecef_m.normalize()).norm() < 1e-9);
            // Xb along the inertial velocity rotated into ECEF (not along v_ecef).
            let v_rot = e.c_eci_ecef(t) * v;
            assert!((c * Vec3::x() - v_rot.normalize()).norm() < 1e-9);
            assert!((c * Vec3::x() - st.v_ecef_mps.normalize()).norm() > 1e-3);
            // Yb along the negative orbit normal.
            let h_ecef = e.c_eci_ecef(t) * r.cross(&v);
            assert!((c * Vec3::y() + h_ecef.normalize()).norm() < 1e-9);
            // Position and velocity are the Earth-rotation transform of the ECI state.
            let (r_e, v_e) = e.eci_to_ecef(t, &r, &v);
            assert_eq!((st.r_ecef_m, st.v_ecef_mps), (r_e, v_e));
        }
    }

    #[test]
    fn yaw_and_pitch_turn_the_body_within_the_orbital_frame() {
        let e = earth();
        let (r, v) = circular(100.0, 7e6, 0.9, 0.2);
        let c_orb_ecef = e.c_eci_ecef(100.0) * c_orbital_eci(&r, &v);
        // Yaw +90 deg: Xb goes to Yo (thesis eq. 2.5-6 with phi_y = 90 deg).
        let st = leo_state(&e, 100.0, &r, &v, YawPitchRoll::new(FRAC_PI_2, 0.0, 0.0));
        assert!((st.c_body_ecef * Vec3::x() - c_orb_ecef * Vec3::y()).norm() < 1e-12);
        assert_eq!(st.attitude, YawPitchRoll::new(FRAC_PI_2, 0.0, 0.0));
        // Pitch +90 deg: Xb goes to -Zo (nose up, away from the Earth).
        let st = leo_state(&e, 100.0, &r, &v, YawPitchRoll::new(0.0, FRAC_PI_2, 0.0));
        assert!((st.c_body_ecef * Vec3::x() + c_orb_ecef * Vec3::z()).norm() < 1e-12);
    }
}
