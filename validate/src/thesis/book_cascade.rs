//! B-3.2, cascaded: the book's cascaded GPS/INS simulations (3.2.1; `BOOK_PAPER001_TARGETS.md`
//! spec 3.5): the SINS of [`super::book_gps_ins`]'s flight corrected by a GPS receiver's
//! position fixes every 25 s (position only: horizontal error about 40 m, altitude about
//! 75 m, velocity about 0.5 m/s in straight flight and up to 1.8 m/s in manoeuvres, level
//! attitude about 1.5' and azimuth about 5' at 500 s) or its velocity every second
//! (velocity only: about 0.1 m/s, azimuth about 3' within about 150 s).
//!
//! **Run** (each seed): the flight, IMU and perturbed start of `book_gps_ins::Flight`; the
//! receiver's output is the book's Table 3-1 receiver, made here as the book made it (its
//! cascaded simulation models the receiver's fixes, not its ranges): the antenna's true
//! position plus white noise of 20 m and Gauss-Markov biases of 35 m per horizontal axis
//! and 80 m in height (1200 s), its true velocity plus white 0.3 m/s, from the seed's own
//! stream. The 15-state loosely coupled filter takes them with the covariance of the white
//! and bias parts together (it has no bias states: assumed, the book's filter sizes are
//! not stated for 3.2.1). The filter reads the fixes and the increments; the comparison is
//! with the flight's truth.
//!
//! **Statistics and verdicts** (registered before the first run; the book's numbers are
//! read off its figures, so "about"): RMS over the seeds of the mean absolute horizontal
//! and height errors over 100-550 s (position only), of the velocity error's RMS over the
//! last straight leg 320-550 s and of its largest value in the turn 200-260 s, of the
//! level and azimuth errors at 500 s; for velocity only, of the velocity error's RMS over
//! 320-550 s and of the azimuth error at 150 s. Each within a factor 2.

use super::book_gps_ins::{
    FACTOR_TWO, Flight, TABLE, attitude_error_ned, azimuth_error, band_row, nwu_errors, rms,
    settings,
};
use crate::draw::Draw;
use crate::report::Row;
use crate::thesis::ValidateError;
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, StandardNormal};
use rayon::prelude::*;
use skyforge_navigation::gnss_ins::{GnssFix, LooselyCoupled};
use skyforge_orbits::frames::{c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::platform::PlatformWindow;
use skyforge_orbits::{Mat3, Vec3};
use skyforge_signals::errors::{Stream, stream_rng};

/// Registered runs (assumed: as the 18-state rows).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 20;
/// Table 3-1's receiver: white position, horizontal and height biases and their
/// correlation time, white velocity.
const WHITE_M: f64 = 20.0;
const HORIZONTAL_BIAS_M: f64 = 35.0;
const HEIGHT_BIAS_M: f64 = 80.0;
const BIAS_TAU_S: f64 = 1200.0;
const VELOCITY_MPS: f64 = 0.3;
/// The book's update periods (s).
const POSITION_EVERY_S: u64 = 25;
const VELOCITY_EVERY_S: u64 = 1;
/// Where the statistics are read (s): the errors' settled span, the last straight leg,
/// the turn, the attitude epochs (assumed readings of the book's text and figures).
const SETTLED_FROM_S: f64 = 100.0;
const STRAIGHT_S: (f64, f64) = (320.0, 550.0);
const TURN_S: (f64, f64) = (200.0, 260.0);
const ATTITUDE_AT_S: f64 = 500.0;
const AZIMUTH_VELOCITY_ONLY_AT_S: f64 = 150.0;

/// The aiding of a run.
#[derive(Clone, Copy, PartialEq)]
enum Aiding {
    Position,
    Velocity,
}

/// One seed's statistics of one aiding.
struct CascadeStats {
    horizontal_m: f64,
    height_m: f64,
    straight_mps: f64,
    turn_max_mps: f64,
    level_arcmin: f64,
    azimuth_arcmin: f64,
}

/// The receiver's output errors: Gauss-Markov biases (north, east, down) and white noise.
struct Receiver {
    rng: ChaCha20Rng,
    bias_ned: Vec3,
}

impl Receiver {
    fn new(seed: u64) -> Self {
        let mut rng = stream_rng(seed, Stream::Named("b-3.2 gps receiver"), 0);
        let bias_ned = Vec3::new(
            HORIZONTAL_BIAS_M * normal(&mut rng),
            HORIZONTAL_BIAS_M * normal(&mut rng),
            HEIGHT_BIAS_M * normal(&mut rng),
        );
        Self { rng, bias_ned }
    }

    /// Moves the biases over `dt_s` (exact discrete Gauss-Markov).
    fn advance(&mut self, dt_s: f64) {
        let decay = (-dt_s / BIAS_TAU_S).exp();
        let step = (1.0 - decay * decay).sqrt();
        let sigmas = [HORIZONTAL_BIAS_M, HORIZONTAL_BIAS_M, HEIGHT_BIAS_M];
        for (k, sigma) in sigmas.into_iter().enumerate() {
            self.bias_ned[k] = decay * self.bias_ned[k] + sigma * step * normal(&mut self.rng);
        }
    }

    /// A position error (NED, m) and a velocity error (NED, m/s) now.
    fn errors(&mut self) -> (Vec3, Vec3) {
        let mut white = |sigma: f64| {
            Vec3::new(
                normal(&mut self.rng),
                normal(&mut self.rng),
                normal(&mut self.rng),
            ) * sigma
        };
        let position = self.bias_ned + white(WHITE_M);
        (position, white(VELOCITY_MPS))
    }
}

fn normal(rng: &mut ChaCha20Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// The fix's covariance in ECEF at `r`: white plus bias variances, NED-diagonal.
fn covariances(r: &Vec3) -> (Mat3, Mat3) {
    let g = ecef_to_geodetic(r);
    let to_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
    let h = WHITE_M.powi(2) + HORIZONTAL_BIAS_M.powi(2);
    let v = WHITE_M.powi(2) + HEIGHT_BIAS_M.powi(2);
    let p = to_ecef * Mat3::from_diagonal(&Vec3::new(h, h, v)) * to_ecef.transpose();
    (p, Mat3::identity() * VELOCITY_MPS.powi(2))
}

fn run(seed: u64, aiding: Aiding) -> Result<CascadeStats, ValidateError> {
    let fail = |e: String| ValidateError::Pipeline(format!("{TABLE} cascade seed {seed}: {e}"));
    let flight = Flight::new(seed)?;
    let (filter_config, _) = settings(flight.lever);
    let mut filter =
        LooselyCoupled::new(flight.start, filter_config).map_err(|e| fail(e.to_string()))?;
    let mut receiver = Receiver::new(seed);
    let every = match aiding {
        Aiding::Position => POSITION_EVERY_S,
        Aiding::Velocity => VELOCITY_EVERY_S,
    };
    let rate = flight
        .scenario
        .imu
        .as_ref()
        .map_or(100.0, |i| i.rate_hz)
        .round() as usize;
    let (mut horizontal, mut height, mut straight) = (Vec::new(), Vec::new(), Vec::new());
    let (mut turn_max, mut level, mut azimuth) = (0.0f64, None, None);
    for (k, inc) in flight.increments.iter().enumerate() {
        filter.propagate(inc).map_err(|e| fail(e.to_string()))?;
        if !(k + 1).is_multiple_of(rate) {
            continue;
        }
        let second = ((k + 1) / rate) as u64;
        let t_s = second as f64;
        let truth = flight.truth(t_s)?;
        receiver.advance(1.0);
        let (dr, dv) = receiver.errors();
        if second.is_multiple_of(every) {
            let g = ecef_to_geodetic(&truth.r_ecef_m);
            let to_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
            let lever = truth.c_body_ecef * flight.lever;
            let k = PlatformWindow::kinematics(&flight.motion, t_s)
                .ok_or_else(|| fail(format!("no truth at {t_s} s")))?;
            let antenna_v =
                truth.v_ecef_mps + truth.c_body_ecef * k.omega_eb_body_rps.cross(&flight.lever);
            let (r_cov, v_cov) = covariances(&truth.r_ecef_m);
            let result = match aiding {
                Aiding::Position => filter.update(&GnssFix {
                    t: inc.t_end,
                    r_ecef_m: truth.r_ecef_m + lever + to_ecef * dr,
                    r_cov_m2: r_cov,
                    v_ecef_mps: None,
                }),
                Aiding::Velocity => {
                    filter.update_velocity(inc.t_end, &(antenna_v + to_ecef * dv), &v_cov)
                }
            };
            result.map_err(|e| fail(e.to_string()))?;
        }
        let (p, v) = nwu_errors(filter.state(), &truth);
        let speed_error = Vec3::from(v).norm();
        if t_s >= SETTLED_FROM_S {
            horizontal.push(p[0].hypot(p[1]));
            height.push(p[2].abs());
        }
        if (STRAIGHT_S.0..=STRAIGHT_S.1).contains(&t_s) {
            straight.push(speed_error);
        }
        if (TURN_S.0..=TURN_S.1).contains(&t_s) {
            turn_max = turn_max.max(speed_error);
        }
        if second == ATTITUDE_AT_S as u64 {
            level = Some(level_error(filter.state(), &truth));
        }
        let azimuth_at = match aiding {
            Aiding::Position => ATTITUDE_AT_S,
            Aiding::Velocity => AZIMUTH_VELOCITY_ONLY_AT_S,
        };
        if second == azimuth_at as u64 {
            azimuth = Some(azimuth_error(filter.state(), &truth).abs());
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    let arcmin = |rad: Option<f64>| {
        rad.map(|r| r.to_degrees() * 60.0)
            .ok_or_else(|| fail("no attitude epoch".into()))
    };
    Ok(CascadeStats {
        horizontal_m: mean(&horizontal),
        height_m: mean(&height),
        straight_mps: rms(straight.iter().copied()),
        turn_max_mps: turn_max,
        level_arcmin: arcmin(level)?,
        azimuth_arcmin: arcmin(azimuth)?,
    })
}

/// The level (tilt) error per axis (rad): the horizontal part of the attitude error, its
/// magnitude over sqrt(2) (the book gives one value for north and west).
fn level_error(
    est: &skyforge_navigation::ins::InsState,
    truth: &skyforge_navigation::ins::InsState,
) -> f64 {
    let ned = attitude_error_ned(est, truth);
    ned.x.hypot(ned.y) / std::f64::consts::SQRT_2
}

/// The cascaded rows over the draw's seeds.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let seeds = draw.seeds(FIRST_SEED, RUNS);
    let both = |aiding: Aiding| -> Result<Vec<CascadeStats>, ValidateError> {
        seeds
            .clone()
            .into_par_iter()
            .map(|s| run(s, aiding))
            .collect()
    };
    let (position, velocity) = (both(Aiding::Position)?, both(Aiding::Velocity)?);
    let note = format!(
        "RMS over seeds {}..{}; the receiver's fixes made from Table 3-1's errors; the \
         spans read and the filter without bias states assumed (book_cascade.rs)",
        seeds.start,
        seeds.end - 1
    );
    let row = |name: &str, unit: &str, book: f64, ours: f64| {
        band_row(name, unit, (book, ours), FACTOR_TWO, &note)
    };
    let of = |stats: &[CascadeStats], f: fn(&CascadeStats) -> f64| rms(stats.iter().map(f));
    Ok(vec![
        row(
            "position-only cascade (T = 25 s) mean horizontal error",
            "m",
            40.0,
            of(&position, |s| s.horizontal_m),
        ),
        row(
            "position-only cascade mean altitude error",
            "m",
            75.0,
            of(&position, |s| s.height_m),
        ),
        row(
            "position-only cascade velocity error, straight flight",
            "m/s",
            0.5,
            of(&position, |s| s.straight_mps),
        ),
        row(
            "position-only cascade largest velocity error in the turn",
            "m/s",
            1.8,
            of(&position, |s| s.turn_max_mps),
        ),
        row(
            "position-only cascade level error at 500 s",
            "arcmin",
            1.5,
            of(&position, |s| s.level_arcmin),
        ),
        row(
            "position-only cascade azimuth error at 500 s",
            "arcmin",
            5.0,
            of(&position, |s| s.azimuth_arcmin),
        ),
        row(
            "velocity-only cascade (T = 1 s) velocity error, straight flight",
            "m/s",
            0.1,
            of(&velocity, |s| s.straight_mps),
        ),
        row(
            "velocity-only cascade azimuth error at 150 s",
            "arcmin",
            3.0,
            of(&velocity, |s| s.azimuth_arcmin),
        ),
    ])
}
