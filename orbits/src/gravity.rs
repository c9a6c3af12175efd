//! Normal gravity of the WGS-84 ellipsoid near the Earth's surface: the world's gravity
//! where SkyForge simulates inertial sensors, and the model a strapdown INS subtracts.
//! Gravity here is the gravitational attraction plus the centrifugal acceleration of the
//! Earth's rotation (what a plumb line shows); gravity anomalies and deflections of the
//! vertical are not simulated.
//!
//! Somigliana's formula at the ellipsoid (NIMA TR8350.2 eq. 4-1; Groves 2013 eq. 2.134)
//! `g0 = g_e (1 + k sin^2 L) / sqrt(1 - e^2 sin^2 L)`, and its height dependence to second
//! order (TR8350.2 eq. 4-3; Groves eq. 2.139)
//! `g_D = g0 (1 - 2 h (1 + f + m - 2 f sin^2 L) / a + 3 h^2 / a^2)`, with the small north
//! component `g_N = -8.08e-9 h sin 2L` m/s^2 (Groves eq. 2.140).

use crate::Vec3;
use crate::constants::J2;
use crate::constants::{OMEGA_E_GPS, WGS84_A_M, WGS84_F};
use crate::frames::geodetic::Geodetic;
use crate::frames::ned::c_ecef_ned;
use crate::propagate::forces::{J3, J4, J5, J6, zonal_gravitation};

/// Normal gravity at the equator (m/s^2), TR8350.2 table 3.4.
const GAMMA_E_MPS2: f64 = 9.780_325_335_9;
/// Somigliana's constant `k`, TR8350.2 table 3.4.
const SOMIGLIANA_K: f64 = 0.001_931_852_652_41;
/// First eccentricity squared of WGS-84.
const E2: f64 = WGS84_F * (2.0 - WGS84_F);
/// The geodetic constant `m = w^2 a^2 b / GM` of WGS-84, TR8350.2 table 3.4.
const M_RATIO: f64 = 0.003_449_786_506_84;

/// Normal gravity (m/s^2) in the local NED frame at `g` (north and down components; east
/// is zero).
pub fn normal_gravity_ned(g: &Geodetic) -> Vec3 {
    let s2 = g.lat_rad.sin().powi(2);
    let g0 = GAMMA_E_MPS2 * (1.0 + SOMIGLIANA_K * s2) / (1.0 - E2 * s2).sqrt();
    let h = g.h_m;
    let down = g0
        * (1.0 - 2.0 * h / WGS84_A_M * (1.0 + WGS84_F + M_RATIO - 2.0 * WGS84_F * s2)
            + 3.0 * h * h / (WGS84_A_M * WGS84_A_M));
    Vec3::new(-8.08e-9 * h * (2.0 * g.lat_rad).sin(), 0.0, down)
}

/// Normal gravity (m/s^2) in ECEF at `g`.
pub fn normal_gravity_ecef(g: &Geodetic) -> Vec3 {
    c_ecef_ned(g.lat_rad, g.lon_rad).transpose() * normal_gravity_ned(g)
}

/// The gravity a strapdown INS subtracts (ECEF, gravitation plus the centrifugal term).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GravityModel {
    /// Normal gravity of the WGS-84 ellipsoid ([`normal_gravity_ecef`]): near the surface.
    #[default]
    Normal,
    /// In orbit: the point mass and the zonal harmonics `J_2 .. J_degree` (degree 0: the
    /// point mass alone; 2: J2; at most 6) of the LEO propagator's force model, plus the
    /// centrifugal acceleration `-w_ie x (w_ie x r)`: the gravity a LEO propagated with
    /// the same terms obeys.
    Zonal {
        /// The highest degree, 0 or 2..=6.
        degree: u8,
    },
}

impl GravityModel {
    /// The gravity at `r_ecef_m` (m/s^2, ECEF).
    pub fn ecef(&self, r_ecef_m: &Vec3) -> Vec3 {
        match *self {
            GravityModel::Normal => normal_gravity_ecef(&crate::frames::ecef_to_geodetic(r_ecef_m)),
            GravityModel::Zonal { degree } => {
                let zonals = [0.0, 0.0, J2, J3, J4, J5, J6];
                let degree = usize::from(degree.min(6));
                let w = earth_rate_ecef();
                zonal_gravitation(r_ecef_m, &zonals, degree) - w.cross(&w.cross(r_ecef_m))
            }
        }
    }
}

/// The Earth's rotation vector in ECEF (rad/s): WGS-84's rate about the z axis.
pub fn earth_rate_ecef() -> Vec3 {
    Vec3::new(0.0, 0.0, OMEGA_E_GPS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// TR8350.2 table 3.4: normal gravity at the equator 9.7803253359 and at the poles
    /// 9.8321849378 m/s^2.
    #[test]
    fn equator_and_pole_values() {
        let eq = normal_gravity_ned(&Geodetic::from_degrees(0.0, 0.0, 0.0));
        assert!((eq.z - 9.780_325_335_9).abs() < 1e-10 && eq.x == 0.0);
        let pole = normal_gravity_ned(&Geodetic::from_degrees(90.0, 0.0, 0.0));
        assert!((pole.z - 9.832_184_937_8).abs() < 1e-9, "{}", pole.z);
    }

    /// The free-air gradient near the surface, about -3.086e-6 s^-2 (TR8350.2 sec. 4).
    #[test]
    fn free_air_gradient() {
        let lat = 45.0;
        let g0 = normal_gravity_ned(&Geodetic::from_degrees(lat, 0.0, 0.0)).z;
        let g1 = normal_gravity_ned(&Geodetic::from_degrees(lat, 0.0, 1000.0)).z;
        let gradient = (g1 - g0) / 1000.0;
        assert!((gradient + 3.086e-6).abs() < 0.01e-6, "{gradient}");
    }
}
