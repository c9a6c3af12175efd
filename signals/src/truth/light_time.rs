//! Light time between a transmitting GNSS satellite and a receiving antenna, solved
//! iteratively in the inertial frame (Sagnac effect included).
//!
//! The satellite (its broadcast ephemeris, plus its orbit error where the run has one)
//! is given in the Earth-fixed frame of the transmit instant. Rotating that position about Z by `omega_e * tau` expresses it in the
//! Earth-fixed frame of the receive instant; the distance between the two points is then
//! the inertial (straight-line, constant-speed) signal path. With the Earth-rotation-only
//! ECI of `skyforge_orbits::frames::earth_rotation` this is exact, not an approximation.
//! The fixed-point iteration contracts by about |v_sat|/c ~ 1e-5 per step, so it is run to
//! the floating-point floor (a few 1e-17 s, far below 1 mm), which keeps finite
//! differences of the range smooth.

use super::TrueSatellite;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;

/// Iteration stops when the light time changes by less than this (s): 3e-9 mm.
const TAU_CONVERGED_S: f64 = 1e-17;
/// More iterations than convergence from a 0.1 s error ever needs.
const MAX_ITERATIONS: usize = 8;

/// A solved signal path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightTime {
    /// Signal travel time (s).
    pub tau_s: f64,
    /// Satellite antenna phase centre at transmit time, in the Earth-fixed frame of the
    /// receive instant (m).
    pub r_sat_rx_frame_m: Vec3,
}

impl LightTime {
    /// Geometric range c * tau (m).
    pub fn range_m(&self) -> f64 {
        self.tau_s * C_MPS
    }
}

/// `r_ecef` at transmit time, expressed in the Earth-fixed frame `tau_s` later.
pub fn rotate_to_receive_frame(r_ecef_m: &Vec3, omega_e: f64, tau_s: f64) -> Vec3 {
    let (s, c) = (omega_e * tau_s).sin_cos();
    Vec3::new(
        c * r_ecef_m.x + s * r_ecef_m.y,
        -s * r_ecef_m.x + c * r_ecef_m.y,
        r_ecef_m.z,
    )
}

/// Solve the light time for a signal received at `t_rx_s` by an antenna at `r_rx_ecef_m`
/// (Earth-fixed at the receive instant), starting from `tau_guess_s`.
pub fn solve(sat: &TrueSatellite, r_rx_ecef_m: &Vec3, t_rx_s: f64, tau_guess_s: f64) -> LightTime {
    let omega_e = sat.eph.eph.sat.system.earth_rotation_rad_s();
    let mut tau_s = tau_guess_s;
    let mut r_sat = rotate_to_receive_frame(&sat.position_ecef(t_rx_s - tau_s), omega_e, tau_s);
    for _ in 0..MAX_ITERATIONS {
        let next = (r_sat - r_rx_ecef_m).norm() / C_MPS;
        let change = (next - tau_s).abs();
        tau_s = next;
        r_sat = rotate_to_receive_frame(&sat.position_ecef(t_rx_s - tau_s), omega_e, tau_s);
        if change < TAU_CONVERGED_S {
            break;
        }
    }
    LightTime {
        tau_s,
        r_sat_rx_frame_m: r_sat,
    }
}
