//! The outputs of `skyforge attitude --estimate-geometry`: the geometry-offset estimate
//! after every update of the thesis 4.3 UKF as a row of `geometry_offsets.csv` and of
//! `geometry_offsets.h5` (schema in docs/geometry.md), and the corrected body geometry
//! `geometry_corrected.toml` that `skyforge attitude --geometry` and `skyforge receive
//! --geometry` read.

use hifitime::Epoch;
use skyforge_formats::h5::{append_rows, create_epoch_file, create_rows};
use skyforge_navigation::attitude::BodyGeometry;
use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_navigation::geometry_offset::stacked_ukf::OffsetState;
use std::path::Path;

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

/// The geometry file of `original` with every antenna but the master moved to the
/// master plus its corrected baseline.
pub fn corrected_file(original: &BodyGeometryFile, corrected: &BodyGeometry) -> BodyGeometryFile {
    let master = original.positions().first().copied().unwrap_or_default();
    BodyGeometryFile::from_positions(original.antennas.iter().enumerate().map(|(k, a)| {
        let p = match k.checked_sub(1).and_then(|i| corrected.baselines().get(i)) {
            Some(b) => master + b,
            None => master,
        };
        (a.name.clone(), p)
    }))
}
