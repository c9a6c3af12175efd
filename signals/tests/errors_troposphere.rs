//! Saastamoinen troposphere with the standard atmosphere and Chao mapping.

use proptest::prelude::*;
use skyforge_signals::errors::{
    TROPOSPHERE_CEILING_M, TropoConfig, TropoModel, chao_mapping, saastamoinen_zenith_m,
    standard_atmosphere,
};

const D2R: f64 = std::f64::consts::PI / 180.0;

/// Sea level, 45 deg: hydrostatic 0.0022768 * 1013.25 = 2.3070 m (the latitude term
/// vanishes at 45 deg); wet about 0.10 m at 18 deg C and 50 % humidity; total 2.3-2.45 m.
#[test]
fn zenith_delay_at_sea_level() {
    let atm = standard_atmosphere(0.0, 0.5);
    assert!((atm.pressure_hpa - 1013.25).abs() < 1e-9);
    assert!((atm.temperature_k - 291.15).abs() < 1e-9);
    // Saturation pressure at 18 deg C is 20.6 hPa (WMO tables), so e = 10.3 hPa.
    assert!(
        (atm.water_vapour_hpa - 10.32).abs() < 0.05,
        "{}",
        atm.water_vapour_hpa
    );
    let (zhd, zwd) = saastamoinen_zenith_m(&atm, 45.0 * D2R, 0.0);
    assert!((zhd - 2.3070).abs() < 5e-4, "{zhd}");
    assert!((0.08..0.12).contains(&zwd), "{zwd}");
    let zenith = TropoConfig::default().delay_m(45.0 * D2R, 0.0, 90.0 * D2R);
    assert!((2.3..2.45).contains(&zenith), "{zenith}");
    // A dry atmosphere leaves the hydrostatic part only.
    let dry = TropoConfig {
        sea_level_relative_humidity: 0.0,
        ..TropoConfig::default()
    };
    assert!((dry.delay_m(45.0 * D2R, 0.0, 90.0 * D2R) - zhd).abs() < 1e-12);
}

/// 5 deg elevation: about ten times the zenith value (1/sin 5 deg = 11.5; ray-traced
/// mapping functions give about 10.2), i.e. some 25 m.
#[test]
fn low_elevation_delay_is_about_25_m() {
    let d5 = TropoConfig::default().delay_m(45.0 * D2R, 0.0, 5.0 * D2R);
    assert!((22.0..28.0).contains(&d5), "{d5}");
    let (m_dry, m_wet) = chao_mapping(5.0 * D2R);
    assert!(
        (9.8..10.6).contains(&m_dry) && (10.0..11.5).contains(&m_wet),
        "{m_dry} {m_wet}"
    );
    let (z_dry, z_wet) = chao_mapping(90.0 * D2R);
    // At the zenith the Chao functions are 1 / (1 + a / b) with tan E -> infinity: 1.
    assert!((z_dry - 1.0).abs() < 1e-12 && (z_wet - 1.0).abs() < 1e-12);
}

/// Pressure at 5.5 km is about half the sea-level value (standard-atmosphere fact).
#[test]
fn standard_atmosphere_halves_pressure_near_5_5_km() {
    let p = standard_atmosphere(5_500.0, 0.5).pressure_hpa;
    assert!((490.0..520.0).contains(&p), "{p}");
    // Continuous across the tropopause.
    let below = standard_atmosphere(11_000.0 - 1e-6, 0.5).pressure_hpa;
    let above = standard_atmosphere(11_000.0 + 1e-6, 0.5).pressure_hpa;
    assert!((below - above).abs() < 1e-6);
}

#[test]
fn zero_above_the_ceiling_or_when_off() {
    let cfg = TropoConfig::default();
    assert_eq!(cfg.delay_m(0.3, TROPOSPHERE_CEILING_M + 1.0, 0.2), 0.0);
    assert_eq!(cfg.delay_m(0.3, 500e3, 0.2), 0.0);
    assert!(cfg.delay_m(0.3, TROPOSPHERE_CEILING_M - 1.0, 0.2) < 0.01);
    let off = TropoConfig {
        model: TropoModel::Off,
        ..TropoConfig::default()
    };
    assert_eq!(off.delay_m(0.3, 0.0, 0.2), 0.0);
}

#[test]
fn config_check_rejects_bad_humidity() {
    assert!(TropoConfig::default().check().is_ok());
    let bad = TropoConfig {
        sea_level_relative_humidity: 1.2,
        ..TropoConfig::default()
    };
    assert_eq!(
        bad.check().err().map(|e| e.field),
        Some("sea_level_relative_humidity".to_string())
    );
}

proptest! {
    #[test]
    fn delay_decreases_with_elevation_and_height(
        lat in -90.0_f64..90.0,
        h in -400.0_f64..45_000.0,
        dh in 1.0_f64..5_000.0,
        el in 0.0_f64..89.0,
        de in 0.1_f64..10.0,
    ) {
        let cfg = TropoConfig::default();
        let lat = lat * D2R;
        let d = cfg.delay_m(lat, h, el * D2R);
        prop_assert!(d.is_finite() && d > 0.0);
        prop_assert!(cfg.delay_m(lat, h, (el + de).min(90.0) * D2R) <= d);
        prop_assert!(cfg.delay_m(lat, h + dh, el * D2R) < d);
    }
}
