//! A trajectory read from CSV, interpolated smoothly (e.g. cubic Hermite or spline).
//!
//! Columns `t_s,x_m,y_m,z_m[,vx_mps,vy_mps,vz_mps]` (ECEF, `t` in seconds from the
//! scenario start, strictly increasing), `#` comments, optional header line. Positions are
//! interpolated by cubic Hermite segments with the given velocities, or, without velocity
//! columns, with velocities estimated by a five-point Lagrange derivative (fourth-order
//! accurate). The reference frame of the attitude is NED at the current position.
//!
//! Windows may reach [`EDGE_MARGIN_S`] beyond the data (finite-difference stencils at the
//! scenario edges); there the motion continues in a straight line at the end velocity.

use super::csv_table::read_numeric_csv;
use super::hermite::Hermite3;
use super::{EDGE_MARGIN_S, PlatformError};
use crate::Vec3;
use crate::check::{Allowed, Invalid, NEAR_EARTH_RADIUS_M, check_position};
use std::path::Path;

/// Column names of the trajectory CSV, in order.
const COLUMNS: [&str; 7] = ["t_s", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps"];

/// Velocity components (m/s) of a trajectory: assumed up to 100 km/s, nine times the
/// Earth's escape speed (11.2 km/s).
const VELOCITY_MPS: Allowed = Allowed::closed(-100e3, 100e3, "m/s");

/// A row's position at a radius SkyForge supports ([`NEAR_EARTH_RADIUS_M`]) and its
/// velocity (when given) within [`VELOCITY_MPS`].
fn check_row(values: &[f64]) -> Result<(), Invalid> {
    check_position(
        "x_m, y_m, z_m",
        &[values[1], values[2], values[3]],
        NEAR_EARTH_RADIUS_M,
    )?;
    for (name, v) in COLUMNS[4..].iter().zip(values.iter().skip(4)) {
        VELOCITY_MPS.check(name, *v)?;
    }
    Ok(())
}

/// An interpolated ECEF trajectory.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    positions: Hermite3,
}

impl Trajectory {
    /// Reads a trajectory CSV.
    pub fn from_csv(path: &Path) -> Result<Self, PlatformError> {
        let rows = read_numeric_csv(path, &COLUMNS, &[4, 7])?;
        for row in &rows {
            check_row(&row.values).map_err(|e| PlatformError::Csv {
                path: path.display().to_string(),
                line: row.line,
                message: e.to_string(),
            })?;
        }
        let t_s = rows.iter().map(|r| r.values[0]).collect();
        let r: Vec<Vec3> = rows
            .iter()
            .map(|row| Vec3::new(row.values[1], row.values[2], row.values[3]))
            .collect();
        let positions = if rows[0].values.len() == 7 {
            let v = rows
                .iter()
                .map(|row| Vec3::new(row.values[4], row.values[5], row.values[6]))
                .collect();
            Hermite3::with_slopes(t_s, r, v)
        } else {
            Hermite3::with_estimated_slopes(t_s, r)
        };
        Ok(Self { positions })
    }

    /// First and last time covered (s since the scenario start).
    pub fn span(&self) -> (f64, f64) {
        self.positions.span()
    }

    /// Checks that `[t0_s, t1_s]` lies within the data widened by
    /// [`EDGE_MARGIN_S`] on both sides.
    pub fn check_covers(&self, t0_s: f64, t1_s: f64) -> Result<(), PlatformError> {
        let (first_s, last_s) = self.span();
        let allowed = first_s - EDGE_MARGIN_S..=last_s + EDGE_MARGIN_S;
        match [t0_s, t1_s].into_iter().find(|t| !allowed.contains(t)) {
            Some(t_s) => Err(PlatformError::OutsideTrajectory {
                t_s,
                first_s,
                last_s,
            }),
            None => Ok(()),
        }
    }

    /// ECEF position (m) and velocity (m/s) at `t_s`; outside the span the motion continues
    /// at the end velocity.
    pub fn state_ecef(&self, t_s: f64) -> (Vec3, Vec3) {
        self.positions.eval(t_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Write as _;
    use std::path::PathBuf;

    /// A car on a horizontal circle of radius 100 m, 10 m/s (period ~63 s), around a
    /// point 6378 km from the centre.
    fn circle(t: f64) -> (Vec3, Vec3) {
        let (radius, w) = (100.0, 0.1);
        let c = Vec3::new(6_378_137.0, 0.0, 0.0);
        let (s, co) = (w * t).sin_cos();
        (
            c + radius * Vec3::new(0.0, co, s),
            radius * w * Vec3::new(0.0, -s, co),
        )
    }

    fn write_csv(name: &str, with_velocity: bool) -> PathBuf {
        let mut text = String::from("# circle\nt_s,x_m,y_m,z_m");
        text.push_str(if with_velocity {
            ",vx_mps,vy_mps,vz_mps\n"
        } else {
            "\n"
        });
        for k in 0..=200 {
            let t = f64::from(k);
            let (r, v) = circle(t);
            let _ = write!(text, "{t},{:.6},{:.6},{:.6}", r.x, r.y, r.z);
            if with_velocity {
                let _ = write!(text, ",{:.9},{:.9},{:.9}", v.x, v.y, v.z);
            }
            text.push('\n');
        }
        let dir = std::env::temp_dir().join(format!("skyforge-trajectory-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
        path
    }

    #[test]
    fn circle_at_1_hz_within_1_mm() {
        for with_velocity in [true, false] {
            let path = write_csv(&format!("circle-{with_velocity}.csv"), with_velocity);
            let traj = Trajectory::from_csv(&path).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(traj.span(), (0.0, 200.0));
            let (mut worst_r, mut worst_v) = (0.0f64, 0.0f64);
            for k in 0..=2000 {
                let t = 0.1 * f64::from(k) + 0.0137;
                let (r, v) = traj.state_ecef(t.min(200.0));
                let (r0, v0) = circle(t.min(200.0));
                worst_r = worst_r.max((r - r0).norm());
                worst_v = worst_v.max((v - v0).norm());
            }
            assert!(
                worst_r < 1e-3,
                "position error {worst_r} m (velocities given: {with_velocity})"
            );
            assert!(
                worst_v < 1e-3,
                "velocity error {worst_v} m/s (velocities given: {with_velocity})"
            );
        }
    }

    #[test]
    fn outside_the_data_is_an_error() {
        let traj =
            Trajectory::from_csv(&write_csv("span.csv", false)).unwrap_or_else(|e| panic!("{e}"));
        assert!(traj.check_covers(0.0, 200.0).is_ok());
        assert!(
            traj.check_covers(-EDGE_MARGIN_S, 200.0 + EDGE_MARGIN_S)
                .is_ok()
        );
        let late = 200.0 + EDGE_MARGIN_S + 0.5;
        match traj.check_covers(150.0, late) {
            Err(PlatformError::OutsideTrajectory {
                t_s,
                first_s,
                last_s,
            }) => {
                assert_eq!((t_s, first_s, last_s), (late, 0.0, 200.0));
            }
            other => panic!("{other:?}"),
        }
        assert!(traj.check_covers(-EDGE_MARGIN_S - 1.0, 5.0).is_err());
    }

    #[test]
    fn malformed_rows_report_file_and_line() {
        let dir = std::env::temp_dir().join(format!("skyforge-trajectory-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join("bad.csv");
        std::fs::write(&path, "0,1,2,3\n1,1,2,3\n# gap\n1,1,2,3\n")
            .unwrap_or_else(|e| panic!("{e}"));
        match Trajectory::from_csv(&path) {
            Err(PlatformError::Csv { line, message, .. }) => {
                assert_eq!(line, 4);
                assert!(message.contains("strictly increasing"), "{message}");
            }
            other => panic!("{other:?}"),
        }
        std::fs::write(&path, "0,1,2,3,4,5\n").unwrap_or_else(|e| panic!("{e}"));
        let err = Trajectory::from_csv(&path)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            err.contains("bad.csv:1:") && err.contains("t_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps"),
            "{err}"
        );
    }
}
