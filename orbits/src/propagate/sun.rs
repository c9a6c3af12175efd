//! Low-precision geocentric Sun position (Montenbruck & Gill, *Satellite Orbits*, 2000,
//! section 3.3.2, eq. 3.43-3.46), used for the diurnal bulge of the Harris-Priester
//! atmosphere. Accuracy about 0.1 % in distance and, in direction, about 1 arcmin near 2000
//! degrading by ~0.3 deg per century (the formula keeps the longitude of perigee fixed in
//! the J2000 frame; it moves 0.32 deg/century): 0.07 deg in 2023, far below what the
//! 30-deg-lagged, broad diurnal bulge is sensitive to.

use crate::Vec3;

/// Obliquity of the ecliptic at J2000 (rad), M&G eq. 3.45.
const OBLIQUITY_J2000_RAD: f64 = 23.439_291_11 * std::f64::consts::PI / 180.0;
/// Julian date of J2000 (2000-01-01 12:00 TT).
const JD_J2000: f64 = 2_451_545.0;

/// Geocentric Sun position (m) in the mean equator and equinox of J2000 at the Julian date
/// `jd_tt` (Terrestrial Time). The scenario ECI frame is taken as this frame (the
/// difference, precession since J2000, is below 0.5 deg until 2035: irrelevant for a
/// density bulge).
pub fn sun_position_eci_m(jd_tt: f64) -> Vec3 {
    let t_centuries = (jd_tt - JD_J2000) / 36_525.0;
    // Mean anomaly and ecliptic longitude (Omega + omega = 282.9400 deg), M&G eq. 3.43.
    let m = (357.5256_f64 + 35_999.049 * t_centuries).to_radians();
    let arcsec = (1.0_f64 / 3600.0).to_radians();
    let lambda =
        282.9400_f64.to_radians() + m + 6892.0 * arcsec * m.sin() + 72.0 * arcsec * (2.0 * m).sin();
    // Distance, M&G eq. 3.44.
    let r_m = (149.619 - 2.499 * m.cos() - 0.021 * (2.0 * m).cos()) * 1e9;
    // Ecliptic (latitude 0) to equatorial, M&G eq. 3.46.
    let (sin_l, cos_l) = lambda.sin_cos();
    let (sin_eps, cos_eps) = OBLIQUITY_J2000_RAD.sin_cos();
    Vec3::new(cos_l, sin_l * cos_eps, sin_l * sin_eps) * r_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::Epoch;

    fn jd_tt(epoch: Epoch) -> f64 {
        epoch.to_jde_tt_days()
    }

    /// Ecliptic longitude (J2000) of a J2000 equatorial vector.
    fn ecliptic_longitude_deg(r: &Vec3) -> f64 {
        let (s, c) = OBLIQUITY_J2000_RAD.sin_cos();
        let y_ecl = r.y * c + r.z * s;
        y_ecl.atan2(r.x).to_degrees()
    }

    #[test]
    fn march_equinox_2023() {
        // The March equinox of 2023 was 2023-03-20 21:24 UTC (US Naval Observatory): the
        // Sun's longitude of date is 0 there, so its J2000 longitude is minus the general
        // precession since J2000 (50.29 arcsec/yr x 23.22 yr = 0.324 deg). Tolerance: the
        // formula's fixed-perigee drift (0.07 deg in 2023) plus aberration and nutation
        // (< 0.01 deg).
        let epoch = Epoch::from_gregorian_utc(2023, 3, 20, 21, 24, 0, 0);
        let r = sun_position_eci_m(jd_tt(epoch));
        let lon = ecliptic_longitude_deg(&r);
        assert!((lon - -0.324).abs() < 0.09, "longitude {lon} deg");
        // Declination in J2000 is small (precession in declination ~0.13 deg).
        let dec = (r.z / r.norm()).asin().to_degrees();
        assert!(dec.abs() < 0.2, "declination {dec} deg");
    }

    #[test]
    fn perihelion_and_aphelion_distances() {
        // Perihelion 2023-01-04 16:17 UTC at 0.983 296 AU; aphelion 2023-07-06 20:07 UTC
        // at 1.016 681 AU (USNO); 1 AU = 149 597 870.7 km (IAU 2012).
        let au_m = 149_597_870_700.0;
        let peri = sun_position_eci_m(jd_tt(Epoch::from_gregorian_utc(2023, 1, 4, 16, 17, 0, 0)));
        let aph = sun_position_eci_m(jd_tt(Epoch::from_gregorian_utc(2023, 7, 6, 20, 7, 0, 0)));
        assert!(
            (peri.norm() / au_m - 0.983_296).abs() < 5e-4,
            "{}",
            peri.norm() / au_m
        );
        assert!(
            (aph.norm() / au_m - 1.016_681).abs() < 5e-4,
            "{}",
            aph.norm() / au_m
        );
    }

    #[test]
    fn june_solstice_declination() {
        // June solstice 2023-06-21 14:58 UTC: declination of date = +23.44 deg (J2000
        // differs by < 0.01 deg at RA 90 deg).
        let r = sun_position_eci_m(jd_tt(Epoch::from_gregorian_utc(2023, 6, 21, 14, 58, 0, 0)));
        let dec = (r.z / r.norm()).asin().to_degrees();
        assert!((dec - 23.44).abs() < 0.02, "declination {dec}");
    }
}
