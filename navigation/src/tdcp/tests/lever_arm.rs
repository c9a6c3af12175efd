//! The IMU's displacement through a lever arm on a turning body.

use super::world::{World, quiet};
use crate::tdcp::{
    ImuPose, LeverArm, TdcpConfig, solve_double, solve_single, time_differences,
    time_differences_imu,
};
use skyforge_orbits::{Mat3, Vec3};

/// A body moving north at 5 m/s and turning right at 10 deg/s (yaw), with its antenna
/// 1 m from the IMU (0.8 m forward, 0.6 m up), at 1 Hz: the antenna moves 0.14 m more
/// than the IMU. Differences built at the antenna from the IMU's poses give the IMU at
/// `t2` to a millimetre (single and double differences); the same observations taken as
/// the IMU's own are off by the lever-arm term, more than 10 cm.
#[test]
fn imu_displacement_through_a_turning_lever_arm() {
    let w = World::new(1e-7);
    let lever = LeverArm {
        body_m: Vec3::new(0.8, 0.0, -0.6),
    };
    let pose = |t: f64| {
        let yaw = (30.0 + 10.0 * (t - 50.0)).to_radians();
        let (s, c) = yaw.sin_cos();
        let c_body_ned = Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        ImuPose {
            r_ecef_m: w.site + w.ned(5.0, 0.0, 0.0) * (t - 50.0),
            c_body_ecef: w.c_ecef_ned.transpose() * c_body_ned,
        }
    };
    let (p1, p2) = (pose(50.0), pose(51.0));
    let prev = w.epoch(50.0, lever.antenna(&p1), &mut quiet);
    let cur = w.epoch(51.0, lever.antenna(&p2), &mut quiet);
    let config = TdcpConfig::default();
    // A priori at t2: the IMU where it was at t1, the attitude known.
    let p2_hat = ImuPose {
        r_ecef_m: p1.r_ecef_m,
        ..p2
    };
    let term = lever.displacement_term_m(&p1.c_body_ecef, &p2.c_body_ecef);
    let antenna_moved = lever.antenna(&p2) - lever.antenna(&p1);
    assert!((antenna_moved - (p2.r_ecef_m - p1.r_ecef_m) - term).norm() < 1e-8);
    let epoch = time_differences_imu(
        (&prev, &cur),
        (&p1, &p2_hat),
        &lever,
        &w.store,
        &w.origin,
        &config,
    )
    .unwrap();
    let sd = solve_single(&epoch).unwrap();
    let dd = solve_double(&epoch.double_differences().unwrap()).unwrap();
    for (name, s) in [("SD", &sd), ("DD", &dd)] {
        let imu2 = lever.imu(s.r2_m, &p2.c_body_ecef);
        let error = (imu2 - p2.r_ecef_m).norm();
        let via_delta = (p2_hat.r_ecef_m + s.delta_r_m - p2.r_ecef_m).norm();
        println!("{name}: IMU error {error:.2e} m (r2_hat + delta_r: {via_delta:.2e} m)");
        assert!(error < 1e-3 && via_delta < 1e-3);
    }
    // Without the lever arm: the IMU's poses taken as the antenna's.
    let naive = time_differences(
        &prev,
        &cur,
        p1.r_ecef_m,
        p1.r_ecef_m,
        &w.store,
        &w.origin,
        &config,
    )
    .unwrap();
    let naive = solve_double(&naive.double_differences().unwrap()).unwrap();
    let naive_error = (naive.r2_m - p2.r_ecef_m).norm();
    println!(
        "lever-arm term {:.4} m; ignoring it: IMU error {naive_error:.4} m",
        term.norm()
    );
    assert!((naive_error - term.norm()).abs() < 1e-3 && naive_error > 0.1);
}
