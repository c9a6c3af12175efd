//! The broadcast ionosphere models, as every GNSS user applies them: GPS Klobuchar
//! (IS-GPS-200 20.3.3.5.2.5) and the BeiDou variant (BDS-SIS-ICD-B1I 5.2.4.7). The
//! synthesiser puts them into the signal; a receiver removes them.

use std::f64::consts::PI;

/// Night-time (constant) vertical delay of both Klobuchar variants (s).
const NIGHT_DELAY_S: f64 = 5e-9;
/// Local time of the cosine peak (s): 14:00.
const PEAK_LOCAL_TIME_S: f64 = 50_400.0;
/// Smallest period of the cosine (s).
const MIN_PERIOD_S: f64 = 72_000.0;
/// Largest period of the BeiDou cosine (s), BDS-SIS-ICD-B1I 5.2.4.7.
const BDS_MAX_PERIOD_S: f64 = 172_800.0;
const SECONDS_PER_DAY: f64 = 86_400.0;
/// Earth radius and shell height of the BeiDou model (m), BDS-SIS-ICD-B1I 5.2.4.7.
const BDS_EARTH_RADIUS_M: f64 = 6_378_000.0;
const BDS_SHELL_HEIGHT_M: f64 = 375_000.0;
/// Broadcast Klobuchar coefficients: `alpha` (s, s/semicircle, s/semicircle^2,
/// s/semicircle^3) and `beta` (s, s/semicircle, ...), as broadcast and as in RINEX.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KlobucharCoeffs {
    pub alpha: [f64; 4],
    pub beta: [f64; 4],
}

fn cubic(c: &[f64; 4], x: f64) -> f64 {
    c[0] + x * (c[1] + x * (c[2] + x * c[3]))
}

/// GPS Klobuchar slant delay at L1 (s), IS-GPS-200 20.3.3.5.2.5 and figure 20-4.
///
/// Receiver geodetic latitude/longitude, satellite azimuth/elevation (rad); `gps_time_s`
/// is GPS time in seconds from any midnight (seconds of week are fine).
pub fn gps_klobuchar_l1_s(
    c: &KlobucharCoeffs,
    lat_rad: f64,
    lon_rad: f64,
    az_rad: f64,
    el_rad: f64,
    gps_time_s: f64,
) -> f64 {
    let el_sc = el_rad.max(0.0) / PI;
    let psi_sc = 0.0137 / (el_sc + 0.11) - 0.022;
    let lat_i_sc = (lat_rad / PI + psi_sc * az_rad.cos()).clamp(-0.416, 0.416);
    let lon_i_sc = lon_rad / PI + psi_sc * az_rad.sin() / (lat_i_sc * PI).cos();
    let lat_m_sc = lat_i_sc + 0.064 * ((lon_i_sc - 1.617) * PI).cos();
    let t_s = (4.32e4 * lon_i_sc + gps_time_s).rem_euclid(SECONDS_PER_DAY);
    let obliquity = 1.0 + 16.0 * (0.53 - el_sc).powi(3);
    let amplitude_s = cubic(&c.alpha, lat_m_sc).max(0.0);
    let period_s = cubic(&c.beta, lat_m_sc).max(MIN_PERIOD_S);
    let x = 2.0 * PI * (t_s - PEAK_LOCAL_TIME_S) / period_s;
    let vertical_s = if x.abs() < 1.57 {
        NIGHT_DELAY_S + amplitude_s * (1.0 - x * x / 2.0 + x.powi(4) / 24.0)
    } else {
        NIGHT_DELAY_S
    };
    obliquity * vertical_s
}

/// BeiDou Klobuchar slant delay at B1I (s), BDS-SIS-ICD-B1I-3.0 section 5.2.4.7: pierce
/// point on a 375 km shell over a 6378 km sphere, coefficients in the pierce point's
/// geographic |latitude| (semicircles), period clamped to [72000, 172800] s, cosine
/// (not its series), mapping `1 / sqrt(1 - (R cos E / (R + h))^2)`.
///
/// `bdt_s` is BeiDou time in seconds from any BDT midnight.
pub fn bds_klobuchar_b1i_s(
    c: &KlobucharCoeffs,
    lat_rad: f64,
    lon_rad: f64,
    az_rad: f64,
    el_rad: f64,
    bdt_s: f64,
) -> f64 {
    let el = el_rad.max(0.0);
    let k = BDS_EARTH_RADIUS_M / (BDS_EARTH_RADIUS_M + BDS_SHELL_HEIGHT_M) * el.cos();
    let psi = PI / 2.0 - el - k.asin();
    let lat_m = (lat_rad.sin() * psi.cos() + lat_rad.cos() * psi.sin() * az_rad.cos())
        .clamp(-1.0, 1.0)
        .asin();
    let lon_m = lon_rad
        + (psi.sin() * az_rad.sin() / lat_m.cos())
            .clamp(-1.0, 1.0)
            .asin();
    let t_s = (bdt_s + lon_m * 43_200.0 / PI).rem_euclid(SECONDS_PER_DAY);
    let lat_m_sc = (lat_m / PI).abs();
    let a2_s = cubic(&c.alpha, lat_m_sc).max(0.0);
    let a4_s = cubic(&c.beta, lat_m_sc).clamp(MIN_PERIOD_S, BDS_MAX_PERIOD_S);
    let vertical_s = if (t_s - PEAK_LOCAL_TIME_S).abs() < a4_s / 4.0 {
        NIGHT_DELAY_S + a2_s * (2.0 * PI * (t_s - PEAK_LOCAL_TIME_S) / a4_s).cos()
    } else {
        NIGHT_DELAY_S
    };
    vertical_s / (1.0 - k * k).sqrt()
}
