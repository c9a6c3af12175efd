//! `ins.csv`: a GNSS/INS solution (`skyforge ins`), one row per observation epoch after
//! the alignment: the IMU's position, velocity and attitude, the filter's position
//! sigmas, and whether a fix updated it or an outage made on purpose hid it. Writer and
//! reader together.

use crate::FormatError;
use crate::csv::{Fields, read_csv, require_columns};
use hifitime::Epoch;
use skyforge_navigation::gnss_ins::InsSolution;
use skyforge_orbits::Vec3;
use std::io::Write;
use std::path::Path;

/// The file's name in an output directory.
pub const INS_CSV: &str = "ins.csv";

/// The columns, in order.
const COLUMNS: [&str; 18] = [
    "time_gpst",
    "x_m",
    "y_m",
    "z_m",
    "vx_mps",
    "vy_mps",
    "vz_mps",
    "lat_deg",
    "lon_deg",
    "height_m",
    "yaw_deg",
    "pitch_deg",
    "roll_deg",
    "sigma_n_m",
    "sigma_e_m",
    "sigma_d_m",
    "gnss",
    "outage",
];

/// One row read back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InsRow {
    /// Time of validity (GPST).
    pub t: Epoch,
    /// The IMU's position and velocity (ECEF).
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    /// Yaw, pitch, roll relative to NED (deg).
    pub ypr_deg: Vec3,
    /// 1-sigma position errors north, east, down (m).
    pub sigma_ned_m: Vec3,
    /// A fix updated the filter; the epoch lay in an outage made on purpose.
    pub gnss: bool,
    pub outage: bool,
}

/// Writes `solutions` as [`INS_CSV`] at `path`.
pub fn write_ins_csv(path: &Path, solutions: &[InsSolution]) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(w, "{}", COLUMNS.join(","))?;
    for s in solutions {
        let st = &s.state;
        let g = st.geodetic();
        let a = st.attitude_ned();
        let (r, v, sg) = (st.r_ecef_m, st.v_ecef_mps, s.sigma_ned_m);
        writeln!(
            w,
            "{},{:.4},{:.4},{:.4},{:.5},{:.5},{:.5},{:.9},{:.9},{:.4},{:.5},{:.5},{:.5},{:.4},{:.4},{:.4},{},{}",
            st.t,
            r.x,
            r.y,
            r.z,
            v.x,
            v.y,
            v.z,
            g.lat_rad.to_degrees(),
            g.lon_rad.to_degrees(),
            g.h_m,
            a.yaw_rad.to_degrees(),
            a.pitch_rad.to_degrees(),
            a.roll_rad.to_degrees(),
            sg.x,
            sg.y,
            sg.z,
            u8::from(s.gnss),
            u8::from(s.in_outage),
        )?;
    }
    w.flush()
}

/// Every row of [`INS_CSV`] at `path`, times increasing.
pub fn read_ins_csv(path: &Path) -> Result<Vec<InsRow>, FormatError> {
    let mut rows: Vec<InsRow> = Vec::new();
    let columns: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
    read_csv(
        path,
        |header| require_columns(path, header, &columns),
        |header, line, text| {
            let f = Fields::new(path, line, header, text)?;
            let number = |c: &str| f.number(c)?.ok_or_else(|| f.error(format!("{c} is empty")));
            let vec = |a: &str, b: &str, c: &str| -> Result<Vec3, FormatError> {
                Ok(Vec3::new(number(a)?, number(b)?, number(c)?))
            };
            let t = f.epoch("time_gpst")?;
            if rows.last().is_some_and(|r| r.t >= t) {
                return Err(f.error("time_gpst does not increase".into()));
            }
            rows.push(InsRow {
                t,
                r_ecef_m: vec("x_m", "y_m", "z_m")?,
                v_ecef_mps: vec("vx_mps", "vy_mps", "vz_mps")?,
                ypr_deg: vec("yaw_deg", "pitch_deg", "roll_deg")?,
                sigma_ned_m: vec("sigma_n_m", "sigma_e_m", "sigma_d_m")?,
                gnss: f.flag("gnss")?,
                outage: f.flag("outage")?,
            });
            Ok(())
        },
    )?;
    Ok(rows)
}
