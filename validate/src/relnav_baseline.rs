//! The baseline of `skyforge relnav`'s `double-difference` estimates against the truth,
//! free of the target frame's orientation: each estimate's Earth-fixed baseline (chaser
//! minus target, `relnav.csv`'s `bx_ecef_m..`) minus the truth's (the two vehicles'
//! `truth.h5` centres of mass, cubic Hermite between geometry epochs), that error then
//! expressed in the target's true orbit frame (x along-track, y negative orbit normal, z
//! nadir). The estimates' own frame comes from the target's estimated orbit: across
//! 200 km, 1e-7 rad of its orientation (0.7 m of along-track position, 0.8 mm/s of
//! cross-track velocity) is 2 cm of position in that frame, an error of the target's
//! absolute orbit, not of the relative navigation. Also the fraction of the
//! double-difference ambiguities fixed.

use serde::Serialize;
use skyforge_formats::FormatError;
use skyforge_formats::relative::RelativeRow;
use skyforge_formats::truth::{PlatformSeries, TRUTH_H5, TruthFile};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;
use std::path::Path;

/// Most geometry epochs read from a truth file (48 days at 1 Hz).
const MAX_ROWS: usize = 1 << 22;

/// The double-difference ambiguities over the compared estimates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FixedFraction {
    pub fixed: usize,
    pub float: usize,
    /// `fixed / (fixed + float)` (NaN without any).
    pub fraction: f64,
}

/// What [`compare_baselines`] measured.
#[derive(Debug, Clone, PartialEq)]
pub struct BaselineErrors {
    /// Each compared estimate's error in the target's true orbit frame (m), from the
    /// settling time on, inside the truth.
    pub errors: Vec<Vec3>,
    pub ambiguities: Option<FixedFraction>,
}

/// The position and velocity of `s` at `t_s` (cubic Hermite between its epochs).
fn hermite(s: &PlatformSeries, t_s: f64) -> Option<(Vec3, Vec3)> {
    let k = s.t_s.partition_point(|&t| t <= t_s);
    let (i, j) = if k == s.t_s.len() {
        // At the last epoch (within a millisecond), or past the truth.
        let i = k.checked_sub(2)?;
        (t_s - s.t_s[k - 1] < 1e-3).then_some((i, i + 1))?
    } else {
        (k.checked_sub(1)?, k)
    };
    let h = s.t_s[j] - s.t_s[i];
    let u = (t_s - s.t_s[i]) / h;
    let (p0, p1, m0, m1) = (
        s.r_ecef_m[i],
        s.r_ecef_m[j],
        s.v_ecef_mps[i] * h,
        s.v_ecef_mps[j] * h,
    );
    let (u2, u3) = (u * u, u * u * u);
    let r = p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
        + m0 * (u3 - 2.0 * u2 + u)
        + p1 * (-2.0 * u3 + 3.0 * u2)
        + m1 * (u3 - u2);
    let v = (p0 * (6.0 * u2 - 6.0 * u)
        + m0 * (3.0 * u2 - 4.0 * u + 1.0)
        + p1 * (-6.0 * u2 + 6.0 * u)
        + m1 * (3.0 * u2 - 2.0 * u))
        / h;
    Some((r, v))
}

/// Compare the baselines of `estimates` (one vehicle relative to one target, with
/// `baseline_ecef_m`) from `settle_s` seconds after the first on with the vehicles'
/// truth in `truth_dir` (`<name>/truth.h5`); `None` when no estimate has a baseline.
pub fn compare_baselines(
    truth_dir: &Path,
    estimates: &[RelativeRow],
    settle_s: f64,
) -> Result<Option<BaselineErrors>, FormatError> {
    let Some(first) = estimates.first() else {
        return Ok(None);
    };
    if estimates.iter().all(|e| e.baseline_ecef_m.is_none()) {
        return Ok(None);
    }
    let open = |name: &str| -> Result<(hifitime::Epoch, PlatformSeries), FormatError> {
        let f = TruthFile::open(&truth_dir.join(name).join(TRUTH_H5))?;
        Ok((f.start_epoch()?, f.platform(MAX_ROWS)?))
    };
    let (start, target) = open(&first.target)?;
    let (_, vehicle) = open(&first.vehicle)?;
    let earth = EarthRotation::at_origin(start);
    let (mut errors, mut fixed, mut float) = (Vec::new(), 0, 0);
    for e in estimates {
        let Some(b) = e.baseline_ecef_m else {
            continue;
        };
        if (e.time - first.time).to_seconds() < settle_s {
            continue;
        }
        let t = (e.time - start).to_seconds();
        let (Some((rt, vt)), Some((rc, _))) = (hermite(&target, t), hermite(&vehicle, t)) else {
            continue;
        };
        let (rt_eci, vt_eci) = earth.ecef_to_eci(t, &rt, &vt);
        let c = earth.c_eci_ecef(t);
        let error_eci = c.transpose() * (b - (rc - rt));
        let (in_frame, _) = relative_in_frame_of(&rt_eci, &vt_eci, &error_eci, &Vec3::zeros());
        errors.push(in_frame);
        if let Some(a) = e.ambiguities {
            fixed += a.fixed;
            float += a.float;
        }
    }
    if errors.is_empty() {
        return Ok(None);
    }
    let ambiguities = (fixed + float > 0).then(|| FixedFraction {
        fixed,
        float,
        fraction: fixed as f64 / (fixed + float) as f64,
    });
    Ok(Some(BaselineErrors {
        errors,
        ambiguities,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circular orbit sampled every second: Hermite between the samples is within a
    /// micrometre of the orbit (linear interpolation would be 1 m off mid-way).
    #[test]
    fn hermite_follows_an_orbit_between_samples() {
        let (r, n) = (6.878e6_f64, 1.1e-3_f64);
        let at = |t: f64| {
            let (s, c) = (n * t).sin_cos();
            (
                Vec3::new(r * c, r * s, 0.0),
                Vec3::new(-r * n * s, r * n * c, 0.0),
            )
        };
        let t_s: Vec<f64> = (0..10).map(f64::from).collect();
        let series = PlatformSeries {
            r_ecef_m: t_s.iter().map(|&t| at(t).0).collect(),
            v_ecef_mps: t_s.iter().map(|&t| at(t).1).collect(),
            q_body_ecef: vec![Default::default(); t_s.len()],
            t_s,
        };
        for t in [0.0, 0.37, 4.5, 8.999, 9.0] {
            let (p, v) = hermite(&series, t).unwrap();
            assert!((p - at(t).0).norm() < 1e-6, "{t}: {}", (p - at(t).0).norm());
            assert!((v - at(t).1).norm() < 1e-6, "{t}");
        }
        assert!(hermite(&series, 9.5).is_none());
        assert!(hermite(&series, -0.5).is_none());
    }
}
