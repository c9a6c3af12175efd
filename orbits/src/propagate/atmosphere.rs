//! Atmospheric density models and the height they are evaluated at.
//!
//! Height: geodetic height above the WGS-84 ellipsoid. It depends only on the distance from
//! the rotation axis and on `z`, which the Earth-rotation-only ECI <-> ECEF transformation
//! leaves unchanged, so it is computed directly from the ECI position.

use crate::Vec3;
use crate::constants::{WGS84_A_M, WGS84_F};

/// Piecewise exponential atmosphere, Vallado, *Fundamentals of Astrodynamics and
/// Applications* (4th ed.), table 8-4: base height (km), nominal density (kg/m^3), scale
/// height (km). The profile is continuous at the base heights.
const EXPONENTIAL_TABLE: [(f64, f64, f64); 28] = [
    (0.0, 1.225, 7.249),
    (25.0, 3.899e-2, 6.349),
    (30.0, 1.774e-2, 6.682),
    (40.0, 3.972e-3, 7.554),
    (50.0, 1.057e-3, 8.382),
    (60.0, 3.206e-4, 7.714),
    (70.0, 8.770e-5, 6.549),
    (80.0, 1.905e-5, 5.799),
    (90.0, 3.396e-6, 5.382),
    (100.0, 5.297e-7, 5.877),
    (110.0, 9.661e-8, 7.263),
    (120.0, 2.438e-8, 9.473),
    (130.0, 8.484e-9, 12.636),
    (140.0, 3.845e-9, 16.149),
    (150.0, 2.070e-9, 22.523),
    (180.0, 5.464e-10, 29.740),
    (200.0, 2.789e-10, 37.105),
    (250.0, 7.248e-11, 45.546),
    (300.0, 2.418e-11, 53.628),
    (350.0, 9.518e-12, 53.298),
    (400.0, 3.725e-12, 58.515),
    (450.0, 1.585e-12, 60.828),
    (500.0, 6.967e-13, 63.822),
    (600.0, 1.454e-13, 71.835),
    (700.0, 3.614e-14, 88.667),
    (800.0, 1.170e-14, 124.64),
    (900.0, 5.245e-15, 181.05),
    (1000.0, 3.019e-15, 268.00),
];

/// Harris-Priester densities for mean solar activity, Montenbruck & Gill, *Satellite
/// Orbits* (2000), table 3.8: height (km), minimum (antapex) and maximum (apex of the
/// diurnal bulge) density in g/km^3 (= 1e-12 kg/m^3).
const HARRIS_PRIESTER_TABLE: [(f64, f64, f64); 50] = [
    (100.0, 497_400.0, 497_400.0),
    (120.0, 24_900.0, 24_900.0),
    (130.0, 8377.0, 8710.0),
    (140.0, 3899.0, 4059.0),
    (150.0, 2122.0, 2215.0),
    (160.0, 1263.0, 1344.0),
    (170.0, 800.8, 875.8),
    (180.0, 528.3, 601.0),
    (190.0, 361.7, 429.7),
    (200.0, 255.7, 316.2),
    (210.0, 183.9, 239.6),
    (220.0, 134.1, 185.3),
    (230.0, 99.49, 145.5),
    (240.0, 74.88, 115.7),
    (250.0, 57.09, 93.08),
    (260.0, 44.03, 75.55),
    (270.0, 34.30, 61.82),
    (280.0, 26.97, 50.95),
    (290.0, 21.39, 42.26),
    (300.0, 17.08, 35.26),
    (320.0, 10.99, 25.11),
    (340.0, 7.214, 18.19),
    (360.0, 4.824, 13.37),
    (380.0, 3.274, 9.955),
    (400.0, 2.249, 7.492),
    (420.0, 1.558, 5.684),
    (440.0, 1.091, 4.355),
    (460.0, 0.7701, 3.362),
    (480.0, 0.5474, 2.612),
    (500.0, 0.3916, 2.042),
    (520.0, 0.2819, 1.605),
    (540.0, 0.2042, 1.267),
    (560.0, 0.1488, 1.005),
    (580.0, 0.1092, 0.7997),
    (600.0, 0.08070, 0.6390),
    (620.0, 0.06012, 0.5123),
    (640.0, 0.04519, 0.4121),
    (660.0, 0.03430, 0.3325),
    (680.0, 0.02632, 0.2691),
    (700.0, 0.02043, 0.2185),
    (720.0, 0.01607, 0.1779),
    (740.0, 0.01281, 0.1452),
    (760.0, 0.01036, 0.1190),
    (780.0, 0.008496, 0.09776),
    (800.0, 0.007069, 0.08059),
    (840.0, 0.004680, 0.05741),
    (880.0, 0.003200, 0.04210),
    (920.0, 0.002210, 0.03130),
    (960.0, 0.001560, 0.02360),
    (1000.0, 0.001150, 0.01810),
];

/// Right-ascension lag of the diurnal bulge apex behind the Sun (M&G section 3.5.2: 30 deg).
const BULGE_LAG_RAD: f64 = std::f64::consts::PI / 6.0;

/// Piecewise exponential density (kg/m^3) at geodetic height `h_m` (Vallado table 8-4).
/// Below 0 m the first layer and above 1000 km the last layer are extrapolated.
pub fn exponential_density_kg_m3(h_m: f64) -> f64 {
    let h_km = h_m * 1e-3;
    let layer = EXPONENTIAL_TABLE.partition_point(|&(base, _, _)| base <= h_km);
    let (base_km, rho0, scale_km) = EXPONENTIAL_TABLE[layer.saturating_sub(1)];
    rho0 * (-(h_km - base_km) / scale_km).exp()
}

/// The Harris-Priester density model (M&G section 3.5.2) for mean solar activity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HarrisPriester {
    /// Exponent `n` of `cos^n(psi / 2)`: M&G recommend 2 for low-inclination and 6 for
    /// polar orbits.
    pub exponent: f64,
}

impl HarrisPriester {
    /// The exponent for an orbit of inclination `i_rad`: linear in the inclination from
    /// n = 2 (equatorial) to n = 6 (polar), symmetric for retrograde orbits. This blend of
    /// the two values M&G recommend is a SkyForge choice.
    pub fn for_inclination(i_rad: f64) -> Self {
        let i_deg = i_rad.to_degrees().clamp(0.0, 180.0);
        let from_equator_deg = i_deg.min(180.0 - i_deg);
        Self {
            exponent: 2.0 + 4.0 * from_equator_deg / 90.0,
        }
    }

    /// Density (kg/m^3) at geodetic height `h_m` and ECI position `r_eci_m`, with the Sun
    /// at `sun_eci_m`. Between table heights the minimum and maximum densities are
    /// interpolated exponentially (M&G eq. 3.100); outside 100..1000 km the nearest
    /// layer's exponential is extrapolated (M&G set the density to 0 there; extrapolating
    /// keeps the force continuous; below 100 km the satellite is decaying anyway).
    pub fn density_kg_m3(&self, h_m: f64, r_eci_m: &Vec3, sun_eci_m: &Vec3) -> f64 {
        let h_km = h_m * 1e-3;
        let upper = HARRIS_PRIESTER_TABLE
            .partition_point(|&(base, _, _)| base <= h_km)
            .clamp(1, HARRIS_PRIESTER_TABLE.len() - 1);
        let (h0, min0, max0) = HARRIS_PRIESTER_TABLE[upper - 1];
        let (h1, min1, max1) = HARRIS_PRIESTER_TABLE[upper];
        let interpolate = |rho0: f64, rho1: f64| {
            let scale_km = (h0 - h1) / (rho1 / rho0).ln();
            rho0 * ((h0 - h_km) / scale_km).exp()
        };
        let rho_min = interpolate(min0, min1);
        let rho_max = interpolate(max0, max1);
        // Apex of the bulge: Sun direction turned by the lag in right ascension (eq. 3.103).
        let ra_sun = sun_eci_m.y.atan2(sun_eci_m.x);
        let dec_sun = (sun_eci_m.z / sun_eci_m.norm()).asin();
        let (sin_ra, cos_ra) = (ra_sun + BULGE_LAG_RAD).sin_cos();
        let apex = Vec3::new(
            dec_sun.cos() * cos_ra,
            dec_sun.cos() * sin_ra,
            dec_sun.sin(),
        );
        // cos^n(psi/2) = (1/2 + cos(psi)/2)^(n/2), eq. 3.104.
        let cos_psi = r_eci_m.dot(&apex) / r_eci_m.norm();
        let bulge = (0.5 + 0.5 * cos_psi).max(0.0).powf(0.5 * self.exponent);
        (rho_min + (rho_max - rho_min) * bulge) * 1e-12
    }
}

/// Height above the WGS-84 ellipsoid (m) of an ECI or ECEF position (Bowring's formula
/// with one iteration; error below 1 mm for heights up to a few thousand km).
pub fn geodetic_height_m(r_m: &Vec3) -> f64 {
    let a = WGS84_A_M;
    let b = a * (1.0 - WGS84_F);
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let ep2 = e2 / (1.0 - e2);
    let p = r_m.x.hypot(r_m.y);
    let z = r_m.z;
    // Parametric latitude guess, then the geodetic latitude (Bowring 1976).
    let beta = (a * z).atan2(b * p);
    let (sb, cb) = beta.sin_cos();
    let lat = (z + ep2 * b * sb.powi(3)).atan2(p - e2 * a * cb.powi(3));
    let beta = (b * lat.sin()).atan2(a * lat.cos());
    let (sb, cb) = beta.sin_cos();
    let lat = (z + ep2 * b * sb.powi(3)).atan2(p - e2 * a * cb.powi(3));
    let (s, c) = lat.sin_cos();
    // Height from the foot point, well conditioned at any latitude.
    p * c + z * s - a * (1.0 - e2 * s * s).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_table_is_continuous_at_its_base_heights() {
        // Vallado built the table so each layer's exponential meets the next base value:
        // an independent check of the transcribed numbers.
        for pair in EXPONENTIAL_TABLE.windows(2) {
            let (h0, rho0, scale) = pair[0];
            let (h1, rho1, _) = pair[1];
            let extrapolated = rho0 * (-(h1 - h0) / scale).exp();
            assert!(
                (extrapolated / rho1 - 1.0).abs() < 0.02,
                "layer {h0} km: {extrapolated:e} vs {rho1:e}"
            );
        }
    }

    #[test]
    fn exponential_density_at_table_heights_and_between() {
        assert_eq!(exponential_density_kg_m3(400e3), 3.725e-12);
        assert_eq!(exponential_density_kg_m3(0.0), 1.225);
        let rho_425 = exponential_density_kg_m3(425e3);
        let expected = 3.725e-12 * (-25.0_f64 / 58.515).exp();
        assert!((rho_425 / expected - 1.0).abs() < 1e-12);
        assert!(exponential_density_kg_m3(1500e3) < 3.019e-15);
        assert!(exponential_density_kg_m3(-1e3) > 1.225);
    }

    #[test]
    fn harris_priester_table_is_ordered() {
        for pair in HARRIS_PRIESTER_TABLE.windows(2) {
            assert!(pair[1].0 > pair[0].0);
            assert!(pair[1].1 < pair[0].1 && pair[1].2 < pair[0].2);
        }
        for &(_, rho_min, rho_max) in &HARRIS_PRIESTER_TABLE {
            assert!(rho_max >= rho_min);
        }
    }

    #[test]
    fn harris_priester_bulge_limits() {
        let hp = HarrisPriester { exponent: 2.0 };
        let sun = Vec3::new(1.5e11, 0.0, 0.0);
        let h = 400e3;
        // At the apex (Sun direction + 30 deg in RA) the density is the maximum, at the
        // antapex the minimum (M&G table 3.8, 400 km: 2.249 / 7.492 g/km^3).
        let (s, c) = BULGE_LAG_RAD.sin_cos();
        let apex = Vec3::new(c, s, 0.0) * 6.778e6;
        let rho_apex = hp.density_kg_m3(h, &apex, &sun);
        let rho_anti = hp.density_kg_m3(h, &-apex, &sun);
        assert!((rho_apex / 7.492e-12 - 1.0).abs() < 1e-9, "{rho_apex:e}");
        assert!((rho_anti / 2.249e-12 - 1.0).abs() < 1e-9, "{rho_anti:e}");
        // 90 deg from the apex with n = 2: cos^2(45 deg) = 1/2 of the way.
        let side = Vec3::new(0.0, 0.0, 6.778e6);
        let rho_side = hp.density_kg_m3(h, &side, &sun);
        assert!((rho_side / (0.5 * (2.249e-12 + 7.492e-12)) - 1.0).abs() < 1e-9);
        // Between table heights: exponential interpolation of the minimum.
        let rho_410 = hp.density_kg_m3(410e3, &-apex, &sun);
        assert!((rho_410 / (2.249e-12_f64 * 1.558e-12).sqrt() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn harris_priester_exponent_follows_inclination() {
        assert_eq!(HarrisPriester::for_inclination(0.0).exponent, 2.0);
        assert_eq!(
            HarrisPriester::for_inclination(90f64.to_radians()).exponent,
            6.0
        );
        let retro = HarrisPriester::for_inclination(135f64.to_radians()).exponent;
        assert!((retro - 4.0).abs() < 1e-12);
    }

    #[test]
    fn geodetic_height_matches_forward_formula() {
        // Forward WGS-84 formula (geodetic -> ECEF) as the oracle.
        let a = WGS84_A_M;
        let e2 = WGS84_F * (2.0 - WGS84_F);
        for lat_deg in [-90.0, -60.0, -34.9, 0.0, 10.0, 45.0, 80.0, 89.999, 90.0] {
            for h in [0.0, 80e3, 400e3, 600e3, 2000e3, 20_000e3] {
                let lat: f64 = f64::to_radians(lat_deg);
                let n = a / (1.0 - e2 * lat.sin().powi(2)).sqrt();
                let r = Vec3::new(
                    (n + h) * lat.cos() * 0.6,
                    (n + h) * lat.cos() * 0.8,
                    (n * (1.0 - e2) + h) * lat.sin(),
                );
                let got = geodetic_height_m(&r);
                assert!((got - h).abs() < 1e-3, "lat {lat_deg} h {h}: {got}");
            }
        }
    }
}
