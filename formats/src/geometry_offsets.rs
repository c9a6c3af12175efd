//! The outputs of `skyforge attitude --estimate-geometry`: the geometry-offset estimate
//! after every update of the thesis 4.3 UKF as a row of [`GEOMETRY_OFFSETS_CSV`] and of
//! [`GEOMETRY_OFFSETS_H5`] (schema in docs/geometry.md; [`read_h5`] reads it back for the
//! report), and the name of the corrected body geometry [`GEOMETRY_CORRECTED_TOML`] (a
//! `geometry.toml`, `skyforge_navigation::geometry_file`).

use crate::csv::FormatError;
use crate::h5::{append_rows, create_epoch_file, create_rows, read_column};
use hifitime::Epoch;
use skyforge_navigation::geometry_offset::OffsetState;
use std::path::Path;

/// One row per update.
pub const GEOMETRY_OFFSETS_CSV: &str = "geometry_offsets.csv";
/// The same as columns.
pub const GEOMETRY_OFFSETS_H5: &str = "geometry_offsets.h5";
/// The nominal geometry with the estimated offsets applied.
pub const GEOMETRY_CORRECTED_TOML: &str = "geometry_corrected.toml";
/// Most updates read back (48 days at 1 Hz).
const MAX_ROWS: usize = 1 << 22;

/// One update: the time of the newest epoch and the estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct OffsetRow {
    pub time: Epoch,
    pub state: OffsetState,
    pub chi_square: f64,
    pub dof: usize,
}

const NAMES: [&str; 6] = ["dx1", "dy1", "dz1", "dx2", "dy2", "dz2"];

/// The six offsets (m) and their standard deviations (m).
fn offsets(s: &OffsetState) -> ([f64; 6], [f64; 6]) {
    let v = [0, 1, 2, 3, 4, 5].map(|i| s.offsets_m[i / 3][i % 3]);
    let sd = [0, 1, 2, 3, 4, 5].map(|i| s.offsets_covariance_m2[(i, i)].sqrt());
    (v, sd)
}

/// Yaw, pitch, roll of the newest stacked epoch (deg).
fn newest_deg(s: &OffsetState) -> [f64; 3] {
    let a = s.window[s.window.len() - 1];
    [a.yaw_rad, a.pitch_rad, a.roll_rad].map(f64::to_degrees)
}

/// The CSV header.
pub fn csv_header() -> String {
    let sigma: Vec<String> = NAMES.iter().map(|n| format!("sigma_{n}_m")).collect();
    let values: Vec<String> = NAMES.iter().map(|n| format!("{n}_m")).collect();
    format!(
        "time_gpst,{},{},offset_rate_m_s,yaw_deg,pitch_deg,roll_deg,chi_square,dof",
        values.join(","),
        sigma.join(",")
    )
}

/// One CSV row.
pub fn csv_row(r: &OffsetRow) -> String {
    let (v, sd) = offsets(&r.state);
    let join = |a: &[f64]| {
        a.iter()
            .map(|x| format!("{x:.6e}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    let att = newest_deg(&r.state);
    format!(
        "{},{},{},{:.6e},{:.6},{:.6},{:.6},{:.3},{}",
        r.time,
        join(&v),
        join(&sd),
        r.state.offset_rate_m_s,
        att[0],
        att[1],
        att[2],
        r.chi_square,
        r.dof
    )
}

/// `geometry_offsets.h5`.
pub fn write_h5(path: &Path, rows: &[OffsetRow]) -> hdf5::Result<()> {
    let start = rows.first().map(|r| r.time);
    let file = create_epoch_file(path, "skyforge geometry_offsets.h5 version 1", start)?;
    let root: &hdf5::Group = &file;
    let chunk = rows.len().clamp(1, 4096);
    let column = |name: &str, width: usize, unit: &str, what: &str, data: Vec<f64>| {
        let ds = create_rows::<f64>(root, name, width, chunk, unit, what)?;
        append_rows(&ds, 0, &data, width)
    };
    let per = |f: &dyn Fn(&OffsetRow) -> Vec<f64>| rows.iter().flat_map(f).collect();
    column(
        "t_s",
        0,
        "s",
        "time of the newest stacked epoch since start_gpst",
        per(&|r| vec![start.map_or(0.0, |s| (r.time - s).to_seconds())]),
    )?;
    column(
        "offsets",
        6,
        "m",
        "dB0 columns: dx1, dy1, dz1, dx2, dy2, dz2 (body frame)",
        per(&|r| offsets(&r.state).0.to_vec()),
    )?;
    column(
        "offsets_covariance",
        36,
        "m^2",
        "covariance of the six offsets, row-major 6 x 6",
        per(&|r| {
            let p = r.state.offsets_covariance_m2.transpose();
            p.as_slice().to_vec()
        }),
    )?;
    column(
        "offset_rate",
        0,
        "m/s",
        "the common offset rate Delta' (thesis eq. 4.3-5)",
        per(&|r| vec![r.state.offset_rate_m_s]),
    )?;
    column(
        "attitude",
        3,
        "deg",
        "yaw, pitch, roll of the newest stacked epoch",
        per(&|r| newest_deg(&r.state).to_vec()),
    )?;
    column(
        "chi_square",
        0,
        "-",
        "innovation chi-square of the update (degrees of freedom in dof)",
        per(&|r| vec![r.chi_square]),
    )?;
    column(
        "dof",
        0,
        "-",
        "degrees of freedom of chi_square",
        per(&|r| vec![r.dof as f64]),
    )
}

/// `geometry_offsets.h5` read back: per update, the time and the six offsets with their
/// covariance.
#[derive(Debug, Clone, PartialEq)]
pub struct OffsetsH5 {
    /// Time of the newest stacked epoch since the file's `start_gpst` (s).
    pub t_s: Vec<f64>,
    /// dx1, dy1, dz1, dx2, dy2, dz2 (m, body frame).
    pub offsets_m: Vec<[f64; 6]>,
    /// Their covariance, row-major 6 x 6 (m^2).
    pub covariance_m2: Vec<[f64; 36]>,
}

/// Read `geometry_offsets.h5` at `path` (at most [`MAX_ROWS`] updates).
pub fn read_h5(path: &Path) -> Result<OffsetsH5, FormatError> {
    let file = hdf5::File::open(path)
        .map_err(|e| FormatError::file(path, format!("not readable as HDF5: {e}")))?;
    let t_s: Vec<f64> = read_column(&file, path, "t_s", MAX_ROWS)?;
    let offsets: Vec<f64> = read_column(&file, path, "offsets", 6 * MAX_ROWS)?;
    let covariance: Vec<f64> = read_column(&file, path, "offsets_covariance", 36 * MAX_ROWS)?;
    if offsets.len() != 6 * t_s.len() || covariance.len() != 36 * t_s.len() {
        return Err(FormatError::file(
            path,
            format!(
                "{} updates, {} offset and {} covariance values: not 6 offsets and 36 covariances per update",
                t_s.len(),
                offsets.len(),
                covariance.len()
            ),
        ));
    }
    Ok(OffsetsH5 {
        offsets_m: rows(&offsets),
        covariance_m2: rows(&covariance),
        t_s,
    })
}

/// `v` cut into rows of `N` (its length a multiple of `N`).
fn rows<const N: usize>(v: &[f64]) -> Vec<[f64; N]> {
    v.chunks_exact(N)
        .map(|c| {
            let mut row = [0.0; N];
            row.copy_from_slice(c);
            row
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::Vec3;
    use skyforge_orbits::frames::YawPitchRoll;

    fn row(t_s: f64, k: f64) -> OffsetRow {
        let angles = YawPitchRoll {
            yaw_rad: 0.1 * k,
            pitch_rad: -0.2,
            roll_rad: 0.3,
        };
        let mut covariance = nalgebra::SMatrix::<f64, 6, 6>::from_fn(|i, j| 1e-9 * (i + j) as f64);
        covariance[(0, 5)] = -7e-8;
        OffsetRow {
            time: Epoch::from_gpst_seconds(1.3e9 + t_s),
            state: OffsetState {
                oldest_t_s: t_s - 3.0,
                window: [angles; 4],
                rates_rad_s: Vec3::new(1e-3, 0.0, -1e-3),
                offsets_m: [
                    Vec3::new(1e-3 * k, -2e-3, 5e-4),
                    Vec3::new(0.0, 3e-3, -1e-3 * k),
                ],
                offset_rate_m_s: 1e-6,
                offsets_covariance_m2: covariance,
            },
            chi_square: 4.25,
            dof: 6,
        }
    }

    /// Rows written to `geometry_offsets.h5` read back: times from the first row, the six
    /// offsets and the row-major covariance, exactly.
    #[test]
    fn h5_rows_read_back_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(GEOMETRY_OFFSETS_H5);
        let rows = [row(10.0, 1.0), row(11.0, 2.0), row(12.5, 3.0)];
        write_h5(&path, &rows).unwrap();
        let read = read_h5(&path).unwrap();
        assert_eq!(read.t_s, [0.0, 1.0, 2.5]);
        let read_rows = read.offsets_m.iter().zip(&read.covariance_m2);
        for (r, (six, covariance)) in rows.iter().zip(read_rows) {
            assert_eq!(*six, offsets(&r.state).0);
            let p = &r.state.offsets_covariance_m2;
            for (k, v) in covariance.iter().enumerate() {
                assert_eq!(*v, p[(k / 6, k % 6)], "element {k}");
            }
        }
        // The CSV row has a field per header column.
        assert_eq!(
            csv_row(&rows[0]).split(',').count(),
            csv_header().split(',').count()
        );
    }
}
