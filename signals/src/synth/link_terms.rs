//! The error terms of each link at a geometry epoch: ionosphere, troposphere, antenna
//! phase-centre offset/variation, C/N0 (fixed or from the link budget with the antenna
//! gain pattern) and reflected paths (taps and spacecraft surfaces).

use super::config::SignalConfig;
use super::link::LinkEnd;
use crate::antenna::Antenna;
use crate::errors::ionosphere::IonoConfig;
use crate::errors::multipath::{MultipathConfig, Path, surface_path, tap_path};
use crate::errors::troposphere::TropoConfig;
use crate::truth::geometry::LinkGeometry;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic};
use skyforge_orbits::platform::PlatformState;
use skyforge_orbits::{Mat3, Vec3};

/// The scenario's error sources, applied link by link.
#[derive(Debug, Clone, Copy)]
pub struct LinkTerms<'a> {
    pub signal: &'a SignalConfig,
    pub ionosphere: &'a IonoConfig,
    pub troposphere: &'a TropoConfig,
    pub multipath: &'a MultipathConfig,
    pub antennas: &'a [Antenna],
}

/// One antenna at one epoch: where it is and how its body frame lies.
#[derive(Debug, Clone, Copy)]
pub struct AntennaEpoch {
    pub geodetic: Geodetic,
    /// ECEF to local north-east-down.
    pub c_ecef_ned: Mat3,
    /// Body to ECEF.
    pub c_body_ecef: Mat3,
}

impl AntennaEpoch {
    /// Antenna `antenna` on the platform in state `st`.
    pub fn new(st: &PlatformState, antenna: &Antenna) -> Self {
        let geodetic = ecef_to_geodetic(&(st.r_ecef_m + st.c_body_ecef * antenna.true_body_m));
        Self {
            geodetic,
            c_ecef_ned: c_ecef_ned(geodetic.lat_rad, geodetic.lon_rad),
            c_body_ecef: st.c_body_ecef,
        }
    }

    /// Unit line of sight to a satellite at local azimuth/elevation, in the body frame.
    fn los_body(&self, az_rad: f64, el_rad: f64) -> Vec3 {
        let (se, ce) = el_rad.sin_cos();
        let (sa, ca) = az_rad.sin_cos();
        let ned = Vec3::new(ce * ca, ce * sa, -se);
        self.c_body_ecef.transpose() * (self.c_ecef_ned.transpose() * ned)
    }
}

impl LinkTerms<'_> {
    /// The link of antenna `a` (at `at`) to `sat` transmitting `signal`, at scenario time
    /// `t_s` and `sow` seconds of the satellite system's week; `None` when not visible.
    #[allow(clippy::too_many_arguments)]
    pub fn link_end(
        &self,
        t_s: f64,
        sow: f64,
        a: usize,
        at: &AntennaEpoch,
        sat: SatId,
        signal: Signal,
        g: &LinkGeometry,
    ) -> Option<LinkEnd> {
        if !g.visible {
            return None;
        }
        let antenna = &self.antennas[a];
        let carrier_hz = signal.carrier_hz();
        let (az_ant, el_ant) = (g.antenna_azimuth_rad, g.antenna_elevation_rad);
        let cn0_dbhz = self.signal.fixed_cn0_dbhz(sat).unwrap_or_else(|| {
            self.signal
                .link_budget
                .as_ref()
                .map_or(self.signal.cn0_dbhz, |b| {
                    b.cn0_dbhz(signal, g.range_m, antenna.gain_dbi_at(az_ant, el_ant))
                })
        });
        let end = LinkEnd::from_geometry(g, cn0_dbhz)?;
        Some(LinkEnd {
            iono_m: self
                .ionosphere
                .delay(
                    sat.system,
                    &at.geodetic,
                    g.azimuth_rad,
                    g.elevation_rad,
                    sow,
                    carrier_hz,
                )
                .code_m,
            tropo_m: self.troposphere.delay_m(
                at.geodetic.lat_rad,
                at.geodetic.h_m,
                g.elevation_rad,
            ),
            antenna_m: antenna.phase_centre_delay_m(signal, az_ant, el_ant),
            antenna_by_signal_m: if antenna.phase_centres.is_empty() {
                Vec::new()
            } else {
                (Signal::ALL.iter())
                    .map(|&s| (s, antenna.phase_centre_delay_m(s, az_ant, el_ant)))
                    .collect()
            },
            reflections: self.reflections(t_s, a, at, sat, g),
            ..end
        })
    }

    /// The reflected paths of one link, in a fixed order (taps, then surfaces; a surface
    /// that does not reflect toward the antenna now has amplitude 0).
    fn reflections(
        &self,
        t_s: f64,
        a: usize,
        at: &AntennaEpoch,
        sat: SatId,
        g: &LinkGeometry,
    ) -> Vec<Path> {
        let antenna = &self.antennas[a];
        let mut paths: Vec<Path> = (self.multipath.taps.iter())
            .filter(|tap| tap.applies_to(&antenna.name, sat))
            .map(|tap| tap_path(tap, t_s))
            .collect();
        let surfaces = (self.multipath.surfaces.iter()).filter(|s| s.applies_to(&antenna.name));
        let mut los = None;
        for surface in surfaces {
            let los = *los.get_or_insert_with(|| at.los_body(g.azimuth_rad, g.elevation_rad));
            paths.push(
                surface_path(surface, &antenna.true_body_m, &los).unwrap_or(Path {
                    delay_m: 0.0,
                    relative_amplitude: 0.0,
                    phase_rad: 0.0,
                }),
            );
        }
        paths
    }
}
