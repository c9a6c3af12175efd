//! `<antenna>.nmea`: NMEA 0183 GGA, GSA and RMC sentences of every fix, each line ended by
//! CR LF. The time is the fix's UTC: receiver time minus the clock bias (GPST), converted
//! to UTC with hifitime's leap-second table. RMC needs a velocity: an epoch whose fix has
//! none gets GGA and GSA only.

use super::writing;
use anyhow::Context;
use hifitime::{Duration, Epoch};
use skyforge_navigation::pvt::{Fix, VelocityFix};
use skyforge_navigation::pvt::{gga, gsa, rmc};
use skyforge_orbits::constants::C_MPS;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// One antenna's NMEA log.
#[derive(Debug)]
pub(super) struct NmeaLog {
    path: PathBuf,
    out: BufWriter<File>,
}

/// UTC seconds of the day and `ddmmyy` date of a GPST epoch.
fn utc_of_day(t: Epoch) -> (f64, String) {
    let (y, mo, d, h, mi, s, ns) = t.to_gregorian_utc();
    let seconds =
        f64::from(h) * 3600.0 + f64::from(mi) * 60.0 + f64::from(s) + f64::from(ns) * 1e-9;
    (seconds, format!("{d:02}{mo:02}{:02}", y.rem_euclid(100)))
}

impl NmeaLog {
    pub(super) fn create(path: &Path) -> anyhow::Result<Self> {
        let file = File::create(path).with_context(|| writing(path))?;
        Ok(Self {
            path: path.to_path_buf(),
            out: BufWriter::new(file),
        })
    }

    /// The sentences of `fix` at receiver time `t_rx`.
    pub(super) fn write(
        &mut self,
        t_rx: Epoch,
        fix: &Fix,
        velocity: Option<&VelocityFix>,
    ) -> anyhow::Result<()> {
        let t_fix = t_rx - Duration::from_seconds(fix.clock_bias_m / C_MPS);
        let (sod, ddmmyy) = utc_of_day(t_fix);
        let mut text = format!("{}\r\n{}\r\n", gga(fix, sod), gsa(fix));
        if let Some(v) = velocity {
            text.push_str(&rmc(fix, v, sod, &ddmmyy));
            text.push_str("\r\n");
        }
        self.out
            .write_all(text.as_bytes())
            .with_context(|| writing(&self.path))
    }

    pub(super) fn finish(mut self) -> anyhow::Result<()> {
        self.out.flush().with_context(|| writing(&self.path))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::TimeScale;
    use skyforge_orbits::Vec3;
    use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
    use skyforge_receiver::pipeline::fixtures::{fix, gps};

    /// Check a sentence's checksum: the XOR of the bytes between `$` and `*` (NMEA 0183).
    fn checksum_ok(line: &str) -> bool {
        let Some(body) = line.strip_prefix('$') else {
            return false;
        };
        let Some((body, sum)) = body.split_once('*') else {
            return false;
        };
        let mut x = 0u8;
        for b in body.bytes() {
            x ^= b;
        }
        u8::from_str_radix(sum, 16) == Ok(x)
    }

    #[test]
    fn sentences_carry_utc_and_valid_checksums() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ant1.nmea");
        let mut log = NmeaLog::create(&path).unwrap();
        let site = geodetic_to_ecef(&Geodetic {
            lat_rad: 48.1173f64.to_radians(),
            lon_rad: 11.516_666_666_7f64.to_radians(),
            h_m: 545.4,
        });
        let mut f = fix(site, &[gps(7), gps(12), gps(19), gps(22)]);
        // GPS - UTC = 18 s from 2017-01-01 on (IERS Bulletin C): 00:00:30 GPST is
        // 00:00:12 UTC; the clock bias (1 ms late) is taken off first.
        f.clock_bias_m = 1e-3 * C_MPS;
        let t = Epoch::from_gregorian(2022, 1, 1, 0, 0, 30, 1_000_000, TimeScale::GPST);
        let vel = VelocityFix {
            v_ecef_mps: Vec3::zeros(),
            clock_drift_mps: 0.0,
        };
        log.write(t, &f, Some(&vel)).unwrap();
        // 00:00:10 GPST is 23:59:52 UTC of the previous day and year.
        let t = Epoch::from_gregorian(2022, 1, 1, 0, 0, 10, 1_000_000, TimeScale::GPST);
        log.write(t, &f, Some(&vel)).unwrap();
        log.write(t, &f, None).unwrap();
        log.finish().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.ends_with("\r\n"));
        let lines: Vec<&str> = text.split_terminator("\r\n").collect();
        assert_eq!(lines.len(), 8);
        for l in &lines {
            assert!(checksum_ok(l), "{l}");
        }
        let kinds: Vec<&str> = lines.iter().map(|l| &l[3..6]).collect();
        assert_eq!(
            kinds,
            ["GGA", "GSA", "RMC", "GGA", "GSA", "RMC", "GGA", "GSA"]
        );
        assert!(lines[0].starts_with("$GPGGA,000012.00,4807.03800,N,01131.00000,E,1,04,"));
        assert!(lines[2].starts_with("$GPRMC,000012.00,A,4807.03800,N,01131.00000,E,"));
        assert!(lines[2].contains(",010122,"), "{}", lines[2]);
        assert!(lines[3].starts_with("$GPGGA,235952.00,"));
        assert!(lines[5].contains(",311221,"), "{}", lines[5]);
    }
}
