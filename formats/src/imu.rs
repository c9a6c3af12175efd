//! The IMU's truth file [`IMU_H5`]: per IMU sample, the increments the IMU output, the
//! error-free ones, the platform's truth at the interval's end (position, velocity,
//! attitude) and the sensors' biases then, written row by row in constant memory
//! ([`ImuH5Writer`]) and read back by [`read_h5`] for `validate`. The IMU's own files (what
//! an INS reads: SkyForge's IMU CSV, KF-GINS's text) are `skyforge_gnss::imu`'s; this one
//! holds truth and stays on the simulator's side of the firewall. Schema in docs/imu.md.

use crate::FormatError;
use crate::h5::{append_rows, create_epoch_file, create_rows, read_column, read_text_attr};
use hdf5::Dataset;
use hifitime::Epoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::time::parse_epoch;
use std::path::Path;

/// The IMU's samples with their truth.
pub const IMU_H5: &str = "imu.h5";
/// The `schema` attribute of [`IMU_H5`].
const SCHEMA: &str = "skyforge imu.h5 version 1";
/// The `start_gpst` attribute: `t_s` counts from it.
const START_ATTR: &str = "start_gpst";
/// Most samples read back (2^26: 18.6 h at 1 kHz).
const MAX_ROWS: usize = 1 << 26;
/// Rows buffered before they are appended.
const CHUNK_ROWS: usize = 4096;

/// One IMU sample with its truth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuRow {
    /// End of the interval (s since `start_gpst`) and its length (s).
    pub t_s: f64,
    pub dt_s: f64,
    /// What the IMU output: angle (rad) and velocity (m/s) increments, body axes.
    pub dtheta_rad: Vec3,
    pub dv_mps: Vec3,
    /// The error-free increments of the same interval.
    pub ideal_dtheta_rad: Vec3,
    pub ideal_dv_mps: Vec3,
    /// The IMU's position and velocity (ECEF) and its body -> ECEF attitude as a unit
    /// quaternion `[w, x, y, z]`, at the interval's end.
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    pub q_body_ecef: [f64; 4],
    /// The gyros' (rad/s) and accelerometers' (m/s^2) biases at the interval's end,
    /// body axes.
    pub gyro_bias_rps: Vec3,
    pub accel_bias_mps2: Vec3,
}

/// The columns: name, width, unit, description, and how a row fills them.
type Column = (
    &'static str,
    usize,
    &'static str,
    &'static str,
    fn(&ImuRow) -> Vec<f64>,
);

/// Every dataset of [`IMU_H5`], in order.
const COLUMNS: [Column; 11] = [
    (
        "t_s",
        0,
        "s",
        "end of the interval, since start_gpst (GPST)",
        |r| vec![r.t_s],
    ),
    ("dt_s", 0, "s", "interval length", |r| vec![r.dt_s]),
    (
        "dtheta_rad",
        3,
        "rad",
        "angle increments the IMU output, body axes",
        |r| v3(r.dtheta_rad),
    ),
    (
        "dv_mps",
        3,
        "m/s",
        "velocity increments the IMU output, body axes",
        |r| v3(r.dv_mps),
    ),
    (
        "ideal_dtheta_rad",
        3,
        "rad",
        "error-free angle increments",
        |r| v3(r.ideal_dtheta_rad),
    ),
    (
        "ideal_dv_mps",
        3,
        "m/s",
        "error-free velocity increments",
        |r| v3(r.ideal_dv_mps),
    ),
    (
        "r_ecef_m",
        3,
        "m",
        "IMU position at the interval's end, ECEF",
        |r| v3(r.r_ecef_m),
    ),
    (
        "v_ecef_mps",
        3,
        "m/s",
        "IMU velocity at the interval's end, ECEF (Earth-fixed)",
        |r| v3(r.v_ecef_mps),
    ),
    (
        "q_body_ecef",
        4,
        "1",
        "body -> ECEF attitude at the interval's end, unit quaternion [w, x, y, z]",
        |r| r.q_body_ecef.to_vec(),
    ),
    (
        "gyro_bias_rps",
        3,
        "rad/s",
        "gyro biases at the interval's end, body axes",
        |r| v3(r.gyro_bias_rps),
    ),
    (
        "accel_bias_mps2",
        3,
        "m/s^2",
        "accelerometer biases at the interval's end, body axes",
        |r| v3(r.accel_bias_mps2),
    ),
];

fn v3(v: Vec3) -> Vec<f64> {
    vec![v.x, v.y, v.z]
}

/// Writes [`IMU_H5`] row by row; [`Self::finish`] appends what is buffered.
#[derive(Debug)]
pub struct ImuH5Writer {
    _file: hdf5::File,
    datasets: Vec<Dataset>,
    buffered: Vec<ImuRow>,
    written: usize,
}

impl ImuH5Writer {
    /// Creates the file at `path` for a run that started at `start`.
    pub fn create(path: &Path, start: Epoch) -> hdf5::Result<Self> {
        let file = create_epoch_file(path, SCHEMA, Some(start))?;
        let root: &hdf5::Group = &file;
        let datasets = COLUMNS
            .iter()
            .map(|(name, width, unit, what, _)| {
                create_rows::<f64>(root, name, *width, CHUNK_ROWS, unit, what)
            })
            .collect::<hdf5::Result<_>>()?;
        Ok(Self {
            _file: file,
            datasets,
            buffered: Vec::with_capacity(CHUNK_ROWS),
            written: 0,
        })
    }

    /// Adds one sample.
    pub fn push(&mut self, row: ImuRow) -> hdf5::Result<()> {
        self.buffered.push(row);
        if self.buffered.len() == CHUNK_ROWS {
            self.flush()?;
        }
        Ok(())
    }

    fn flush(&mut self) -> hdf5::Result<()> {
        for (ds, (_, width, _, _, fill)) in self.datasets.iter().zip(COLUMNS.iter()) {
            let data: Vec<f64> = self.buffered.iter().flat_map(fill).collect();
            append_rows(ds, self.written, &data, *width)?;
        }
        self.written += self.buffered.len();
        self.buffered.clear();
        Ok(())
    }

    /// Appends what is buffered and closes the file.
    pub fn finish(mut self) -> hdf5::Result<()> {
        self.flush()
    }
}

/// [`IMU_H5`] read back.
#[derive(Debug, Clone, PartialEq)]
pub struct ImuH5 {
    /// The epoch `t_s` counts from (GPST).
    pub start: Epoch,
    pub rows: Vec<ImuRow>,
}

/// Reads [`IMU_H5`] at `path` (at most [`MAX_ROWS`] samples, every value finite, times
/// increasing).
pub fn read_h5(path: &Path) -> Result<ImuH5, FormatError> {
    let err = |m: String| FormatError::file(path, m);
    let file = hdf5::File::open(path).map_err(|e| err(format!("not readable as HDF5: {e}")))?;
    let start_text = read_text_attr(&file, path, START_ATTR)?;
    let start =
        parse_epoch(&start_text).map_err(|e| err(format!("attribute {START_ATTR}: {e}")))?;
    let mut columns = Vec::with_capacity(COLUMNS.len());
    for (name, width, ..) in COLUMNS {
        let values: Vec<f64> = read_column(&file, path, name, width.max(1) * MAX_ROWS)?;
        if values.iter().any(|x| !x.is_finite()) {
            return Err(err(format!("dataset {name}: a value is not finite")));
        }
        columns.push(values);
    }
    let n = columns[0].len();
    if let Some(((name, ..), c)) = COLUMNS
        .iter()
        .zip(&columns)
        .find(|((_, width, ..), c)| c.len() != width.max(&1) * n)
    {
        return Err(err(format!(
            "dataset {name} holds {} values for {n} samples",
            c.len()
        )));
    }
    if columns[0].windows(2).any(|w| w[1] <= w[0]) {
        return Err(err("t_s is not increasing".into()));
    }
    let rows = (0..n).map(|k| row_from(&columns, k)).collect();
    Ok(ImuH5 { start, rows })
}

/// Row `k` of the read columns (in [`COLUMNS`]' order).
fn row_from(c: &[Vec<f64>], k: usize) -> ImuRow {
    let v = |i: usize| Vec3::new(c[i][3 * k], c[i][3 * k + 1], c[i][3 * k + 2]);
    ImuRow {
        t_s: c[0][k],
        dt_s: c[1][k],
        dtheta_rad: v(2),
        dv_mps: v(3),
        ideal_dtheta_rad: v(4),
        ideal_dv_mps: v(5),
        r_ecef_m: v(6),
        v_ecef_mps: v(7),
        q_body_ecef: std::array::from_fn(|j| c[8][4 * k + j]),
        gyro_bias_rps: v(9),
        accel_bias_mps2: v(10),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(k: usize) -> ImuRow {
        let x = k as f64;
        let v = |a: f64| Vec3::new(a, -2.0 * a, 0.5 * a + 1.0);
        ImuRow {
            t_s: 0.01 * (x + 1.0),
            dt_s: 0.01,
            dtheta_rad: v(1e-5 * x),
            dv_mps: v(0.098 + x),
            ideal_dtheta_rad: v(2e-5 * x),
            ideal_dv_mps: v(0.097 - x),
            r_ecef_m: v(6.4e6 + x),
            v_ecef_mps: v(3.0 * x),
            q_body_ecef: [0.5, 0.5, -0.5, 0.5],
            gyro_bias_rps: v(1e-8 * x),
            accel_bias_mps2: v(1e-4),
        }
    }

    /// More rows than a chunk, read back bit for bit.
    #[test]
    fn rows_read_back_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(IMU_H5);
        let start = Epoch::from_gregorian_utc_hms(2026, 12, 1, 0, 0, 0);
        let mut w = ImuH5Writer::create(&path, start).unwrap();
        let rows: Vec<ImuRow> = (0..CHUNK_ROWS + 17).map(row).collect();
        for r in &rows {
            w.push(*r).unwrap();
        }
        w.finish().unwrap();
        let back = read_h5(&path).unwrap();
        assert_eq!(back.rows, rows);
        assert_eq!(back.start, start);
    }

    /// A file that is not HDF5 is one error naming it.
    #[test]
    fn not_hdf5_is_one_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(IMU_H5);
        std::fs::write(&path, "no").unwrap();
        let e = read_h5(&path).unwrap_err().to_string();
        assert!(e.contains("imu.h5") && e.contains("HDF5"), "{e}");
    }
}
