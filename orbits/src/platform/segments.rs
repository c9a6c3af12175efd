//! A vehicle's motion generated from legs: straight runs, accelerations, turns and climbs
//! on the WGS-84 ellipsoid, with an optional heave, from one model that gives position,
//! velocity, acceleration, attitude and angular rate consistently (what an IMU needs:
//! position three times differentiable, attitude twice).
//!
//! Per leg, three rates are held: the along-track acceleration `a`, the heading rate `r`
//! and the vertical speed `w`; at the start of each leg they blend from the previous
//! leg's values by a smoothstep `3 s^2 - 2 s^3` over `ramp_s`, so each is once
//! continuously differentiable. The speed `v = v0 + int a`, the heading
//! `psi = psi0 + int r` and the height `h = h0 + int w (+ heave)` are their closed-form
//! integrals. The velocity in NED is `[v cos psi, v sin psi, -w]`; its derivative
//! `[a cos psi - v r sin psi, a sin psi + v r cos psi, -w']`. Latitude and longitude
//! follow `lat' = v_N / (M + h)`, `lon' = v_E / ((N + h) cos lat)` (Groves 2013 eq. 2.111),
//! integrated by fourth-order Runge-Kutta from nodes one second apart; the ECEF
//! acceleration is `C_n^e (a_n + w_en^n x v_n)` with the transport rate
//! `w_en^n = [lon' cos lat, -lat', -lon' sin lat]` (Groves eq. 5.44), the exact
//! derivative of `C_n^e v_n`.
//!
//! The path frame turns with the heading (yaw), the flight-path angle `atan2(w, v)`
//! (pitch) and, with `coordinated_turns`, the bank `atan(v r / g)` (roll); the body is the
//! path frame turned by `[platform.attitude]` (a boat's pitch and roll waves).

use super::config::{HeaveConfig, LegConfig, SegmentsConfig};
use super::{EDGE_MARGIN_S, PlatformError};
use crate::check::{Allowed, Invalid, check_table, shown};
use crate::frames::euler::YawPitchRoll;
use crate::frames::geodetic::{Geodetic, geodetic_to_ecef, radii_of_curvature_m};
use crate::frames::ned::c_ecef_ned;
use crate::{Mat3, Vec3};
use std::f64::consts::TAU;

/// Spacing (s) of the stored latitude/longitude nodes.
const NODE_S: f64 = 0.5;
/// Runge-Kutta steps from a node to any instant up to the next node: always this many,
/// of equal length, so the position is a smooth function of time within a node's
/// interval and meets the next node exactly (the nodes are made the same way). At 62.5 ms
/// a step's error is below 1e-9 m even inside a ramp.
const SUBSTEPS: usize = 8;
/// The longest motion the legs may define (s): 11.6 days, 2e6 nodes of 16 bytes.
const MOST_S: f64 = 1e6;
/// Standard gravity (m/s^2) of the coordinated-turn bank `atan(v r / g)`.
const G0_MPS2: f64 = 9.806_65;
/// Where the legs' checks look at the speed and latitude (s).
const CHECK_STEP_S: f64 = 0.05;
/// The lowest horizontal speed (m/s) at which a vehicle may climb or descend: the
/// flight-path angle `atan2(w, v)` is the pitch, so a vertical climb would stand the
/// vehicle on its tail.
const CLIMB_MIN_SPEED_MPS: f64 = 0.5;

/// Latitudes (deg) a generated path may start at and reach: the transport rate grows
/// as `1 / cos(lat)` towards the poles.
const LATITUDE_DEG: Allowed = Allowed::closed(-85.0, 85.0, "deg");

/// A quantity held per leg and blended between legs by a smoothstep over `ramp_s` at
/// the start of each leg; with its rate and its integral from 0 in closed form.
#[derive(Debug, Clone, PartialEq)]
struct Ramped {
    /// Each leg's start (s); the first is 0.
    starts: Vec<f64>,
    values: Vec<f64>,
    /// The integral from 0 to each leg's start.
    integrals: Vec<f64>,
    ramp_s: f64,
}

/// `(value, rate, integral)` of a blend from `from` to `to` over `ramp_s`, `u` s in.
fn blend(from: f64, to: f64, ramp_s: f64, u: f64) -> (f64, f64, f64) {
    if u >= ramp_s {
        let held = from * ramp_s + 0.5 * (to - from) * ramp_s + to * (u - ramp_s);
        return (to, 0.0, held);
    }
    let s = u / ramp_s;
    let d = to - from;
    (
        from + d * s * s * (3.0 - 2.0 * s),
        d * 6.0 * s * (1.0 - s) / ramp_s,
        from * u + d * ramp_s * (s * s * s - 0.5 * s * s * s * s),
    )
}

impl Ramped {
    fn new(durations: &[f64], values: Vec<f64>, ramp_s: f64) -> Self {
        let mut starts = vec![0.0];
        let mut integrals = vec![0.0];
        for (k, d) in durations.iter().enumerate().take(durations.len() - 1) {
            let from = values[k.saturating_sub(1)];
            let (_, _, integral) = blend(from, values[k], ramp_s, *d);
            starts.push(starts[k] + d);
            integrals.push(integrals[k] + integral);
        }
        Self {
            starts,
            values,
            integrals,
            ramp_s,
        }
    }

    /// `(value, rate, integral from 0)` at `t_s`; before 0 the first leg's value, after
    /// the last leg its value continues.
    fn at(&self, t_s: f64) -> (f64, f64, f64) {
        if t_s < 0.0 {
            return (self.values[0], 0.0, self.values[0] * t_s);
        }
        let k = self.starts.partition_point(|&s| s <= t_s) - 1;
        let from = self.values[k.saturating_sub(1)];
        let (value, rate, integral) =
            blend(from, self.values[k], self.ramp_s, t_s - self.starts[k]);
        (value, rate, self.integrals[k] + integral)
    }
}

/// The heave `A sin(w t + phase)` with its first two derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Heave {
    amplitude_m: f64,
    rate_rad_s: f64,
    phase_rad: f64,
}

impl Heave {
    /// `(height, vertical speed, vertical acceleration)` at `t_s`.
    fn at(&self, t_s: f64) -> (f64, f64, f64) {
        let (s, c) = (self.rate_rad_s * t_s + self.phase_rad).sin_cos();
        let (a, w) = (self.amplitude_m, self.rate_rad_s);
        (a * s, a * w * c, -a * w * w * s)
    }
}

/// The vehicle's motion along its path at one instant, in the local NED frame.
#[derive(Debug, Clone, Copy)]
struct PathPoint {
    h_m: f64,
    v_ned: Vec3,
    a_ned: Vec3,
    /// Path frame relative to NED, and the rates of its angles.
    path: YawPitchRoll,
    path_rates: YawPitchRoll,
}

/// The generated motion (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Segments {
    lat0_rad: f64,
    lon0_rad: f64,
    h0_m: f64,
    heading0_rad: f64,
    speed0_mps: f64,
    acceleration: Ramped,
    turn: Ramped,
    climb: Ramped,
    heave: Option<Heave>,
    coordinated_turns: bool,
    /// Latitude and longitude (rad) at `first_node_s + k NODE_S`.
    nodes: Vec<(f64, f64)>,
    first_node_s: f64,
    end_s: f64,
}

/// What the generator gives at one instant: ECEF position, velocity and acceleration,
/// the path frame relative to NED and the NED frame's transport rate.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SegmentsState {
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    pub a_ecef_mps2: Vec3,
    pub c_ned_ecef: Mat3,
    pub path: YawPitchRoll,
    pub path_rates: YawPitchRoll,
    /// The NED frame's rate relative to ECEF, NED axes (rad/s).
    pub omega_en_ned: Vec3,
}

/// Checks the settings of `[platform.segments]` (field paths relative to `segments`).
fn check_config(cfg: &SegmentsConfig) -> Result<(), Invalid> {
    check_table(&[
        ("latitude_deg", cfg.latitude_deg, LATITUDE_DEG),
        (
            "longitude_deg",
            cfg.longitude_deg,
            Allowed::closed(-180.0, 360.0, "deg"),
        ),
        (
            "height_m",
            cfg.height_m,
            Allowed::closed(-1000.0, 100e3, "m"),
        ),
        (
            "heading_deg",
            cfg.heading_deg,
            Allowed::closed(-360.0, 360.0, "deg"),
        ),
        (
            "speed_mps",
            cfg.speed_mps,
            Allowed::closed(0.0, 3000.0, "m/s"),
        ),
        ("ramp_s", cfg.ramp_s, Allowed::above(0.0, 600.0, "s")),
    ])?;
    if cfg.legs.is_empty() {
        return Err(Invalid::new("legs", "[]", "give at least one leg"));
    }
    let total_s: f64 = cfg.legs.iter().map(|l| l.duration_s).sum();
    if total_s > MOST_S {
        return Err(Invalid::new(
            "legs",
            format!("{} s in all", shown(total_s)),
            format!("the legs may last {} s in all", shown(MOST_S)),
        ));
    }
    for (k, leg) in cfg.legs.iter().enumerate() {
        check_leg(leg, cfg.ramp_s).map_err(|e| e.within(&format!("legs[{k}]")))?;
    }
    if let Some(heave) = &cfg.heave {
        check_heave(heave).map_err(|e| e.within("heave"))?;
    }
    Ok(())
}

/// One leg: rates a vehicle can hold (# assumed bounds: 5 g along the track, 180 deg/s,
/// 1000 m/s vertical), and at least `ramp_s` long so each blend completes.
fn check_leg(leg: &LegConfig, ramp_s: f64) -> Result<(), Invalid> {
    check_table(&[
        (
            "duration_s",
            leg.duration_s,
            Allowed::closed(ramp_s, 1e6, "s (at least ramp_s)"),
        ),
        (
            "acceleration_mps2",
            leg.acceleration_mps2,
            Allowed::closed(-50.0, 50.0, "m/s^2"),
        ),
        (
            "turn_rate_deg_s",
            leg.turn_rate_deg_s,
            Allowed::closed(-180.0, 180.0, "deg/s"),
        ),
        (
            "climb_mps",
            leg.climb_mps,
            Allowed::closed(-1000.0, 1000.0, "m/s"),
        ),
    ])
}

/// The heave: up to 100 m (# assumed: beyond any sea state), a period from 0.1 s.
fn check_heave(heave: &HeaveConfig) -> Result<(), Invalid> {
    check_table(&[
        (
            "amplitude_m",
            heave.amplitude_m,
            Allowed::closed(0.0, 100.0, "m"),
        ),
        ("period_s", heave.period_s, Allowed::closed(0.1, 1e5, "s")),
        (
            "phase_deg",
            heave.phase_deg,
            Allowed::closed(-360.0, 360.0, "deg"),
        ),
    ])
}

impl Segments {
    /// Builds the motion of `[platform.segments]`; errors name the field relative to
    /// `segments` (a leg whose speed falls below zero, a climb at rest, a path that
    /// leaves the latitudes in [`LATITUDE_DEG`]).
    pub fn new(cfg: &SegmentsConfig) -> Result<Self, Invalid> {
        check_config(cfg).map_err(|e| e.within("segments"))?;
        let durations: Vec<f64> = cfg.legs.iter().map(|l| l.duration_s).collect();
        let per_leg = |f: fn(&LegConfig) -> f64| {
            Ramped::new(&durations, cfg.legs.iter().map(f).collect(), cfg.ramp_s)
        };
        let mut segments = Self {
            lat0_rad: cfg.latitude_deg.to_radians(),
            lon0_rad: cfg.longitude_deg.to_radians(),
            h0_m: cfg.height_m,
            heading0_rad: cfg.heading_deg.to_radians(),
            speed0_mps: cfg.speed_mps,
            acceleration: per_leg(|l| l.acceleration_mps2),
            turn: per_leg(|l| l.turn_rate_deg_s.to_radians()),
            climb: per_leg(|l| l.climb_mps),
            heave: cfg.heave.as_ref().map(|h| Heave {
                amplitude_m: h.amplitude_m,
                rate_rad_s: TAU / h.period_s,
                phase_rad: h.phase_deg.to_radians(),
            }),
            coordinated_turns: cfg.coordinated_turns,
            nodes: Vec::new(),
            first_node_s: -(EDGE_MARGIN_S + NODE_S),
            end_s: durations.iter().sum(),
        };
        segments.check_path(cfg)?;
        segments.integrate_nodes();
        segments.check_latitudes(cfg)?;
        Ok(segments)
    }

    /// Checks that `[t0_s, t1_s]` lies within the legs' span widened by
    /// [`EDGE_MARGIN_S`].
    pub fn check_covers(&self, t0_s: f64, t1_s: f64) -> Result<(), PlatformError> {
        let allowed = -EDGE_MARGIN_S..=self.end_s + EDGE_MARGIN_S;
        match [t0_s, t1_s].into_iter().find(|t| !allowed.contains(t)) {
            Some(t_s) => Err(PlatformError::OutsideSegments {
                t_s,
                last_s: self.end_s,
            }),
            None => Ok(()),
        }
    }

    /// The speed never below zero, and at least [`CLIMB_MIN_SPEED_MPS`] while climbing.
    fn check_path(&self, cfg: &SegmentsConfig) -> Result<(), Invalid> {
        let steps = (self.end_s / CHECK_STEP_S).ceil() as usize;
        for i in 0..=steps {
            let t = (i as f64 * CHECK_STEP_S).min(self.end_s);
            let (_, _, dv) = self.acceleration.at(t);
            let (w, _, _) = self.climb.at(t);
            let v = self.speed0_mps + dv;
            let leg = self.acceleration.starts.partition_point(|&s| s <= t) - 1;
            let field = format!("segments.legs[{leg}]");
            if v < -1e-9 {
                return Err(Invalid::new(
                    format!("{field}.acceleration_mps2"),
                    shown(cfg.legs[leg].acceleration_mps2),
                    format!(
                        "the speed falls below zero at {} s ({} m/s)",
                        shown(t),
                        shown(v)
                    ),
                ));
            }
            if w != 0.0 && v < CLIMB_MIN_SPEED_MPS {
                return Err(Invalid::new(
                    format!("{field}.climb_mps"),
                    shown(cfg.legs[leg].climb_mps),
                    format!(
                        "a vehicle climbs or descends only when moving at {CLIMB_MIN_SPEED_MPS} m/s or more; at {} s its speed is {} m/s",
                        shown(t),
                        shown(v)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Every node within [`LATITUDE_DEG`].
    fn check_latitudes(&self, cfg: &SegmentsConfig) -> Result<(), Invalid> {
        match self
            .nodes
            .iter()
            .find(|(lat, _)| !LATITUDE_DEG.contains(lat.to_degrees()))
        {
            Some((lat, _)) => Err(Invalid::new(
                "segments.latitude_deg",
                shown(cfg.latitude_deg),
                format!(
                    "the path reaches latitude {} deg; generated paths stay within {LATITUDE_DEG}",
                    shown(lat.to_degrees())
                ),
            )),
            None => Ok(()),
        }
    }

    /// The path at `t_s` (see the module doc).
    fn path(&self, t_s: f64) -> PathPoint {
        let (a, _, dv) = self.acceleration.at(t_s);
        let (r, r_rate, dpsi) = self.turn.at(t_s);
        let (w, w_rate, dh) = self.climb.at(t_s);
        let (heave_h, heave_w, heave_a) = self.heave.map_or((0.0, 0.0, 0.0), |h| h.at(t_s));
        let v = self.speed0_mps + dv;
        let psi = self.heading0_rad + dpsi;
        let (s, c) = psi.sin_cos();
        let v_ned = Vec3::new(v * c, v * s, -(w + heave_w));
        let a_ned = Vec3::new(a * c - v * r * s, a * s + v * r * c, -(w_rate + heave_a));
        let speed2 = v * v + w * w;
        let (pitch, pitch_rate) = if speed2 > 0.0 {
            (w.atan2(v), (w_rate * v - w * a) / speed2)
        } else {
            (0.0, 0.0)
        };
        let (bank, bank_rate) = if self.coordinated_turns {
            let x = v * r / G0_MPS2;
            (x.atan(), (a * r + v * r_rate) / G0_MPS2 / (1.0 + x * x))
        } else {
            (0.0, 0.0)
        };
        PathPoint {
            h_m: self.h0_m + dh + heave_h,
            v_ned,
            a_ned,
            path: YawPitchRoll::new(psi, pitch, bank),
            path_rates: YawPitchRoll::new(r, pitch_rate, bank_rate),
        }
    }

    /// `(lat', lon')` (rad/s) at `t_s` and latitude `lat_rad`.
    fn geodetic_rates(&self, t_s: f64, lat_rad: f64) -> (f64, f64) {
        let p = self.path(t_s);
        let (m, n) = radii_of_curvature_m(lat_rad);
        (
            p.v_ned.x / (m + p.h_m),
            p.v_ned.y / ((n + p.h_m) * lat_rad.cos()),
        )
    }

    /// One fourth-order Runge-Kutta step of `(lat, lon)` from `t_s` by `h_s`.
    fn rk4(&self, t_s: f64, (lat, lon): (f64, f64), h_s: f64) -> (f64, f64) {
        let k1 = self.geodetic_rates(t_s, lat);
        let k2 = self.geodetic_rates(t_s + 0.5 * h_s, lat + 0.5 * h_s * k1.0);
        let k3 = self.geodetic_rates(t_s + 0.5 * h_s, lat + 0.5 * h_s * k2.0);
        let k4 = self.geodetic_rates(t_s + h_s, lat + h_s * k3.0);
        let step = |a: f64, b: f64, c: f64, d: f64| h_s / 6.0 * (a + 2.0 * b + 2.0 * c + d);
        (
            lat + step(k1.0, k2.0, k3.0, k4.0),
            lon + step(k1.1, k2.1, k3.1, k4.1),
        )
    }

    /// `(lat, lon)` at `t1_s` from `start` at `t0_s`, in [`SUBSTEPS`] equal steps.
    fn integrate(&self, t0_s: f64, start: (f64, f64), t1_s: f64) -> (f64, f64) {
        let h = (t1_s - t0_s) / SUBSTEPS as f64;
        (0..SUBSTEPS).fold(start, |y, i| self.rk4(t0_s + i as f64 * h, y, h))
    }

    /// The nodes from [`Self::first_node_s`] to a node past the end and its margin: back
    /// from the start point to the first node, then forward.
    fn integrate_nodes(&mut self) {
        let mut y = (self.lat0_rad, self.lon0_rad);
        let back = (-self.first_node_s / NODE_S).round() as usize;
        for k in 0..back {
            let t = -(k as f64) * NODE_S;
            y = self.integrate(t, y, t - NODE_S);
        }
        let count = ((self.end_s + EDGE_MARGIN_S - self.first_node_s) / NODE_S).ceil() as usize + 2;
        let mut nodes = Vec::with_capacity(count);
        for k in 0..count {
            nodes.push(y);
            let t = self.first_node_s + k as f64 * NODE_S;
            y = self.integrate(t, y, t + NODE_S);
        }
        self.nodes = nodes;
    }

    /// The motion at `t_s` (within the span and its margin).
    pub(crate) fn state(&self, t_s: f64) -> SegmentsState {
        let k = (((t_s - self.first_node_s) / NODE_S).floor().max(0.0) as usize)
            .min(self.nodes.len() - 1);
        let t_k = self.first_node_s + k as f64 * NODE_S;
        let (lat, lon) = self.integrate(t_k, self.nodes[k], t_s);
        let p = self.path(t_s);
        let (m, n) = radii_of_curvature_m(lat);
        let lat_rate = p.v_ned.x / (m + p.h_m);
        let lon_rate = p.v_ned.y / ((n + p.h_m) * lat.cos());
        let omega_en_ned = Vec3::new(lon_rate * lat.cos(), -lat_rate, -lon_rate * lat.sin());
        let c_ned_ecef = c_ecef_ned(lat, lon).transpose();
        SegmentsState {
            r_ecef_m: geodetic_to_ecef(&Geodetic {
                lat_rad: lat,
                lon_rad: lon,
                h_m: p.h_m,
            }),
            v_ecef_mps: c_ned_ecef * p.v_ned,
            a_ecef_mps2: c_ned_ecef * (p.a_ned + omega_en_ned.cross(&p.v_ned)),
            c_ned_ecef,
            path: p.path,
            path_rates: p.path_rates,
            omega_en_ned,
        }
    }
}
