//! The navigation state a strapdown INS carries in the Earth-centred, Earth-fixed frame.

use hifitime::Epoch;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::{Mat3, Vec3};

/// Position, velocity and attitude of the IMU's body frame at time `t`, ECEF-resolved
/// (Groves 2013 sec. 5.2: the ECEF-frame navigation solution).
///
/// Conventions: `c_body_ecef` maps body components (front-right-down) to ECEF components,
/// `x_ecef = c_body_ecef * x_body` (Groves' `C_b^e`); `v_ecef_mps` is the velocity
/// relative to the Earth, ECEF-resolved (Groves' `v_eb^e`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InsState {
    /// Time of validity (GPS time).
    pub t: Epoch,
    /// Position of the IMU, ECEF (m).
    pub r_ecef_m: Vec3,
    /// Velocity relative to the Earth, ECEF axes (m/s).
    pub v_ecef_mps: Vec3,
    /// Body-to-ECEF direction-cosine matrix, kept orthonormal by every update.
    pub c_body_ecef: Mat3,
}

impl InsState {
    /// A state at rest relative to the Earth at `r_ecef_m` with attitude `c_body_ecef`.
    pub fn at_rest(t: Epoch, r_ecef_m: Vec3, c_body_ecef: Mat3) -> Self {
        Self {
            t,
            r_ecef_m,
            v_ecef_mps: Vec3::zeros(),
            c_body_ecef,
        }
    }

    /// Geodetic position of the state.
    pub fn geodetic(&self) -> Geodetic {
        ecef_to_geodetic(&self.r_ecef_m)
    }

    /// Velocity in the local north-east-down frame at the state's position (m/s).
    pub fn v_ned_mps(&self) -> Vec3 {
        let g = self.geodetic();
        c_ecef_ned(g.lat_rad, g.lon_rad) * self.v_ecef_mps
    }

    /// Heading, pitch and roll of the body relative to the local NED frame at the state's
    /// position.
    pub fn attitude_ned(&self) -> YawPitchRoll {
        attitude_ned(&self.c_body_ecef, &self.geodetic())
    }

    /// Height held, as a marine INS holds it (the free vertical channel diverges with a
    /// time constant of about `sqrt(R / 2g)`, 570 s, and a vessel knows its height): the
    /// state moved along its local vertical to `h_m` above the ellipsoid and its
    /// vertical velocity removed.
    pub fn hold_height(&mut self, h_m: f64) {
        let g = self.geodetic();
        let c = c_ecef_ned(g.lat_rad, g.lon_rad);
        let mut v_ned = c * self.v_ecef_mps;
        v_ned.z = 0.0;
        self.v_ecef_mps = c.transpose() * v_ned;
        self.r_ecef_m = geodetic_to_ecef(&Geodetic { h_m, ..g });
    }
}

/// Heading (yaw), pitch and roll of a body with attitude `c_body_ecef` relative to the
/// NED frame at `position`.
pub fn attitude_ned(c_body_ecef: &Mat3, position: &Geodetic) -> YawPitchRoll {
    let c_body_ned = c_ecef_ned(position.lat_rad, position.lon_rad) * c_body_ecef;
    YawPitchRoll::from_c_ref_body(&c_body_ned.transpose())
}
