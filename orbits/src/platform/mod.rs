//! The receiving platform: a numerically propagated LEO, a static ground site, a
//! trajectory from CSV, or a vehicle's motion generated from legs, each with its attitude.
//!
//! Reference frames of the attitude (thesis section 2.5.1): the orbital frame for a LEO,
//! built from the ECI position and velocity, with
//! `c_body_ecef = c_eci_ecef(t) * c_orbital_eci(r_eci, v_eci) * c_body_orbital`; the local
//! NED frame otherwise (at the site, or at the current trajectory position), with
//! `c_body_ecef = c_ned_ecef * c_body_ned`; for generated legs the reference is the
//! vehicle's path frame (heading, flight-path angle, bank) within NED. The body frame is the reference
//! frame turned by the profile's yaw/pitch/roll (3-2-1, thesis eq. 2.5-6), so with zero
//! attitude a LEO's Zb points to the Earth centre and a ground receiver's -Zb points up.
//!
//! [`Platform::window`] hands out a [`PlatformWindow`]: an immutable, `Send + Sync` value
//! holding only what the window needs (a LEO's dense output for the window; ground sites
//! and trajectories share their data through `Arc`), so many threads can query it.

pub(crate) mod attitude;
pub(crate) mod config;
pub(crate) mod csv_table;
pub(crate) mod ground;
pub(crate) mod hermite;
mod leo;
pub(crate) mod segments;
pub(crate) mod trajectory;

pub use attitude::{AttitudeConfig, AxisProfileConfig};
pub use config::{
    GroundConfig, HeaveConfig, LegConfig, PlatformConfig, SegmentsConfig, TrajectoryConfig,
};

pub use hermite::Hermite3;

use crate::check::Invalid;
use crate::frames::earth_rotation::EarthRotation;
use crate::frames::euler::YawPitchRoll;
use crate::frames::geodetic::ecef_to_geodetic;
use crate::frames::ned::c_ecef_ned;
use crate::gravity::normal_gravity_ecef;
use crate::propagate::leo::{DenseTrajectory, LeoPropagator};
use crate::time::TimeOrigin;
use crate::{Mat3, Vec3};
use attitude::AttitudeProfile;
use ground::GroundSite;
use segments::Segments;
use std::path::Path;
use std::sync::Arc;
use trajectory::Trajectory;

/// How far (s) a window may reach beyond the data of a trajectory or attitude table; there
/// the motion (attitude) continues at the end velocity (angular rate). It lets
/// finite-difference stencils straddle the scenario edges.
pub const EDGE_MARGIN_S: f64 = 5.0;

/// The platform at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlatformState {
    /// Centre-of-mass position (ECEF, m).
    pub r_ecef_m: Vec3,
    /// Centre-of-mass velocity (ECEF, m/s).
    pub v_ecef_mps: Vec3,
    /// Body -> ECEF rotation.
    pub c_body_ecef: Mat3,
    /// Attitude relative to the platform's reference frame (orbital frame for a LEO, NED
    /// otherwise).
    pub attitude: YawPitchRoll,
}

/// Error building or moving a platform.
#[derive(Debug, thiserror::Error)]
pub enum PlatformError {
    #[error(transparent)]
    Propagate(#[from] crate::propagate::PropagateError),
    /// A CSV input (trajectory or attitude) is unreadable or malformed.
    #[error("{path}:{line}: {message}")]
    Csv {
        path: String,
        line: usize,
        message: String,
    },
    /// A window outside the data a trajectory file covers.
    #[error("time {t_s} s is outside the trajectory ({first_s} .. {last_s} s)")]
    OutsideTrajectory { t_s: f64, first_s: f64, last_s: f64 },
    /// A window outside the span of generated legs.
    #[error("time {t_s} s is outside the legs' span (0 .. {last_s} s)")]
    OutsideSegments { t_s: f64, last_s: f64 },
    /// A window outside the data an attitude table covers.
    #[error("time {t_s} s is outside the attitude table ({first_s} .. {last_s} s)")]
    OutsideAttitude { t_s: f64, first_s: f64, last_s: f64 },
    /// An invalid `[platform]` setting (field path relative to `[platform]`).
    #[error("invalid platform setting: {0}")]
    Config(#[from] Invalid),
}

/// Which kind of platform, and so which attitude reference frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlatformKind {
    /// Numerically propagated LEO; attitude relative to the orbital frame.
    Leo,
    /// Static ground site; attitude relative to NED.
    Ground,
    /// Trajectory from CSV; attitude relative to NED at the current position.
    Trajectory,
    /// Motion generated from legs; attitude relative to the path frame (heading,
    /// flight-path angle, bank) within NED at the current position.
    Segments,
}

/// The platform's motion at one instant to second order, as an IMU senses it: position,
/// velocity and acceleration of the centre of mass, attitude and angular rate, all
/// consistent (each the derivative of the one before).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Position, velocity and acceleration relative to the Earth (ECEF; m, m/s, m/s^2).
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    pub a_ecef_mps2: Vec3,
    /// Body -> ECEF rotation.
    pub c_body_ecef: Mat3,
    /// Angular rate of the body relative to the Earth, body axes (rad/s).
    pub omega_eb_body_rps: Vec3,
    /// The gravity acting at the platform (ECEF, m/s^2): the gravitation plus the
    /// centrifugal acceleration of the Earth's rotation, what accelerometers do not sense.
    /// Normal gravity near the surface (`crate::gravity`); a LEO's propagator's
    /// gravitation in orbit.
    pub gravity_ecef_mps2: Vec3,
}

/// How the platform moves.
#[derive(Debug)]
enum Motion {
    Leo {
        propagator: Box<LeoPropagator>,
        earth: EarthRotation,
    },
    Ground(GroundSite),
    Trajectory(Arc<Trajectory>),
    Segments(Arc<Segments>),
}

/// A receiving platform.
#[derive(Debug)]
pub struct Platform {
    motion: Motion,
    attitude: AttitudeProfile,
}

/// How the platform moves within one window.
#[derive(Debug, Clone)]
enum WindowMotion {
    Leo {
        dense: DenseTrajectory,
        earth: EarthRotation,
    },
    Ground(GroundSite),
    Trajectory(Arc<Trajectory>),
    Segments(Arc<Segments>),
}

/// The platform over a window of time; cheap to query from many threads.
#[derive(Debug, Clone)]
pub struct PlatformWindow {
    t0_s: f64,
    t1_s: f64,
    motion: WindowMotion,
    attitude: AttitudeProfile,
}

impl Platform {
    /// Builds the platform of `[platform]`. Exactly one of `leo`, `ground`, `trajectory`,
    /// `segments` must be given; relative CSV paths start at `base_dir` (the scenario file's folder).
    /// A LEO's ECI frame is [`EarthRotation::at_origin`] of the scenario start.
    pub fn new(
        cfg: &PlatformConfig,
        origin: &TimeOrigin,
        base_dir: &Path,
    ) -> Result<Platform, PlatformError> {
        let attitude = AttitudeProfile::from_config(&cfg.attitude, base_dir)?;
        let motion = match (&cfg.leo, &cfg.ground, &cfg.trajectory, &cfg.segments) {
            (Some(leo), None, None, None) => {
                let earth = EarthRotation::at_origin(origin.start());
                let propagator = Box::new(LeoPropagator::new(leo, origin, &earth)?);
                Motion::Leo { propagator, earth }
            }
            (None, Some(ground), None, None) => Motion::Ground(GroundSite::from_config(ground)?),
            (None, None, Some(trajectory), None) => Motion::Trajectory(Arc::new(
                Trajectory::from_csv(&base_dir.join(&trajectory.csv))?,
            )),
            (None, None, None, Some(segments)) => {
                Motion::Segments(Arc::new(Segments::new(segments)?))
            }
            _ => {
                let given = [
                    ("leo", cfg.leo.is_some()),
                    ("ground", cfg.ground.is_some()),
                    ("trajectory", cfg.trajectory.is_some()),
                    ("segments", cfg.segments.is_some()),
                ];
                let names: Vec<&str> = given.iter().filter(|(_, g)| *g).map(|(n, _)| *n).collect();
                return Err(Invalid::new(
                    "",
                    format!("[{}]", names.join(", ")),
                    "give exactly one of [platform.leo], [platform.ground], [platform.trajectory], [platform.segments]",
                )
                .into());
            }
        };
        Ok(Self { motion, attitude })
    }

    /// The kind of platform.
    pub fn kind(&self) -> PlatformKind {
        match self.motion {
            Motion::Leo { .. } => PlatformKind::Leo,
            Motion::Ground(_) => PlatformKind::Ground,
            Motion::Trajectory(_) => PlatformKind::Trajectory,
            Motion::Segments(_) => PlatformKind::Segments,
        }
    }

    /// The attitude profile (relative to the reference frame of [`Self::kind`]).
    pub fn attitude(&self) -> &AttitudeProfile {
        &self.attitude
    }

    /// The platform's state over `[t0_s, t1_s]` (windows move forward in time).
    ///
    /// Trajectory and attitude tables must cover the window up to [`EDGE_MARGIN_S`]; a LEO
    /// window follows the propagator's rules.
    pub fn window(&mut self, t0_s: f64, t1_s: f64) -> Result<PlatformWindow, PlatformError> {
        if let Some((first_s, last_s)) = self.attitude.span()
            && let Some(t_s) = [t0_s, t1_s]
                .into_iter()
                .find(|t| !(first_s - EDGE_MARGIN_S..=last_s + EDGE_MARGIN_S).contains(t))
        {
            return Err(PlatformError::OutsideAttitude {
                t_s,
                first_s,
                last_s,
            });
        }
        let motion = match &mut self.motion {
            Motion::Leo { propagator, earth } => WindowMotion::Leo {
                dense: propagator.window(t0_s, t1_s)?,
                earth: *earth,
            },
            Motion::Ground(site) => WindowMotion::Ground(*site),
            Motion::Trajectory(trajectory) => {
                trajectory.check_covers(t0_s, t1_s)?;
                WindowMotion::Trajectory(Arc::clone(trajectory))
            }
            Motion::Segments(segments) => {
                segments.check_covers(t0_s, t1_s)?;
                WindowMotion::Segments(Arc::clone(segments))
            }
        };
        Ok(PlatformWindow {
            t0_s,
            t1_s,
            motion,
            attitude: self.attitude.clone(),
        })
    }
}

impl PlatformWindow {
    /// The window `[t0_s, t1_s]` this was made for.
    pub fn span(&self) -> (f64, f64) {
        (self.t0_s, self.t1_s)
    }

    /// The state at `t_s` within the window.
    pub fn state(&self, t_s: f64) -> PlatformState {
        let attitude = self.attitude.at(t_s);
        match &self.motion {
            WindowMotion::Leo { dense, earth } => {
                let (r_eci_m, v_eci_mps) = dense.position_velocity_eci(t_s);
                leo::leo_state(earth, t_s, &r_eci_m, &v_eci_mps, attitude)
            }
            WindowMotion::Ground(site) => PlatformState {
                r_ecef_m: site.r_ecef_m,
                v_ecef_mps: Vec3::zeros(),
                c_body_ecef: site.c_ned_ecef * attitude.c_body_ref(),
                attitude,
            },
            WindowMotion::Trajectory(trajectory) => {
                let (r_ecef_m, v_ecef_mps) = trajectory.state_ecef(t_s);
                let g = ecef_to_geodetic(&r_ecef_m);
                let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
                PlatformState {
                    r_ecef_m,
                    v_ecef_mps,
                    c_body_ecef: c_ned_ecef * attitude.c_body_ref(),
                    attitude,
                }
            }
            WindowMotion::Segments(segments) => {
                let s = segments.state(t_s);
                let c_body_ned = s.path.c_body_ref() * attitude.c_body_ref();
                PlatformState {
                    r_ecef_m: s.r_ecef_m,
                    v_ecef_mps: s.v_ecef_mps,
                    c_body_ecef: s.c_ned_ecef * c_body_ned,
                    attitude: YawPitchRoll::from_c_ref_body(&c_body_ned.transpose()),
                }
            }
        }
    }

    /// The motion at `t_s` to second order with the angular rate and the gravity acting
    /// ([`Kinematics`]), for the platforms that define it: a ground site, generated legs
    /// and a LEO (its propagator's acceleration). `None` for a CSV trajectory (its cubic
    /// interpolation's acceleration jumps at every row).
    pub fn kinematics(&self, t_s: f64) -> Option<Kinematics> {
        let attitude = self.attitude.at(t_s);
        let attitude_rate = attitude.body_rate(&self.attitude.rates(t_s));
        match &self.motion {
            WindowMotion::Ground(site) => Some(Kinematics {
                r_ecef_m: site.r_ecef_m,
                v_ecef_mps: Vec3::zeros(),
                a_ecef_mps2: Vec3::zeros(),
                c_body_ecef: site.c_ned_ecef * attitude.c_body_ref(),
                omega_eb_body_rps: attitude_rate,
                gravity_ecef_mps2: normal_gravity_ecef(&ecef_to_geodetic(&site.r_ecef_m)),
            }),
            WindowMotion::Segments(segments) => {
                let s = segments.state(t_s);
                let c_body_path = attitude.c_body_ref();
                let c_body_ned = s.path.c_body_ref() * c_body_path;
                let path_rate = c_body_path.transpose() * s.path.body_rate(&s.path_rates);
                Some(Kinematics {
                    r_ecef_m: s.r_ecef_m,
                    v_ecef_mps: s.v_ecef_mps,
                    a_ecef_mps2: s.a_ecef_mps2,
                    c_body_ecef: s.c_ned_ecef * c_body_ned,
                    omega_eb_body_rps: c_body_ned.transpose() * s.omega_en_ned
                        + path_rate
                        + attitude_rate,
                    gravity_ecef_mps2: normal_gravity_ecef(&ecef_to_geodetic(&s.r_ecef_m)),
                })
            }
            WindowMotion::Leo { dense, earth } => {
                Some(leo::leo_kinematics(dense, earth, t_s, &|t| {
                    self.attitude.at(t)
                }))
            }
            WindowMotion::Trajectory(_) => None,
        }
    }
}
