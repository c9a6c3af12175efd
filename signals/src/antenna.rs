//! Antennas on the platform: lever arm, true-minus-nominal geometry offset, boresight,
//! field of view, elevation mask, phase-centre offset/variation and gain pattern (carried
//! as data for the signal stage).

use skyforge_orbits::Vec3;
use skyforge_orbits::check::Invalid;

/// A phase-centre-variation or gain grid over the antenna frame: values at
/// `zenith_deg[i]` x `azimuth_deg[j]`, row-major (`values[i * azimuth.len() + j]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntennaGrid {
    pub zenith_deg: Vec<f64>,
    pub azimuth_deg: Vec<f64>,
    pub values: Vec<f64>,
}

/// `[[antennas]]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntennaConfig {
    /// Unique name, used in output paths.
    pub name: String,
    /// Nominal phase-centre reference point in the body frame, from the centre of mass (m):
    /// what the receiver is told.
    pub position_body_m: [f64; 3],
    /// True minus nominal position (m), body frame (thesis chapter 4 geometry offsets).
    #[serde(default)]
    pub offset_body_m: [f64; 3],
    /// Boresight in the body frame (default -Zb: away from the Earth for an earth-pointing LEO,
    /// up for a ground platform whose body frame is NED).
    #[serde(default = "default_boresight")]
    pub boresight_body: [f64; 3],
    /// Field-of-view half-angle about the boresight (deg).
    #[serde(default = "default_fov")]
    pub fov_half_angle_deg: f64,
    /// Elevation mask above the local horizon (deg); -90 disables it.
    #[serde(default = "default_mask")]
    pub elevation_mask_deg: f64,
    /// Phase-centre offset in the antenna frame (m).
    #[serde(default)]
    pub pco_m: [f64; 3],
    /// Phase-centre variation (m) over the antenna frame.
    #[serde(default)]
    pub pcv_m: Option<AntennaGrid>,
    /// Gain pattern (dBi) over the antenna frame.
    #[serde(default)]
    pub gain_dbi: Option<AntennaGrid>,
}

fn default_boresight() -> [f64; 3] {
    [0.0, 0.0, -1.0]
}
fn default_fov() -> f64 {
    90.0
}
fn default_mask() -> f64 {
    -90.0
}

/// A resolved antenna.
#[derive(Debug, Clone, PartialEq)]
pub struct Antenna {
    pub name: String,
    /// Nominal lever arm (body, m).
    pub nominal_body_m: Vec3,
    /// True lever arm = nominal + offset (body, m).
    pub true_body_m: Vec3,
    /// Unit boresight (body).
    pub boresight_body: Vec3,
    pub fov_half_angle_rad: f64,
    pub elevation_mask_rad: f64,
    pub pco_m: Vec3,
    pub pcv_m: Option<AntennaGrid>,
    pub gain_dbi: Option<AntennaGrid>,
}

impl AntennaConfig {
    /// Checks: finite numbers, non-zero boresight, FOV in (0, 180], mask in [-90, 90],
    /// grids rectangular and sorted.
    pub fn check(&self) -> Result<(), Invalid> {
        todo!()
    }
    /// The resolved antenna (call after `check`).
    pub fn resolve(&self) -> Antenna {
        todo!()
    }
}
