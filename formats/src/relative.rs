//! `relative.csv`, the relative truth of a scenario with several vehicles: every vehicle
//! after the first relative to the first (the target), in the target's orbit frame (book
//! eqs. 5-54/5-55, `orbits::frames::relative_in_target_frame`), at every geometry epoch
//! of their `truth.h5` files. [`write_relative_truth`] writes it beside the vehicles'
//! directories; `skyforge relnav` writes its estimates in the same layout
//! ([`write_relative_csv`], `relnav.csv`); [`read_relative_csv`] reads either back.
//! Columns in docs/scenario.md. Estimates of relnav's `double-difference` mode add
//! [`EXTRA_COLUMNS`] after them: the baseline in the Earth-fixed frame (free of the
//! target frame's orientation) and the double-difference ambiguities fixed and float; a
//! file without them (the truth, the other modes) keeps the eleven columns.

use crate::FormatError;
use crate::csv::{Fields, read_csv, require_columns};
use crate::truth::{PlatformSeries, TruthFile};
use hifitime::{Epoch, Unit};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_target_frame;
use std::io::Write;
use std::path::Path;

/// The file's name in a multi-vehicle run's directory.
pub const RELATIVE_CSV: &str = "relative.csv";
/// What `skyforge relnav` writes, in the same layout.
pub const RELNAV_CSV: &str = "relnav.csv";
/// Most geometry epochs read from a truth file (48 days at 1 Hz).
const MAX_ROWS: usize = 1 << 22;

const COLUMNS: [&str; 11] = [
    "time_gpst",
    "t_s",
    "vehicle",
    "target",
    "x_m",
    "y_m",
    "z_m",
    "vx_mps",
    "vy_mps",
    "vz_mps",
    "range_m",
];

/// The optional columns of a `double-difference` estimate (module docs).
pub const EXTRA_COLUMNS: [&str; 5] = ["bx_ecef_m", "by_ecef_m", "bz_ecef_m", "fixed", "float"];

/// The double-difference ambiguities of one estimate after its epoch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FixedFloat {
    pub fixed: usize,
    pub float: usize,
}

/// One row: a vehicle relative to the target at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct RelativeRow {
    /// The epoch (GPST); the file's `t_s` counts from the writer's start.
    pub time: Epoch,
    pub vehicle: String,
    pub target: String,
    /// Position in the target's orbit frame (x along-track, y negative orbit normal, z
    /// nadir; m).
    pub position_m: Vec3,
    /// Its rate in that rotating frame (m/s).
    pub velocity_mps: Vec3,
    /// The vehicle minus the target in the Earth-fixed frame (m), where estimated so.
    pub baseline_ecef_m: Option<Vec3>,
    /// The double-difference ambiguities, where resolved.
    pub ambiguities: Option<FixedFloat>,
}

/// A vehicle's name and its `truth.h5`.
pub type VehicleTruth<'a> = (&'a str, &'a Path);

/// Write `rows` (their `t_s` since `start`) as a `relative.csv` at `path`: the truth's
/// layout, also what `skyforge relnav` writes its estimates in.
pub fn write_relative_csv(
    path: &Path,
    start: Epoch,
    rows: &[RelativeRow],
) -> Result<(), FormatError> {
    let write_err = |e: std::io::Error| FormatError::file(path, format!("cannot write: {e}"));
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).map_err(write_err)?);
    let extra = (rows.iter()).any(|r| r.baseline_ecef_m.is_some() || r.ambiguities.is_some());
    let mut header = COLUMNS.join(",");
    if extra {
        header = format!("{header},{}", EXTRA_COLUMNS.join(","));
    }
    writeln!(w, "{header}").map_err(write_err)?;
    for r in rows {
        let (p, v) = (r.position_m, r.velocity_mps);
        write!(
            w,
            "{},{:.3},{},{},{:.4},{:.4},{:.4},{:.6},{:.6},{:.6},{:.4}",
            r.time,
            (r.time - start).to_seconds(),
            r.vehicle,
            r.target,
            p.x,
            p.y,
            p.z,
            v.x,
            v.y,
            v.z,
            p.norm()
        )
        .map_err(write_err)?;
        if extra {
            let b = r.baseline_ecef_m.map_or_else(
                || ",,".to_string(),
                |b| format!("{:.5},{:.5},{:.5}", b.x, b.y, b.z),
            );
            let a = r
                .ambiguities
                .map_or_else(|| ",".to_string(), |a| format!("{},{}", a.fixed, a.float));
            write!(w, ",{b},{a}").map_err(write_err)?;
        }
        writeln!(w).map_err(write_err)?;
    }
    w.flush().map_err(write_err)
}

/// Write `relative.csv` at `path`: each of `others` relative to `target`, at every epoch
/// of the target's truth (all runs of one scenario share the epochs; a mismatch is an
/// error naming both files).
pub fn write_relative_truth(
    path: &Path,
    target: VehicleTruth,
    others: &[VehicleTruth],
) -> Result<(), FormatError> {
    let open = |p: &Path| -> Result<(Epoch, PlatformSeries), FormatError> {
        let f = TruthFile::open(p)?;
        Ok((f.start_epoch()?, f.platform(MAX_ROWS)?))
    };
    let (start, t) = open(target.1)?;
    let earth = EarthRotation::at_origin(start);
    let eci = |s: &PlatformSeries, k: usize| {
        earth.ecef_to_eci(s.t_s[k], &s.r_ecef_m[k], &s.v_ecef_mps[k])
    };
    let mut rows = Vec::new();
    for (name, truth) in others {
        let (other_start, o) = open(truth)?;
        if other_start != start || o.t_s != t.t_s {
            return Err(FormatError::file(
                truth,
                format!(
                    "its epochs are not those of {} (one scenario's vehicles share them)",
                    target.1.display()
                ),
            ));
        }
        for k in 0..t.t_s.len() {
            let (rt, vt) = eci(&t, k);
            let (r, v) = eci(&o, k);
            let (position_m, velocity_mps) = relative_in_target_frame(&rt, &vt, &r, &v);
            rows.push(RelativeRow {
                time: start + Unit::Second * t.t_s[k],
                vehicle: name.to_string(),
                target: target.0.to_string(),
                position_m,
                velocity_mps,
                baseline_ecef_m: None,
                ambiguities: None,
            });
        }
    }
    write_relative_csv(path, start, &rows)
}

/// Read `relative.csv` at `path`: every row, in file order.
pub fn read_relative_csv(path: &Path) -> Result<Vec<RelativeRow>, FormatError> {
    let required: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
    let mut rows = Vec::new();
    let each = |header: &[&str], line: usize, text: &str| {
        let f = Fields::new(path, line, header, text)?;
        let num = |c: &str| f.number(c)?.ok_or_else(|| f.error(format!("{c} is empty")));
        let optional = |c: &str| -> Result<Option<f64>, FormatError> {
            if f.has(c) { f.number(c) } else { Ok(None) }
        };
        let baseline_ecef_m = match (
            optional("bx_ecef_m")?,
            optional("by_ecef_m")?,
            optional("bz_ecef_m")?,
        ) {
            (Some(x), Some(y), Some(z)) => Some(Vec3::new(x, y, z)),
            _ => None,
        };
        let count = |c: &str| -> Result<Option<usize>, FormatError> {
            match optional(c)? {
                Some(v) if v >= 0.0 && v.fract() == 0.0 && v <= 1e9 => Ok(Some(v as usize)),
                Some(v) => Err(f.error(format!("{c} = {v} is not a count"))),
                None => Ok(None),
            }
        };
        let ambiguities = match (count("fixed")?, count("float")?) {
            (Some(fixed), Some(float)) => Some(FixedFloat { fixed, float }),
            _ => None,
        };
        rows.push(RelativeRow {
            time: f.epoch("time_gpst")?,
            vehicle: f.text("vehicle")?.to_string(),
            target: f.text("target")?.to_string(),
            position_m: Vec3::new(num("x_m")?, num("y_m")?, num("z_m")?),
            velocity_mps: Vec3::new(num("vx_mps")?, num("vy_mps")?, num("vz_mps")?),
            baseline_ecef_m,
            ambiguities,
        });
        Ok(())
    };
    read_csv(path, |names| require_columns(path, names, &required), each)?;
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows written read back to the file's resolution (0.1 mm, 1 um/s).
    #[test]
    fn rows_read_back_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(RELNAV_CSV);
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, hifitime::TimeScale::GPST);
        let rows: Vec<RelativeRow> = (0..3_i32)
            .map(|k| RelativeRow {
                time: start + Unit::Second * f64::from(k),
                vehicle: "chaser".into(),
                target: "target".into(),
                position_m: Vec3::new(-32_000.123_4 + f64::from(k), 0.5, 76.25),
                velocity_mps: Vec3::new(0.001_234, -0.000_5, 0.361_5),
                baseline_ecef_m: None,
                ambiguities: None,
            })
            .collect();
        write_relative_csv(&path, start, &rows).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(!text.contains("bx_ecef_m"), "{text}");
        let read = read_relative_csv(&path).unwrap();
        assert_eq!(read.len(), 3);
        assert!(
            read.iter()
                .all(|r| r.baseline_ecef_m.is_none() && r.ambiguities.is_none())
        );
        for (r, w) in read.iter().zip(&rows) {
            assert_eq!(
                (r.time, &r.vehicle, &r.target),
                (w.time, &w.vehicle, &w.target)
            );
            assert!((r.position_m - w.position_m).norm() < 1e-4);
            assert!((r.velocity_mps - w.velocity_mps).norm() < 1e-6);
        }
        // The double-difference columns: written when a row has them, read back.
        let mut extra = rows.clone();
        extra[1].baseline_ecef_m = Some(Vec3::new(-150_000.123_45, 98_765.432_1, 1.0));
        extra[1].ambiguities = Some(FixedFloat {
            fixed: 20,
            float: 2,
        });
        write_relative_csv(&path, start, &extra).unwrap();
        let read = read_relative_csv(&path).unwrap();
        assert_eq!(read[0].baseline_ecef_m, None);
        let b = read[1].baseline_ecef_m.unwrap();
        assert!((b - extra[1].baseline_ecef_m.unwrap()).norm() < 1e-5);
        assert_eq!(read[1].ambiguities, extra[1].ambiguities);
        std::fs::write(&path, "time_gpst,t_s\n").unwrap();
        let e = read_relative_csv(&path).unwrap_err().to_string();
        assert!(e.contains("no column vehicle"), "{e}");
    }
}
