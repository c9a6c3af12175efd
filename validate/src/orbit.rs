//! `skyforge validate od`: an estimated orbit (`orbit.h5` of `skyforge od`) against the
//! truth's (`truth.h5` of the run), after a settling time: errors per axis in the truth's
//! orbit frame (radial, along-track, cross-track) and in ECEF, 3-D RMS, and whether the
//! filter's covariance describes its errors (mean position NEES, expected 3, and the
//! fraction of ECEF axis errors inside 3 sigma, expected 0.997 for Gaussian errors).

use crate::observables::ErrorStats;
use crate::stats::rms;
use serde::Serialize;
use skyforge_formats::FormatError;
use skyforge_formats::orbit::{OrbitH5, read_h5};
use skyforge_formats::truth::TruthFile;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::frames::c_rac_eci;
use skyforge_orbits::platform::Hermite3;
use std::path::Path;

/// Most truth epochs read (48 days at 1 Hz).
const MAX_TRUTH_ROWS: usize = 1 << 22;

/// Mean, standard deviation and RMS of one axis's errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AxisErrors {
    pub mean: f64,
    pub std: f64,
    pub rms: f64,
}

impl AxisErrors {
    fn of(values: &[f64]) -> Self {
        let s = ErrorStats::of(values);
        Self {
            mean: s.mean.unwrap_or(f64::NAN),
            std: s.std.unwrap_or(f64::NAN),
            rms: rms(values),
        }
    }
}

/// Errors of one quantity (position or velocity) per axis of two frames.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrameErrors {
    /// Radial, along-track, cross-track (the truth's orbit frame).
    pub rac: [AxisErrors; 3],
    pub ecef: [AxisErrors; 3],
    /// RMS of the 3-D error.
    pub rms_3d: f64,
}

/// What `validate od` measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OrbitComparison {
    pub filter: String,
    /// Estimates in the file, and those compared (after `settle_s`, inside the truth).
    pub estimates: usize,
    pub compared: usize,
    pub settle_s: f64,
    /// Position errors (m) and velocity errors (m/s).
    pub position_m: FrameErrors,
    pub velocity_mps: FrameErrors,
    /// Mean of `e' P^-1 e` over the compared position errors (3 when the covariance is
    /// right).
    pub position_nees_mean: f64,
    /// Fraction of ECEF position axis errors within 3 of the filter's sigmas.
    pub position_within_3_sigma: f64,
}

/// The quantity's errors per axis in both frames.
fn frame_errors(ecef: &[Vec3], rac: &[Vec3]) -> FrameErrors {
    let axes = |v: &[Vec3]| -> [AxisErrors; 3] {
        std::array::from_fn(|i| AxisErrors::of(&v.iter().map(|e| e[i]).collect::<Vec<_>>()))
    };
    FrameErrors {
        rac: axes(rac),
        ecef: axes(ecef),
        rms_3d: rms(&ecef.iter().map(|e| e.norm()).collect::<Vec<_>>()),
    }
}

/// Compare the orbit at `orbit_h5` with the truth at `truth_h5`, leaving out the
/// estimates of the first `settle_s` seconds of the orbit file.
pub fn compare_orbit(
    truth_h5: &Path,
    orbit_h5: &Path,
    settle_s: f64,
) -> Result<OrbitComparison, FormatError> {
    let truth = TruthFile::open(truth_h5)?;
    let truth_start = truth.start_epoch()?;
    let platform = truth.platform(MAX_TRUTH_ROWS)?;
    let orbit = read_h5(orbit_h5)?;
    let offset_s = (orbit.start - truth_start).to_seconds();
    let (first, last) = (platform.t_s[0], platform.t_s[platform.t_s.len() - 1]);
    let path = Hermite3::with_slopes(platform.t_s, platform.r_ecef_m, platform.v_ecef_mps);
    let mut errors = Errors::default();
    for k in 0..orbit.t_s.len() {
        let t = orbit.t_s[k] + offset_s;
        if orbit.t_s[k] < settle_s || t < first || t > last {
            continue;
        }
        let (r, v) = path.eval(t);
        errors.push(&orbit, k, &r, &v);
    }
    if errors.dr_ecef.is_empty() {
        return Err(FormatError::file(
            orbit_h5,
            format!(
                "no estimate after {settle_s} s inside the truth's span ({} estimates; truth \
                 from {first} s to {last} s of its run, the orbit's start {offset_s} s into it)",
                orbit.t_s.len()
            ),
        ));
    }
    let n = errors.dr_ecef.len();
    Ok(OrbitComparison {
        filter: orbit.filter.clone(),
        estimates: orbit.t_s.len(),
        compared: n,
        settle_s,
        position_m: frame_errors(&errors.dr_ecef, &errors.dr_rac),
        velocity_mps: frame_errors(&errors.dv_ecef, &errors.dv_rac),
        position_nees_mean: errors.nees.iter().sum::<f64>() / n as f64,
        position_within_3_sigma: errors.within as f64 / (3 * n) as f64,
    })
}

/// The errors gathered so far.
#[derive(Default)]
struct Errors {
    dr_ecef: Vec<Vec3>,
    dv_ecef: Vec<Vec3>,
    dr_rac: Vec<Vec3>,
    dv_rac: Vec<Vec3>,
    nees: Vec<f64>,
    within: usize,
}

impl Errors {
    /// Estimate `k` of `orbit` against the truth's `r`, `v` (ECEF) at its time.
    fn push(&mut self, orbit: &OrbitH5, k: usize, r: &Vec3, v: &Vec3) {
        let dr = orbit.r_ecef_m[k] - r;
        let dv = orbit.v_ecef_mps[k] - v;
        // The orbit frame of the inertial velocity, in ECEF axes.
        let v_inertial = v + Vec3::new(0.0, 0.0, OMEGA_E_GPS).cross(r);
        let c = c_rac_eci(r, &v_inertial).transpose();
        let p = nalgebra::Matrix3::from_fn(|i, j| orbit.covariance[k][6 * i + j]);
        let nees = p
            .try_inverse()
            .map_or(f64::NAN, |pi| (dr.transpose() * pi * dr)[0]);
        self.within += (0..3)
            .filter(|&i| dr[i].abs() <= 3.0 * p[(i, i)].max(0.0).sqrt())
            .count();
        self.dr_ecef.push(dr);
        self.dv_ecef.push(dv);
        self.dr_rac.push(c * dr);
        self.dv_rac.push(c * dv);
        self.nees.push(nees);
    }
}

/// The comparison as a table.
pub fn print_orbit(c: &OrbitComparison, out: &mut impl std::io::Write) -> std::io::Result<()> {
    writeln!(
        out,
        "orbit      {} estimates of {}, {} compared (after {} s)",
        c.estimates, c.filter, c.compared, c.settle_s
    )?;
    writeln!(
        out,
        "{:<22}{:>12}{:>12}{:>12}",
        "error (mean/std/rms)", "radial", "along", "cross"
    )?;
    let row = |name: &str, a: &[AxisErrors; 3], digits: usize| {
        let cells: Vec<String> = a
            .iter()
            .map(|x| format!("{:>12}", format!("{:.d$}", x.rms, d = digits)))
            .collect();
        let means: Vec<String> = a
            .iter()
            .map(|x| format!("{:.d$}/{:.d$}", x.mean, x.std, d = digits))
            .collect();
        format!(
            "{name:<22}{}   (mean/std {})",
            cells.concat(),
            means.join(", ")
        )
    };
    writeln!(out, "{}", row("position RMS (m)", &c.position_m.rac, 3))?;
    writeln!(out, "{}", row("velocity RMS (m/s)", &c.velocity_mps.rac, 5))?;
    writeln!(
        out,
        "3-D RMS    position {:.3} m, velocity {:.5} m/s",
        c.position_m.rms_3d, c.velocity_mps.rms_3d
    )?;
    writeln!(
        out,
        "covariance position NEES mean {:.2} (3 if consistent), {:.1} % of axis errors within 3 sigma",
        c.position_nees_mean,
        100.0 * c.position_within_3_sigma
    )
}
