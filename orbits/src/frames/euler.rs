//! Yaw/pitch/roll, 3-2-1 rotation (thesis eq. 2.5-3..2.5-6), DCMs and quaternions.
//!
//! Thesis section 2.5.2: the body frame is reached from the reference frame (NED for a
//! ground receiver, the orbital frame for a LEO) by turning yaw `phi_y` about Z, then
//! pitch `theta_p` about the new Y, then roll `psi_r` about the new X. With the frame
//! rotation matrices `R_Z`, `R_Y`, `R_X` of eqs. 2.5-3..2.5-5,
//!
//! * `c_ref_body = R_X(roll) R_Y(pitch) R_Z(yaw)` maps reference components to body
//!   components;
//! * `c_body_ref = R(xi) = R_Z^T(yaw) R_Y^T(pitch) R_X^T(roll)` is the thesis'
//!   attitude matrix of eq. 2.5-6 (body to reference, `B_NED = R(xi) B_0`, eq. 2.5-7).
//!
//! So [`YawPitchRoll::c_ref_body`] is the transpose of the thesis' `R(xi)` and
//! [`YawPitchRoll::c_body_ref`] is `R(xi)` itself; both follow the crate's `c_from_to`
//! naming.

use crate::Mat3;
use nalgebra::{Rotation3, UnitQuaternion};

/// Attitude angles of the body frame relative to a reference frame (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct YawPitchRoll {
    pub yaw_rad: f64,
    pub pitch_rad: f64,
    pub roll_rad: f64,
}

/// Thesis eq. 2.5-3: frame rotation about Z by `a`.
fn r_z(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0)
}

/// Thesis eq. 2.5-4: frame rotation about Y by `a`.
fn r_y(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c)
}

/// Thesis eq. 2.5-5: frame rotation about X by `a`.
fn r_x(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c)
}

impl YawPitchRoll {
    /// Angles in radians.
    pub fn new(yaw_rad: f64, pitch_rad: f64, roll_rad: f64) -> Self {
        Self {
            yaw_rad,
            pitch_rad,
            roll_rad,
        }
    }
    /// `c_ref_body`: the 3-2-1 rotation (yaw about Z, then pitch about Y, then roll about X).
    /// `R_X(roll) R_Y(pitch) R_Z(yaw)` of thesis eqs. 2.5-3..2.5-5; the transpose of the
    /// thesis' `R(xi)` (eq. 2.5-6).
    pub fn c_ref_body(&self) -> Mat3 {
        r_x(self.roll_rad) * r_y(self.pitch_rad) * r_z(self.yaw_rad)
    }
    /// `c_body_ref`: the thesis' attitude matrix `R(xi)` of eq. 2.5-6 (body to reference).
    pub fn c_body_ref(&self) -> Mat3 {
        self.c_ref_body().transpose()
    }
    /// Angles from `c_ref_body` (pitch in [-pi/2, pi/2]).
    ///
    /// From eq. 2.5-6 (`R = c_ref_body^T`): `pitch = -asin(R31)`, `yaw = atan2(R21, R11)`,
    /// `roll = atan2(R32, R33)`; yaw and roll are in (-pi, pi]. At gimbal lock
    /// (|pitch| = pi/2) only yaw -/+ roll is defined; roll is then returned as 0.
    pub fn from_c_ref_body(c_ref_body: &Mat3) -> Self {
        let r = c_ref_body.transpose();
        let pitch_rad = (-r[(2, 0)]).clamp(-1.0, 1.0).asin();
        let cos_pitch = r[(0, 0)].hypot(r[(1, 0)]);
        if cos_pitch > 1e-12 {
            Self {
                yaw_rad: r[(1, 0)].atan2(r[(0, 0)]),
                pitch_rad,
                roll_rad: r[(2, 1)].atan2(r[(2, 2)]),
            }
        } else {
            // R12 = -sin(yaw -/+ roll), R22 = cos(yaw -/+ roll) when roll = 0.
            Self {
                yaw_rad: (-r[(0, 1)]).atan2(r[(1, 1)]),
                pitch_rad,
                roll_rad: 0.0,
            }
        }
    }
    /// The angular rate of the body relative to the reference frame, in body axes
    /// (rad/s), from the angles' rates `rates` (rad/s): the 3-2-1 kinematic relation
    /// (Groves 2013 eq. 2.59, inverted; Titterton and Weston 2004 eq. 3.35)
    /// `w = [r' - y' sin p, p' cos r + y' cos p sin r, -p' sin r + y' cos p cos r]`.
    pub fn body_rate(&self, rates: &YawPitchRoll) -> crate::Vec3 {
        let (sp, cp) = self.pitch_rad.sin_cos();
        let (sr, cr) = self.roll_rad.sin_cos();
        let (y, p, r) = (rates.yaw_rad, rates.pitch_rad, rates.roll_rad);
        crate::Vec3::new(r - y * sp, p * cr + y * cp * sr, -p * sr + y * cp * cr)
    }
    /// The rotation as a unit quaternion (body->ref, i.e. rotates body components into ref).
    pub fn q_body_ref(&self) -> UnitQuaternion<f64> {
        // nalgebra's (roll, pitch, yaw) constructor is Rz(yaw) Ry(pitch) Rx(roll) in the
        // active sense, which is R(xi) of eq. 2.5-6.
        UnitQuaternion::from_euler_angles(self.roll_rad, self.pitch_rad, self.yaw_rad)
    }
    /// Angles from a body->ref quaternion (inverse of [`Self::q_body_ref`]).
    pub fn from_q_body_ref(q_body_ref: &UnitQuaternion<f64>) -> Self {
        let c_body_ref: Rotation3<f64> = q_body_ref.to_rotation_matrix();
        Self::from_c_ref_body(&c_body_ref.matrix().transpose())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Thesis eq. 2.5-6 written out element by element (the oracle).
    fn thesis_r_xi(y: f64, p: f64, r: f64) -> Mat3 {
        let (sy, cy) = y.sin_cos();
        let (sp, cp) = p.sin_cos();
        let (sr, cr) = r.sin_cos();
        Mat3::new(
            cy * cp,
            cy * sp * sr - sy * cr,
            cy * sp * cr + sy * sr,
            sy * cp,
            sy * sp * sr + cy * cr,
            sy * sp * cr - cy * sr,
            -sp,
            cp * sr,
            cp * cr,
        )
    }

    /// The body rate against the derivative of the attitude matrix by central
    /// differences: `[w x] = C_body_ref^T dC_body_ref/dt`.
    #[test]
    fn body_rate_is_the_attitude_matrix_derivative() {
        let angles = |t: f64| YawPitchRoll::new(0.3 + 0.2 * t, -0.7 + 0.1 * t * t, 1.9 - 0.4 * t);
        let t = 0.6;
        let rates = YawPitchRoll::new(0.2, 0.2 * t, -0.4);
        let h = 1e-5;
        let dc = (angles(t + h).c_body_ref() - angles(t - h).c_body_ref()) / (2.0 * h);
        let skew = angles(t).c_body_ref().transpose() * dc;
        let w = Vec3::new(skew[(2, 1)], skew[(0, 2)], skew[(1, 0)]);
        let got = angles(t).body_rate(&rates);
        assert!((got - w).norm() < 1e-9, "{got} vs {w}");
    }

    #[test]
    fn c_body_ref_is_thesis_eq_2_5_6() {
        let a = YawPitchRoll::new(0.3, -0.7, 1.9);
        let r = thesis_r_xi(0.3, -0.7, 1.9);
        assert!((a.c_body_ref() - r).norm() < 1e-15);
        assert!((a.c_ref_body() - r.transpose()).norm() < 1e-15);
    }

    #[test]
    fn pure_yaw_turns_body_x_towards_east() {
        // From NED, yaw +90 deg points the body X axis (nose) east, Z still down.
        let c_body_ned = YawPitchRoll::new(FRAC_PI_2, 0.0, 0.0).c_body_ref();
        assert!((c_body_ned * Vec3::x() - Vec3::y()).norm() < 1e-15);
        assert!((c_body_ned * Vec3::z() - Vec3::z()).norm() < 1e-15);
        // Pitch +90 deg raises the nose: body X points up (-Z in NED).
        let c = YawPitchRoll::new(0.0, FRAC_PI_2, 0.0).c_body_ref();
        assert!((c * Vec3::x() + Vec3::z()).norm() < 1e-15);
        // Roll +90 deg turns the right wing (body Y) down.
        let c = YawPitchRoll::new(0.0, 0.0, FRAC_PI_2).c_body_ref();
        assert!((c * Vec3::y() - Vec3::z()).norm() < 1e-15);
    }

    #[test]
    fn gimbal_lock_keeps_the_rotation() {
        let a = YawPitchRoll::new(0.4, FRAC_PI_2, 0.1);
        let b = YawPitchRoll::from_c_ref_body(&a.c_ref_body());
        assert!((b.c_ref_body() - a.c_ref_body()).norm() < 1e-7);
        assert_eq!(b.roll_rad, 0.0);
    }

    fn angles() -> impl Strategy<Value = YawPitchRoll> {
        (
            -PI + 1e-9..PI,
            -FRAC_PI_2 + 1e-3..FRAC_PI_2 - 1e-3,
            -PI + 1e-9..PI,
        )
            .prop_map(|(y, p, r)| YawPitchRoll::new(y, p, r))
    }

    proptest! {
        #[test]
        fn ypr_dcm_round_trip(a in angles()) {
            let c = a.c_ref_body();
            prop_assert!((c * c.transpose() - Mat3::identity()).norm() < 1e-14);
            prop_assert!((c.determinant() - 1.0).abs() < 1e-14);
            prop_assert!((c.transpose() - thesis_r_xi(a.yaw_rad, a.pitch_rad, a.roll_rad)).norm() < 1e-14);
            let b = YawPitchRoll::from_c_ref_body(&c);
            prop_assert!((b.yaw_rad - a.yaw_rad).abs() < 1e-10);
            prop_assert!((b.pitch_rad - a.pitch_rad).abs() < 1e-10);
            prop_assert!((b.roll_rad - a.roll_rad).abs() < 1e-10);
        }

        #[test]
        fn ypr_quaternion_round_trip(a in angles(), vx in -1.0f64..1.0, vy in -1.0f64..1.0, vz in -1.0f64..1.0) {
            let q = a.q_body_ref();
            let v_body = Vec3::new(vx, vy, vz);
            // The quaternion rotates body components into reference components.
            prop_assert!((q * v_body - a.c_body_ref() * v_body).norm() < 1e-14);
            prop_assert!((q.to_rotation_matrix().matrix() - a.c_body_ref()).norm() < 1e-14);
            let b = YawPitchRoll::from_q_body_ref(&q);
            prop_assert!((b.yaw_rad - a.yaw_rad).abs() < 1e-9);
            prop_assert!((b.pitch_rad - a.pitch_rad).abs() < 1e-9);
            prop_assert!((b.roll_rad - a.roll_rad).abs() < 1e-9);
        }
    }
}
