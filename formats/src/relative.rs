//! `relative.csv`, the relative truth of a scenario with several vehicles: every vehicle
//! after the first relative to the first (the target), in the target's orbit frame (book
//! eqs. 5-54/5-55, `orbits::frames::relative_in_target_frame`), at every geometry epoch
//! of their `truth.h5` files. [`write_relative_truth`] writes it beside the vehicles'
//! directories; [`read_relative_csv`] reads it back (for relative navigation's
//! validation). Columns in docs/scenario.md.

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

/// One row: a vehicle relative to the target at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct RelativeRow {
    pub t_s: f64,
    pub vehicle: String,
    pub target: String,
    /// Position in the target's orbit frame (x along-track, y negative orbit normal, z
    /// nadir; m).
    pub position_m: Vec3,
    /// Its rate in that rotating frame (m/s).
    pub velocity_mps: Vec3,
}

/// A vehicle's name and its `truth.h5`.
pub type VehicleTruth<'a> = (&'a str, &'a Path);

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
    let write_err = |e: std::io::Error| FormatError::file(path, format!("cannot write: {e}"));
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).map_err(write_err)?);
    writeln!(w, "{}", COLUMNS.join(",")).map_err(write_err)?;
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
            let (rho, rho_dot) = relative_in_target_frame(&rt, &vt, &r, &v);
            writeln!(
                w,
                "{},{:.3},{name},{},{:.4},{:.4},{:.4},{:.6},{:.6},{:.6},{:.4}",
                start + Unit::Second * t.t_s[k],
                t.t_s[k],
                target.0,
                rho.x,
                rho.y,
                rho.z,
                rho_dot.x,
                rho_dot.y,
                rho_dot.z,
                rho.norm()
            )
            .map_err(write_err)?;
        }
    }
    w.flush().map_err(write_err)
}

/// Read `relative.csv` at `path`: every row, in file order.
pub fn read_relative_csv(path: &Path) -> Result<Vec<RelativeRow>, FormatError> {
    let required: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
    let mut rows = Vec::new();
    let each = |header: &[&str], line: usize, text: &str| {
        let f = Fields::new(path, line, header, text)?;
        let num = |c: &str| f.number(c)?.ok_or_else(|| f.error(format!("{c} is empty")));
        rows.push(RelativeRow {
            t_s: num("t_s")?,
            vehicle: f.text("vehicle")?.to_string(),
            target: f.text("target")?.to_string(),
            position_m: Vec3::new(num("x_m")?, num("y_m")?, num("z_m")?),
            velocity_mps: Vec3::new(num("vx_mps")?, num("vy_mps")?, num("vz_mps")?),
        });
        Ok(())
    };
    read_csv(path, |names| require_columns(path, names, &required), each)?;
    Ok(rows)
}
