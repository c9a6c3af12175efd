//! A satellite as its signal leaves it: the broadcast orbit and clock, plus the
//! satellite-side errors of the run where it has them (`errors::SatelliteErrors`).

use crate::errors::SatelliteTrack;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::BoundEphemeris;
use skyforge_orbits::frames::c_rac_eci;

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

    /// The orbit error at `t_s` in the Earth-fixed frame (m): the track's radial,
    /// along-track and cross-track components on the axes of the broadcast orbit (the
    /// along-track axis from the inertial velocity).
    pub fn orbit_error_ecef(&self, t_s: f64) -> Vec3 {
        match self.error {
            None => Vec3::zeros(),
            Some(track) => {
                let (r, v) = self.eph.state_ecef(t_s);
                self.error_on_axes(track, &r, &v, t_s)
            }
        }
    }

    /// The antenna phase centre at `t_s` (Earth-fixed frame of `t_s`, m).
    pub fn position_ecef(&self, t_s: f64) -> Vec3 {
        match self.error {
            None => self.eph.position_ecef(t_s),
            Some(track) => {
                let (r, v) = self.eph.state_ecef(t_s);
                r + self.error_on_axes(track, &r, &v, t_s)
            }
        }
    }

    /// `track`'s orbit error at `t_s` on the axes of the broadcast state `r`, `v`.
    fn error_on_axes(&self, track: &SatelliteTrack, r: &Vec3, v: &Vec3, t_s: f64) -> Vec3 {
        let omega = Vec3::new(0.0, 0.0, self.eph.eph.sat.system.earth_rotation_rad_s());
        c_rac_eci(r, &(v + omega.cross(r))) * track.orbit_rac_m(t_s)
    }

    /// The clock error at `t_s` (s) and its rate (s/s): zero without a track.
    pub fn clock_error(&self, t_s: f64) -> (f64, f64) {
        self.error.map_or((0.0, 0.0), |track| {
            let (m, rate) = track.clock_m_and_rate(t_s);
            (m / C_MPS, rate / C_MPS)
        })
    }
}
