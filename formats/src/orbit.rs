//! What `skyforge od` writes: the estimated orbit after every fix as a row of
//! [`ORBIT_CSV`] and of [`ORBIT_H5`] (with the full 6 x 6 covariance; [`read_h5`] reads it
//! back for `skyforge validate od`), and as the SP3 file [`ORBIT_SP3`]; and the truth's
//! orbit of a LEO as [`TRUTH_SP3`] beside `truth.h5` ([`write_truth_sp3`]). Schema in
//! docs/orbit-determination.md.

use crate::FormatError;
use crate::h5::{append_rows, create_epoch_file, create_rows, read_column, read_text_attr};
use crate::truth::TruthFile;
use hifitime::{Epoch, Unit};
use skyforge_navigation::orbit_determination::EcefEstimate;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{Sp3Header, Sp3Series, Sp3State, write_sp3};
use skyforge_orbits::time::parse_epoch;
use std::io::Write;
use std::path::Path;

/// One row per estimate.
pub const ORBIT_CSV: &str = "orbit.csv";
/// The same as columns, with the covariance.
pub const ORBIT_H5: &str = "orbit.h5";
/// The estimate as an SP3-c file (positions and velocities, ECEF).
pub const ORBIT_SP3: &str = "orbit.sp3";
/// The truth's orbit of a LEO platform, beside `truth.h5`.
pub const TRUTH_SP3: &str = "truth.sp3";
/// The SP3 identifier of the receiving LEO in both files.
pub const LEO_SP3_ID: &str = "L01";
/// Most estimates read back (48 days at 1 Hz).
const MAX_ROWS: usize = 1 << 22;
/// The `start_gpst` attribute of [`ORBIT_H5`].
const START_ATTR: &str = "start_gpst";

/// Names of the six state components, in the covariance's order.
const STATE: [&str; 6] = ["x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps"];

/// The six values of an estimate: position (m) and velocity (m/s), ECEF.
fn state(e: &EcefEstimate) -> [f64; 6] {
    let (r, v) = (e.r_ecef_m, e.v_ecef_mps);
    [r.x, r.y, r.z, v.x, v.y, v.z]
}

/// The CSV header.
pub fn csv_header() -> String {
    let sigma: Vec<String> = STATE.iter().map(|n| format!("sigma_{n}")).collect();
    format!("time_gpst,t_s,{},{}", STATE.join(","), sigma.join(","))
}

/// One CSV row of the estimate `e` of a run that started at `start`.
pub fn csv_row(start: Epoch, e: &EcefEstimate) -> String {
    let values: Vec<String> = state(e).iter().map(|x| format!("{x:.4}")).collect();
    let sigma: Vec<String> = (0..6)
        .map(|i| format!("{:.4e}", e.covariance[(i, i)].max(0.0).sqrt()))
        .collect();
    format!(
        "{},{:.3},{},{}",
        start + Unit::Second * e.t_s,
        e.t_s,
        values.join(","),
        sigma.join(",")
    )
}

/// `orbit.csv` at `path`.
pub fn write_csv(path: &Path, start: Epoch, estimates: &[EcefEstimate]) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(w, "{}", csv_header())?;
    for e in estimates {
        writeln!(w, "{}", csv_row(start, e))?;
    }
    w.flush()
}

/// `orbit.h5` at `path`; `filter` names the filter (an attribute).
pub fn write_h5(
    path: &Path,
    start: Epoch,
    filter: &str,
    estimates: &[EcefEstimate],
) -> hdf5::Result<()> {
    let file = create_epoch_file(path, "skyforge orbit.h5 version 1", Some(start))?;
    crate::h5::text_attr(&file, "filter", filter)?;
    let root: &hdf5::Group = &file;
    let chunk = estimates.len().clamp(1, 4096);
    let column = |name: &str, width: usize, unit: &str, what: &str, data: Vec<f64>| {
        let ds = create_rows::<f64>(root, name, width, chunk, unit, what)?;
        append_rows(&ds, 0, &data, width)
    };
    let per = |f: &dyn Fn(&EcefEstimate) -> Vec<f64>| estimates.iter().flat_map(f).collect();
    column(
        "t_s",
        0,
        "s",
        "time of the estimate since start_gpst (GPST)",
        per(&|e| vec![e.t_s]),
    )?;
    column(
        "r_ecef_m",
        3,
        "m",
        "estimated centre-of-mass position, ECEF",
        per(&|e| e.r_ecef_m.iter().copied().collect()),
    )?;
    column(
        "v_ecef_mps",
        3,
        "m/s",
        "estimated centre-of-mass velocity, ECEF (Earth-fixed)",
        per(&|e| e.v_ecef_mps.iter().copied().collect()),
    )?;
    column(
        "covariance",
        36,
        "m^2, m^2/s, m^2/s^2",
        "covariance of [r_ecef, v_ecef], row-major 6 x 6",
        per(&|e| e.covariance.transpose().as_slice().to_vec()),
    )
}

/// `orbit.h5` read back.
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitH5 {
    /// The epoch `t_s` counts from (GPST).
    pub start: Epoch,
    /// The filter that made it.
    pub filter: String,
    pub t_s: Vec<f64>,
    pub r_ecef_m: Vec<Vec3>,
    pub v_ecef_mps: Vec<Vec3>,
    /// Covariance of `[r, v]`, row-major 6 x 6.
    pub covariance: Vec<[f64; 36]>,
}

/// Read `orbit.h5` at `path` (at most 2^22 estimates, every value finite).
pub fn read_h5(path: &Path) -> Result<OrbitH5, FormatError> {
    let err = |m: String| FormatError::file(path, m);
    let file = hdf5::File::open(path).map_err(|e| err(format!("not readable as HDF5: {e}")))?;
    let start_text = read_text_attr(&file, path, START_ATTR)?;
    let start =
        parse_epoch(&start_text).map_err(|e| err(format!("attribute {START_ATTR}: {e}")))?;
    let filter = read_text_attr(&file, path, "filter")?;
    let t_s: Vec<f64> = read_column(&file, path, "t_s", MAX_ROWS)?;
    let r: Vec<f64> = read_column(&file, path, "r_ecef_m", 3 * MAX_ROWS)?;
    let v: Vec<f64> = read_column(&file, path, "v_ecef_mps", 3 * MAX_ROWS)?;
    let p: Vec<f64> = read_column(&file, path, "covariance", 36 * MAX_ROWS)?;
    let n = t_s.len();
    if r.len() != 3 * n || v.len() != 3 * n || p.len() != 36 * n {
        return Err(err(format!(
            "{n} times, {} positions, {} velocities, {} covariances: not one of each per time",
            r.len() / 3,
            v.len() / 3,
            p.len() / 36
        )));
    }
    if [&t_s, &r, &v, &p]
        .iter()
        .any(|c| c.iter().any(|x| !x.is_finite()))
    {
        return Err(err("a value is not finite".into()));
    }
    if t_s.windows(2).any(|w| w[1] <= w[0]) {
        return Err(err("t_s is not increasing".into()));
    }
    Ok(OrbitH5 {
        start,
        filter,
        t_s,
        r_ecef_m: r.chunks_exact(3).map(Vec3::from_column_slice).collect(),
        v_ecef_mps: v.chunks_exact(3).map(Vec3::from_column_slice).collect(),
        covariance: p
            .chunks_exact(36)
            .map(|c| std::array::from_fn(|i| c[i]))
            .collect(),
    })
}

/// An SP3 file of the one vehicle [`LEO_SP3_ID`] at `path`.
fn write_leo_sp3(
    path: &Path,
    orbit_type: &str,
    comment: &str,
    states: &[Sp3State],
) -> std::io::Result<()> {
    let header = Sp3Header {
        data_used: "u",
        coordinate_system: "WGS84",
        orbit_type,
        agency: "SKYF",
        file_type: 'L',
        comment,
    };
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    let series = [Sp3Series {
        id: LEO_SP3_ID,
        states,
    }];
    write_sp3(&mut w, &header, &series)?;
    w.flush()
}

/// `orbit.sp3` at `path`: the estimates of a run that started at `start`.
pub fn write_orbit_sp3(
    path: &Path,
    start: Epoch,
    filter: &str,
    estimates: &[EcefEstimate],
) -> std::io::Result<()> {
    let states: Vec<Sp3State> = estimates
        .iter()
        .map(|e| Sp3State {
            epoch: start + Unit::Second * e.t_s,
            r_ecef_m: e.r_ecef_m,
            v_ecef_mps: Some(e.v_ecef_mps),
            clock_s: None,
        })
        .collect();
    let comment = format!("SkyForge skyforge od: {filter} estimate of the receiving LEO");
    write_leo_sp3(path, "EST", &comment, &states)
}

/// `truth.sp3` at `path`: the platform's centre of mass at every epoch of the `truth.h5`
/// at `truth` (a LEO's orbit as a precise-orbit user reads it).
pub fn write_truth_sp3(truth: &Path, path: &Path) -> Result<(), FormatError> {
    let file = TruthFile::open(truth)?;
    let start = file.start_epoch()?;
    let platform = file.platform(MAX_ROWS)?;
    let states: Vec<Sp3State> = (platform.t_s.iter())
        .zip(platform.r_ecef_m.iter().zip(&platform.v_ecef_mps))
        .map(|(t, (r, v))| Sp3State {
            epoch: start + Unit::Second * *t,
            r_ecef_m: *r,
            v_ecef_mps: Some(*v),
            clock_s: None,
        })
        .collect();
    let comment = "SkyForge truth: the simulated platform's centre of mass";
    write_leo_sp3(path, "FIT", comment, &states)
        .map_err(|e| FormatError::file(path, format!("cannot write: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix6;
    use skyforge_orbits::ephemeris::parse_sp3_vehicle;

    fn estimate(t_s: f64, k: f64) -> EcefEstimate {
        let mut covariance = Matrix6::from_fn(|i, j| 1e-3 * (1 + i + j) as f64);
        covariance[(0, 5)] = -7e-4;
        EcefEstimate {
            t_s,
            r_ecef_m: Vec3::new(6.9e6 + k, -1.2e5 * k, 3.3e5),
            v_ecef_mps: Vec3::new(12.5, 7500.25 - k, -4.0),
            covariance,
        }
    }

    fn start() -> Epoch {
        Epoch::from_gregorian(2020, 6, 25, 0, 0, 0, 0, hifitime::TimeScale::GPST)
    }

    /// Estimates written to `orbit.h5` read back exactly: start, filter, times, states
    /// and the row-major covariance.
    #[test]
    fn h5_estimates_read_back_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(ORBIT_H5);
        let rows = [estimate(0.0, 1.0), estimate(10.0, 2.0), estimate(30.0, 3.0)];
        write_h5(&path, start(), "position-filter", &rows).unwrap();
        let read = read_h5(&path).unwrap();
        assert_eq!(read.start, start());
        assert_eq!(read.filter, "position-filter");
        assert_eq!(read.t_s, [0.0, 10.0, 30.0]);
        for (k, e) in rows.iter().enumerate() {
            assert_eq!(read.r_ecef_m[k], e.r_ecef_m);
            assert_eq!(read.v_ecef_mps[k], e.v_ecef_mps);
            for (i, v) in read.covariance[k].iter().enumerate() {
                assert_eq!(*v, e.covariance[(i / 6, i % 6)], "element {i}");
            }
        }
        assert_eq!(
            csv_row(start(), &rows[0]).split(',').count(),
            csv_header().split(',').count()
        );
    }

    /// `orbit.sp3` carries the estimates at their epochs (to the format's 1 mm).
    #[test]
    fn sp3_holds_the_estimates_at_their_epochs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(ORBIT_SP3);
        let rows = [estimate(0.0, 1.0), estimate(10.0, 2.0)];
        write_orbit_sp3(&path, start(), "position-filter", &rows).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let read = parse_sp3_vehicle(&text, "orbit.sp3", LEO_SP3_ID).unwrap();
        assert_eq!(read.len(), 2);
        assert_eq!(read[1].epoch, start() + Unit::Second * 10);
        assert!((read[1].r_ecef_m - rows[1].r_ecef_m).norm() < 1e-3);
        assert!((read[1].v_ecef_mps.unwrap() - rows[1].v_ecef_mps).norm() < 1e-6);
    }

    #[test]
    fn a_missing_or_malformed_file_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("none.h5");
        let e = read_h5(&path).unwrap_err().to_string();
        assert!(e.contains("none.h5"), "{e}");
        std::fs::write(&path, "not hdf5").unwrap();
        assert!(read_h5(&path).unwrap_err().to_string().contains("HDF5"));
    }
}
