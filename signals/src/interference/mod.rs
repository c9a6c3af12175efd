//! Interference: jammers in the scenario (`[[jammers]]`) and what each antenna receives
//! of them. A jammer is fixed on the Earth, with an isotropic antenna, switched on and
//! off at set times; it reaches every antenna with its own range (path loss, carrier
//! phase) and the antenna's gain towards it, coherently with the satellites' signals, so
//! several antennas see one jammer from one direction. The renderer adds its waveform to
//! the samples (`synth::jamming`).

mod config;

pub use config::{JammerConfig, JammerWaveform, MAX_JAMMERS, MAX_JS_DB};

/// The C/N0 below which a receiver loses lock (dB-Hz), for the observation level's
/// jammed links. # assumed: the bundled receiver's default `cn0_lock_threshold_dbhz`.
pub const LOCK_THRESHOLD_DBHZ: f64 = 25.0;

/// The effective-C/N0 relation for noise jammers filling a band of `bandwidth_hz`
/// (docs/interference.md): `(C/N0)_eff = [ (C/N0)^-1 + (J/S) / B ]^-1`, i.e. the noise
/// density raised by `J/B`; returns the loss `10 log10(1 + sum J/(N0 B))` (dB) for the
/// jammers' J/N0 values `jn0_dbhz`.
pub fn cn0_loss_db(jn0_dbhz: impl IntoIterator<Item = f64>, bandwidth_hz: f64) -> f64 {
    let raised: f64 = jn0_dbhz
        .into_iter()
        .map(|j| 10f64.powf(j / 10.0) / bandwidth_hz)
        .sum();
    10.0 * (1.0 + raised).log10()
}

use crate::antenna::Antenna;
use crate::truth::geometry::{AntennaFrame, az_el_xyz};
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_orbits::{Mat3, Vec3};

/// A jammer placed: its settings, its position and its power at the reference point.
#[derive(Debug, Clone, PartialEq)]
pub struct Jammer {
    pub config: JammerConfig,
    /// Its antenna (ECEF, m).
    pub r_ecef_m: Vec3,
    /// J/N0 (dB-Hz) an isotropic antenna receives at `range_ref_m`.
    pub jn0_ref_dbhz: f64,
    /// The range of the reference point: the platform's body origin at the start (m).
    pub range_ref_m: f64,
}

/// A jammer as one antenna receives it at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JammerLink {
    /// Range from the jammer to the antenna (m).
    pub range_m: f64,
    /// Jammer power over the thermal noise density (dB-Hz), with the antenna's gain.
    pub jn0_dbhz: f64,
    /// Its direction in the antenna frame (rad): azimuth from X towards Y, elevation
    /// above the XY plane (Z the boresight).
    pub azimuth_rad: f64,
    pub elevation_rad: f64,
}

impl Jammer {
    /// `config` placed, its J/S referred to a satellite signal at `cn0_dbhz` received at
    /// `reference_ecef_m` (the platform's body origin at the start).
    pub fn new(config: &JammerConfig, cn0_dbhz: f64, reference_ecef_m: &Vec3) -> Self {
        let position =
            Geodetic::from_degrees(config.latitude_deg, config.longitude_deg, config.height_m);
        let r_ecef_m = geodetic_to_ecef(&position);
        Self {
            config: config.clone(),
            r_ecef_m,
            jn0_ref_dbhz: config.js_db + cn0_dbhz,
            range_ref_m: (r_ecef_m - reference_ecef_m).norm().max(1.0),
        }
    }

    /// What `antenna`, its reference point at `r_ecef_m` on a body lying as
    /// `c_body_ecef`, receives: the power falls with the range squared (free space) and
    /// follows the antenna's gain pattern (0 dBi without one).
    pub fn link(&self, antenna: &Antenna, r_ecef_m: &Vec3, c_body_ecef: &Mat3) -> JammerLink {
        let towards = self.r_ecef_m - r_ecef_m;
        let range_m = towards.norm().max(1.0);
        let frame = AntennaFrame::new(&antenna.boresight_body);
        let (azimuth_rad, elevation_rad) =
            az_el_xyz(&(frame.c_body_antenna * (c_body_ecef.transpose() * towards)));
        let path_db = 20.0 * (self.range_ref_m / range_m).log10();
        JammerLink {
            range_m,
            jn0_dbhz: self.jn0_ref_dbhz + path_db + antenna.gain_dbi_at(azimuth_rad, elevation_rad),
            azimuth_rad,
            elevation_rad,
        }
    }
}
