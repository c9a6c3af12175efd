//! `skyforge validate ins`: a GNSS/INS solution (`ins.csv`) against the IMU's truth
//! (`imu.h5`): position errors while GNSS updates the filter, and the drift over each
//! GNSS outage made on purpose, `|e(end) - e(start)|` between the last updated epoch
//! before the outage and its last epoch (how far the INS alone wandered, whatever the
//! GNSS fixes' own error when it began); and the attitude's errors, yaw (heading), pitch
//! and roll from the local NED frame, at the first solution (what the alignment left) and
//! as RMS over the updated epochs.

use crate::attitude::compare::attitude_errors_deg;
use nalgebra::{Quaternion, UnitQuaternion};
use serde::Serialize;
use skyforge_formats::imu::{ImuH5, ImuRow};
use skyforge_formats::ins::InsRow;
use skyforge_navigation::gnss_ins::ImuNoise;
use skyforge_navigation::ins::attitude_ned;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::{YawPitchRoll, c_ecef_ned, ecef_to_geodetic};
use skyforge_signals::imu::{AccelSpec, GyroSpec, TriadErrors};

/// One outage's drift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OutageDrift {
    /// Seconds from the first solution to the outage's start and end.
    pub start_s: f64,
    pub end_s: f64,
    /// The drift (m): 3-D and horizontal.
    pub drift_3d_m: f64,
    pub drift_horizontal_m: f64,
}

/// The comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InsComparison {
    /// Solutions compared, and how many of them a fix updated.
    pub epochs: usize,
    pub updated: usize,
    /// RMS of the 3-D and horizontal position errors over the updated epochs (m).
    pub rms_3d_m: f64,
    pub rms_horizontal_m: f64,
    /// Estimated minus true yaw, pitch and roll (deg) at the first solution: what the
    /// alignment left.
    pub first_attitude_error_deg: [f64; 3],
    /// RMS of the yaw, pitch and roll errors over the updated epochs (deg).
    pub rms_attitude_deg: [f64; 3],
    /// Every complete outage, in order.
    pub outages: Vec<OutageDrift>,
}

impl InsComparison {
    /// RMS over the outages of their 3-D drift (m); `None` without outages.
    pub fn rms_outage_drift_3d_m(&self) -> Option<f64> {
        let n = self.outages.len();
        (n > 0).then(|| {
            (self
                .outages
                .iter()
                .map(|o| o.drift_3d_m.powi(2))
                .sum::<f64>()
                / n as f64)
                .sqrt()
        })
    }
}

/// The truth row at `row`'s time.
fn truth_at<'a>(row: &InsRow, truth: &'a ImuH5) -> Result<&'a ImuRow, String> {
    let t_s = (row.t - truth.start).to_seconds();
    let k = truth.rows.partition_point(|r| r.t_s < t_s - 1e-6);
    match truth.rows.get(k) {
        Some(r) if (r.t_s - t_s).abs() <= 1e-6 => Ok(r),
        _ => Err(format!(
            "no truth sample at {} ({t_s} s into imu.h5)",
            row.t
        )),
    }
}

/// `row`'s errors against its truth row: position (ECEF, m), and yaw, pitch, roll (deg).
fn errors(row: &InsRow, truth: &ImuRow) -> (Vec3, [f64; 3]) {
    let [w, x, y, z] = truth.q_body_ecef;
    let c = UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
    let true_attitude = attitude_ned(
        &c.to_rotation_matrix().into_inner(),
        &ecef_to_geodetic(&truth.r_ecef_m),
    );
    let ypr = row.ypr_deg.map(f64::to_radians);
    let estimate = YawPitchRoll {
        yaw_rad: ypr.x,
        pitch_rad: ypr.y,
        roll_rad: ypr.z,
    };
    (
        row.r_ecef_m - truth.r_ecef_m,
        attitude_errors_deg(&estimate, &true_attitude),
    )
}

/// The horizontal part of `e` at `r`.
fn horizontal(e: &Vec3, r: &Vec3) -> f64 {
    let g = ecef_to_geodetic(r);
    let ned = c_ecef_ned(g.lat_rad, g.lon_rad) * e;
    ned.x.hypot(ned.y)
}

/// Compares `rows` with `truth`, which must hold a sample at every row's time.
pub fn compare_ins(rows: &[InsRow], truth: &ImuH5) -> Result<InsComparison, String> {
    let first = rows.first().ok_or("ins.csv holds no solution")?;
    let (errors, attitude): (Vec<Vec3>, Vec<[f64; 3]>) = rows
        .iter()
        .map(|r| truth_at(r, truth).map(|t| errors(r, t)))
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip();
    let updated: Vec<usize> = (0..rows.len()).filter(|&k| rows[k].gnss).collect();
    let mean_square = |f: &dyn Fn(usize) -> f64| {
        (updated.iter().map(|&k| f(k).powi(2)).sum::<f64>() / updated.len().max(1) as f64).sqrt()
    };
    let mut outages = Vec::new();
    let mut k = 0;
    while k < rows.len() {
        if !rows[k].outage || k == 0 {
            k += 1;
            continue;
        }
        let start = k - 1;
        let end = (k..rows.len())
            .take_while(|&j| rows[j].outage)
            .last()
            .unwrap_or(k);
        if end + 1 < rows.len() {
            let d = errors[end] - errors[start];
            let since = |j: usize| (rows[j].t - first.t).to_seconds();
            outages.push(OutageDrift {
                start_s: since(start),
                end_s: since(end),
                drift_3d_m: d.norm(),
                drift_horizontal_m: horizontal(&d, &rows[end].r_ecef_m),
            });
        }
        k = end + 1;
    }
    Ok(InsComparison {
        epochs: rows.len(),
        updated: updated.len(),
        rms_3d_m: mean_square(&|k| errors[k].norm()),
        rms_horizontal_m: mean_square(&|k| horizontal(&errors[k], &rows[k].r_ecef_m)),
        first_attitude_error_deg: attitude[0],
        rms_attitude_deg: [0, 1, 2].map(|i| mean_square(&|k| attitude[k][i])),
        outages,
    })
}

/// The comparison as text.
pub fn print_ins(c: &InsComparison, out: &mut impl std::io::Write) -> std::io::Result<()> {
    writeln!(
        out,
        "epochs     {} ({} updated by a GNSS fix)",
        c.epochs, c.updated
    )?;
    writeln!(
        out,
        "position   RMS 3-D {:.3} m, horizontal {:.3} m (updated epochs)",
        c.rms_3d_m, c.rms_horizontal_m
    )?;
    let [y, p, r] = c.first_attitude_error_deg;
    writeln!(
        out,
        "aligned    yaw {y:.4} pitch {p:.4} roll {r:.4} deg off (the first solution)"
    )?;
    let [y, p, r] = c.rms_attitude_deg;
    writeln!(
        out,
        "attitude   RMS yaw {y:.4} pitch {p:.4} roll {r:.4} deg (updated epochs)"
    )?;
    for o in &c.outages {
        writeln!(
            out,
            "outage     {:.1}-{:.1} s: drift 3-D {:.3} m, horizontal {:.3} m",
            o.start_s, o.end_s, o.drift_3d_m, o.drift_horizontal_m
        )?;
    }
    if let Some(rms) = c.rms_outage_drift_3d_m() {
        writeln!(
            out,
            "outages    {} complete, RMS of the 3-D drift {rms:.3} m",
            c.outages.len()
        )?;
    }
    Ok(())
}

/// An INS filter's model of an IMU from its data sheet (a grade's or the user's): white
/// noise, and each bias a constant (no instability) or a Gauss-Markov process of the
/// instability's correlation time with the turn-on and instability sigmas combined.
/// Scale factors and misalignments are left out: errors the filter does not know.
pub fn filter_noise((gyro, accel): (GyroSpec, AccelSpec)) -> ImuNoise {
    let (g, a) = (TriadErrors::from(gyro), TriadErrors::from(accel));
    let tau = |t: &TriadErrors| (t.instability > 0.0).then_some(t.instability_tau_s);
    ImuNoise {
        gyro_arw: g.density,
        accel_vrw: a.density,
        gyro_bias: g.bias.hypot(g.instability),
        gyro_bias_tau_s: tau(&g),
        accel_bias: a.bias.hypot(a.instability),
        accel_bias_tau_s: tau(&a),
    }
}
