//! Coarse and fine alignment on static increments at latitude 30 deg, heading 40 deg.

use super::truth::{Bias, Static, increments, site, true_state};
use crate::ins::fine_alignment::wrap_pi;
use crate::ins::rotation::rodrigues;
use crate::ins::{
    FineAlignmentConfig, attitude_ned, coarse_alignment, fine_alignment,
    heading_error_from_east_gyro_bias_rad, static_means,
};
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::{Mat3, Vec3};

const HEADING_DEG: f64 = 40.0;

fn truth() -> Static {
    let ypr = YawPitchRoll::new(
        HEADING_DEG.to_radians(),
        1.5f64.to_radians(),
        -2f64.to_radians(),
    );
    Static::new(&site(), ypr)
}

/// 0.01 deg/h along local east, in body axes.
fn east_gyro_bias(traj: &Static) -> Bias {
    let site = site();
    let east_ecef = c_ecef_ned(site.lat_rad, site.lon_rad).transpose() * Vec3::y();
    let b = 0.01f64.to_radians() / 3600.0;
    Bias {
        gyro_rps: traj.c.transpose() * east_ecef * b,
        ..Bias::default()
    }
}

/// The filter told the increments are clean (they are: error-free but for any bias).
fn clean_data_config() -> FineAlignmentConfig {
    FineAlignmentConfig {
        gyro_arw_rad_per_sqrt_s: 1e-9,
        accel_vrw_mps_per_sqrt_s: 1e-8,
        zupt_sigma_mps: 1e-5,
        ..FineAlignmentConfig::default()
    }
}

/// Computed minus true heading (rad).
fn heading_error(c: &Mat3, traj: &Static) -> f64 {
    let site = site();
    wrap_pi(attitude_ned(c, &site).yaw_rad - attitude_ned(&traj.c, &site).yaw_rad)
}

fn coarse(bias: &Bias) -> (Static, Mat3) {
    let traj = truth();
    let means = static_means(&increments(&traj, 0.01, 6000, bias)).unwrap();
    let c = coarse_alignment(&means.f_body_mps2, &means.w_body_rps, &site()).unwrap();
    (traj, c)
}

/// (d) Error-free increments: heading well under 0.01 deg, level to 1e-9 rad.
#[test]
fn coarse_alignment_error_free() {
    let (traj, c) = coarse(&Bias::default());
    let err = heading_error(&c, &traj);
    let (est, tru) = (attitude_ned(&c, &site()), attitude_ned(&traj.c, &site()));
    println!(
        "coarse, error-free: heading error {:e} deg",
        err.to_degrees()
    );
    assert!(err.abs() < 0.01f64.to_radians(), "{err:e} rad");
    assert!((est.pitch_rad - tru.pitch_rad).abs() < 1e-9);
    assert!((est.roll_rad - tru.roll_rad).abs() < 1e-9);
    assert!((c.transpose() * c - Mat3::identity()).norm() < 1e-14);
}

/// (d) An east gyro bias of 0.01 deg/h turns the heading by `-b / (w_ie cos L)`
/// (0.044 deg at 30 deg); within 20 % of that theory.
#[test]
fn coarse_alignment_heading_error_follows_gyro_bias() {
    let (traj, c) = coarse(&east_gyro_bias(&truth()));
    let err = heading_error(&c, &traj);
    let theory = heading_error_from_east_gyro_bias_rad(0.01f64.to_radians() / 3600.0, &site());
    println!(
        "coarse, 0.01 deg/h east: heading error {} deg, theory {} deg",
        err.to_degrees(),
        theory.to_degrees()
    );
    assert!(
        (err - theory).abs() < 0.2 * theory.abs(),
        "{err:e} vs {theory:e}"
    );
}

/// Fine alignment over 300 s at rest from an attitude 0.5 deg off in heading and 0.05 deg
/// in level: the zero-velocity filter must find the heading to 0.01 deg.
#[test]
fn fine_alignment_removes_heading_error() {
    let traj = truth();
    let incs = increments(&traj, 0.01, 30_000, &Bias::default());
    let mut initial = true_state(&traj, 0.0);
    let site = site();
    let c_ned_ecef = c_ecef_ned(site.lat_rad, site.lon_rad).transpose();
    let tilt = Vec3::new(0.05, -0.03, 0.5).map(f64::to_radians);
    initial.c_body_ecef = rodrigues(&(c_ned_ecef * tilt)) * initial.c_body_ecef;
    let out = fine_alignment(&initial, &incs, &clean_data_config()).unwrap();
    let err = heading_error(&out.state.c_body_ecef, &traj);
    println!(
        "fine, from 0.5 deg: heading error {:e} deg, sigma {:e} deg, correction {} deg, level sigma {:e} rad, innovation rms {:e} m/s, {} updates",
        err.to_degrees(),
        out.heading_sigma_rad.to_degrees(),
        out.heading_correction_rad.to_degrees(),
        out.level_sigma_rad,
        out.innovation_rms_mps,
        out.updates
    );
    assert!(err.abs() < 0.01f64.to_radians(), "{err:e} rad");
    assert!((out.heading_correction_rad + 0.5f64.to_radians()).abs() < 0.01f64.to_radians());
    assert!(out.heading_sigma_rad < 0.01f64.to_radians());
    assert!(err.abs() < 3.0 * out.heading_sigma_rad);
    assert_eq!(out.updates, 3000);
}

/// Fine alignment cannot see an east gyro bias: the heading converges to the coarse
/// alignment's biased value, within 20 % of `-b / (w_ie cos L)`.
#[test]
fn fine_alignment_keeps_the_gyro_bias_heading_error() {
    let traj = truth();
    let incs = increments(&traj, 0.01, 30_000, &east_gyro_bias(&traj));
    let initial = true_state(&traj, 0.0);
    let out = fine_alignment(&initial, &incs, &clean_data_config()).unwrap();
    let err = heading_error(&out.state.c_body_ecef, &traj);
    let theory = heading_error_from_east_gyro_bias_rad(0.01f64.to_radians() / 3600.0, &site());
    println!(
        "fine, 0.01 deg/h east: heading error {} deg, theory {} deg",
        err.to_degrees(),
        theory.to_degrees()
    );
    assert!(
        (err - theory).abs() < 0.2 * theory.abs(),
        "{err:e} vs {theory:e}"
    );
}

/// With the default (navigation-grade) noise, the filter's heading standard deviation
/// after 300 s matches the gyrocompassing limit `ARW / (w_ie cos L sqrt(T))` (0.03 deg)
/// within 20 %, and the error-free run stays within it.
#[test]
fn fine_alignment_heading_sigma_follows_gyro_noise() {
    let traj = truth();
    let incs = increments(&traj, 0.01, 30_000, &Bias::default());
    let mut initial = true_state(&traj, 0.0);
    let site = site();
    let c_ned_ecef = c_ecef_ned(site.lat_rad, site.lon_rad).transpose();
    let heading_off = Vec3::new(0.0, 0.0, 0.5f64.to_radians());
    initial.c_body_ecef = rodrigues(&(c_ned_ecef * heading_off)) * initial.c_body_ecef;
    let cfg = FineAlignmentConfig::default();
    let out = fine_alignment(&initial, &incs, &cfg).unwrap();
    let theory = cfg.gyro_arw_rad_per_sqrt_s / (OMEGA_E_GPS * site.lat_rad.cos() * 300f64.sqrt());
    let err = heading_error(&out.state.c_body_ecef, &traj);
    println!(
        "fine, default noise: heading sigma {} deg, theory {} deg, error {} deg",
        out.heading_sigma_rad.to_degrees(),
        theory.to_degrees(),
        err.to_degrees()
    );
    assert!((out.heading_sigma_rad - theory).abs() < 0.2 * theory);
    assert!(err.abs() < out.heading_sigma_rad);
}
