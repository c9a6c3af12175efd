//! Error-free IMU increments from closed-form trajectories, for the tests: the truth's
//! body rate and specific force integrated over each interval by 3-point Gauss-Legendre
//! quadrature (exact for polynomials of degree 5; for the motions here, rotating at
//! <= 2 pi rad/s, its error is below 1e-13 of the increment), the coning motion's rate
//! relative to the Earth integrated in closed form.

use crate::ins::InsState;
use hifitime::{Duration, Epoch};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::gravity::{earth_rate_ecef, normal_gravity_ecef};
use skyforge_orbits::{Mat3, Vec3};

/// A motion known in closed form; times in seconds from the start.
pub trait Trajectory {
    /// Position, ECEF (m).
    fn r(&self, t: f64) -> Vec3;
    /// Velocity relative to the Earth, ECEF (m/s).
    fn v(&self, t: f64) -> Vec3;
    /// Acceleration relative to the Earth, ECEF (m/s^2).
    fn a(&self, t: f64) -> Vec3;
    /// Body-to-ECEF attitude.
    fn c_body_ecef(&self, t: f64) -> Mat3;
    /// Body rate relative to the Earth, body axes (rad/s).
    fn w_eb_body(&self, t: f64) -> Vec3;
    /// Integral of `w_eb_body` over `[t0, t1]` (quadrature unless known in closed form).
    fn dtheta_eb(&self, t0: f64, t1: f64) -> Vec3 {
        gauss_legendre3(|t| self.w_eb_body(t), t0, t1)
    }
}

/// 3-point Gauss-Legendre quadrature of `f` over `[t0, t1]`.
pub fn gauss_legendre3(f: impl Fn(f64) -> Vec3, t0: f64, t1: f64) -> Vec3 {
    let x = (0.6_f64).sqrt();
    let (m, h) = ((t0 + t1) / 2.0, (t1 - t0) / 2.0);
    (f(m - h * x) * 5.0 + f(m) * 8.0 + f(m + h * x) * 5.0) * (h / 9.0)
}

/// Specific force in body axes, Groves 2013 sec. 5.2 rearranged:
/// `f_b = C_e^b (a_e + 2 w_ie x v_e - g_normal(r_e))`.
fn specific_force_body(traj: &dyn Trajectory, t: f64) -> Vec3 {
    let r = traj.r(t);
    let g = normal_gravity_ecef(&ecef_to_geodetic(&r));
    let f_e = traj.a(t) + earth_rate_ecef().cross(&traj.v(t)) * 2.0 - g;
    traj.c_body_ecef(t).transpose() * f_e
}

/// The Earth's rate in body axes.
fn earth_rate_body(traj: &dyn Trajectory, t: f64) -> Vec3 {
    traj.c_body_ecef(t).transpose() * earth_rate_ecef()
}

/// The start epoch of every test.
pub fn t0() -> Epoch {
    Epoch::from_gpst_seconds(1.4e9)
}

/// Constant sensor biases, body axes.
#[derive(Debug, Clone, Copy, Default)]
pub struct Bias {
    /// Gyro bias (rad/s).
    pub gyro_rps: Vec3,
    /// Accelerometer bias (m/s^2).
    pub accel_mps2: Vec3,
}

/// `n` increments of `dt` seconds from `t0()`, error-free but for constant `bias`.
pub fn increments(traj: &dyn Trajectory, dt: f64, n: usize, bias: &Bias) -> Vec<ImuIncrement> {
    (0..n)
        .map(|k| {
            let (ta, tb) = (k as f64 * dt, (k + 1) as f64 * dt);
            let dtheta = traj.dtheta_eb(ta, tb)
                + gauss_legendre3(|t| earth_rate_body(traj, t), ta, tb)
                + bias.gyro_rps * dt;
            ImuIncrement {
                t_end: t0() + Duration::from_seconds(tb),
                dt_s: dt,
                dtheta_rad: dtheta,
                dv_mps: gauss_legendre3(|t| specific_force_body(traj, t), ta, tb)
                    + bias.accel_mps2 * dt,
            }
        })
        .collect()
}

/// The true state at `t` seconds.
pub fn true_state(traj: &dyn Trajectory, t: f64) -> InsState {
    InsState {
        t: t0() + Duration::from_seconds(t),
        r_ecef_m: traj.r(t),
        v_ecef_mps: traj.v(t),
        c_body_ecef: traj.c_body_ecef(t),
    }
}

/// The test site: latitude 30 deg, longitude 10 deg, 50 m.
pub fn site() -> Geodetic {
    Geodetic::from_degrees(30.0, 10.0, 50.0)
}

/// NED-to-ECEF at the site.
fn c_ned_ecef(g: &Geodetic) -> Mat3 {
    c_ecef_ned(g.lat_rad, g.lon_rad).transpose()
}

/// At rest at `site` with heading, pitch and roll `ypr` (rad).
#[derive(Debug)]
pub struct Static {
    pub r: Vec3,
    pub c: Mat3,
}

impl Static {
    pub fn new(site: &Geodetic, ypr: YawPitchRoll) -> Self {
        Self {
            r: geodetic_to_ecef(site),
            c: c_ned_ecef(site) * ypr.c_body_ref(),
        }
    }
}

impl Trajectory for Static {
    fn r(&self, _: f64) -> Vec3 {
        self.r
    }
    fn v(&self, _: f64) -> Vec3 {
        Vec3::zeros()
    }
    fn a(&self, _: f64) -> Vec3 {
        Vec3::zeros()
    }
    fn c_body_ecef(&self, _: f64) -> Mat3 {
        self.c
    }
    fn w_eb_body(&self, _: f64) -> Vec3 {
        Vec3::zeros()
    }
}

/// A level circle at constant speed in the tangent plane of `site`, heading along the
/// velocity (turning right), starting at the site heading north.
#[derive(Debug)]
pub struct Circle {
    pub r0: Vec3,
    pub c_ned_ecef: Mat3,
    pub radius_m: f64,
    pub speed_mps: f64,
}

impl Circle {
    pub fn new(site: &Geodetic, radius_m: f64, speed_mps: f64) -> Self {
        Self {
            r0: geodetic_to_ecef(site),
            c_ned_ecef: c_ned_ecef(site),
            radius_m,
            speed_mps,
        }
    }
    fn rate(&self) -> f64 {
        self.speed_mps / self.radius_m
    }
}

impl Trajectory for Circle {
    fn r(&self, t: f64) -> Vec3 {
        let (s, c) = (self.rate() * t).sin_cos();
        self.r0 + self.c_ned_ecef * Vec3::new(s, 1.0 - c, 0.0) * self.radius_m
    }
    fn v(&self, t: f64) -> Vec3 {
        let (s, c) = (self.rate() * t).sin_cos();
        self.c_ned_ecef * Vec3::new(c, s, 0.0) * self.speed_mps
    }
    fn a(&self, t: f64) -> Vec3 {
        let (s, c) = (self.rate() * t).sin_cos();
        self.c_ned_ecef * Vec3::new(-s, c, 0.0) * (self.speed_mps * self.rate())
    }
    fn c_body_ecef(&self, t: f64) -> Mat3 {
        self.c_ned_ecef * YawPitchRoll::new(self.rate() * t, 0.0, 0.0).c_body_ref()
    }
    fn w_eb_body(&self, _: f64) -> Vec3 {
        Vec3::new(0.0, 0.0, self.rate())
    }
}

/// At rest at `site`, the body's z axis precessing about the local down axis at
/// `rate_rps` with half-angle `beta_rad` (classical coning):
/// `C_b^n = Rz(W t) Rx(beta) Rz(-W t)`, whose body rate is `W (C_n^b z - z)`.
#[derive(Debug)]
pub struct Coning {
    pub r: Vec3,
    pub c_ned_ecef: Mat3,
    pub beta_rad: f64,
    pub rate_rps: f64,
}

impl Coning {
    pub fn new(site: &Geodetic, beta_rad: f64, rate_rps: f64) -> Self {
        Self {
            r: geodetic_to_ecef(site),
            c_ned_ecef: c_ned_ecef(site),
            beta_rad,
            rate_rps,
        }
    }
}

/// Active rotation by `a` about axis `axis` (0 = x, 2 = z).
fn rot(axis: usize, a: f64) -> Mat3 {
    let mut v = Vec3::zeros();
    v[axis] = a;
    nalgebra::Rotation3::new(v).into_inner()
}

impl Trajectory for Coning {
    fn r(&self, _: f64) -> Vec3 {
        self.r
    }
    fn v(&self, _: f64) -> Vec3 {
        Vec3::zeros()
    }
    fn a(&self, _: f64) -> Vec3 {
        Vec3::zeros()
    }
    fn c_body_ecef(&self, t: f64) -> Mat3 {
        let wt = self.rate_rps * t;
        self.c_ned_ecef * rot(2, wt) * rot(0, self.beta_rad) * rot(2, -wt)
    }
    fn w_eb_body(&self, t: f64) -> Vec3 {
        let (s, c) = (self.rate_rps * t).sin_cos();
        let (sb, cb) = self.beta_rad.sin_cos();
        Vec3::new(-sb * s, sb * c, cb - 1.0) * self.rate_rps
    }
    /// The closed-form integral of `w_eb_body`.
    fn dtheta_eb(&self, t0: f64, t1: f64) -> Vec3 {
        let (s0, c0) = (self.rate_rps * t0).sin_cos();
        let (s1, c1) = (self.rate_rps * t1).sin_cos();
        let (sb, cb) = self.beta_rad.sin_cos();
        Vec3::new(
            sb * (c1 - c0),
            sb * (s1 - s0),
            (cb - 1.0) * self.rate_rps * (t1 - t0),
        )
    }
}
