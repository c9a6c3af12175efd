//! NMEA 0183 sentences of a fix: GGA (position), GSA (DOP and satellites), RMC (position,
//! speed, course). Heights are ellipsoidal: the receiver carries no geoid model, so GGA
//! gives the WGS-84 height as "altitude" with a geoid separation of 0.

use super::{Fix, VelocityFix};
use skyforge_orbits::ephemeris::System;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::ecef_to_geodetic;

/// Knots per m/s.
const KNOTS_PER_MPS: f64 = 3600.0 / 1852.0;

/// `$<body>*<checksum>`: the XOR of the body's bytes in two hex digits.
pub fn sentence(body: &str) -> String {
    let sum = body.bytes().fold(0u8, |acc, b| acc ^ b);
    format!("${body}*{sum:02X}")
}

/// `ddmm.mmmmm` and hemisphere of an angle (deg) with `deg_digits` degree digits.
fn angle(deg: f64, deg_digits: usize, pos: char, neg: char) -> (String, char) {
    let hemi = if deg < 0.0 { neg } else { pos };
    let a = deg.abs();
    let mut d = a.trunc();
    let mut m = (a - d) * 60.0;
    // Rounding to 5 decimals may carry into the degrees.
    if (m * 1e5).round() >= 60.0 * 1e5 {
        d += 1.0;
        m = 0.0;
    }
    (format!("{:0w$}{:08.5}", d as u32, m, w = deg_digits), hemi)
}

/// Talker of a fix: `GP` for GPS only, `BD` for BeiDou only, `GN` for both.
fn talker(fix: &Fix) -> &'static str {
    let has = |s: System| fix.used.iter().any(|u| u.0.system == s);
    match (has(System::Gps), has(System::Beidou)) {
        (true, false) => "GP",
        (false, true) => "BD",
        _ => "GN",
    }
}

/// UTC time of day of the fix as `hhmmss.ss`, from seconds of the UTC day.
fn hms(utc_seconds_of_day: f64) -> String {
    let cs = (utc_seconds_of_day * 100.0).round() as u64 % 8_640_000;
    format!(
        "{:02}{:02}{:02}.{:02}",
        cs / 360_000,
        cs / 6000 % 60,
        cs / 100 % 60,
        cs % 100
    )
}

/// GGA: time (UTC seconds of day), position, fix quality 1 (GNSS), satellites, HDOP, height.
pub fn gga(fix: &Fix, utc_seconds_of_day: f64) -> String {
    let g = ecef_to_geodetic(&fix.r_ecef_m);
    let (lat, ns) = angle(g.lat_rad.to_degrees(), 2, 'N', 'S');
    let (lon, ew) = angle(g.lon_rad.to_degrees(), 3, 'E', 'W');
    sentence(&format!(
        "{}GGA,{},{lat},{ns},{lon},{ew},1,{:02},{:.1},{:.3},M,0.0,M,,",
        talker(fix),
        hms(utc_seconds_of_day),
        fix.used.len(),
        fix.dop.hdop,
        g.h_m
    ))
}

/// GSA: automatic 3D fix, the PRNs used (at most 12 fields), PDOP, HDOP, VDOP.
pub fn gsa(fix: &Fix) -> String {
    let mut prns: Vec<String> = fix.used.iter().map(|u| u.0.prn.to_string()).collect();
    prns.truncate(12);
    prns.resize(12, String::new());
    sentence(&format!(
        "{}GSA,A,3,{},{:.1},{:.1},{:.1}",
        talker(fix),
        prns.join(","),
        fix.dop.pdop,
        fix.dop.hdop,
        fix.dop.vdop
    ))
}

/// RMC: time, status A, position, speed over ground (knots), course (deg true), date
/// `ddmmyy`.
pub fn rmc(fix: &Fix, vel: &VelocityFix, utc_seconds_of_day: f64, ddmmyy: &str) -> String {
    let g = ecef_to_geodetic(&fix.r_ecef_m);
    let (lat, ns) = angle(g.lat_rad.to_degrees(), 2, 'N', 'S');
    let (lon, ew) = angle(g.lon_rad.to_degrees(), 3, 'E', 'W');
    let v_ned = c_ecef_ned(g.lat_rad, g.lon_rad) * vel.v_ecef_mps;
    let speed_kn = v_ned.x.hypot(v_ned.y) * KNOTS_PER_MPS;
    let course = v_ned.y.atan2(v_ned.x).to_degrees().rem_euclid(360.0);
    sentence(&format!(
        "{}RMC,{},A,{lat},{ns},{lon},{ew},{speed_kn:.2},{course:.1},{ddmmyy},,,A",
        talker(fix),
        hms(utc_seconds_of_day)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checksum_of_the_textbook_sentence() {
        // The GGA example of the NMEA 0183 literature, checksum 47.
        assert_eq!(
            sentence("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"),
            "$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47"
        );
    }

    #[test]
    fn angles_and_times() {
        assert_eq!(angle(48.1173, 2, 'N', 'S'), ("4807.03800".into(), 'N'));
        assert_eq!(
            angle(-11.516_666_666_7, 3, 'E', 'W'),
            ("01131.00000".into(), 'W')
        );
        assert_eq!(angle(29.999_999_999, 2, 'N', 'S').0, "3000.00000");
        assert_eq!(hms(12.0 * 3600.0 + 35.0 * 60.0 + 19.256), "123519.26");
    }
}
