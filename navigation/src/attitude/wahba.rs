//! Wahba's problem in closed form (Markley's SVD method, J. Astronaut. Sci. 36(3), 1988):
//! the rotation `C` (body -> reference, the thesis' `R(xi)`) minimising
//! `sum_i a_i |v_i - C b_i|^2` over body vectors `b_i` and reference vectors `v_i`.
//!
//! With `M = sum_i a_i v_i b_i^T = U S V^T`, `C = U diag(1, 1, det U det V) V^T`. The vectors
//! are used as given (not normalised), so with equal weights this is exactly the LS cost
//! of eqs. 2.5-9..2.5-12 with `Q_BB = s^2 I`; with other weights it is the start value of
//! that LS.

use super::{AttitudeError, BodyGeometry, NedBaselines, YawPitchRoll};
use skyforge_orbits::{Mat3, Vec3};

/// Ratio of the second-largest to the largest singular value of `M` below which the
/// rotation is not determined (the pairs are collinear).
const MIN_SINGULAR_RATIO: f64 = 1e-9;

/// The optimal rotation `C` (body -> reference) for `(body, reference, weight)` pairs.
/// Needs at least two non-collinear pairs and positive finite weights.
pub fn wahba_svd(pairs: &[(Vec3, Vec3, f64)]) -> Result<Mat3, AttitudeError> {
    if pairs.iter().any(|(b, v, a)| {
        !(a.is_finite() && *a > 0.0 && b.iter().chain(v.iter()).all(|x| x.is_finite()))
    }) {
        return Err(AttitudeError::Measurement(
            "Wahba: vectors must be finite and weights finite and > 0".into(),
        ));
    }
    let m: Mat3 = pairs
        .iter()
        .map(|(b, v, a)| *a * v * b.transpose())
        .fold(Mat3::zeros(), |acc, x| acc + x);
    let svd = m.svd(true, true);
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
        return Err(AttitudeError::Singular(
            "Wahba: SVD did not converge".into(),
        ));
    };
    let s = svd.singular_values;
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| s[j].total_cmp(&s[i]));
    let determined = s[order[1]] > MIN_SINGULAR_RATIO * s[order[0]];
    if !determined {
        return Err(AttitudeError::Singular(
            "Wahba: the vector pairs are collinear, the rotation about them is undetermined".into(),
        ));
    }
    let d = u.determinant() * v_t.determinant();
    let mut diag = Vec3::new(1.0, 1.0, 1.0);
    diag[order[2]] = d.signum();
    Ok(u * Mat3::from_diagonal(&diag) * v_t)
}

/// The Wahba attitude of one epoch: body baselines paired with the measured ones, each
/// weighted by `3 / trace(Q_ii)` (its own 3x3 covariance block; the cross-covariances are
/// left to the LS it starts).
pub fn wahba_attitude(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
) -> Result<YawPitchRoll, AttitudeError> {
    geometry.check_count(measured)?;
    if geometry.len() < 2 {
        return Err(AttitudeError::SingleBaseline);
    }
    let q = measured.covariance();
    let pairs: Vec<(Vec3, Vec3, f64)> = geometry
        .baselines()
        .iter()
        .zip(measured.baselines())
        .enumerate()
        .map(|(i, (b, v))| {
            let tr = q[(3 * i, 3 * i)] + q[(3 * i + 1, 3 * i + 1)] + q[(3 * i + 2, 3 * i + 2)];
            (*b, *v, 3.0 / tr)
        })
        .collect();
    let c_body_ref = wahba_svd(&pairs)?;
    Ok(YawPitchRoll::from_c_ref_body(&c_body_ref.transpose()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_an_exact_rotation() {
        let truth = YawPitchRoll::new(-2.9, 0.4, 1.1);
        let c = truth.c_body_ref();
        let bodies = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.3, 1.2, -0.2)];
        let pairs: Vec<_> = bodies.iter().map(|b| (*b, c * b, 1.0)).collect();
        let est = wahba_svd(&pairs).unwrap();
        assert!((est - c).amax() < 1e-13);
    }

    #[test]
    fn collinear_pairs_are_an_error() {
        let pairs = [
            (Vec3::x(), Vec3::y(), 1.0),
            (2.0 * Vec3::x(), 2.0 * Vec3::y(), 1.0),
        ];
        assert!(matches!(wahba_svd(&pairs), Err(AttitudeError::Singular(_))));
        assert!(wahba_svd(&[(Vec3::x(), Vec3::y(), f64::NAN)]).is_err());
    }
}
