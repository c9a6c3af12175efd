//! A LEO's kinematics for an IMU (`PlatformWindow::kinematics` on `[leo]`): velocity,
//! acceleration and angular rate are the derivatives of the position, velocity and
//! attitude the platform reports, the gravity acting is the propagator's (a drag-free
//! orbit's specific force is zero), and an Earth-pointing body turns at the orbit rate
//! about its pitch axis.

use hifitime::Epoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::gravity::earth_rate_ecef;
use skyforge_orbits::platform::{Kinematics, Platform, PlatformConfig, PlatformWindow};
use skyforge_orbits::time::TimeOrigin;
use std::path::Path;

/// The thesis LEO (table 1.2-1) with J2 and the given drag, Earth-pointing.
fn leo(drag: bool) -> String {
    format!(
        r#"
[leo.elements]
semi_major_axis_km = 6971.593
eccentricity = 0.000846
inclination_deg = 34.911
raan_deg = -78.005
arg_perigee_deg = 47.757
mean_anomaly_deg = 351.636
[leo.forces]
j2 = true
drag = {drag}
"#
    )
}

fn window(text: &str, t1_s: f64) -> PlatformWindow {
    let cfg: PlatformConfig = toml::from_str(text).unwrap_or_else(|e| panic!("{e}"));
    let origin = TimeOrigin::new(Epoch::from_gregorian_utc_hms(2020, 6, 25, 0, 0, 0));
    let mut p = Platform::new(&cfg, &origin, Path::new(".")).unwrap_or_else(|e| panic!("{e}"));
    p.window(0.0, t1_s).unwrap_or_else(|e| panic!("{e}"))
}

fn kin(w: &PlatformWindow, t: f64) -> Kinematics {
    w.kinematics(t).expect("a LEO gives kinematics")
}

/// Central differences over 0.1 s at 40 instants of 10 minutes: the velocity within 1e-4
/// m/s of the position's derivative (truncation `h^2 / 6` times the jerk, 1e-2 m/s^3:
/// 2e-5), the acceleration within 1e-6 m/s^2 of the velocity's (rounding of 7 km/s over
/// 0.2 s: 1e-11; truncation 2e-8), the angular rate within 1e-9 rad/s of the attitude's.
#[test]
fn velocity_acceleration_and_rate_are_the_derivatives() {
    let w = window(&leo(true), 620.0);
    let h = 0.1;
    let d = |f: &dyn Fn(f64) -> Vec3, t: f64| (f(t + h) - f(t - h)) / (2.0 * h);
    let mut worst = [0.0f64; 3];
    for i in 0..40 {
        let t = 5.0 + 15.0 * f64::from(i) + 0.37;
        let k = kin(&w, t);
        let dr = d(&|s| kin(&w, s).r_ecef_m, t);
        let dv = d(&|s| kin(&w, s).v_ecef_mps, t);
        let dc = (kin(&w, t + h).c_body_ecef - kin(&w, t - h).c_body_ecef) / (2.0 * h);
        let skew = k.c_body_ecef.transpose() * dc;
        let rate = Vec3::new(skew[(2, 1)], skew[(0, 2)], skew[(1, 0)]);
        worst[0] = worst[0].max((dr - k.v_ecef_mps).norm());
        worst[1] = worst[1].max((dv - k.a_ecef_mps2).norm());
        worst[2] = worst[2].max((rate - k.omega_eb_body_rps).norm());
        assert_eq!(w.state(t).r_ecef_m, k.r_ecef_m);
    }
    assert!(worst[0] < 1e-4, "velocity {worst:?}");
    assert!(worst[1] < 1e-6, "acceleration {worst:?}");
    assert!(worst[2] < 1e-9, "angular rate {worst:?}");
}

/// Without drag the LEO falls freely: its specific force `C^T (a + 2 w x v - g)` is zero
/// (to the rounding of 9 m/s^2 terms); with the exponential atmosphere at 600 km it is
/// the drag, against the flight (under 1e-5 m/s^2 and along -x of the body). An
/// Earth-pointing body turns relative to inertial space at the orbit rate `|r x v| /
/// r^2` about -y (J2 tilts the orbital frame by about its normal acceleration over the
/// speed, 1e-3 of the rate: bound 3e-3).
#[test]
fn specific_force_is_the_drag_and_the_body_turns_at_the_orbit_rate() {
    let w_ie = earth_rate_ecef();
    let specific = |k: &Kinematics| {
        k.c_body_ecef.transpose()
            * (k.a_ecef_mps2 + 2.0 * w_ie.cross(&k.v_ecef_mps) - k.gravity_ecef_mps2)
    };
    let (free, dragged) = (window(&leo(false), 620.0), window(&leo(true), 620.0));
    for t in [10.0, 300.0, 600.0] {
        let f = specific(&kin(&free, t));
        assert!(f.norm() < 1e-9, "free fall at {t} s: {f:?}");
        let k = kin(&dragged, t);
        let f = specific(&k);
        assert!(f.norm() > 0.0 && f.norm() < 1e-5, "drag at {t} s: {f:?}");
        assert!(
            f.x < 0.0 && f.x.abs() > 0.9 * f.norm(),
            "drag along -x: {f:?}"
        );
        let omega_ib = k.omega_eb_body_rps + k.c_body_ecef.transpose() * w_ie;
        let (r, v) = (k.r_ecef_m, k.v_ecef_mps + w_ie.cross(&k.r_ecef_m));
        let n = r.cross(&v).norm() / r.norm_squared();
        let error = (omega_ib - Vec3::new(0.0, -n, 0.0)).norm();
        assert!(error < 3e-3 * n, "rate at {t} s: {omega_ib:?} against {n}");
    }
}
