//! `pvt.csv`: one row per antenna and epoch with a position fix, in the columns of
//! [`HEADER`]. `gps_week`/`tow_s` are the receiver's time tag of the epoch (GPST scale,
//! receiver clock); the fix's GPST is `tow_s - clock_bias_m / c`. Geodetic coordinates are
//! WGS-84; velocity and clock-drift fields are empty without a velocity fix, `isb_m`
//! (c x (BeiDou clock - GPS clock)) without both systems; `sats` counts the satellites
//! used and `excluded` lists those the residual test removed, separated by spaces.
//! `hpl_m`/`vpl_m` are the protection levels of the residual test (docs/raim.md) and
//! `integrity` its verdict (`available`, `unavailable`, `excluded`, `alarm`); all three are
//! empty when RAIM is off or has too few satellites.

use super::writing;
use anyhow::Context;
use hifitime::Epoch;
use skyforge_navigation::pvt::{Fix, IntegrityStatus, VelocityFix};
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::time::gpst_week_sow;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// The header line.
pub(super) const HEADER: &str = "antenna,gps_week,tow_s,x_m,y_m,z_m,lat_deg,lon_deg,height_m,clock_bias_m,isb_m,vx_mps,vy_mps,vz_mps,clock_drift_mps,gdop,pdop,hdop,vdop,sats,excluded,hpl_m,vpl_m,integrity";

/// `pvt.csv` being written.
#[derive(Debug)]
pub(super) struct PvtCsv {
    path: PathBuf,
    out: BufWriter<File>,
}

/// A text field, quoted when it holds a comma, a quote or a line break (RFC 4180).
fn text_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// An optional number with `decimals`, empty when absent.
fn optional(v: Option<f64>, decimals: usize) -> String {
    v.map_or(String::new(), |v| format!("{v:.decimals$}"))
}

impl PvtCsv {
    pub(super) fn create(path: &Path) -> anyhow::Result<Self> {
        let file = File::create(path).with_context(|| writing(path))?;
        let mut out = BufWriter::new(file);
        writeln!(out, "{HEADER}").with_context(|| writing(path))?;
        Ok(Self {
            path: path.to_path_buf(),
            out,
        })
    }

    /// The row of `antenna`'s fix at receiver time `t_rx`.
    pub(super) fn row(
        &mut self,
        antenna: &str,
        t_rx: Epoch,
        fix: &Fix,
        velocity: Option<&VelocityFix>,
    ) -> anyhow::Result<()> {
        let (week, tow_s) = gpst_week_sow(t_rx);
        let r = &fix.r_ecef_m;
        let g = ecef_to_geodetic(r);
        let v = |i: usize| optional(velocity.map(|v| v.v_ecef_mps[i]), 4);
        let excluded: Vec<String> = fix.excluded.iter().map(|s| s.to_string()).collect();
        let p = fix.protection.as_ref();
        let integrity = p.map_or("", |p| match p.status {
            IntegrityStatus::Available => "available",
            IntegrityStatus::Unavailable => "unavailable",
            IntegrityStatus::Excluded => "excluded",
            IntegrityStatus::Alarm => "alarm",
        });
        writeln!(
            self.out,
            "{},{week},{tow_s:.9},{:.4},{:.4},{:.4},{:.9},{:.9},{:.4},{:.4},{},{},{},{},{},{:.3},{:.3},{:.3},{:.3},{},{},{},{},{integrity}",
            text_field(antenna),
            r.x,
            r.y,
            r.z,
            g.lat_rad.to_degrees(),
            g.lon_rad.to_degrees(),
            g.h_m,
            fix.clock_bias_m,
            optional(fix.inter_system_bias_m, 4),
            v(0),
            v(1),
            v(2),
            optional(velocity.map(|v| v.clock_drift_mps), 4),
            fix.dop.gdop,
            fix.dop.pdop,
            fix.dop.hdop,
            fix.dop.vdop,
            fix.used.len(),
            excluded.join(" "),
            optional(p.map(|p| p.hpl_m), 3),
            optional(p.map(|p| p.vpl_m), 3),
        )
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
    use skyforge_navigation::pvt::Protection;
    use skyforge_orbits::Vec3;
    use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
    use skyforge_receiver::pipeline::fixtures::{bds, fix, gps};

    #[test]
    fn header_and_rows() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("pvt.csv");
        let mut csv = PvtCsv::create(&path).unwrap();
        // 2022-01-01 is a Saturday of GPS week 2190 (GPS week 0 began 1980-01-06).
        let t = Epoch::from_gregorian(2022, 1, 1, 12, 0, 30, 500_000_000, TimeScale::GPST);
        let site = Geodetic {
            lat_rad: 30f64.to_radians(),
            lon_rad: (-114f64).to_radians(),
            h_m: 50.0,
        };
        let mut f = fix(geodetic_to_ecef(&site), &[gps(7), gps(12), bds(19)]);
        f.inter_system_bias_m = Some(-12.5);
        f.excluded = vec![gps(30), bds(6)];
        csv.row("ant,1", t, &f, None).unwrap();
        let vel = VelocityFix {
            v_ecef_mps: Vec3::new(7000.0, -1.0, 0.5),
            clock_drift_mps: 0.125,
        };
        f.inter_system_bias_m = None;
        f.excluded.clear();
        f.protection = Some(Protection {
            hpl_m: 41.25,
            vpl_m: 60.5,
            threshold: 13.8,
            lambda_det: 40.0,
            slopes: Vec::new(),
            alarm: false,
            chi2_all: 1.0,
            r_all_ecef_m: f.r_ecef_m,
            status: IntegrityStatus::Unavailable,
        });
        csv.row("ant2", t, &f, Some(&vel)).unwrap();
        csv.finish().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0], HEADER);
        let n = HEADER.split(',').count();
        // Row 1: the quoted antenna name holds a comma.
        let row1: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(row1.len(), n + 1);
        assert_eq!(row1[0..2].join(","), "\"ant,1\"");
        let row1 = &row1[1..];
        assert_eq!(row1[1], "2190");
        // Saturday 12:00:30.5 = 6 days + 43230.5 s.
        assert_eq!(row1[2], "561630.500000000");
        let lat: f64 = row1[6].parse().unwrap();
        let lon: f64 = row1[7].parse().unwrap();
        let h: f64 = row1[8].parse().unwrap();
        assert!((lat - 30.0).abs() < 1e-8 && (lon + 114.0).abs() < 1e-8 && (h - 50.0).abs() < 1e-3);
        assert_eq!(row1[9], "1500.0000");
        assert_eq!(row1[10], "-12.5000");
        assert_eq!(&row1[11..15], ["", "", "", ""]);
        assert_eq!(&row1[15..19], ["2.500", "2.100", "1.200", "1.700"]);
        assert_eq!(row1[19], "3");
        assert_eq!(row1[20], "G30 C06");
        assert_eq!(&row1[21..24], ["", "", ""]);
        let row2: Vec<&str> = lines[2].split(',').collect();
        assert_eq!(row2.len(), n);
        assert_eq!(row2[10], "");
        assert_eq!(&row2[11..15], ["7000.0000", "-1.0000", "0.5000", "0.1250"]);
        assert_eq!(row2[20], "");
        assert_eq!(&row2[21..24], ["41.250", "60.500", "unavailable"]);
    }
}
