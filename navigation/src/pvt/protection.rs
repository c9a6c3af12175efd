//! Protection levels of the snapshot residual test (Brown & Chin 1997 slope method; Yuan
//! 2000 section 5.2.3, eqs. 5-10..5-12 written for weighted least squares).
//!
//! With the weighted least-squares estimate x = A z, A = (H^T W H)^-1 H^T W, the residuals
//! are S z with S = I - H A and the test statistic is z^T S^T W S z = z^T W S z. A bias b on
//! satellite i moves the estimate by b A_{.i} and gives the statistic the noncentrality
//! lambda = b^2 (W S)_ii = b^2 S_ii / sigma_i^2 (Yuan 2000 eq. 5-10 with sigma_i in place of
//! the book's common sigma). The horizontal error per square root of noncentrality is the
//! slope
//!
//!   slope_i = sqrt(A_Ni^2 + A_Ei^2) sigma_i / sqrt(S_ii)
//!
//! (eq. 5-10's lambda = R_h^2 / (delta-H(i)^2 sigma^2): the slope is delta-H(i) sigma_i;
//! eq. 5-12 writes delta-H(i) with a factor (m - 4) that belongs to the normalised
//! statistic r = sqrt(D / (m - 4)) of eq. 5-6, not to D, which the receiver tests), and
//! the protection level is the error of the worst satellite at the noncentrality a test
//! detects with probability 1 - P_md: HPL = max_i slope_i sqrt(lambda_det) (eq. 5-10
//! solved for R_h with the largest delta-H(i) of eq. 5-12); VPL likewise with |A_Di|.

use super::exclusion::UNOBSERVABLE_S_II;
use nalgebra::{DMatrix, DVector};

/// Slopes of one satellite: local position error per square root of noncentrality (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slope {
    /// Horizontal (north and east) slope (m).
    pub horizontal_m: f64,
    /// Vertical (down) slope (m).
    pub vertical_m: f64,
}

/// The slopes of every measurement of a weighted least-squares fix.
///
/// `h_local` is the design matrix with its first three columns the local north, east and
/// down position partials (the rest clocks or other states), `weights` the inverse
/// measurement variances. `None` when H^T W H is singular or the sizes disagree.
pub fn slopes(h_local: &DMatrix<f64>, weights: &DVector<f64>) -> Option<Vec<Slope>> {
    let (n, m) = h_local.shape();
    if weights.len() != n || m < 3 || n < m {
        return None;
    }
    let w = DMatrix::from_diagonal(weights);
    let htw = h_local.transpose() * &w;
    let a = (&htw * h_local).try_inverse()? * htw;
    let s = DMatrix::<f64>::identity(n, n) - h_local * &a;
    Some(
        (0..n)
            .map(|i| {
                let s_ii = s[(i, i)];
                let sigma_i = weights[i].recip().sqrt();
                if s_ii < UNOBSERVABLE_S_II {
                    return Slope {
                        horizontal_m: f64::INFINITY,
                        vertical_m: f64::INFINITY,
                    };
                }
                let scale = sigma_i / s_ii.sqrt();
                Slope {
                    horizontal_m: a[(0, i)].hypot(a[(1, i)]) * scale,
                    vertical_m: a[(2, i)].abs() * scale,
                }
            })
            .collect(),
    )
}

/// Yuan 2000 eqs. 5-10 and 5-12 (Brown & Chin 1997): the protection levels (HPL, VPL) (m) of
/// `slopes` at the detection noncentrality `lambda_det`: the largest slope times
/// sqrt(lambda_det).
pub fn protection_levels(slopes: &[Slope], lambda_det: f64) -> (f64, f64) {
    let root = lambda_det.max(0.0).sqrt();
    let max = |f: fn(&Slope) -> f64| slopes.iter().map(f).fold(0.0, f64::max) * root;
    (max(|s| s.horizontal_m), max(|s| s.vertical_m))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pvt::test_geometry::six_satellites;

    #[test]
    fn slopes_match_a_brute_force_bias_injection() {
        // Oracle: for each satellite in turn, a bias b on it alone, the estimate solved by
        // QR of the whitened system (not the normal equations of `slopes`), the statistic
        // from the residuals, b scaled so the statistic equals lambda; the horizontal and
        // vertical error must then be slope * sqrt(lambda).
        let (h, w) = six_satellites();
        let lambda = 37.3;
        let sl = slopes(&h, &w).unwrap();
        let root_w = DMatrix::from_diagonal(&w.map(f64::sqrt));
        let hw = &root_w * &h;
        let qr = hw.clone().qr();
        for (i, s) in sl.iter().enumerate() {
            let error_for = |b: f64| {
                let mut z = DVector::zeros(h.nrows());
                z[i] = b;
                let zw = &root_w * &z;
                let x = qr
                    .r()
                    .solve_upper_triangular(&(qr.q().transpose() * &zw))
                    .unwrap();
                let res = &zw - &hw * &x;
                (x, res.norm_squared())
            };
            let (_, stat_1m) = error_for(1.0);
            let b = (lambda / stat_1m).sqrt();
            let (x, stat) = error_for(b);
            assert!((stat - lambda).abs() < 1e-9 * lambda);
            let hpe = x[0].hypot(x[1]);
            assert!(
                (hpe - s.horizontal_m * lambda.sqrt()).abs() < 1e-9 * hpe.max(1.0),
                "sat {i}: {hpe} vs {}",
                s.horizontal_m * lambda.sqrt()
            );
            assert!((x[2].abs() - s.vertical_m * lambda.sqrt()).abs() < 1e-9 * hpe.max(1.0));
        }
        let (hpl, vpl) = protection_levels(&sl, lambda);
        let worst = sl.iter().map(|s| s.horizontal_m).fold(0.0, f64::max);
        assert_eq!(hpl, worst * lambda.sqrt());
        assert!(vpl > 0.0);
    }

    #[test]
    fn a_satellite_the_test_cannot_see_has_an_infinite_slope() {
        // As many measurements as unknowns: S = 0, no fault shows in the residuals.
        let (h, w) = six_satellites();
        let h4 = h.rows(0, 4).into_owned();
        let w4 = w.rows(0, 4).into_owned();
        let sl = slopes(&h4, &w4).unwrap();
        assert!(sl.iter().all(|s| s.horizontal_m.is_infinite()));
        assert_eq!(slopes(&h, &w4), None);
    }
}
