//! Covariances outside the accepted range.

use super::*;

/// Issue #32 (6): a variance of 1e308 made both squared norms 0 and the ratio 0/0 (NaN);
/// larger correlated ones overflowed into "not positive definite", tiny ones into
/// errors about non-finite values or positive definiteness. Covariances outside
/// `[MIN_VARIANCE, MAX_VARIANCE]` are refused, naming the entry, its value and the range.
#[test]
fn covariances_outside_the_range_are_refused() {
    let a = DVector::from_vec(vec![0.3, -1.2, 2.45]);
    let scaled =
        |s: f64| DMatrix::from_row_slice(3, 3, &[1.0, 0.2, 0.1, 0.2, 1.0, 0.3, 0.1, 0.3, 1.0]) * s;
    let mut huge_offdiagonal = scaled(1.0);
    huge_offdiagonal[(2, 0)] = 1e200;
    huge_offdiagonal[(0, 2)] = 1e200;
    let mut tiny_variance = DMatrix::identity(3, 3);
    tiny_variance[(1, 1)] = 1e-320;
    let one = DVector::from_vec(vec![0.3]);
    for (a, q, entry) in [
        (&one, DMatrix::from_element(1, 1, 1e308), "Q[0][0] = 1e308"),
        (&a, scaled(1e308), "Q[0][0] = 1e308"),
        (&a, scaled(1e150), "Q[0][0] = 1e150"),
        (&a, huge_offdiagonal, "Q[2][0] = 1e200"),
        (&a, tiny_variance, "Q[1][1] = 1e-320"),
    ] {
        let err = lambda(a, &q, 2).unwrap_err();
        let msg = err.to_string();
        assert!(
            matches!(err, AmbiguityError::CovarianceOutOfRange { .. }),
            "{msg}"
        );
        assert!(
            msg.contains(entry) && msg.contains("1e-100") && msg.contains("1e100"),
            "{msg}"
        );
        assert_eq!(bootstrapped_success_rate(&q).unwrap_err(), err);
        assert!(matches!(
            partial(a, &q, 0.9),
            Err(AmbiguityError::CovarianceOutOfRange { .. })
        ));
    }
    // At the ends of the range the norms and the ratio are finite and positive.
    for s in [MAX_VARIANCE, MIN_VARIANCE * 1.0001] {
        let sol = lambda(&a, &scaled(s), 2).unwrap();
        let ratio = sol.ratio().unwrap();
        assert!(
            sol.best().squared_norm > 0.0 && ratio.is_finite() && ratio >= 1.0,
            "scale {s:e}"
        );
        assert_eq!(sol.best().integers, vec![0, -1, 2], "scale {s:e}");
    }
}
