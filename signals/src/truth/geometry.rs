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

use super::TrueSatellite;
use super::light_time::{self, LightTime};
use crate::antenna::Antenna;
use crate::errors::{SatelliteErrors, SatelliteTrack};
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BoundEphemeris, EphemerisStore, SatId, System};
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::frames::{az_el, c_ecef_ned};
use skyforge_orbits::platform::{Platform, PlatformError, PlatformState, PlatformWindow};
use skyforge_orbits::time::GstGpsOffset;
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
    /// The satellite's orbit error (true minus broadcast position at transmit time) along
    /// the line of sight from the antenna: what it adds to the range (m; zero without
    /// `[errors.satellite]`).
    pub sat_orbit_error_m: f64,
    /// The satellite's clock error (true minus broadcast clock at transmit time) times c:
    /// what it takes off the pseudorange (m; included in `sat_clock_s`).
    pub sat_clock_error_m: f64,
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
        sat_orbit_error_m: f64::NAN,
        sat_clock_error_m: f64::NAN,
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
pub(crate) struct AntennaFrame {
    pub(crate) c_body_antenna: Mat3,
}

impl AntennaFrame {
    pub(crate) fn new(boresight_body: &Vec3) -> Self {
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

/// An antenna's phase-centre reference point and local NED frame at one sample time.
#[derive(Debug, Clone, Copy)]
struct AntennaAt {
    r_ecef_m: Vec3,
    c_ecef_ned: Mat3,
}

impl AntennaAt {
    fn new(st: &PlatformState, ant: &Antenna) -> Self {
        let r_ecef_m = st.r_ecef_m + st.c_body_ecef * ant.true_body_m;
        let g = ecef_to_geodetic(&r_ecef_m);
        Self {
            r_ecef_m,
            c_ecef_ned: c_ecef_ned(g.lat_rad, g.lon_rad),
        }
    }
}

/// Azimuth (from X towards Y, [0, 2pi)) and elevation above the XY plane of a vector.
pub(crate) fn az_el_xyz(v: &Vec3) -> (f64, f64) {
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
    /// The epoch whose ephemeris selection a sample uses (its own epoch, clamped).
    fn epoch_of(&self, i: usize, n_epochs: usize) -> usize {
        let k = if self.shared {
            i.saturating_sub(2)
        } else {
            i / 5
        };
        k.min(n_epochs - 1)
    }
    /// The epochs whose stencils contain sample `i`.
    fn epochs_using(&self, i: usize, n_epochs: usize) -> std::ops::Range<usize> {
        if self.shared {
            i.saturating_sub(4)..(i + 1).min(n_epochs)
        } else {
            i / 5..i / 5 + 1
        }
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
    /// GST - GPST, in Galileo's satellite clocks.
    gst_gps: GstGpsOffset,
    /// Each satellite's error track (none: it follows its broadcast ephemeris).
    tracks: Vec<Option<&'a SatelliteTrack>>,
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
                .map(|s| Signal::of_system(s.system).carrier_hz())
                .collect(),
            step_s,
            stencil: Stencil::new(step_s),
            gst_gps: GstGpsOffset::default(),
            tracks: vec![None; satellites.len()],
        }
    }

    /// The satellites follow their true orbits and clocks: the broadcast ones plus
    /// `errors` (`[errors.satellite]`).
    pub fn with_satellite_errors(self, errors: &'a SatelliteErrors) -> Self {
        Self {
            tracks: self.satellites.iter().map(|&s| errors.track(s)).collect(),
            ..self
        }
    }

    /// Satellite `s` as its signal leaves it.
    fn true_satellite(&self, eph: &'a BoundEphemeris, s: usize) -> TrueSatellite<'a> {
        TrueSatellite {
            eph,
            error: self.tracks[s],
        }
    }

    /// Galileo's satellite clocks keep GST, `gst_gps` ahead of GPST: each one's offset from
    /// GPST is its broadcast clock (against GST) plus `gst_gps` (Galileo OS SIS ICD §5.1.8).
    pub fn with_gst_gps(self, gst_gps: GstGpsOffset) -> Self {
        Self { gst_gps, ..self }
    }

    /// Extra time a platform window needs on each side of a chunk's epochs.
    pub fn window_margin_s(&self) -> f64 {
        2.0 * self.stencil.h_s
    }

    /// Geometry of `n_epochs` epochs starting at `t_first_s`; `window` must cover
    /// `[t_first_s - margin, t_last + margin]` (see [`Self::window_margin_s`]).
    pub fn chunk(&self, window: &PlatformWindow, t_first_s: f64, n_epochs: usize) -> GeometryChunk {
        let (n_ant, n_sat) = (self.antennas.len(), self.satellites.len());
        let n_links = n_ant * n_sat;
        let n_samples = self.stencil.n_samples(n_epochs);
        let sample_t: Vec<f64> = (0..n_samples)
            .map(|i| self.stencil.sample_time(t_first_s, self.step_s, i))
            .collect();
        let states: Vec<PlatformState> = sample_t.par_iter().map(|&t| window.state(t)).collect();
        let antennas: Vec<AntennaAt> = states
            .par_iter()
            .flat_map_iter(|st| self.antennas.iter().map(move |a| AntennaAt::new(st, a)))
            .collect();
        // The ephemeris used for each epoch's satellite; a stencil point whose own epoch
        // selects another set is recomputed with the centre's, so that an ephemeris change
        // never lands inside a finite difference.
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
        // Pass 1: quick screen of every link at each epoch, from one approximate satellite
        // position per epoch and satellite. Holds the approximate range, NaN when screened out.
        let screen: Vec<f64> = (0..n_epochs)
            .into_par_iter()
            .flat_map_iter(|k| {
                let i = self.stencil.sample(k, 0);
                let r_sats: Vec<Option<Vec3>> = (0..n_sat)
                    .map(|s| {
                        ephs[k * n_sat + s].map(|e| e.position_ecef(sample_t[i] - SCREEN_TAU_S))
                    })
                    .collect();
                let ants = &antennas[i * n_ant..(i + 1) * n_ant];
                let st = &states[i];
                (0..n_links).map(move |l| {
                    let (a, s) = (l / n_sat, l % n_sat);
                    match r_sats[s] {
                        Some(r_sat) if self.passes(a, &ants[a], st, &r_sat, SCREEN_MARGIN_RAD) => {
                            (r_sat - ants[a].r_ecef_m).norm()
                        }
                        _ => f64::NAN,
                    }
                })
            })
            .collect();
        // Pass 2: one light-time solution per stencil sample of every screened link. An
        // antenna whose satellite an earlier antenna solved starts from the distance to
        // that solution (off by the satellite's motion over the lever arm's flight time,
        // 1e-14 s), so it needs two iterations fewer than from the screen's range.
        let solved: Vec<Option<LightTime>> = (0..n_samples)
            .into_par_iter()
            .flat_map_iter(|i| {
                let k_own = self.stencil.epoch_of(i, n_epochs);
                let users = self.stencil.epochs_using(i, n_epochs);
                let (screen, ephs, antennas, t) = (&screen, &ephs, &antennas, sample_t[i]);
                let mut by_sat: Vec<Option<LightTime>> = vec![None; n_sat];
                (0..n_links).map(move |l| {
                    let s = l % n_sat;
                    let screened = users
                        .clone()
                        .map(|k| screen[k * n_links + l])
                        .find(|r| !r.is_nan())?;
                    let eph = ephs[k_own * n_sat + s]?;
                    let r_rx = &antennas[i * n_ant + l / n_sat].r_ecef_m;
                    let guess =
                        by_sat[s].map_or(screened, |lt| (lt.r_sat_rx_frame_m - r_rx).norm());
                    let lt =
                        light_time::solve(&self.true_satellite(eph, s), r_rx, t, guess / C_MPS);
                    by_sat[s] = Some(lt);
                    Some(lt)
                })
            })
            .collect();
        // Pass 3: derivatives, angles, exact visibility.
        let links: Vec<LinkGeometry> = (0..n_epochs * n_links)
            .into_par_iter()
            .map(|link| {
                let (k, l) = (link / n_links, link % n_links);
                let (a, s) = (l / n_sat, l % n_sat);
                let Some(eph) = ephs[k * n_sat + s].filter(|_| !screen[link].is_nan()) else {
                    return LinkGeometry::NOT_VISIBLE;
                };
                let mut paths = [None; 5];
                for (path, j) in paths.iter_mut().zip(-2..=2) {
                    let i = self.stencil.sample(k, j);
                    let own = ephs[self.stencil.epoch_of(i, n_epochs) * n_sat + s];
                    *path = match (solved[i * n_links + l], own) {
                        (Some(lt), Some(e)) if std::ptr::eq(e, eph) => Some(lt),
                        _ => {
                            let guess = solved[self.stencil.sample(k, 0) * n_links + l]
                                .map_or(SCREEN_TAU_S, |c| c.tau_s);
                            Some(light_time::solve(
                                &self.true_satellite(eph, s),
                                &antennas[i * n_ant + a].r_ecef_m,
                                sample_t[i],
                                guess,
                            ))
                        }
                    };
                }
                let i = self.stencil.sample(k, 0);
                let rho = paths.map(|p| p.map_or(f64::NAN, |p| p.range_m()));
                match paths[2] {
                    Some(centre) => self.link(
                        &self.true_satellite(eph, s),
                        a,
                        s,
                        &states[i],
                        &antennas[i * n_ant + a],
                        sample_t[i],
                        &centre,
                        &rho,
                    ),
                    None => LinkGeometry::NOT_VISIBLE,
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
        at: &AntennaAt,
        st: &PlatformState,
        r_sat: &Vec3,
        margin_rad: f64,
    ) -> bool {
        let ant = &self.antennas[a];
        let los_ecef = (r_sat - at.r_ecef_m).normalize();
        let los_body = st.c_body_ecef.transpose() * los_ecef;
        if !within_fov(
            &los_body,
            &ant.boresight_body,
            ant.fov_half_angle_rad + margin_rad,
        ) {
            return false;
        }
        if ant.elevation_mask_rad > -std::f64::consts::FRAC_PI_2 {
            let (_, el) = az_el(&(at.c_ecef_ned * los_ecef));
            if el < ant.elevation_mask_rad - margin_rad {
                return false;
            }
        }
        let grazing = if margin_rad > 0.0 {
            GRAZING_HEIGHT_M - 1e4
        } else {
            GRAZING_HEIGHT_M
        };
        !earth_blocked(&at.r_ecef_m, r_sat, grazing)
    }

    #[allow(clippy::too_many_arguments)]
    fn link(
        &self,
        sat: &TrueSatellite,
        a: usize,
        s: usize,
        st: &PlatformState,
        at: &AntennaAt,
        t_s: f64,
        lt: &LightTime,
        rho: &[f64; 5],
    ) -> LinkGeometry {
        if !self.passes(a, at, st, &lt.r_sat_rx_frame_m, 0.0) {
            return LinkGeometry::NOT_VISIBLE;
        }
        let h = self.stencil.h_s;
        let rate = (rho[0] - 8.0 * rho[1] + 8.0 * rho[3] - rho[4]) / (12.0 * h);
        let accel =
            (-rho[0] + 16.0 * rho[1] - 30.0 * rho[2] + 16.0 * rho[3] - rho[4]) / (12.0 * h * h);
        let jerk = (-rho[0] + 2.0 * rho[1] - 2.0 * rho[3] + rho[4]) / (2.0 * h * h * h);
        let per_m = -self.carriers_hz[s] / C_MPS;
        let los = lt.r_sat_rx_frame_m - at.r_ecef_m;
        let (azimuth_rad, elevation_rad) = az_el(&(at.c_ecef_ned * los));
        let los_antenna = self.frames[a].c_body_antenna * (st.c_body_ecef.transpose() * los);
        let (antenna_azimuth_rad, antenna_elevation_rad) = az_el_xyz(&los_antenna);
        let t_tx_s = t_s - lt.tau_s;
        let (mut sat_clock_s, mut sat_clock_drift) = sat.eph.clock_offset_and_drift(t_tx_s);
        if sat.eph.eph.sat.system == System::Galileo {
            sat_clock_s += self.gst_gps.at(t_tx_s);
            sat_clock_drift += self.gst_gps.a1;
        }
        let (clock_error_s, clock_error_rate) = sat.clock_error(t_tx_s);
        sat_clock_s += clock_error_s;
        sat_clock_drift += clock_error_rate;
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
            sat_clock_s,
            sat_clock_drift,
            sat_orbit_error_m: sat.orbit_error_along(t_tx_s, lt.tau_s, &los.normalize()),
            sat_clock_error_m: clock_error_s * C_MPS,
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
