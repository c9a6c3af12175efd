//! Large well-conditioned problems against independent oracles, many candidates against
//! exhaustive enumeration, and covariances outside the accepted range.

use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A diagonal problem in the coordinates `w = U a` (`U` unimodular): `a_hat = V w_hat`,
/// `Q = V diag(var) V^T` with `V = U^{-1}` a unit lower-triangular integer matrix
/// (`V = I` gives a diagonal `Q`). ILS then rounds each `w_hat_j`: the best candidate is
/// `V round(w_hat)`, and the second-best moves the one `w_j` whose second-nearest
/// integer costs least, `(1 - 2 |y_j|) / var_j` with `y_j = w_hat_j - round(w_hat_j)`.
struct Separable {
    a_hat: DVector<f64>,
    q: DMatrix<f64>,
    v: Vec<Vec<i64>>,
    w_hat: Vec<f64>,
    var: Vec<f64>,
}

impl Separable {
    /// `extra` random `+-1` entries below the diagonal of `V` (0: `Q` diagonal).
    fn new(rng: &mut ChaCha8Rng, n: usize, var: Vec<f64>, extra: usize) -> Self {
        let mut v: Vec<Vec<i64>> = (0..n)
            .map(|i| (0..n).map(|j| i64::from(i == j)).collect())
            .collect();
        for _ in 0..extra {
            let i = rng.random_range(1..n);
            let j = rng.random_range(0..i);
            v[i][j] += if rng.random_bool(0.5) { 1 } else { -1 };
        }
        let w_hat: Vec<f64> = (0..n).map(|_| rng.random_range(-1000.0..1000.0)).collect();
        let vf = DMatrix::from_fn(n, n, |i, j| v[i][j] as f64);
        let a_hat = &vf * DVector::from_column_slice(&w_hat);
        let q = &vf * DMatrix::from_diagonal(&DVector::from_column_slice(&var)) * vf.transpose();
        Self {
            a_hat,
            q,
            v,
            w_hat,
            var,
        }
    }

    fn to_a(&self, w: &[i64]) -> Vec<i64> {
        self.v
            .iter()
            .map(|row| row.iter().zip(w).map(|(x, y)| x * y).sum())
            .collect()
    }

    /// The best and second-best `a` with their squared norms, and the gap between the
    /// two cheapest moves (the second-best is unique when it is clearly positive).
    fn oracle(&self) -> (Integers, Integers, f64) {
        let w: Vec<i64> = self.w_hat.iter().map(|x| x.round() as i64).collect();
        let y: Vec<f64> = self
            .w_hat
            .iter()
            .zip(&w)
            .map(|(a, b)| a - *b as f64)
            .collect();
        let best: f64 = y.iter().zip(&self.var).map(|(y, v)| y * y / v).sum();
        let mut moves: Vec<(f64, usize)> = y
            .iter()
            .zip(&self.var)
            .enumerate()
            .map(|(j, (y, v))| ((1.0 - 2.0 * y.abs()) / v, j))
            .collect();
        moves.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (cost, j) = moves[0];
        let mut w2 = w.clone();
        w2[j] += if y[j] > 0.0 { 1 } else { -1 };
        (
            (self.to_a(&w), best),
            (self.to_a(&w2), best + cost),
            moves[1].0 - cost,
        )
    }
}

/// An integer vector and its squared norm.
type Integers = (Vec<i64>, f64);

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Issue #32 (6): with 100 and 500 ambiguities of a diagonal covariance (identity, or
/// variances 0.02..0.5), or one that is diagonal after an integer change of coordinates,
/// the search stopped at its node limit; the two best candidates and their norms are
/// those of rounding.
#[test]
fn diagonal_problems_of_100_and_500_ambiguities_are_rounded() {
    let mut rng = ChaCha8Rng::seed_from_u64(326);
    for n in [100, 500] {
        let identity = vec![1.0; n];
        let spread: Vec<f64> = (0..n).map(|_| rng.random_range(0.02..0.5)).collect();
        for (var, extra) in [(identity, 0), (spread.clone(), 0), (spread, n)] {
            let p = Separable::new(&mut rng, n, var, extra);
            let sol = lambda(&p.a_hat, &p.q, 2).unwrap();
            let ((a1, n1), (a2, n2), gap) = p.oracle();
            assert_eq!(sol.candidates[0].integers, a1, "n {n}, extra {extra}");
            assert!(rel(sol.candidates[0].squared_norm, n1) < 1e-9, "n {n}");
            assert!(rel(sol.candidates[1].squared_norm, n2) < 1e-9, "n {n}");
            if gap > 1e-6 {
                assert_eq!(sol.candidates[1].integers, a2, "n {n}, extra {extra}");
            }
        }
    }
}

/// `Q = 0.05 I` plus off-diagonal entries up to `eps * 0.05`, 100 and 500 ambiguities,
/// `a_hat` uniform or integers plus noise of covariance `Q`: solved (the search stopped at
/// its node limit), the norms are those of the candidates (from `Q^{-1}` by Cholesky), and
/// no vector one unit step from the best in one or two ambiguities is better than the
/// second-best.
#[test]
fn nearly_diagonal_problems_of_100_and_500_ambiguities_are_solved() {
    let mut rng = ChaCha8Rng::seed_from_u64(3262);
    for (n, eps, uniform) in [
        (100, 1e-3, true),
        (100, 1e-3, false),
        (500, 1e-5, true),
        (500, 1e-4, false),
    ] {
        let mut q = DMatrix::identity(n, n) * 0.05;
        for i in 0..n {
            for j in 0..i {
                let e = eps * 0.05 * rng.random_range(-1.0..1.0);
                q[(i, j)] = e;
                q[(j, i)] = e;
            }
        }
        let chol = q.clone().cholesky().unwrap();
        let a_hat = if uniform {
            DVector::from_fn(n, |_, _| rng.random_range(-1000.0..1000.0))
        } else {
            let noise = chol.l()
                * DVector::from_fn(n, |_, _| rng.sample::<f64, _>(rand_distr::StandardNormal));
            DVector::from_fn(n, |i, _| {
                f64::from(rng.random_range(-1000..1000)) + noise[i]
            })
        };
        let sol = lambda(&a_hat, &q, 2).unwrap();
        let w = chol.inverse();
        let residual = |a: &[i64]| DVector::from_fn(n, |i, _| a_hat[i] - a[i] as f64);
        for c in &sol.candidates {
            let r = residual(&c.integers);
            let direct = r.dot(&(&w * &r));
            assert!(
                rel(c.squared_norm, direct) < 1e-9,
                "n {n}: {} vs {direct}",
                c.squared_norm
            );
        }
        // |r - s e_i - t e_j|^2_W = N - 2 (s g_i + t g_j) + W_ii + W_jj + 2 s t W_ij.
        let best = sol.candidates[0].squared_norm;
        let second = sol.candidates[1].squared_norm * (1.0 - 1e-9);
        let g = &w * residual(&sol.candidates[0].integers);
        for i in 0..n {
            for s in [-1.0, 1.0] {
                let one = best - 2.0 * s * g[i] + w[(i, i)];
                assert!(one >= second, "n {n}: a[{i}] {s:+} gives {one}");
                for j in 0..i {
                    for t in [-1.0, 1.0] {
                        let two = one - 2.0 * t * g[j] + w[(j, j)] + 2.0 * s * t * w[(i, j)];
                        assert!(
                            two >= second,
                            "n {n}: a[{i}] {s:+}, a[{j}] {t:+} gives {two}"
                        );
                    }
                }
            }
        }
    }
}

/// The `count` integer vectors `w` nearest to `w_hat` in the metric of `q0^{-1}`, by
/// enumerating the box `|w_i - w_hat_i| <= sqrt(chi2 q0_ii)`, where `chi2` is the
/// `count`-th smallest norm of a smaller box around `round(w_hat)` (every vector with a
/// norm up to `chi2` lies in the larger box, so the `count` best do).
fn enumerate(w_hat: &DVector<f64>, q0: &DMatrix<f64>, count: usize) -> Vec<Integers> {
    let n = w_hat.len();
    let w = q0.clone().cholesky().unwrap().inverse();
    let norm = |k: &[i64]| {
        let r = DVector::from_fn(n, |i, _| w_hat[i] - k[i] as f64);
        r.dot(&(&w * &r))
    };
    let best_in = |lo: &[i64], hi: &[i64]| {
        let mut all = Vec::new();
        let mut k = lo.to_vec();
        'odometer: loop {
            all.push((k.clone(), norm(&k)));
            for i in 0..n {
                if k[i] < hi[i] {
                    k[i] += 1;
                    continue 'odometer;
                }
                k[i] = lo[i];
            }
            break;
        }
        all.sort_by(|a, b| a.1.total_cmp(&b.1));
        all.truncate(count);
        all
    };
    let mut radius = 0;
    while (2 * radius + 1usize).pow(n as u32) < count {
        radius += 1;
    }
    let center: Vec<i64> = w_hat.iter().map(|x| x.round() as i64).collect();
    let r = radius as i64;
    let lo: Vec<i64> = center.iter().map(|c| c - r).collect();
    let hi: Vec<i64> = center.iter().map(|c| c + r).collect();
    let chi2 = best_in(&lo, &hi)[count - 1].1 * (1.0 + 1e-9);
    let half = |i: usize| (chi2 * q0[(i, i)]).sqrt();
    let lo: Vec<i64> = (0..n).map(|i| (w_hat[i] - half(i)).ceil() as i64).collect();
    let hi: Vec<i64> = (0..n)
        .map(|i| (w_hat[i] + half(i)).floor() as i64)
        .collect();
    best_in(&lo, &hi)
}

/// Up to 20 candidates of random problems (n = 1..6, `Q = V Q0 V^T` with `Q0`
/// well-conditioned and `V` unimodular, so that `Q` is correlated) are those of
/// exhaustive enumeration (in `w = V^{-1} a`), norms to 1e-9, from `lambda` and from the
/// search with its lower bounds of the levels below from the first node on (small
/// problems finish before `lambda` uses them): the bounds prune nothing the ellipsoid
/// holds, also with many candidates (the integration tests compare two).
#[test]
fn many_candidates_match_exhaustive_enumeration() {
    let mut rng = ChaCha8Rng::seed_from_u64(3263);
    for t in 0..600 {
        let n = 1 + t % 6;
        let count = 1 + rng.random_range(0..20);
        let m = n + 2;
        let g = DMatrix::from_fn(m, n, |_, _| rng.random_range(-1.0..1.0));
        let q0 = (g.transpose() * g / m as f64 + DMatrix::identity(n, n) * 0.05)
            * rng.random_range(0.05..0.5);
        let mut v = DMatrix::<f64>::identity(n, n);
        for _ in 0..2 * n {
            if n > 1 {
                let i = rng.random_range(0..n);
                let j = (i + rng.random_range(1..n)) % n;
                let mu = f64::from(rng.random_range(-2..=2));
                for c in 0..n {
                    v[(i, c)] += mu * v[(j, c)];
                }
            }
        }
        let w_hat = DVector::from_fn(n, |_, _| rng.random_range(-50.0..50.0));
        let a_hat = &v * &w_hat;
        let q = &v * &q0 * v.transpose();
        let q = (&q + q.transpose()) * 0.5;
        let expected = enumerate(&w_hat, &q0, count);
        let problem = Decorrelated::new(&a_hat, &q).unwrap();
        let r = &problem.reduced;
        let bounded =
            search::search_bounded_after(&r.l, &r.d, r.z_hat.as_slice(), count, 1).unwrap();
        let bounded: Vec<Integers> = bounded
            .iter()
            .map(|(z, norm)| (problem.to_ambiguities(z).unwrap(), *norm))
            .collect();
        let plain: Vec<Integers> = lambda(&a_hat, &q, count)
            .unwrap()
            .candidates
            .into_iter()
            .map(|c| (c.integers, c.squared_norm))
            .collect();
        for found in [plain, bounded] {
            assert_eq!(found.len(), count);
            for ((a, norm), (w, expected_norm)) in found.iter().zip(&expected) {
                assert!(
                    rel(*norm, *expected_norm) < 1e-9,
                    "case {t}: {norm} vs {expected_norm}"
                );
                let tied = expected
                    .iter()
                    .filter(|(_, other)| rel(*other, *expected_norm) < 1e-9)
                    .count();
                if tied == 1 {
                    let expected_a: Vec<i64> = (0..n)
                        .map(|i| (0..n).map(|j| v[(i, j)] as i64 * w[j]).sum())
                        .collect();
                    assert_eq!(*a, expected_a, "case {t}, count {count}");
                }
            }
        }
    }
}

/// The lower bounds only prune subtrees without a leaf inside the ellipsoid: with them
/// from the first node on, the candidates and their norms are bit for bit those of the
/// search without them, on random problems (n up to 14, correlated, nearly diagonal or
/// ill-conditioned, 1 to 200 candidates).
#[test]
fn lower_bounds_leave_the_result_unchanged() {
    let mut rng = ChaCha8Rng::seed_from_u64(3264);
    let mut compared = 0;
    for t in 0..1500 {
        let n = 2 + rng.random_range(0..13);
        let q = match t % 3 {
            0 => {
                let b = DMatrix::from_fn(n, 3.min(n), |_, _| rng.random_range(-1.0..1.0));
                (&b * b.transpose() + DMatrix::identity(n, n) * 0.02) * 0.05
            }
            1 => {
                let eps = [0.0, 1e-3, 0.05][rng.random_range(0..3)];
                let mut q = DMatrix::from_diagonal(&DVector::from_fn(n, |_, _| {
                    rng.random_range(0.02..1.0)
                }));
                for i in 0..n {
                    for j in 0..i {
                        let e = eps * rng.random_range(-1.0..1.0);
                        q[(i, j)] = e;
                        q[(j, i)] = e;
                    }
                }
                q
            }
            _ => {
                let g = DMatrix::from_fn(n + 1, n, |_, _| rng.random_range(-1.0..1.0));
                g.transpose() * g * rng.random_range(0.01..1.0)
                    + DMatrix::identity(n, n) * 10f64.powf(rng.random_range(-8.0..-1.0))
            }
        };
        let count = 1 + rng.random_range(0..200);
        let a_hat = DVector::from_fn(n, |_, _| rng.random_range(-1e4..1e4));
        let Ok(problem) = Decorrelated::new(&a_hat, &q) else {
            continue;
        };
        let r = &problem.reduced;
        let z_hat = r.z_hat.as_slice();
        let with = search::search_bounded_after(&r.l, &r.d, z_hat, count, 1).unwrap();
        let without = search::search_bounded_after(&r.l, &r.d, z_hat, count, u64::MAX).unwrap();
        assert_eq!(with.len(), without.len(), "case {t}");
        for ((z1, n1), (z2, n2)) in with.iter().zip(&without) {
            assert_eq!(z1, z2, "case {t}");
            assert_eq!(n1.to_bits(), n2.to_bits(), "case {t}");
        }
        compared += 1;
    }
    assert!(compared > 1400, "{compared}");
}

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

/// The node limit says what happened (too many integer vectors within the bound, for
/// how many ambiguities) and no longer blames the conditioning of `Q`.
#[test]
fn the_node_limit_names_its_cause() {
    let msg = AmbiguityError::SearchLimit { n: 500 }.to_string();
    assert!(
        msg.contains("500 ambiguities") && msg.contains("too many integer vectors"),
        "{msg}"
    );
    assert!(!msg.contains("ill-conditioned"), "{msg}");
}
