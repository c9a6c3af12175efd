//! `[platform.segments]`: the generated motion is consistent with itself (velocity,
//! acceleration and angular rate are the derivatives of position, velocity and attitude),
//! smooth across legs, and where it should be; bad legs are refused by field.

use hifitime::Epoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::platform::{
    Kinematics, Platform, PlatformConfig, PlatformError, PlatformWindow,
};
use skyforge_orbits::time::TimeOrigin;
use std::path::Path;

fn origin() -> TimeOrigin {
    TimeOrigin::new(Epoch::from_gregorian_utc_hms(2020, 6, 25, 0, 0, 0))
}

fn platform(text: &str) -> Result<Platform, PlatformError> {
    let cfg: PlatformConfig = toml::from_str(text).unwrap_or_else(|e| panic!("{e}"));
    Platform::new(&cfg, &origin(), Path::new("."))
}

fn window(text: &str, t1_s: f64) -> PlatformWindow {
    let mut p = platform(text).unwrap_or_else(|e| panic!("{e}"));
    p.window(0.0, t1_s).unwrap_or_else(|e| panic!("{e}"))
}

fn kin(w: &PlatformWindow, t: f64) -> Kinematics {
    w.kinematics(t).expect("segments give kinematics")
}

/// A boat-like and an aircraft-like run in one: accelerations, turns both ways, a climb
/// with coordinated turns, a heave and sinusoidal pitch and roll on top.
const RICH: &str = r#"
[segments]
latitude_deg = 28.2
longitude_deg = 112.9
height_m = 50.0
heading_deg = 30.0
speed_mps = 5.0
ramp_s = 2.0
coordinated_turns = true
heave = { amplitude_m = 0.4, period_s = 6.0, phase_deg = 10.0 }
[[segments.legs]]
duration_s = 20.0
acceleration_mps2 = 0.5
[[segments.legs]]
duration_s = 30.0
turn_rate_deg_s = 6.0
climb_mps = 2.0
[[segments.legs]]
duration_s = 25.0
turn_rate_deg_s = -4.0
acceleration_mps2 = -0.2
[[segments.legs]]
duration_s = 30.0
[attitude]
pitch = { amplitude_deg = 3.0, period_s = 7.0 }
roll = { amplitude_deg = 5.0, period_s = 5.0, phase_deg = 40.0 }
"#;

/// Central difference of `f` at `t` with step `h`.
fn derivative<F: Fn(f64) -> Vec3>(f: F, t: f64, h: f64) -> Vec3 {
    (f(t + h) - f(t - h)) / (2.0 * h)
}

#[test]
fn velocity_acceleration_and_rate_are_the_derivatives() {
    let w = window(RICH, 105.0);
    let h = 1e-3;
    let mut worst = [0.0f64; 3];
    // Off the ramps' ends, where the jerk jumps (a central difference there is off by
    // the jump times h / 4).
    for i in 0..420 {
        let t = 0.25 * i as f64 + 0.1;
        let k = kin(&w, t);
        let dr = derivative(|s| kin(&w, s).r_ecef_m, t, h);
        let dv = derivative(|s| kin(&w, s).v_ecef_mps, t, h);
        // [w x] = C^T dC/dt for the body's rate relative to the Earth.
        let dc = (kin(&w, t + h).c_body_ecef - kin(&w, t - h).c_body_ecef) / (2.0 * h);
        let skew = k.c_body_ecef.transpose() * dc;
        let rate = Vec3::new(skew[(2, 1)], skew[(0, 2)], skew[(1, 0)]);
        worst[0] = worst[0].max((dr - k.v_ecef_mps).norm());
        worst[1] = worst[1].max((dv - k.a_ecef_mps2).norm());
        worst[2] = worst[2].max((rate - k.omega_eb_body_rps).norm());
        let state = w.state(t);
        assert_eq!(state.r_ecef_m, k.r_ecef_m);
        assert!((state.c_body_ecef - k.c_body_ecef).norm() < 1e-15);
    }
    // Central differences of a smooth motion at 1 ms: O(h^2) truncation and the
    // rounding of 6.4e6 m positions (1e-9 m / 1e-3 s), the velocity's
    // differences of the same rounding (1e-12 m/s / 1e-3 s).
    assert!(worst[0] < 1e-5, "velocity {worst:?}");
    assert!(worst[1] < 1e-4, "acceleration {worst:?}");
    // The rate's O(h^2) truncation, h^2 / 6 times its third derivative (the waves' and
    // the banking's, under 1 rad/s^3 here): under 2e-7 rad/s.
    assert!(worst[2] < 3e-7, "angular rate {worst:?}");
}

/// Across each leg boundary and each ramp's end the acceleration and the angular rate
/// change continuously: their change across `t +/- d` shrinks with `d` (tenfold from
/// 1 ms to 0.1 ms), where a jump would stay.
#[test]
fn acceleration_and_rate_are_continuous_across_legs() {
    let w = window(RICH, 105.0);
    let jumps = |t: f64, d: f64| {
        let (a, b) = (kin(&w, t - d), kin(&w, t + d));
        (
            (a.a_ecef_mps2 - b.a_ecef_mps2).norm(),
            (a.omega_eb_body_rps - b.omega_eb_body_rps).norm(),
        )
    };
    for t in [20.0, 22.0, 50.0, 52.0, 75.0, 77.0] {
        let (wide, narrow) = (jumps(t, 1e-3), jumps(t, 1e-4));
        assert!(narrow.0 < 0.2 * wide.0 + 1e-9, "t {t}: {wide:?} {narrow:?}");
        assert!(
            narrow.1 < 0.2 * wide.1 + 1e-12,
            "t {t}: {wide:?} {narrow:?}"
        );
    }
}

/// A full circle at constant speed and turn rate returns to its start on the equator (the
/// heading is relative to the local north: at 45 deg the meridians' convergence across
/// the circle turns it by up to 9e-5 rad and it drifts 0.16 m a loop, as
/// `v T (r / (N cos lat)) sin(lat) / 2` predicts); a straight run east covers speed x
/// time.
#[test]
fn a_circle_closes_and_a_straight_run_covers_its_distance() {
    let circle = r#"
[segments]
latitude_deg = 0.0
longitude_deg = 10.0
height_m = 0.0
heading_deg = 0.0
speed_mps = 10.0
[[segments.legs]]
duration_s = 36.0
turn_rate_deg_s = 0.0
[[segments.legs]]
duration_s = 364.0
turn_rate_deg_s = 1.0
"#;
    let w = window(circle, 400.0);
    // After the 2-s ramp (36..38 s) the rate is held: from 38 s the path is a circle of
    // 360 s.
    let start = kin(&w, 38.0).r_ecef_m;
    let end = kin(&w, 398.0).r_ecef_m;
    assert!((end - start).norm() < 0.01, "{} m", (end - start).norm());
    // Radius v / r = 10 / (pi / 180) = 573 m: half-way round the point is 2 r away.
    let across = (kin(&w, 218.0).r_ecef_m - start).norm();
    assert!(
        (across - 2.0 * 10.0 / 1f64.to_radians()).abs() < 0.01,
        "{across}"
    );

    let east = r#"
[segments]
latitude_deg = 0.0
longitude_deg = 0.0
height_m = 0.0
heading_deg = 90.0
speed_mps = 20.0
[[segments.legs]]
duration_s = 100.0
"#;
    let w = window(east, 100.0);
    let g = ecef_to_geodetic(&kin(&w, 100.0).r_ecef_m);
    // Along the equator: 2000 m of arc at the equatorial radius.
    assert!(
        (g.lon_rad * 6_378_137.0 - 2000.0).abs() < 1e-6,
        "{}",
        g.lon_rad
    );
    assert!(g.lat_rad.abs() < 1e-12 && g.h_m.abs() < 1e-6);
    let start = geodetic_to_ecef(&Geodetic::from_degrees(0.0, 0.0, 0.0));
    assert!((kin(&w, 0.0).r_ecef_m - start).norm() < 1e-9);
}

/// A platform at rest on the generated path: zero velocity and acceleration, and the
/// body's rate only what the attitude profile turns.
#[test]
fn a_vehicle_at_rest_stays_put() {
    let w = window(
        "[segments]\nlatitude_deg = 28.2\nlongitude_deg = 112.9\nheight_m = 60.0\n[[segments.legs]]\nduration_s = 50.0\n",
        50.0,
    );
    let k = kin(&w, 33.3);
    assert_eq!(k.v_ecef_mps, Vec3::zeros());
    assert_eq!(k.a_ecef_mps2, Vec3::zeros());
    assert_eq!(k.omega_eb_body_rps, Vec3::zeros());
    assert!((kin(&w, 0.0).r_ecef_m - k.r_ecef_m).norm() == 0.0);
}

/// Bad legs are refused with the field, the value and what is allowed.
#[test]
fn bad_legs_name_their_field() {
    let head =
        "[segments]\nlatitude_deg = 10.0\nlongitude_deg = 0.0\nheight_m = 0.0\nspeed_mps = 2.0\n";
    let cases = [
        (
            "[[segments.legs]]\nduration_s = 10.0\nacceleration_mps2 = -0.5\n",
            "segments.legs[0].acceleration_mps2",
            "below zero",
        ),
        (
            "[[segments.legs]]\nduration_s = 1.0\n",
            "segments.legs[0].duration_s",
            "at least ramp_s",
        ),
        (
            "[[segments.legs]]\nduration_s = 10.0\nturn_rate_deg_s = 400.0\n",
            "segments.legs[0].turn_rate_deg_s",
            "deg/s",
        ),
        (
            "[[segments.legs]]\nduration_s = 10.0\nacceleration_mps2 = -0.18\n[[segments.legs]]\nduration_s = 10.0\nclimb_mps = 1.0\n",
            "segments.legs[1].climb_mps",
            "0.5 m/s or more",
        ),
    ];
    for (legs, field, says) in cases {
        match platform(&format!("{head}{legs}")) {
            Err(PlatformError::Config(inv)) => {
                assert_eq!(inv.field, field, "{inv}");
                assert!(inv.to_string().contains(says), "{inv}");
            }
            other => panic!("{field}: {other:?}"),
        }
    }
    match platform(
        "[segments]\nlatitude_deg = 10.0\nlongitude_deg = 0.0\nheight_m = 0.0\nlegs = []\n",
    ) {
        Err(PlatformError::Config(inv)) => assert_eq!(inv.field, "segments.legs"),
        other => panic!("{other:?}"),
    }
    let mut p = platform(&format!("{head}[[segments.legs]]\nduration_s = 10.0\n")).unwrap();
    assert!(matches!(
        p.window(0.0, 20.0),
        Err(PlatformError::OutsideSegments { .. })
    ));
}
