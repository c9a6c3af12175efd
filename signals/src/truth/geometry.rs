//! Geometry truth for every antenna x visible satellite at a requested rate: light-time
//! range, range rate, acceleration and jerk, Doppler and its derivatives at the carrier of
//! the satellite's signal, azimuth/elevation in the local (NED) and the antenna frame,
//! visibility, and the satellite clock (relativistic term included).
//!
//! Derivatives come from a five-point central-difference stencil of the light-time range
//! with spacing `h` (the output step when it lies in [0.25, 2] s, so neighbouring epochs
//! share stencil points; otherwise 1 s). With ranges exact to ~4e-9 m (f64 at 2e7 m) the
//! rounding errors are below 1e-8 m/s, 2e-8 m/s^2 and 3e-8 m/s^3 at h = 1 s; truncation
//! errors (h^4/30 rho^(5) and h^2/4 rho^(5)) are smaller still at LEO dynamics.

use super::light_time::{self, LightTime};
use crate::antenna::Antenna;
use crate::signal::SignalId;
use rayon::prelude::*;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BoundEphemeris, EphemerisStore, SatId};
use skyforge_orbits::frames::geodetic::ecef_to_geodetic;
use skyforge_orbits::frames::ned::{az_el, c_ecef_ned};
use skyforge_orbits::platform::{Platform, PlatformError, PlatformState, PlatformWindow};
use skyforge_orbits::visibility::{earth_blocked, within_fov};
use skyforge_orbits::{Mat3, Vec3};

/// Lines of sight are blocked by the WGS-84 ellipsoid itself (no atmosphere margin).
const GRAZING_HEIGHT_M: f64 = 0.0;
/// Margin on the quick visibility screen, so that it never misses a link the exact test
/// (at the light-time solution) accepts.
const SCREEN_MARGIN_RAD: f64 = 2e-3;
/// Look-back used for the quick screen's satellite position (a typical light time, s).
const SCREEN_TAU_S: f64 = 0.075;

/// One antenna x satellite link at one epoch. Every field is NaN when not visible.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkGeometry {
    pub visible: bool,
    /// Geometric range c * tau (m).
    pub range_m: f64,
    pub range_rate_mps: f64,
    pub range_accel_mps2: f64,
    pub range_jerk_mps3: f64,
    /// Geometric Doppler at the signal's carrier, -range_rate / lambda (Hz).
    pub doppler_hz: f64,
    pub doppler_rate_hzps: f64,
    pub doppler_accel_hzps2: f64,
    pub light_time_s: f64,
    /// Local NED azimuth/elevation at the antenna (rad).
    pub azimuth_rad: f64,
    pub elevation_rad: f64,
    /// Azimuth/elevation in the antenna frame (elevation = 90 deg - off-boresight angle).
    pub antenna_azimuth_rad: f64,
    pub antenna_elevation_rad: f64,
    /// Satellite clock offset at transmit time, relativistic term included, TGD excluded (s).
    pub sat_clock_s: f64,
    /// Satellite clock drift at transmit time (s/s).
    pub sat_clock_drift: f64,
}

impl LinkGeometry {
    /// A link with no geometry (satellite not visible from the antenna).
    pub const NOT_VISIBLE: LinkGeometry = LinkGeometry {
        visible: false,
        range_m: f64::NAN,
        range_rate_mps: f64::NAN,
        range_accel_mps2: f64::NAN,
        range_jerk_mps3: f64::NAN,
        doppler_hz: f64::NAN,
        doppler_rate_hzps: f64::NAN,
        doppler_accel_hzps2: f64::NAN,
        light_time_s: f64::NAN,
        azimuth_rad: f64::NAN,
        elevation_rad: f64::NAN,
        antenna_azimuth_rad: f64::NAN,
        antenna_elevation_rad: f64::NAN,
        sat_clock_s: f64::NAN,
        sat_clock_drift: f64::NAN,
    };
}

/// Geometry of consecutive epochs: `links[(k * n_antennas + a) * n_satellites + s]`.
#[derive(Debug, Clone)]
pub struct GeometryChunk {
    pub t_s: Vec<f64>,
    pub platform: Vec<PlatformState>,
    pub links: Vec<LinkGeometry>,
    pub n_antennas: usize,
    pub n_satellites: usize,
}

impl GeometryChunk {
    /// The link of epoch `k`, antenna `a`, satellite `s`.
    pub fn link(&self, k: usize, a: usize, s: usize) -> &LinkGeometry {
        &self.links[(k * self.n_antennas + a) * self.n_satellites + s]
    }
}

/// An antenna's fixed frame: rows are the antenna axes in body components; Z = boresight,
/// X = body X (or body Y when the boresight is along X) made orthogonal to it.
#[derive(Debug, Clone, Copy)]
struct AntennaFrame {
    c_body_antenna: Mat3,
}

impl AntennaFrame {
    fn new(boresight_body: &Vec3) -> Self {
        let z = boresight_body.normalize();
        let seed = if z.x.abs() < 0.9 {
            Vec3::x()
        } else {
            Vec3::y()
        };
        let x = (seed - z * seed.dot(&z)).normalize();
        let y = z.cross(&x);
        Self {
            c_body_antenna: Mat3::from_rows(&[x.transpose(), y.transpose(), z.transpose()]),
        }
    }
}

/// Azimuth (from X towards Y, [0, 2pi)) and elevation above the XY plane of a vector.
fn az_el_xyz(v: &Vec3) -> (f64, f64) {
    let az = v.y.atan2(v.x).rem_euclid(std::f64::consts::TAU);
    (az, (v.z / v.norm()).clamp(-1.0, 1.0).asin())
}

/// Five-point stencil layout of a chunk's sample times.
#[derive(Debug, Clone, Copy)]
struct Stencil {
    h_s: f64,
    /// Neighbouring epochs share samples (h equals the output step).
    shared: bool,
}

impl Stencil {
    fn new(step_s: f64) -> Self {
        if (0.25..=2.0).contains(&step_s) {
            Self {
                h_s: step_s,
                shared: true,
            }
        } else {
            Self {
                h_s: 1.0,
                shared: false,
            }
        }
    }
    fn n_samples(&self, n_epochs: usize) -> usize {
        if self.shared {
            n_epochs + 4
        } else {
            5 * n_epochs
        }
    }
    /// Sample index of stencil point `j` (-2..=2) of epoch `k`.
    fn sample(&self, k: usize, j: isize) -> usize {
        let base = if self.shared { k + 2 } else { 5 * k + 2 };
        base.wrapping_add_signed(j)
    }
    fn sample_time(&self, t_first_s: f64, step_s: f64, i: usize) -> f64 {
        if self.shared {
            t_first_s + (i as f64 - 2.0) * step_s
        } else {
            let (k, j) = (i / 5, i % 5);
            t_first_s + k as f64 * step_s + (j as f64 - 2.0) * self.h_s
        }
    }
}

/// Computes geometry truth for a set of satellites and antennas.
#[derive(Debug)]
pub struct GeometryTruth<'a> {
    store: &'a EphemerisStore,
    satellites: &'a [SatId],
    antennas: &'a [Antenna],
    frames: Vec<AntennaFrame>,
    carriers_hz: Vec<f64>,
    step_s: f64,
    stencil: Stencil,
}

/// Error streaming geometry.
#[derive(Debug, thiserror::Error)]
pub enum StreamError<E> {
    #[error(transparent)]
    Platform(#[from] PlatformError),
    #[error(transparent)]
    Sink(E),
}

impl<'a> GeometryTruth<'a> {
    /// Geometry at epochs `k * step_s` for `satellites` x `antennas`.
    pub fn new(
        store: &'a EphemerisStore,
        satellites: &'a [SatId],
        antennas: &'a [Antenna],
        step_s: f64,
    ) -> Self {
        Self {
            store,
            satellites,
            antennas,
            frames: antennas
                .iter()
                .map(|a| AntennaFrame::new(&a.boresight_body))
                .collect(),
            carriers_hz: satellites
                .iter()
                .map(|s| SignalId::primary_for(*s).carrier_hz())
                .collect(),
            step_s,
            stencil: Stencil::new(step_s),
        }
    }

    /// Extra time a platform window needs on each side of a chunk's epochs.
    pub fn window_margin_s(&self) -> f64 {
        2.0 * self.stencil.h_s
    }

    /// Geometry of `n_epochs` epochs starting at `t_first_s`; `window` must cover
    /// `[t_first_s - margin, t_last + margin]` (see [`Self::window_margin_s`]).
    pub fn chunk(&self, window: &PlatformWindow, t_first_s: f64, n_epochs: usize) -> GeometryChunk {
        let (n_ant, n_sat) = (self.antennas.len(), self.satellites.len());
        let n_samples = self.stencil.n_samples(n_epochs);
        let sample_t: Vec<f64> = (0..n_samples)
            .map(|i| self.stencil.sample_time(t_first_s, self.step_s, i))
            .collect();
        let states: Vec<PlatformState> = sample_t.par_iter().map(|&t| window.state(t)).collect();
        let antenna_pos: Vec<Vec3> = states
            .iter()
            .flat_map(|st| {
                self.antennas
                    .iter()
                    .map(move |a| st.r_ecef_m + st.c_body_ecef * a.true_body_m)
            })
            .collect();
        // The ephemeris used for each epoch's satellite, fixed across the epoch's stencil so
        // that an ephemeris change never lands inside a finite difference.
        let t_epochs: Vec<f64> = (0..n_epochs)
            .map(|k| t_first_s + k as f64 * self.step_s)
            .collect();
        let ephs: Vec<Option<&BoundEphemeris>> = t_epochs
            .iter()
            .flat_map(|&t| {
                self.satellites
                    .iter()
                    .map(move |&sat| self.store.select(sat, t))
            })
            .collect();
        // Pass 1: quick screen at each epoch (approximate satellite position).
        let screen: Vec<bool> = (0..n_epochs)
            .into_par_iter()
            .flat_map_iter(|k| {
                let i = self.stencil.sample(k, 0);
                (0..n_ant).flat_map(move |a| (0..n_sat).map(move |s| (k, i, a, s)))
            })
            .map(|(k, i, a, s)| {
                ephs[k * n_sat + s].is_some_and(|eph| {
                    let r_sat = eph.position_ecef(sample_t[i] - SCREEN_TAU_S);
                    self.passes(
                        a,
                        &states[i],
                        &antenna_pos[i * n_ant + a],
                        &r_sat,
                        SCREEN_MARGIN_RAD,
                    )
                })
            })
            .collect();
        // Pass 2: light-time solutions at every stencil point of a screened link.
        let ranges: Vec<f64> = (0..n_epochs)
            .into_par_iter()
            .flat_map_iter(|k| (0..n_ant).flat_map(move |a| (0..n_sat).map(move |s| (k, a, s))))
            .flat_map_iter(|(k, a, s)| {
                let link = (k * n_ant + a) * n_sat + s;
                let eph = if screen[link] {
                    ephs[k * n_sat + s]
                } else {
                    None
                };
                let mut out = [f64::NAN; 5];
                if let Some(eph) = eph {
                    let mut tau = SCREEN_TAU_S;
                    for (slot, j) in out.iter_mut().zip(-2..=2) {
                        let i = self.stencil.sample(k, j);
                        let lt =
                            light_time::solve(eph, &antenna_pos[i * n_ant + a], sample_t[i], tau);
                        tau = lt.tau_s;
                        *slot = lt.range_m();
                    }
                }
                out
            })
            .collect();
        // Pass 3: derivatives, angles, exact visibility.
        let links: Vec<LinkGeometry> = (0..n_epochs * n_ant * n_sat)
            .into_par_iter()
            .map(|link| {
                let (k, a, s) = (link / (n_ant * n_sat), (link / n_sat) % n_ant, link % n_sat);
                let rho = &ranges[5 * link..5 * link + 5];
                match ephs[k * n_sat + s] {
                    Some(eph) if screen[link] => {
                        let i = self.stencil.sample(k, 0);
                        self.link(
                            eph,
                            a,
                            s,
                            &states[i],
                            &antenna_pos[i * n_ant + a],
                            sample_t[i],
                            rho,
                        )
                    }
                    _ => LinkGeometry::NOT_VISIBLE,
                }
            })
            .collect();
        GeometryChunk {
            t_s: t_epochs,
            platform: (0..n_epochs)
                .map(|k| states[self.stencil.sample(k, 0)])
                .collect(),
            links,
            n_antennas: n_ant,
            n_satellites: n_sat,
        }
    }

    /// Field of view, elevation mask and Earth blockage, each widened by `margin_rad`.
    fn passes(
        &self,
        a: usize,
        st: &PlatformState,
        r_ant: &Vec3,
        r_sat: &Vec3,
        margin_rad: f64,
    ) -> bool {
        let ant = &self.antennas[a];
        let los_ecef = (r_sat - r_ant).normalize();
        let los_body = st.c_body_ecef.transpose() * los_ecef;
        if !within_fov(
            &los_body,
            &ant.boresight_body,
            ant.fov_half_angle_rad + margin_rad,
        ) {
            return false;
        }
        if ant.elevation_mask_rad > -std::f64::consts::FRAC_PI_2 {
            let g = ecef_to_geodetic(r_ant);
            let (_, el) = az_el(&(c_ecef_ned(g.lat_rad, g.lon_rad) * los_ecef));
            if el < ant.elevation_mask_rad - margin_rad {
                return false;
            }
        }
        let grazing = if margin_rad > 0.0 {
            GRAZING_HEIGHT_M - 1e4
        } else {
            GRAZING_HEIGHT_M
        };
        !earth_blocked(r_ant, r_sat, grazing)
    }

    #[allow(clippy::too_many_arguments)]
    fn link(
        &self,
        eph: &BoundEphemeris,
        a: usize,
        s: usize,
        st: &PlatformState,
        r_ant: &Vec3,
        t_s: f64,
        rho: &[f64],
    ) -> LinkGeometry {
        let lt: LightTime = light_time::solve(eph, r_ant, t_s, rho[2] / C_MPS);
        if !self.passes(a, st, r_ant, &lt.r_sat_rx_frame_m, 0.0) {
            return LinkGeometry::NOT_VISIBLE;
        }
        let h = self.stencil.h_s;
        let rate = (rho[0] - 8.0 * rho[1] + 8.0 * rho[3] - rho[4]) / (12.0 * h);
        let accel =
            (-rho[0] + 16.0 * rho[1] - 30.0 * rho[2] + 16.0 * rho[3] - rho[4]) / (12.0 * h * h);
        let jerk = (-rho[0] + 2.0 * rho[1] - 2.0 * rho[3] + rho[4]) / (2.0 * h * h * h);
        let per_m = -self.carriers_hz[s] / C_MPS;
        let los = lt.r_sat_rx_frame_m - r_ant;
        let g = ecef_to_geodetic(r_ant);
        let (azimuth_rad, elevation_rad) = az_el(&(c_ecef_ned(g.lat_rad, g.lon_rad) * los));
        let los_antenna = self.frames[a].c_body_antenna * (st.c_body_ecef.transpose() * los);
        let (antenna_azimuth_rad, antenna_elevation_rad) = az_el_xyz(&los_antenna);
        let t_tx = t_s - lt.tau_s;
        LinkGeometry {
            visible: true,
            range_m: lt.range_m(),
            range_rate_mps: rate,
            range_accel_mps2: accel,
            range_jerk_mps3: jerk,
            doppler_hz: rate * per_m,
            doppler_rate_hzps: accel * per_m,
            doppler_accel_hzps2: jerk * per_m,
            light_time_s: lt.tau_s,
            azimuth_rad,
            elevation_rad,
            antenna_azimuth_rad,
            antenna_elevation_rad,
            sat_clock_s: eph.clock_offset_s(t_tx),
            sat_clock_drift: eph.clock_drift(t_tx),
        }
    }

    /// Stream geometry for epochs `0, step, ..., <= duration_s` in chunks of `chunk_epochs`,
    /// handing each chunk to `sink`; memory stays bounded by the chunk size.
    pub fn stream<E>(
        &self,
        platform: &mut Platform,
        duration_s: f64,
        chunk_epochs: usize,
        mut sink: impl FnMut(GeometryChunk) -> Result<(), E>,
    ) -> Result<(), StreamError<E>> {
        let n_total = epoch_count(duration_s, self.step_s);
        let chunk_epochs = chunk_epochs.max(1);
        let margin = self.window_margin_s();
        let mut k0 = 0;
        while k0 < n_total {
            let n = chunk_epochs.min(n_total - k0);
            let t_first = k0 as f64 * self.step_s;
            let t_last = (k0 + n - 1) as f64 * self.step_s;
            let window = platform.window(t_first - margin, t_last + margin)?;
            let chunk = self.chunk(&window, t_first, n);
            sink(chunk).map_err(StreamError::Sink)?;
            k0 += n;
        }
        Ok(())
    }
}

/// Number of epochs `0, step, 2 step, ...` within `[0, duration_s]`.
pub fn epoch_count(duration_s: f64, step_s: f64) -> usize {
    (duration_s / step_s + 1e-9).floor() as usize + 1
}
