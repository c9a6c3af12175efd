//! Klobuchar ionosphere (GPS and BeiDou variants), frequency scaling, sign convention and
//! the height reduction.
//!
//! External oracle: the three GPS cases of Swift Navigation's libswiftnav
//! `test_ionosphere` (values only): inputs and their published L1 delays in metres.

use proptest::prelude::*;
use skyforge_orbits::constants::{C_MPS, F_BDS_B1I_HZ, F_GPS_L1_HZ};
use skyforge_orbits::ephemeris::System;
use skyforge_orbits::frames::Geodetic;
use skyforge_signals::errors::{
    IonoConfig, IonoModel, KlobucharCoeffs, bds_klobuchar_b1i_s, gps_klobuchar_l1_s,
    remaining_fraction, scale_to_frequency,
};

const D2R: f64 = std::f64::consts::PI / 180.0;

fn coeffs(alpha: [f64; 4], beta: [f64; 4]) -> KlobucharCoeffs {
    KlobucharCoeffs { alpha, beta }
}

#[test]
fn gps_matches_published_libswiftnav_cases() {
    // (alpha, beta, lat deg or rad, lon, az, el, GPS time of week s, delay m)
    let cases = [
        (
            coeffs(
                [0.1583e-7, -0.7451e-8, -0.5960e-7, 0.1192e-6],
                [0.1290e6, -0.2130e6, 0.6554e5, 0.3277e6],
            ),
            [-35.3 * D2R, 149.1 * D2R, 0.0, 15.0 * D2R],
            479_820.0,
            7.202,
        ),
        (
            coeffs(
                [0.3820e-7, 0.1490e-7, -0.1790e-6, 0.0],
                [0.1430e6, 0.0, -0.3280e6, 0.1130e6],
            ),
            [40.0 * D2R, 260.0 * D2R, 210.0 * D2R, 20.0 * D2R],
            593_100.0,
            23.784,
        ),
        (
            coeffs(
                [1.304e-8, 0.0, -5.96e-8, 5.96e-8],
                [1.106e5, -65540.0, -2.621e5, 3.932e5],
            ),
            [0.70605, -0.076233, 2.62049, 0.2939],
            345_600.0,
            3.4929,
        ),
    ];
    for (c, [lat, lon, az, el], tow, expected_m) in cases {
        let got_m = gps_klobuchar_l1_s(&c, lat, lon, az, el, tow) * C_MPS;
        assert!((got_m - expected_m).abs() < 1e-3, "{got_m} vs {expected_m}");
    }
}

/// Night-time: the vertical delay is the 5 ns constant; the slant delay is that times the
/// obliquity factor, written out here from IS-GPS-200 figure 20-4: F = 1 + 16 (0.53 - E)^3,
/// E in semicircles.
#[test]
fn gps_night_is_five_ns_times_obliquity() {
    let c = coeffs([2e-8, 0.0, 0.0, 0.0], [72_000.0, 0.0, 0.0, 0.0]);
    // Local time 02:00 at the pierce point: |x| = 2 pi 43200 / 72000 > 1.57.
    for el_deg in [90.0_f64, 45.0, 20.0, 5.0, 0.0] {
        let e_sc = el_deg / 180.0;
        let f = 1.0 + 16.0 * (0.53 - e_sc).powi(3);
        // Azimuth 0 from (0, 0): the pierce point moves north only, so its local time is
        // the GPS time of day.
        let got = gps_klobuchar_l1_s(&c, 0.0, 0.0, 0.0, el_deg * D2R, 7_200.0);
        assert!((got - 5e-9 * f).abs() < 1e-15, "el {el_deg}: {got}");
    }
    // Obliquity range: 1.0004 at zenith, 3.38 at the horizon.
    let ratio = gps_klobuchar_l1_s(&c, 0.0, 0.0, 0.0, 0.0, 3_600.0)
        / gps_klobuchar_l1_s(&c, 0.0, 0.0, 0.0, 90.0 * D2R, 3_600.0);
    assert!((3.37..3.39).contains(&ratio), "{ratio}");
}

/// BeiDou night-time: 5 ns over 1/sqrt(1 - (R cos E / (R + h))^2), R = 6378 km,
/// h = 375 km (BDS-SIS-ICD-B1I 5.2.4.7).
#[test]
fn bds_night_is_five_ns_times_shell_mapping() {
    let c = coeffs([5e-8, 0.0, 0.0, 0.0], [172_800.0, 0.0, 0.0, 0.0]);
    for el_deg in [90.0_f64, 60.0, 30.0, 10.0, 0.0] {
        let k = 6378.0 / (6378.0 + 375.0) * (el_deg * D2R).cos();
        let expected = 5e-9 / (1.0 - k * k).sqrt();
        // BDT 01:00 at longitude 0, azimuth 0: local time 01:00, |t - 50400| > A4/4.
        let got = bds_klobuchar_b1i_s(&c, 0.0, 0.0, 0.0, el_deg * D2R, 3_600.0);
        assert!(
            (got - expected).abs() < 1e-15,
            "el {el_deg}: {got} vs {expected}"
        );
    }
    let horizon = bds_klobuchar_b1i_s(&c, 0.0, 0.0, 0.0, 0.0, 3_600.0) / 5e-9;
    assert!((3.04..3.05).contains(&horizon), "{horizon}");
}

/// BeiDou day-time peak at the zenith: 5 ns + A2 with A2 = alpha0 (|lat| = 0).
#[test]
fn bds_zenith_peak_is_night_plus_amplitude() {
    let c = coeffs([4e-8, 1e-7, 0.0, 0.0], [100_000.0, 0.0, 0.0, 0.0]);
    let got = bds_klobuchar_b1i_s(&c, 0.0, 0.0, 0.0, 90.0 * D2R, 50_400.0);
    assert!((got - 4.5e-8).abs() < 1e-15, "{got}");
    // Southern and northern pierce points of equal |latitude| give the same delay.
    let north = bds_klobuchar_b1i_s(&c, 30.0 * D2R, 0.0, 0.0, 90.0 * D2R, 50_400.0);
    let south = bds_klobuchar_b1i_s(&c, -30.0 * D2R, 0.0, 0.0, 90.0 * D2R, 50_400.0);
    assert!((north - south).abs() < 1e-18);
    // 5 ns + alpha0 + alpha1 / 6 at 30 deg.
    assert!(
        (north - (5e-9 + 4e-8 + 1e-7 / 6.0)).abs() < 1e-15,
        "{north}"
    );
}

/// The cosine is symmetric about 14:00 local time (both variants).
#[test]
fn day_curve_is_symmetric_about_14h() {
    let c = coeffs([3e-8, 0.0, 0.0, 0.0], [90_000.0, 0.0, 0.0, 0.0]);
    for dt in [600.0, 3_600.0, 10_000.0, 20_000.0] {
        let el = 90.0 * D2R;
        let g = |t| gps_klobuchar_l1_s(&c, 0.0, 0.0, 0.0, el, t);
        let b = |t| bds_klobuchar_b1i_s(&c, 0.0, 0.0, 0.0, el, t);
        assert!((g(50_400.0 + dt) - g(50_400.0 - dt)).abs() < 1e-18);
        assert!((b(50_400.0 + dt) - b(50_400.0 - dt)).abs() < 1e-18);
        assert!(g(50_400.0) >= g(50_400.0 + dt));
    }
}

#[test]
fn frequency_scaling_and_sign_convention() {
    // L2 / L1 = (154/120)^2 = 1.6469.
    let l2 = scale_to_frequency(1.0, F_GPS_L1_HZ, 1_227.6e6);
    assert!((l2 - (154.0_f64 / 120.0).powi(2)).abs() < 1e-12);
    let cfg = IonoConfig::default();
    let rx = Geodetic {
        lat_rad: 0.7,
        lon_rad: 0.2,
        h_m: 100.0,
    };
    let d_l1 = cfg.delay(System::Gps, &rx, 1.0, 0.5, 45_000.0, F_GPS_L1_HZ);
    assert!(d_l1.code_m > 0.0 && d_l1.carrier_m == -d_l1.code_m);
    let d_l2 = cfg.delay(System::Gps, &rx, 1.0, 0.5, 45_000.0, 1_227.6e6);
    assert!((d_l2.code_m / d_l1.code_m - l2).abs() < 1e-12);
    let expected = gps_klobuchar_l1_s(&cfg.gps, 0.7, 0.2, 1.0, 0.5, 45_000.0) * C_MPS;
    assert!((d_l1.code_m - expected).abs() < 1e-12);
    let b1 = cfg.delay(System::Beidou, &rx, 1.0, 0.5, 45_000.0, F_BDS_B1I_HZ);
    let b1_expected = bds_klobuchar_b1i_s(&cfg.bds, 0.7, 0.2, 1.0, 0.5, 45_000.0) * C_MPS;
    assert!((b1.code_m - b1_expected).abs() < 1e-12);
    let off = IonoConfig {
        model: IonoModel::Off,
        ..IonoConfig::default()
    };
    assert_eq!(
        off.delay(System::Gps, &rx, 1.0, 0.5, 45_000.0, F_GPS_L1_HZ)
            .code_m,
        0.0
    );
}

/// Yuan 2000 section 5.4.1: 30 % of the ground error above 400 km, 10 % above 500 km,
/// 40 % above 350 km; nothing above 700 km; `leo_scale` overrides it above 100 km.
#[test]
fn height_reduction_follows_the_book_and_the_override() {
    assert_eq!(remaining_fraction(0.0), 1.0);
    assert_eq!(remaining_fraction(100e3), 1.0);
    assert!((remaining_fraction(350e3) - 0.4).abs() < 1e-12);
    assert!((remaining_fraction(400e3) - 0.3).abs() < 1e-12);
    assert!((remaining_fraction(450e3) - 0.2).abs() < 1e-12);
    assert!((remaining_fraction(500e3) - 0.1).abs() < 1e-12);
    assert_eq!(remaining_fraction(700e3), 0.0);
    assert_eq!(remaining_fraction(20_000e3), 0.0);
    let cfg = IonoConfig {
        leo_scale: Some(0.25),
        ..IonoConfig::default()
    };
    assert_eq!(cfg.height_factor(10.0), 1.0);
    assert_eq!(cfg.height_factor(600e3), 0.25);
    let ground = Geodetic {
        lat_rad: 0.3,
        lon_rad: 1.0,
        h_m: 0.0,
    };
    let leo = Geodetic {
        h_m: 450e3,
        ..ground
    };
    let d0 = IonoConfig::default().delay(System::Gps, &ground, 0.3, 0.6, 50_000.0, F_GPS_L1_HZ);
    let d1 = IonoConfig::default().delay(System::Gps, &leo, 0.3, 0.6, 50_000.0, F_GPS_L1_HZ);
    assert!((d1.code_m / d0.code_m - 0.2).abs() < 1e-12);
    // A storm scales the delay whatever the height, code and carrier alike.
    let storm = IonoConfig {
        scale: 3.0,
        ..IonoConfig::default()
    };
    for (rx, d) in [(&ground, d0), (&leo, d1)] {
        let s = storm.delay(System::Gps, rx, 0.3, 0.6, 50_000.0, F_GPS_L1_HZ);
        assert!((s.code_m - 3.0 * d.code_m).abs() < 1e-12 && s.carrier_m == -s.code_m);
    }
}

#[test]
fn config_check_rejects_bad_values() {
    assert!(IonoConfig::default().check().is_ok());
    let bad_scale = IonoConfig {
        leo_scale: Some(1.5),
        ..IonoConfig::default()
    };
    assert_eq!(
        bad_scale.check().err().map(|e| e.field),
        Some("leo_scale".to_string())
    );
    let storm = IonoConfig {
        scale: 11.0,
        ..IonoConfig::default()
    };
    assert_eq!(
        storm.check().err().map(|e| e.field),
        Some("scale".to_string())
    );
    let mut bad_beta = IonoConfig::default();
    bad_beta.bds.beta[2] = f64::INFINITY;
    assert_eq!(
        bad_beta.check().err().map(|e| e.field),
        Some("bds.beta[2]".to_string())
    );
}

proptest! {
    /// Both variants: finite, at least the 5 ns night floor, at most the floor plus the
    /// largest amplitude the coefficients allow, times the largest obliquity.
    #[test]
    fn delays_are_positive_and_bounded(
        lat in -89.9_f64..89.9,
        lon in -180.0_f64..360.0,
        az in 0.0_f64..360.0,
        el in -10.0_f64..90.0,
        t in 0.0_f64..604_800.0,
    ) {
        let cfg = IonoConfig::default();
        let (lat, lon, az, el) = (lat * D2R, lon * D2R, az * D2R, el * D2R);
        let g = gps_klobuchar_l1_s(&cfg.gps, lat, lon, az, el, t);
        let amp_max: f64 = cfg.gps.alpha.iter().map(|a| a.abs()).sum();
        prop_assert!(g.is_finite() && g >= 5e-9 && g <= 3.39 * (5e-9 + amp_max));
        let b = bds_klobuchar_b1i_s(&cfg.bds, lat, lon, az, el, t);
        let amp_max: f64 = cfg.bds.alpha.iter().map(|a| a.abs()).sum();
        prop_assert!(b.is_finite() && b >= 5e-9 && b <= 3.05 * (5e-9 + amp_max));
    }
}
