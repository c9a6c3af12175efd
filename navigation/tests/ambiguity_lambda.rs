//! Oracle tests of the LAMBDA integer ambiguity resolution (`skyforge_navigation::ambiguity`).
//!
//! Oracles: exhaustive enumeration over a box that provably holds the two best integer
//! vectors; Monte Carlo of bootstrapping and ILS; a published worked example.

use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use skyforge_navigation::ambiguity::{
    AmbiguityError, MAX_DIMENSION, bootstrapped_success_rate, erf, lambda, partial,
};

type IntMat = Vec<Vec<i64>>;

/// A random problem with a known unimodular `U` such that `w = U a` has a well-conditioned
/// covariance `Q0 = U Q U^T`, so a box in `w` is small enough to enumerate while `Q`
/// itself can be as ill-conditioned as a short-span GNSS one.
struct Case {
    a_hat: DVector<f64>,
    q: DMatrix<f64>,
    u: IntMat,
    u_inv: IntMat,
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    rng.sample(StandardNormal)
}

/// `Q0 = G^T G / m + 0.05 I` of a random `m x n` design, scaled to a largest variance of
/// `scale` cycles^2.
fn well_conditioned(rng: &mut ChaCha8Rng, n: usize, scale: f64) -> DMatrix<f64> {
    let m = n + 2 + rng.random_range(0..4);
    let g = DMatrix::from_fn(m, n, |_, _| normal(rng));
    let q0 = g.transpose() * g / m as f64 + DMatrix::identity(n, n) * 0.05;
    let max = q0.diagonal().max();
    q0 * (scale / max)
}

/// A random unimodular pair `(U, U^{-1})`: products of integer row operations, swaps and
/// sign changes, entries kept below 3000.
fn unimodular(rng: &mut ChaCha8Rng, n: usize, ops: usize) -> (IntMat, IntMat) {
    let mut u: IntMat = (0..n)
        .map(|i| (0..n).map(|j| i64::from(i == j)).collect())
        .collect();
    let mut v = u.clone();
    for _ in 0..ops {
        if n < 2 {
            break;
        }
        let i = rng.random_range(0..n);
        let j = (i + rng.random_range(1..n)) % n;
        match rng.random_range(0..6) {
            0 => {
                // E = swap rows i, j: U <- E U, U^{-1} <- U^{-1} E.
                u.swap(i, j);
                for row in v.iter_mut() {
                    row.swap(i, j);
                }
            }
            1 => {
                u[i].iter_mut().for_each(|x| *x = -*x);
                v.iter_mut().for_each(|row| row[i] = -row[i]);
            }
            _ => {
                // E = I + mu e_i e_j^T: row i of U += mu row j; column j of U^{-1} -= mu column i.
                let mu = rng.random_range(1..=4) * if rng.random_bool(0.5) { 1 } else { -1 };
                let new: Vec<i64> = (0..n).map(|c| u[i][c] + mu * u[j][c]).collect();
                let new_v: Vec<i64> = (0..n).map(|r| v[r][j] - mu * v[r][i]).collect();
                let big = new.iter().chain(&new_v).any(|x| x.abs() > 3000);
                if !big {
                    u[i] = new;
                    for r in 0..n {
                        v[r][j] = new_v[r];
                    }
                }
            }
        }
    }
    (u, v)
}

/// `A^T Q B` for integer-valued `A`, `B`, accurate to about 1e-16 relative of its entries
/// (exact products `A_ki B_lj` times `Q_kl` split by FMA, double-double sums).
fn congruence(a: &DMatrix<f64>, q: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let n = q.nrows();
    DMatrix::from_fn(a.ncols(), b.ncols(), |i, j| {
        let (mut hi, mut lo) = (0.0f64, 0.0f64);
        for k in 0..n {
            for l in 0..n {
                let w = a[(k, i)] * b[(l, j)]; // an exact integer
                let p = w * q[(k, l)];
                let e = w.mul_add(q[(k, l)], -p);
                let s = hi + p;
                let bb = s - hi;
                let err = (hi - (s - bb)) + (p - bb);
                hi = s;
                lo += err + e;
            }
        }
        hi + lo
    })
}

fn to_f64(m: &IntMat) -> DMatrix<f64> {
    let n = m.len();
    DMatrix::from_fn(n, n, |i, j| m[i][j] as f64)
}

fn random_case(rng: &mut ChaCha8Rng, n: usize) -> Case {
    let scale = 0.05 + 0.5 * rng.random::<f64>();
    let q0 = well_conditioned(rng, n, scale);
    let ops = rng.random_range(0..=4 * n);
    let (u, u_inv) = unimodular(rng, n, ops);
    let v = to_f64(&u_inv);
    let q = &v * &q0 * v.transpose();
    let q = (&q + q.transpose()) * 0.5;
    // w_hat = integer + N(0, Q0) noise; a_hat = U^{-1} w_hat plus a large integer offset.
    let chol = q0.clone().cholesky().unwrap().unpack();
    let noise = &chol * DVector::from_fn(n, |_, _| normal(rng));
    let w_hat = DVector::from_fn(n, |i, _| rng.random_range(-20..=20) as f64 + noise[i]);
    let offset = DVector::from_fn(n, |_, _| rng.random_range(-1_000_000..=1_000_000) as f64);
    let a_hat = &v * w_hat + offset;
    Case { a_hat, q, u, u_inv }
}

fn condition_number(q: &DMatrix<f64>) -> f64 {
    let e = q.clone().symmetric_eigen().eigenvalues;
    e.max() / e.min()
}

/// The two best integer vectors by enumerating every integer `w` in the box
/// `|w_i - w_hat_i| <= sqrt(chi2 Q0_ii)`, where `chi2` is the larger squared norm of two
/// distinct integer vectors (so the two best lie inside the ellipsoid `chi2`, whose
/// bounding box that is). Returns `(a, norm)` best first, and the number of points.
fn enumerate_two_best(c: &Case) -> ([(Vec<i64>, f64); 2], u64) {
    let n = c.a_hat.len();
    let u = to_f64(&c.u);
    // w_hat = U a_hat, split exactly into integer and fractional parts.
    let a_int: Vec<i64> = c.a_hat.iter().map(|x| x.round() as i64).collect();
    let frac = DVector::from_fn(n, |i, _| c.a_hat[i] - c.a_hat[i].round());
    let wf = &u * &frac;
    let w_shift: Vec<i64> = wf.iter().map(|x| x.round() as i64).collect();
    let delta = DVector::from_fn(n, |i, _| wf[i] - wf[i].round());
    let q0 = congruence(&u.transpose(), &c.q, &u.transpose());
    let q0_inv = q0.clone().cholesky().unwrap().inverse();
    let norm = |k: &[i64]| {
        let r = DVector::from_fn(n, |i, _| delta[i] - k[i] as f64);
        (r.transpose() * &q0_inv * &r)[(0, 0)]
    };
    let zero = vec![0i64; n];
    let mut second = f64::INFINITY;
    for j in 0..n {
        let mut k = zero.clone();
        k[j] = if delta[j] > 0.0 { 1 } else { -1 };
        second = second.min(norm(&k));
    }
    let chi2 = norm(&zero).max(second) * (1.0 + 1e-9);
    let lo: Vec<i64> = (0..n)
        .map(|i| (delta[i] - (chi2 * q0[(i, i)]).sqrt()).ceil() as i64)
        .collect();
    let hi: Vec<i64> = (0..n)
        .map(|i| (delta[i] + (chi2 * q0[(i, i)]).sqrt()).floor() as i64)
        .collect();
    let mut best: Vec<(Vec<i64>, f64)> = Vec::new();
    let mut k = lo.clone();
    let mut points = 0u64;
    'odometer: loop {
        points += 1;
        let v = norm(&k);
        best.push((k.clone(), v));
        best.sort_by(|a, b| a.1.total_cmp(&b.1));
        best.truncate(2);
        for i in 0..n {
            if k[i] < hi[i] {
                k[i] += 1;
                continue 'odometer;
            }
            k[i] = lo[i];
        }
        break;
    }
    // a = a_int + U^{-1} (w_shift + k).
    let to_a = |k: &[i64]| -> Vec<i64> {
        (0..n)
            .map(|r| {
                a_int[r]
                    + (0..n)
                        .map(|j| c.u_inv[r][j] * (w_shift[j] + k[j]))
                        .sum::<i64>()
            })
            .collect()
    };
    let pick = |i: usize| (to_a(&best[i].0), best[i].1);
    ([pick(0), pick(1)], points)
}

/// `floor` up to condition numbers of 1e7; beyond, what double precision allows (the
/// factorisation's backward error eps |Q| changes squared norms by about cond * 1e-17).
fn tolerance(cond: f64, floor: f64) -> f64 {
    floor.max(1e-15 * cond)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(1e-12)
}

/// `Q = L^T D L` by an independent route: the Cholesky factor of `J Q J` (J reverses the
/// order) gives `J Q J = M D M^T`, and `L = J M^T J`.
fn ltdl(q: &DMatrix<f64>) -> (DMatrix<f64>, Vec<f64>) {
    let n = q.nrows();
    let rev = DMatrix::from_fn(n, n, |i, j| q[(n - 1 - i, n - 1 - j)]);
    let c = rev.cholesky().unwrap().unpack();
    let m = DMatrix::from_fn(n, n, |i, j| c[(i, j)] / c[(j, j)]);
    let d: Vec<f64> = (0..n).map(|i| c[(n - 1 - i, n - 1 - i)].powi(2)).collect();
    let mt = m.transpose();
    let l = DMatrix::from_fn(n, n, |i, j| mt[(n - 1 - i, n - 1 - j)]);
    (l, d)
}

/// Exact determinant of a small integer matrix (Laplace expansion in i128).
fn det(m: &[Vec<i128>]) -> i128 {
    let n = m.len();
    if n == 1 {
        return m[0][0];
    }
    (0..n)
        .map(|c| {
            let minor: Vec<Vec<i128>> = m[1..]
                .iter()
                .map(|row| {
                    row.iter()
                        .enumerate()
                        .filter(|(j, _)| *j != c)
                        .map(|(_, v)| *v)
                        .collect()
                })
                .collect();
            let sign = if c % 2 == 0 { 1 } else { -1 };
            sign * m[0][c] * det(&minor)
        })
        .sum()
}

/// Tests 1 and 2: on 2400 random problems, n = 1..6, cond(Q) up to 1e6 and far beyond, the
/// best and second-best candidates of `lambda` are those of exhaustive enumeration with
/// squared norms within 1e-8 relative (up to cond 1e7, see [`tolerance`]); `Z` is unimodular and `Z^T Q Z` meets the reduction's
/// conditions (|L_ij| <= 1/2; no swap would lower d_{k+1}), and decorrelation never lowers
/// the bootstrapped success rate (Chang, Wen & Xie 2013, J. Geodesy 87: permutations of
/// the LLL/LAMBDA reduction never decrease it, Gauss transformations leave D unchanged).
#[test]
fn two_best_match_exhaustive_enumeration_and_z_is_a_reduction() {
    let mut rng = ChaCha8Rng::seed_from_u64(20_240_611);
    let mut ill = 0;
    let mut max_cond: f64 = 0.0;
    let cases = 2400;
    for t in 0..cases {
        let n = 1 + t % 6;
        let c = random_case(&mut rng, n);
        let cond = condition_number(&c.q);
        max_cond = max_cond.max(cond);
        if cond >= 1e6 {
            ill += 1;
        }
        let sol = lambda(&c.a_hat, &c.q, 2).unwrap();
        let (expected, _) = enumerate_two_best(&c);
        assert_eq!(sol.candidates.len(), 2);
        let got: Vec<(Vec<i64>, f64)> = sol
            .candidates
            .iter()
            .map(|x| (x.integers.clone(), x.squared_norm))
            .collect();
        let near_tie = rel(expected[0].1, expected[1].1) < 1e-7;
        for i in 0..2 {
            let j = if near_tie && got[i].0 != expected[i].0 {
                1 - i
            } else {
                i
            };
            assert_eq!(
                got[i].0, expected[j].0,
                "case {t} (n {n}, cond {cond:.1e}) candidate {i}"
            );
            assert!(
                rel(got[i].1, expected[j].1) < tolerance(cond, 1e-8),
                "case {t} (cond {cond:.1e}): norm {} vs {}",
                got[i].1,
                expected[j].1
            );
        }

        // Z: integer entries, |det Z| = 1, and Z^T Q Z reduced.
        let z = &sol.z;
        assert!(z.iter().all(|v| v.fract() == 0.0 && v.abs() < 1e12));
        let zi: Vec<Vec<i128>> = (0..n)
            .map(|i| (0..n).map(|j| z[(i, j)] as i128).collect())
            .collect();
        assert_eq!(det(&zi).abs(), 1, "case {t}: Z = {z}");
        let qz = congruence(z, &c.q, z);
        let (l, d) = ltdl(&qz);
        for j in 0..n {
            for i in j + 1..n {
                assert!(
                    l[(i, j)].abs() <= 0.5 + 1e-6,
                    "case {t}: L[{i}][{j}] = {}",
                    l[(i, j)]
                );
            }
        }
        for k in 0..n.saturating_sub(1) {
            let delta = d[k] + l[(k + 1, k)].powi(2) * d[k + 1];
            assert!(
                delta >= d[k + 1] * (1.0 - 1e-6),
                "case {t}: swap test at {k}"
            );
        }
        let p_original = bootstrapped_success_rate(&c.q).unwrap();
        let p_z = bootstrapped_success_rate(&qz).unwrap();
        assert!(
            (sol.success_rate - p_z).abs() < tolerance(cond, 1e-9),
            "case {t}"
        );
        assert!(
            sol.success_rate >= p_original - 1e-9,
            "case {t}: {} < {p_original}",
            sol.success_rate
        );
    }
    assert!(ill >= cases / 10, "only {ill} problems with cond >= 1e6");
    assert!(max_cond > 1e7, "largest condition number {max_cond:.1e}");
}

/// de Jonge & Tiberius 1996, "The LAMBDA method for integer ambiguity estimation:
/// implementation aspects", LGR-Series 12, the 3-D example of §3.8 (Z-transformation) and
/// §4.12 (search): `Q = [6.290 5.978 0.544; 5.978 6.292 2.340; 0.544 2.340 6.288]`,
/// `a_hat = (5.45, 3.10, 2.97)`; §3.8 prints `Q_z = [4.476 0.334 0.230; 0.334 1.146
/// 0.082; 0.230 0.082 0.626]` and `z_hat = (-4.57, 10.02, 2.35)`, and the example's integer
/// solution is `(5, 3, 4)`. (Numbers as reproduced by the report's example program and
/// its MATLAB recoding by K. Borre, "3D-example of sections 3.8 and 4.12".) Our `Z` may
/// order or sign its columns differently: `Q_z` and `z_hat` must agree up to a signed
/// permutation, to the printed digits.
#[test]
fn de_jonge_tiberius_1996_three_dimensional_example() {
    let q = DMatrix::from_row_slice(
        3,
        3,
        &[
            6.290, 5.978, 0.544, 5.978, 6.292, 2.340, 0.544, 2.340, 6.288,
        ],
    );
    let a_hat = DVector::from_vec(vec![5.45, 3.10, 2.97]);
    let sol = lambda(&a_hat, &q, 2).unwrap();
    assert_eq!(sol.best().integers, vec![5, 3, 4]);

    let printed_qz = [
        [4.476, 0.334, 0.230],
        [0.334, 1.146, 0.082],
        [0.230, 0.082, 0.626],
    ];
    let printed_z = [-4.57, 10.02, 2.35];
    let qz = sol.z.transpose() * &q * &sol.z;
    let zh = sol.z.transpose() * &a_hat;
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let matches = perms.iter().any(|p| {
        (0..8).any(|signs: u32| {
            let s = |i: usize| if signs >> i & 1 == 1 { -1.0 } else { 1.0 };
            (0..3).all(|i| {
                (zh[p[i]] * s(i) - printed_z[i]).abs() < 6e-3
                    && (0..3)
                        .all(|j| (qz[(p[i], p[j])] * s(i) * s(j) - printed_qz[i][j]).abs() < 1.5e-3)
            })
        })
    });
    assert!(matches, "Z^T Q Z = {qz}, z_hat = {zh}");
}

/// `a_hat = a + e`, `e ~ N(0, Q)` with `a = 0`: the fraction of samples bootstrapping
/// (sequential conditional rounding, implemented here) gets right.
struct MonteCarlo {
    chol: DMatrix<f64>,
    /// For ambiguity i: the regression of a_i on a_{i+1..n}, `Q_II^{-1} Q_Ii`.
    beta: Vec<DVector<f64>>,
}

impl MonteCarlo {
    fn new(q: &DMatrix<f64>) -> Self {
        let n = q.nrows();
        let beta = (0..n)
            .map(|i| {
                let m = n - i - 1;
                if m == 0 {
                    return DVector::zeros(0);
                }
                let qii = q.view((i + 1, i + 1), (m, m)).into_owned();
                let qi = q.view((i + 1, i), (m, 1)).into_owned();
                qii.cholesky().unwrap().solve(&qi).column(0).into_owned()
            })
            .collect();
        Self {
            chol: q.clone().cholesky().unwrap().unpack(),
            beta,
        }
    }

    fn sample(&self, rng: &mut ChaCha8Rng) -> DVector<f64> {
        let n = self.chol.nrows();
        &self.chol * DVector::from_fn(n, |_, _| normal(rng))
    }

    /// Bootstrapping from the last ambiguity to the first (the `L^T D L` order).
    fn bootstrap(&self, a_hat: &DVector<f64>) -> Vec<f64> {
        let n = a_hat.len();
        let mut fixed = vec![0.0; n];
        for i in (0..n).rev() {
            let mut c = a_hat[i];
            for (k, b) in self.beta[i].iter().enumerate() {
                c -= b * (a_hat[i + 1 + k] - fixed[i + 1 + k]);
            }
            fixed[i] = c.round();
        }
        fixed
    }
}

/// A correlated GNSS-like covariance (rank-3 geometry part plus a small diagonal) scaled
/// so that its bootstrapped success rate (of the problem as given) is `target`.
fn covariance_with_success(rng: &mut ChaCha8Rng, n: usize, target: f64) -> DMatrix<f64> {
    let b = DMatrix::from_fn(n, 3.min(n), |_, _| normal(rng));
    let base = &b * b.transpose() + DMatrix::identity(n, n) * 0.02;
    let (mut lo, mut hi) = (1e-6f64, 1e3f64);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if bootstrapped_success_rate(&(&base * mid)).unwrap() > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    base * lo
}

/// Test 4: the bootstrapped success rate (as given) matches Monte Carlo bootstrapping
/// within 4 sigma; that of the decorrelated problem is at least as high and matches
/// Monte Carlo bootstrapping of `z_hat = Z^T a_hat`; ILS (Monte Carlo with `lambda`) does
/// at least as well as decorrelated bootstrapping (Teunissen 1999: ILS is optimal).
#[test]
fn bootstrapped_success_rate_matches_monte_carlo() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let samples = 40_000;
    for (n, target) in [(2, 0.5), (3, 0.7), (4, 0.85), (5, 0.95), (6, 0.99)] {
        let q = covariance_with_success(&mut rng, n, target);
        let p_boot = bootstrapped_success_rate(&q).unwrap();
        assert!((p_boot - target).abs() < 1e-6);
        let sol = lambda(&DVector::zeros(n), &q, 1).unwrap();
        let qz = sol.z.transpose() * &q * &sol.z;
        let mc = MonteCarlo::new(&q);
        let mc_z = MonteCarlo::new(&qz);
        let (mut boot_ok, mut boot_z_ok, mut ils_ok) = (0u32, 0u32, 0u32);
        for _ in 0..samples {
            let a_hat = mc.sample(&mut rng);
            if mc.bootstrap(&a_hat).iter().all(|&x| x == 0.0) {
                boot_ok += 1;
            }
            if mc_z
                .bootstrap(&(sol.z.transpose() * &a_hat))
                .iter()
                .all(|&x| x == 0.0)
            {
                boot_z_ok += 1;
            }
            if lambda(&a_hat, &q, 1)
                .unwrap()
                .best()
                .integers
                .iter()
                .all(|&x| x == 0)
            {
                ils_ok += 1;
            }
        }
        let f = |k: u32| f64::from(k) / samples as f64;
        let sigma = |p: f64| (p * (1.0 - p) / samples as f64).sqrt().max(1e-4);
        let (p_mc, p_z_mc, p_ils) = (f(boot_ok), f(boot_z_ok), f(ils_ok));
        assert!(
            (p_mc - p_boot).abs() <= 4.0 * sigma(p_boot),
            "n {n}: MC {p_mc} vs {p_boot}"
        );
        assert!(sol.success_rate >= p_boot - 1e-12, "n {n}");
        let pz = sol.success_rate;
        assert!(
            (p_z_mc - pz).abs() <= 4.0 * sigma(pz),
            "n {n}: MC {p_z_mc} vs {pz}"
        );
        assert!(p_ils >= pz - 4.0 * sigma(pz), "n {n}: ILS {p_ils} < {pz}");
    }
}

/// Test 5: `lambda(a_hat + k, Q) = lambda(a_hat, Q) + k` for integer `k`, with the same `Z`
/// and squared norms.
#[test]
fn integer_shifts_shift_the_solution() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for t in 0..300 {
        let n = 1 + t % 6;
        let c = random_case(&mut rng, n);
        let k: Vec<i64> = (0..n)
            .map(|_| rng.random_range(-3_000_000..=3_000_000))
            .collect();
        let shifted = &c.a_hat + DVector::from_fn(n, |i, _| k[i] as f64);
        let s0 = lambda(&c.a_hat, &c.q, 3).unwrap();
        let s1 = lambda(&shifted, &c.q, 3).unwrap();
        assert_eq!(s0.z, s1.z);
        for (x, y) in s0.candidates.iter().zip(&s1.candidates) {
            let moved: Vec<i64> = x.integers.iter().zip(&k).map(|(a, b)| a + b).collect();
            assert!(rel(x.squared_norm, y.squared_norm) < 1e-6, "case {t}");
            if rel(s0.candidates[0].squared_norm, s0.candidates[1].squared_norm) > 1e-6 {
                assert_eq!(moved, y.integers, "case {t}");
            }
        }
        assert_eq!(
            s0.best()
                .integers
                .iter()
                .zip(&k)
                .map(|(a, b)| a + b)
                .collect::<Vec<_>>(),
            s1.best().integers,
            "case {t}"
        );
    }
}

/// Bootstrapped success rates of the trailing subsets `k..n` of the decorrelated problem,
/// from `Z^T Q Z` (the trailing block's own factorisation).
fn trailing_rates(q: &DMatrix<f64>, z: &DMatrix<f64>) -> Vec<f64> {
    let qz = z.transpose() * q * z;
    let n = q.nrows();
    (0..n)
        .map(|k| bootstrapped_success_rate(&qz.view((k, k), (n - k, n - k)).into_owned()).unwrap())
        .collect()
}

/// Test 6: partial fixing takes the largest trailing subset of the decorrelated
/// ambiguities whose bootstrapped success rate reaches the threshold: all of them when the
/// full rate does, a strict subset otherwise, none when even the last one misses it; the
/// fixed integers are the ILS solution of the subset (exhaustive enumeration).
#[test]
fn partial_fixing_takes_the_largest_subset_at_the_threshold() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (mut all, mut some, mut none) = (0, 0, 0);
    for t in 0..400 {
        let n = 2 + t % 5;
        let target = [0.2, 0.6, 0.9, 0.99][t % 4];
        let q = covariance_with_success(&mut rng, n, target);
        let a_hat = DVector::from_fn(n, |_, _| rng.random_range(-1000.0..1000.0));
        let sol = lambda(&a_hat, &q, 1).unwrap();
        let rates = trailing_rates(&q, &sol.z);
        let threshold = [0.5, 0.8, 0.95, 0.999][rng.random_range(0..4)];
        let p = partial(&a_hat, &q, threshold).unwrap();
        let m = p.fixed_count();
        let start = n - m;
        // Largest subset reaching the threshold (rates fall as the subset grows).
        if m > 0 {
            assert!(rates[start] >= threshold * (1.0 - 1e-12), "case {t}");
            assert!((p.success_rate - rates[start]).abs() < 1e-9);
        } else {
            assert_eq!(p.success_rate, 1.0);
        }
        if m < n {
            assert!(
                rates[start - 1] < threshold * (1.0 + 1e-12),
                "case {t}: could fix {}",
                m + 1
            );
        }
        match m {
            0 => none += 1,
            m if m == n => {
                all += 1;
                assert!((sol.success_rate - p.success_rate).abs() < 1e-12);
                let z_best = sol.z.transpose()
                    * DVector::from_iterator(n, sol.best().integers.iter().map(|&x| x as f64));
                assert_eq!(
                    p.integers,
                    z_best.iter().map(|&x| x as i64).collect::<Vec<_>>()
                );
            }
            _ => some += 1,
        }
        // The fixed combinations are the last m columns of Z, with their float values,
        // covariance and ILS integers.
        assert_eq!(p.z_f, sol.z.columns(start, m).into_owned());
        assert!((&p.z_hat - p.z_f.transpose() * &a_hat).amax() < 1e-6);
        assert!((&p.q_zz - p.z_f.transpose() * &q * &p.z_f).amax() < 1e-9 * q.amax());
        if m > 0 {
            let ident: IntMat = (0..m)
                .map(|i| (0..m).map(|j| i64::from(i == j)).collect())
                .collect();
            let sub = Case {
                a_hat: p.z_hat.clone(),
                q: p.q_zz.clone(),
                u: ident.clone(),
                u_inv: ident,
            };
            let (best, _) = enumerate_two_best(&sub);
            if rel(best[0].1, best[1].1) > 1e-7 {
                assert_eq!(p.integers, best[0].0, "case {t}");
            }
        }
    }
    assert!(
        all > 20 && some > 20 && none > 20,
        "all {all}, some {some}, none {none}"
    );
}

/// The bootstrapped success rate of a 1-D problem is `2 Phi(1/(2 sigma)) - 1`: for
/// sigma = 0.5 that is `2 Phi(1) - 1 = erf(1/sqrt 2) = 0.682689492137086` (the one-sigma
/// probability of the normal distribution, A&S 26.2).
#[test]
fn one_dimensional_success_rate_is_the_one_sigma_probability() {
    let q = DMatrix::from_element(1, 1, 0.25);
    let p = bootstrapped_success_rate(&q).unwrap();
    assert!((p - 0.682_689_492_137_086).abs() < 1e-14, "{p}");
    assert!((erf(std::f64::consts::FRAC_1_SQRT_2) - p).abs() < 1e-15);
}

/// Test 7: invalid input gives the error, never a panic.
#[test]
fn invalid_input_is_an_error() {
    let a = DVector::from_vec(vec![0.3, 1.2]);
    let good = DMatrix::from_row_slice(2, 2, &[1.0, 0.2, 0.2, 1.0]);
    let asym = DMatrix::from_row_slice(2, 2, &[1.0, 0.2, 0.3, 1.0]);
    let indefinite = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
    let mut nan = good.clone();
    nan[(1, 1)] = f64::NAN;
    assert!(matches!(
        lambda(&a, &asym, 2),
        Err(AmbiguityError::NotSymmetric { .. })
    ));
    assert!(matches!(
        lambda(&a, &indefinite, 2),
        Err(AmbiguityError::NotPositiveDefinite { .. })
    ));
    assert!(matches!(
        lambda(&a, &nan, 2),
        Err(AmbiguityError::NonFinite { .. })
    ));
    let a_nan = DVector::from_vec(vec![f64::INFINITY, 0.0]);
    assert!(matches!(
        lambda(&a_nan, &good, 2),
        Err(AmbiguityError::NonFinite { .. })
    ));
    let a3 = DVector::from_vec(vec![0.0; 3]);
    assert!(matches!(
        lambda(&a3, &good, 2),
        Err(AmbiguityError::DimensionMismatch { .. })
    ));
    let rect = DMatrix::from_element(2, 3, 0.0);
    assert!(matches!(
        lambda(&a, &rect, 2),
        Err(AmbiguityError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        bootstrapped_success_rate(&rect),
        Err(AmbiguityError::DimensionMismatch { .. })
    ));
    let empty = DVector::<f64>::zeros(0);
    assert!(matches!(
        lambda(&empty, &DMatrix::zeros(0, 0), 1),
        Err(AmbiguityError::Empty)
    ));
    assert!(matches!(
        lambda(&a, &good, 0),
        Err(AmbiguityError::ZeroCount)
    ));
    assert!(matches!(
        lambda(&a, &good, 100_000),
        Err(AmbiguityError::TooManyCandidates(_))
    ));
    let big = MAX_DIMENSION + 1;
    assert!(matches!(
        lambda(&DVector::zeros(big), &DMatrix::identity(big, big), 1),
        Err(AmbiguityError::TooLarge { .. })
    ));
    let far = DVector::from_vec(vec![1e15, 0.0]);
    assert!(matches!(
        lambda(&far, &good, 1),
        Err(AmbiguityError::OutOfRange { .. })
    ));
    for bad in [0.0, -0.1, 1.5, f64::NAN] {
        assert!(matches!(
            partial(&a, &good, bad),
            Err(AmbiguityError::InvalidSuccessRate(_))
        ));
    }
    assert!(matches!(
        partial(&a, &asym, 0.9),
        Err(AmbiguityError::NotSymmetric { .. })
    ));
    // The messages say what is wrong and what is allowed.
    let msg = lambda(&a, &asym, 2).unwrap_err().to_string();
    assert!(
        msg.contains("Q[1][0] = 0.3") && msg.contains("Q[0][1] = 0.2"),
        "{msg}"
    );
}

fn any_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(1e300),
        1 => Just(1e-300),
        1 => -1e12..1e12f64,
    ]
}

proptest! {
    /// Arbitrary small matrices (square or not, symmetric or not, any values) and vectors
    /// never make the module panic.
    #[test]
    fn arbitrary_input_never_panics(
        rows in 0usize..5,
        cols in 0usize..5,
        len in 0usize..5,
        values in prop::collection::vec(any_value(), 25),
        a in prop::collection::vec(any_value(), 5),
        symmetric in any::<bool>(),
        count in 0usize..4,
        threshold in -0.5..1.5f64,
    ) {
        let mut q = DMatrix::from_fn(rows, cols, |i, j| values[i * 5 + j]);
        if symmetric && rows == cols {
            q = DMatrix::from_fn(rows, cols, |i, j| values[i.max(j) * 5 + i.min(j)]);
            // Make some of them positive definite.
            if values[24] > 0.0 {
                q += DMatrix::identity(rows, cols) * 50.0;
            }
        }
        let a = DVector::from_fn(len, |i, _| a[i]);
        let _ = lambda(&a, &q, count);
        let _ = partial(&a, &q, threshold);
        let _ = bootstrapped_success_rate(&q);
    }
}
