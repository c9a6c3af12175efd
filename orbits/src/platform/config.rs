//! `[platform]`: exactly one of `leo`, `ground`, `trajectory`, `segments`, plus
//! `attitude`.

use crate::platform::attitude::AttitudeConfig;
use crate::propagate::config::LeoConfig;
use std::path::PathBuf;

/// `[platform]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlatformConfig {
    #[serde(default)]
    pub leo: Option<LeoConfig>,
    #[serde(default)]
    pub ground: Option<GroundConfig>,
    #[serde(default)]
    pub trajectory: Option<TrajectoryConfig>,
    #[serde(default)]
    pub segments: Option<SegmentsConfig>,
    #[serde(default)]
    pub attitude: AttitudeConfig,
}

/// `[platform.ground]`: a static site, by geodetic coordinates or ECEF.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundConfig {
    #[serde(default)]
    pub latitude_deg: Option<f64>,
    #[serde(default)]
    pub longitude_deg: Option<f64>,
    #[serde(default)]
    pub height_m: Option<f64>,
    #[serde(default)]
    pub ecef_m: Option<[f64; 3]>,
}

/// `[platform.trajectory]`: CSV with columns `t_s,x_m,y_m,z_m[,vx_mps,vy_mps,vz_mps]`
/// (ECEF, t from the scenario start).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrajectoryConfig {
    pub csv: PathBuf,
}

/// `[platform.segments]`: a vehicle's motion generated from legs (straight runs,
/// accelerations, turns, climbs) on the WGS-84 ellipsoid, smooth enough for an IMU:
/// position three times differentiable, attitude twice (docs/scenario.md).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentsConfig {
    /// Start point, geodetic (deg, deg, m above the ellipsoid).
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    pub height_m: f64,
    /// Initial heading (deg clockwise from north) and horizontal speed (m/s).
    #[serde(default)]
    pub heading_deg: f64,
    #[serde(default)]
    pub speed_mps: f64,
    /// How long each change of a leg's rates takes (s): the rates blend from one leg's
    /// to the next's by a smoothstep over this time at the start of the leg.
    #[serde(default = "default_ramp_s")]
    pub ramp_s: f64,
    /// Bank into turns as an aircraft does in a coordinated turn (roll `atan(v r / g)`);
    /// otherwise the path frame stays level (a car, a boat).
    #[serde(default)]
    pub coordinated_turns: bool,
    /// A vertical oscillation added to the height (a boat's heave): `amplitude_m`,
    /// `period_s`, `phase_deg`.
    #[serde(default)]
    pub heave: Option<HeaveConfig>,
    /// The legs, in order; the motion is defined over their total duration.
    pub legs: Vec<LegConfig>,
}

/// The default `ramp_s`: 2 s (# assumed: a vehicle takes a couple of seconds to enter a
/// turn or change its throttle).
fn default_ramp_s() -> f64 {
    2.0
}

/// `[[platform.segments.legs]]`: rates held over `duration_s` (after the ramp).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegConfig {
    pub duration_s: f64,
    /// Along-track acceleration (m/s^2) of the horizontal speed.
    #[serde(default)]
    pub acceleration_mps2: f64,
    /// Heading rate (deg/s, positive turning right, clockwise seen from above).
    #[serde(default)]
    pub turn_rate_deg_s: f64,
    /// Vertical speed (m/s, positive up).
    #[serde(default)]
    pub climb_mps: f64,
}

/// `heave`: `amplitude_m * sin(2 pi t / period_s + phase)`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeaveConfig {
    pub amplitude_m: f64,
    pub period_s: f64,
    #[serde(default)]
    pub phase_deg: f64,
}
