//! A satellite as its signal leaves it: the broadcast orbit and clock, plus the
//! satellite-side errors of the run where it has them (`errors::SatelliteErrors`).

use super::light_time::rotate_to_receive_frame;
use crate::errors::{DrawnTrack, SatelliteTrack};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::BoundEphemeris;
use skyforge_orbits::frames::c_rac_eci;

/// Half the step of the central difference that gives a precise clock error's rate (s).
const CLOCK_RATE_STEP_S: f64 = 0.5;

/// The broadcast ephemeris of a satellite and, if any, its error track.
#[derive(Debug, Clone, Copy)]
pub struct TrueSatellite<'a> {
    pub eph: &'a BoundEphemeris,
    pub error: Option<&'a SatelliteTrack>,
}

impl<'a> TrueSatellite<'a> {
    /// A satellite exactly where its ephemeris puts it.
    pub fn broadcast(eph: &'a BoundEphemeris) -> Self {
        Self { eph, error: None }
    }

    /// The orbit error at `t_s` in the Earth-fixed frame (m): true minus broadcast
    /// antenna phase centre.
    pub fn orbit_error_ecef(&self, t_s: f64) -> Vec3 {
        match self.error {
            None => Vec3::zeros(),
            Some(SatelliteTrack::Drawn(track)) => {
                let (r, v) = self.eph.state_ecef(t_s);
                self.drawn_on_axes(track, &r, &v, t_s)
            }
            Some(SatelliteTrack::Precise(p)) => p.position_ecef(t_s) - self.eph.position_ecef(t_s),
        }
    }

    /// The orbit error at transmit time `t_tx_s` along the unit line of sight `los` of a
    /// signal `tau_s` in flight (`los` in the Earth-fixed frame of the receive instant):
    /// what it adds to the range (m; zero without a track, computed for nothing).
    pub fn orbit_error_along(&self, t_tx_s: f64, tau_s: f64, los: &Vec3) -> f64 {
        if self.error.is_none() {
            return 0.0;
        }
        let omega_e = self.eph.eph.sat.system.earth_rotation_rad_s();
        rotate_to_receive_frame(&self.orbit_error_ecef(t_tx_s), omega_e, tau_s).dot(los)
    }

    /// The antenna phase centre at `t_s` (Earth-fixed frame of `t_s`, m).
    pub fn position_ecef(&self, t_s: f64) -> Vec3 {
        match self.error {
            None => self.eph.position_ecef(t_s),
            Some(SatelliteTrack::Drawn(track)) => {
                let (r, v) = self.eph.state_ecef(t_s);
                r + self.drawn_on_axes(track, &r, &v, t_s)
            }
            Some(SatelliteTrack::Precise(p)) => p.position_ecef(t_s),
        }
    }

    /// `track`'s orbit error at `t_s` on the radial, along-track and cross-track axes of
    /// the broadcast state `r`, `v` (the along-track axis from the inertial velocity).
    fn drawn_on_axes(&self, track: &DrawnTrack, r: &Vec3, v: &Vec3, t_s: f64) -> Vec3 {
        let omega = Vec3::new(0.0, 0.0, self.eph.eph.sat.system.earth_rotation_rad_s());
        c_rac_eci(r, &(v + omega.cross(r))) * track.orbit_rac_m(t_s)
    }

    /// The clock error at `t_s` (s: true minus broadcast clock) and its rate (s/s): zero
    /// without a track. A precise clock's rate is its central difference over
    /// [`CLOCK_RATE_STEP_S`].
    pub fn clock_error(&self, t_s: f64) -> (f64, f64) {
        match self.error {
            None => (0.0, 0.0),
            Some(SatelliteTrack::Drawn(track)) => {
                let (m, rate) = track.clock_m_and_rate(t_s);
                (m / C_MPS, rate / C_MPS)
            }
            Some(SatelliteTrack::Precise(p)) => {
                let h = CLOCK_RATE_STEP_S;
                let at = |t: f64| p.clock_error_s(self.eph, t);
                (at(t_s), (at(t_s + h) - at(t_s - h)) / (2.0 * h))
            }
        }
    }
}
