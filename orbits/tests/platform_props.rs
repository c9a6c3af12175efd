//! Platform behaviour through the public API: ground site, LEO, trajectory, attitude chain.

use hifitime::Epoch;
use proptest::prelude::*;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::platform::{AttitudeConfig, AxisProfileConfig};
use skyforge_orbits::platform::{
    EDGE_MARGIN_S, Platform, PlatformError, PlatformKind, PlatformWindow,
};
use skyforge_orbits::platform::{GroundConfig, PlatformConfig, TrajectoryConfig};
use skyforge_orbits::propagate::LeoPropagator;
use skyforge_orbits::propagate::{
    ForceModelConfig, IntegratorConfig, KeplerianElementsConfig, LeoConfig,
};
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::{Mat3, Vec3};
use std::path::{Path, PathBuf};

fn origin() -> TimeOrigin {
    TimeOrigin::new(Epoch::from_gregorian_utc_hms(2020, 6, 25, 0, 0, 0))
}

fn platform_config() -> PlatformConfig {
    PlatformConfig {
        leo: None,
        ground: None,
        trajectory: None,
        segments: None,
        attitude: AttitudeConfig::default(),
    }
}

fn ground_config(lat: f64, lon: f64, h: f64) -> PlatformConfig {
    PlatformConfig {
        ground: Some(GroundConfig {
            latitude_deg: Some(lat),
            longitude_deg: Some(lon),
            height_m: Some(h),
            ecef_m: None,
        }),
        ..platform_config()
    }
}

fn build(cfg: &PlatformConfig, base_dir: &Path) -> Platform {
    Platform::new(cfg, &origin(), base_dir).unwrap_or_else(|e| panic!("{e}"))
}

fn window(p: &mut Platform, t0: f64, t1: f64) -> PlatformWindow {
    p.window(t0, t1).unwrap_or_else(|e| panic!("{e}"))
}

fn temp_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("skyforge-platform-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    dir
}

#[test]
fn platform_window_is_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<PlatformWindow>();
}

#[test]
fn ground_site_is_constant_with_up_looking_antenna() {
    // Copenhagen-like site; -Zb (the default antenna boresight) must be the local up.
    let mut p = build(&ground_config(55.7, 12.5, 40.0), Path::new("."));
    assert_eq!(p.kind(), PlatformKind::Ground);
    let w = window(&mut p, 0.0, 3600.0);
    let expected = geodetic_to_ecef(&Geodetic {
        lat_rad: 55.7f64.to_radians(),
        lon_rad: 12.5f64.to_radians(),
        h_m: 40.0,
    });
    let up = (geodetic_to_ecef(&Geodetic {
        lat_rad: 55.7f64.to_radians(),
        lon_rad: 12.5f64.to_radians(),
        h_m: 41.0,
    }) - expected)
        .normalize();
    let first = w.state(0.0);
    for t in [0.0, 1.5, 1800.0, 3600.0] {
        let st = w.state(t);
        assert_eq!(st, first);
        assert!((st.r_ecef_m - expected).norm() < 1e-9);
        assert_eq!(st.v_ecef_mps, Vec3::zeros());
        assert!((st.c_body_ecef * -Vec3::z() - up).norm() < 1e-9);
        assert_eq!(st.attitude, YawPitchRoll::default());
    }
}

#[test]
fn ground_attitude_sinusoid_rotates_the_body() {
    // Yaw = 90 deg * sin(2 pi t / 60): at t = 15 s the body X (north at zero yaw) is east.
    let cfg = PlatformConfig {
        attitude: AttitudeConfig {
            yaw: AxisProfileConfig {
                offset_deg: 0.0,
                amplitude_deg: 90.0,
                period_s: 60.0,
                phase_deg: 0.0,
            },
            ..AttitudeConfig::default()
        },
        ..ground_config(0.0, 0.0, 0.0)
    };
    let mut p = build(&cfg, Path::new("."));
    let w = window(&mut p, 0.0, 60.0);
    let st = w.state(15.0);
    assert!((st.attitude.yaw_rad - 90f64.to_radians()).abs() < 1e-12);
    // At (0, 0): east is ECEF +Y, north is ECEF +Z.
    assert!((st.c_body_ecef * Vec3::x() - Vec3::y()).norm() < 1e-12);
    let st = w.state(45.0);
    assert!((st.c_body_ecef * Vec3::x() + Vec3::y()).norm() < 1e-12);
    assert!((w.state(30.0).c_body_ecef * Vec3::x() - Vec3::z()).norm() < 1e-12);
}

fn leo_config() -> LeoConfig {
    LeoConfig {
        elements: Some(KeplerianElementsConfig {
            semi_major_axis_km: 6_878.137,
            eccentricity: 0.001,
            inclination_deg: 97.4,
            raan_deg: 30.0,
            arg_perigee_deg: 10.0,
            mean_anomaly_deg: 20.0,
        }),
        tle: None,
        state: None,
        forces: ForceModelConfig::default(),
        integrator: IntegratorConfig::default(),
    }
}

#[test]
fn leo_state_is_the_propagator_state_in_ecef() {
    let cfg = PlatformConfig {
        leo: Some(leo_config()),
        ..platform_config()
    };
    let mut p = build(&cfg, Path::new("."));
    assert_eq!(p.kind(), PlatformKind::Leo);
    let earth = EarthRotation::at_origin(origin().start());
    let mut prop =
        LeoPropagator::new(&leo_config(), &origin(), &earth).unwrap_or_else(|e| panic!("{e}"));
    let dense = prop.window(0.0, 600.0).unwrap_or_else(|e| panic!("{e}"));
    let w = window(&mut p, 0.0, 600.0);
    for t in [0.0, 12.3, 300.0, 600.0] {
        let st = w.state(t);
        let (r_eci, v_eci, _) = dense.state_eci(t);
        let (r_ecef, v_ecef) = earth.eci_to_ecef(t, &r_eci, &v_eci);
        assert!((st.r_ecef_m - r_ecef).norm() < 1e-6, "t = {t}");
        assert!((st.v_ecef_mps - v_ecef).norm() < 1e-9, "t = {t}");
        // Zero attitude: Zb to the Earth centre, Xb along the inertial flight direction
        // (perpendicular to r, in the orbit plane), seen in ECEF.
        let c = st.c_body_ecef;
        assert!((c.transpose() * c - Mat3::identity()).norm() < 1e-12);
        assert!((c * Vec3::z() + r_ecef.normalize()).norm() < 1e-9);
        let c_eci_ecef = earth.c_eci_ecef(t);
        let h_ecef = c_eci_ecef * r_eci.cross(&v_eci).normalize();
        let x_expected = (-h_ecef).cross(&(-r_ecef.normalize()));
        assert!((c * Vec3::x() - x_expected).norm() < 1e-9);
        // Nearly circular orbit: Xb is within e = 0.001 rad of the velocity direction.
        let v_rot = (c_eci_ecef * v_eci).normalize();
        assert!((c * Vec3::x()).dot(&v_rot) > (2e-3f64).cos());
    }
}

#[test]
fn trajectory_platform_uses_ned_at_the_current_position() {
    // A straight eastward drive along the equator at 20 m/s, 1 Hz, no velocity columns.
    let dir = temp_dir();
    let mut text = String::from("t_s,x_m,y_m,z_m\n");
    let a = 6_378_137.0;
    for k in 0..=100 {
        let lon = 20.0 * f64::from(k) / a;
        text.push_str(&format!(
            "{k},{:.6},{:.6},0\n",
            a * lon.cos(),
            a * lon.sin()
        ));
    }
    std::fs::write(dir.join("drive.csv"), text).unwrap_or_else(|e| panic!("{e}"));
    let cfg = PlatformConfig {
        trajectory: Some(TrajectoryConfig {
            csv: PathBuf::from("drive.csv"),
        }),
        ..platform_config()
    };
    let mut p = build(&cfg, &dir);
    assert_eq!(p.kind(), PlatformKind::Trajectory);
    let w = window(&mut p, 0.0, 100.0);
    let st = w.state(50.5);
    let g = ecef_to_geodetic(&st.r_ecef_m);
    assert!((g.lon_rad - 20.0 * 50.5 / a).abs() < 1e-10);
    assert!(g.h_m.abs() < 1e-3);
    assert!((st.v_ecef_mps.norm() - 20.0).abs() < 1e-3);
    let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
    assert!((st.c_body_ecef - c_ned_ecef).norm() < 1e-12);
    // The window may reach EDGE_MARGIN_S beyond the data, not more.
    assert!(p.window(-EDGE_MARGIN_S, 100.0 + EDGE_MARGIN_S).is_ok());
    match p.window(90.0, 100.0 + EDGE_MARGIN_S + 1.0) {
        Err(PlatformError::OutsideTrajectory {
            first_s, last_s, ..
        }) => {
            assert_eq!((first_s, last_s), (0.0, 100.0));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn attitude_table_must_cover_the_window() {
    let dir = temp_dir();
    std::fs::write(dir.join("att.csv"), "0,0,0,0\n10,10,0,0\n").unwrap_or_else(|e| panic!("{e}"));
    let cfg = PlatformConfig {
        attitude: AttitudeConfig {
            csv: Some(PathBuf::from("att.csv")),
            ..AttitudeConfig::default()
        },
        ..ground_config(10.0, 20.0, 0.0)
    };
    let mut p = build(&cfg, &dir);
    let w = window(&mut p, 0.0, 10.0);
    assert!((w.state(5.0).attitude.yaw_rad - 5f64.to_radians()).abs() < 1e-12);
    assert!(matches!(
        p.window(0.0, 20.0),
        Err(PlatformError::OutsideAttitude { t_s, .. }) if t_s == 20.0
    ));
}

#[test]
fn platform_config_errors() {
    let none = platform_config();
    assert!(matches!(
        Platform::new(&none, &origin(), Path::new(".")),
        Err(PlatformError::Config(_))
    ));
    let two = PlatformConfig {
        leo: Some(leo_config()),
        ..ground_config(0.0, 0.0, 0.0)
    };
    match Platform::new(&two, &origin(), Path::new(".")) {
        Err(PlatformError::Config(inv)) => assert_eq!(inv.value, "[leo, ground]"),
        other => panic!("{other:?}"),
    }
    let missing = PlatformConfig {
        trajectory: Some(TrajectoryConfig {
            csv: PathBuf::from("no-such-file.csv"),
        }),
        ..platform_config()
    };
    match Platform::new(&missing, &origin(), Path::new("/nonexistent-dir")) {
        Err(PlatformError::Csv { path, line, .. }) => {
            assert_eq!(path, "/nonexistent-dir/no-such-file.csv");
            assert_eq!(line, 0);
        }
        other => panic!("{other:?}"),
    }
}

proptest! {
    #[test]
    fn ground_attitude_chain(
        lat in -89.9f64..89.9, lon in -180.0f64..180.0,
        yaw in -179.0f64..179.0, pitch in -89.0f64..89.0, roll in -179.0f64..179.0,
    ) {
        let cfg = PlatformConfig {
            attitude: AttitudeConfig {
                yaw: AxisProfileConfig { offset_deg: yaw, ..AxisProfileConfig::default() },
                pitch: AxisProfileConfig { offset_deg: pitch, ..AxisProfileConfig::default() },
                roll: AxisProfileConfig { offset_deg: roll, ..AxisProfileConfig::default() },
                csv: None,
            },
            ..ground_config(lat, lon, 0.0)
        };
        let mut p = build(&cfg, Path::new("."));
        let st = window(&mut p, 0.0, 1.0).state(0.5);
        let c = st.c_body_ecef;
        prop_assert!((c.transpose() * c - Mat3::identity()).norm() < 1e-13);
        prop_assert!((c.determinant() - 1.0).abs() < 1e-13);
        // Back to NED: the attitude recovered from c_ned_body equals the profile.
        let c_ecef_ned = c_ecef_ned(lat.to_radians(), lon.to_radians());
        let back = YawPitchRoll::from_c_ref_body(&(c_ecef_ned * c).transpose());
        prop_assert!((back.yaw_rad - yaw.to_radians()).abs() < 1e-9);
        prop_assert!((back.pitch_rad - pitch.to_radians()).abs() < 1e-9);
        prop_assert!((back.roll_rad - roll.to_radians()).abs() < 1e-9);
    }
}
