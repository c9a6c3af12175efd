//! Carrier-phase and height aiding against closed-form truth: a car circling at Changsha
//! with an error-free IMU (the INS tests' trajectories), its antenna's L1 phase from the
//! TDCP tests' world (nominal GPS, a drifting receiver clock).

use super::*;
use crate::ins::tests::truth::{Bias, Circle, Trajectory, increments, t0, true_state};
use crate::tdcp::TdcpConfig;
use crate::tdcp::tests::world::World;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic};

const LEVER: [f64; 3] = [0.8, -0.3, -1.2];

pub(super) fn config() -> LooselyCoupledConfig {
    LooselyCoupledConfig {
        imu: ImuNoise {
            gyro_arw: 0.1_f64.to_radians() / 60.0,
            accel_vrw: 0.05 / 60.0,
            gyro_bias: 1.0_f64.to_radians() / 3600.0,
            gyro_bias_tau_s: None,
            accel_bias: 1e-3 * 9.80665,
            accel_bias_tau_s: None,
        },
        lever_arm_body_m: Vec3::from(LEVER),
        initial_position_m: 1.0,
        initial_velocity_mps: 0.2,
        initial_tilt_rad: 1e-3,
        initial_heading_rad: 5e-3,
    }
}

/// The INS's velocity error (m/s) after `seconds` on a 200-m circle at 10 m/s, started
/// 0.1-0.15 m/s wrong, with TDCP updates every second or none.
fn velocity_error(seconds: usize, tdcp: bool) -> f64 {
    let world = World::new(1e-7);
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let shift = |e: hifitime::Epoch| world.start + (e - t0());
    let mut incs = increments(&traj, 0.01, seconds * 100, &Bias::default());
    for inc in &mut incs {
        inc.t_end = shift(inc.t_end);
    }
    let lever = Vec3::from(LEVER);
    let antenna = |t: f64| traj.r(t) + traj.c_body_ecef(t) * lever;
    let epochs: Vec<_> = (0..=seconds)
        .map(|k| world.epoch(k as f64, antenna(k as f64), &mut |_| 0.0))
        .collect();
    let mut start = true_state(&traj, 0.0);
    start.t = shift(start.t);
    start.v_ecef_mps += world.ned(0.1, -0.1, 0.05);
    let mut filter = LooselyCoupled::new(start, config()).unwrap();
    let mut pose = filter.pose();
    let tdcp_config = TdcpConfig::default();
    for (k, inc) in incs.iter().enumerate() {
        filter.propagate(inc).unwrap();
        if (k + 1) % 100 == 0 {
            let s = (k + 1) / 100;
            if tdcp {
                let pair = (&epochs[s - 1], &epochs[s]);
                let u = filter
                    .update_tdcp(pair, &pose, &world.store, &world.origin, &tdcp_config)
                    .unwrap();
                assert!(u.is_some(), "satellites in view at {s} s");
            }
            pose = filter.pose();
        }
    }
    (filter.state().v_ecef_mps - traj.v(seconds as f64)).norm()
}

/// Noise-free phase: a minute of TDCP takes the velocity error from 0.15 m/s to under a
/// millimetre per second (the receive instants differ from the tags by the clock's 0.1 ms,
/// 1 mm at 10 m/s); without it the error stays.
#[test]
fn tdcp_double_differences_find_the_velocity() {
    let with = velocity_error(60, true);
    let without = velocity_error(60, false);
    assert!(with < 1e-3, "with TDCP {with} m/s");
    assert!(without > 0.1, "without {without} m/s");
}

/// A known height pulls a 5-m height error to the constraint's sigma.
#[test]
fn the_height_constraint_fixes_the_height() {
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let mut start = true_state(&traj, 0.0);
    let truth_antenna = start.r_ecef_m + start.c_body_ecef * Vec3::from(LEVER);
    let height = ecef_to_geodetic(&truth_antenna).h_m;
    start.r_ecef_m += start.r_ecef_m.normalize() * 5.0;
    let mut cfg = config();
    cfg.initial_position_m = 5.0;
    let mut filter = LooselyCoupled::new(start, cfg).unwrap();
    let before = filter.update_height(height, 0.1).unwrap();
    assert!(
        (before.innovation[0] - 5.0).abs() < 0.01,
        "{}",
        before.innovation[0]
    );
    let antenna = filter.state().r_ecef_m + filter.state().c_body_ecef * Vec3::from(LEVER);
    let after = ecef_to_geodetic(&antenna).h_m - height;
    assert!(after.abs() < 0.3, "height error after {after} m");
    assert!(filter.update_height(f64::NAN, 0.1).is_err());
}

/// Code differenced between satellites (noise-free, the world's atmosphere-free ranges)
/// pulls a 5-m horizontal position error to centimetres in ten one-second updates; the
/// receiver's 0.1-ms clock offset cancels.
#[test]
fn code_differences_find_the_position() {
    let world = World::new(1e-7);
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let shift = |e: hifitime::Epoch| world.start + (e - t0());
    let mut incs = increments(&traj, 0.01, 1000, &Bias::default());
    for inc in &mut incs {
        inc.t_end = shift(inc.t_end);
    }
    let lever = Vec3::from(LEVER);
    let mut start = true_state(&traj, 0.0);
    start.t = shift(start.t);
    start.r_ecef_m += world.ned(3.0, -4.0, 0.0);
    let mut cfg = config();
    cfg.initial_position_m = 5.0;
    let mut filter = LooselyCoupled::new(start, cfg).unwrap();
    let pvt = crate::pvt::PvtConfig {
        troposphere: false,
        ..Default::default()
    };
    for (k, inc) in incs.iter().enumerate() {
        filter.propagate(inc).unwrap();
        if (k + 1) % 100 == 0 {
            let t = ((k + 1) / 100) as f64;
            let epoch = world.epoch(t, traj.r(t) + traj.c_body_ecef(t) * lever, &mut |_| 0.0);
            let u = filter.update_code(&epoch, &world.store, &world.origin, &pvt, 0.5);
            assert!(u.unwrap().is_some());
        }
    }
    let error = (filter.state().r_ecef_m - traj.r(10.0)).norm();
    assert!(error < 0.05, "position error after 10 s {error} m");
}

/// Velocity-only aiding (the book's velocity sub-filter): noise-free antenna velocities
/// every second (1 cm/s assumed) take a 0.14-m/s velocity error under 2 cm/s in 20 s;
/// a velocity more than an IMU interval away is refused.
#[test]
fn velocity_updates_find_the_velocity() {
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let lever = Vec3::from(LEVER);
    let antenna = |t: f64| traj.r(t) + traj.c_body_ecef(t) * lever;
    let incs = increments(&traj, 0.01, 2000, &Bias::default());
    let mut start = true_state(&traj, 0.0);
    start.v_ecef_mps += Vec3::new(0.1, -0.1, 0.0);
    let mut filter = LooselyCoupled::new(start, config()).unwrap();
    let cov = skyforge_orbits::Mat3::identity() * 1e-4;
    for (k, inc) in incs.iter().enumerate() {
        filter.propagate(inc).unwrap();
        if (k + 1) % 100 == 0 {
            let t = ((k + 1) / 100) as f64;
            let v = (antenna(t + 1e-3) - antenna(t - 1e-3)) / 2e-3;
            filter.update_velocity(inc.t_end, &v, &cov).unwrap();
        }
    }
    let error = (filter.state().v_ecef_mps - traj.v(20.0)).norm();
    assert!(error < 0.02, "velocity error after 20 s {error} m/s");
    let late = incs[0].t_end + hifitime::Duration::from_seconds(30.0);
    assert!(filter.update_velocity(late, &Vec3::zeros(), &cov).is_err());
}
