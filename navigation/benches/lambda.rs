//! LAMBDA on 20 ambiguities (issue bar: median under 50 us), and on large well-conditioned
//! problems of 100 and 500 ambiguities (issue #32).
//!
//! The covariance is that of a single-epoch double-difference GPS L1 model: 11 satellites
//! at spread elevations and azimuths, two baselines sharing antenna A (A-B, A-C), 10 DD
//! phase (3 mm undifferenced) and 10 DD code (0.3 m) observations per baseline, the
//! baseline-to-baseline correlation 0.5 of the shared antenna; unknowns two baselines
//! (3 + 3) and 20 DD ambiguities (cycles, L1 wavelength 0.1903 m). `Q_NN` is the
//! ambiguity block of the inverse normal matrix (the baselines eliminated).

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use skyforge_navigation::ambiguity::lambda;
use std::hint::black_box;

const WAVELENGTH_M: f64 = 0.1903;
const SIGMA_PHASE_M: f64 = 0.003;
const SIGMA_CODE_M: f64 = 0.3;

/// Unit line-of-sight vectors (ENU) of 11 satellites, elevations 15..85 deg.
fn line_of_sight() -> Vec<[f64; 3]> {
    (0..11)
        .map(|i| {
            let el = (15.0 + 7.0 * i as f64).to_radians();
            let az = (i as f64 * 137.5).to_radians();
            [el.cos() * az.sin(), el.cos() * az.cos(), el.sin()]
        })
        .collect()
}

/// The ambiguity covariance `Q_NN` (cycles^2) of the two-baseline DD model.
fn dd_covariance() -> DMatrix<f64> {
    let los = line_of_sight();
    let s = los.len();
    // Reference satellite: the highest (last).
    let r = s - 1;
    let m = s - 1;
    // Rows of the DD geometry: -(e_i - e_ref) for a baseline b (range decreases along e).
    let g = DMatrix::from_fn(m, 3, |i, k| -(los[i][k] - los[r][k]));
    // Single differences between receivers have variance 2 sigma^2 (sigma per receiver);
    // DD = D SD with D = [I, -1], so cov = 2 sigma^2 D D^T; across the two baselines only
    // antenna A's noise is shared: sigma^2 D D^T (correlation 0.5).
    let dd = DMatrix::from_fn(m, m, |i, j| if i == j { 2.0 } else { 1.0 });
    let obs = 4 * m; // phase A-B, code A-B, phase A-C, code A-C
    let unknowns = 6 + 2 * m;
    let mut a = DMatrix::zeros(obs, unknowns);
    let mut cov = DMatrix::zeros(obs, obs);
    for bl in 0..2 {
        let phase = bl * 2 * m;
        let code = phase + m;
        a.view_mut((phase, 3 * bl), (m, 3)).copy_from(&g);
        a.view_mut((code, 3 * bl), (m, 3)).copy_from(&g);
        for i in 0..m {
            a[(phase + i, 6 + bl * m + i)] = WAVELENGTH_M;
        }
        for other in 0..2 {
            let shared = if bl == other { 2.0 } else { 1.0 };
            let (p2, c2) = (other * 2 * m, other * 2 * m + m);
            let block = &dd * shared;
            cov.view_mut((phase, p2), (m, m))
                .copy_from(&(&block * SIGMA_PHASE_M.powi(2)));
            cov.view_mut((code, c2), (m, m))
                .copy_from(&(&block * SIGMA_CODE_M.powi(2)));
        }
    }
    let w = cov.try_inverse().expect("DD covariance is invertible");
    let normal = a.transpose() * w * &a;
    let inv = normal.try_inverse().expect("normal matrix is invertible");
    let q = inv.view((6, 6), (2 * m, 2 * m)).into_owned();
    (&q + q.transpose()) * 0.5
}

/// A float solution drawn from N(integers, Q) with a fixed pseudo-random sequence.
fn float_solution(q: &DMatrix<f64>) -> DVector<f64> {
    let n = q.nrows();
    let l = q
        .clone()
        .cholesky()
        .expect("Q_NN is positive definite")
        .unpack();
    let mut x: u64 = 0x2545_f491_4f6c_dd1d;
    let mut uniform = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    // Box-Muller normals.
    let e = DVector::from_fn(n, |_, _| {
        let (u1, u2) = (uniform().max(1e-300), uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
    });
    DVector::from_fn(n, |i, _| (i as f64 * 37.0 - 300.0) + (&l * &e)[i])
}

fn bench(c: &mut Criterion) {
    let q = dd_covariance();
    let a_hat = float_solution(&q);
    let sol = lambda(&a_hat, &q, 2).expect("LAMBDA solves the DD problem");
    eprintln!(
        "20 DD ambiguities: sigma_a from {:.2} to {:.2} cycles, bootstrapped success rate {:.4}, ratio {:.2}",
        q.diagonal().min().sqrt(),
        q.diagonal().max().sqrt(),
        sol.success_rate,
        sol.ratio().unwrap_or(f64::NAN)
    );
    c.bench_function("lambda_20_dd_two_baselines", |b| {
        b.iter(|| lambda(black_box(&a_hat), black_box(&q), 2))
    });
}

/// Large problems (issue #32): `n` ambiguities with `a_hat` uniform over [-50, 50) cycles
/// (a fixed xorshift sequence) and `Q = var I` plus symmetric off-diagonals uniform in
/// `+/- off * var` (0 for a diagonal `Q`).
fn large_problem(n: usize, var: f64, off: f64) -> (DVector<f64>, DMatrix<f64>) {
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let a_hat = DVector::from_fn(n, |_, _| 100.0 * uniform() - 50.0);
    let mut q = DMatrix::identity(n, n) * var;
    for i in 0..n {
        for j in 0..i {
            let v = off * var * (2.0 * uniform() - 1.0);
            q[(i, j)] = v;
            q[(j, i)] = v;
        }
    }
    (a_hat, q)
}

fn bench_large(c: &mut Criterion) {
    let mut group = c.benchmark_group("lambda_large");
    group.sample_size(10);
    for (name, n, var, off) in [
        ("identity_100", 100, 1.0, 0.0),
        ("identity_500", 500, 1.0, 0.0),
        ("near_diagonal_1e-5_500", 500, 0.05, 1e-5),
    ] {
        let (a_hat, q) = large_problem(n, var, off);
        lambda(&a_hat, &q, 2).expect("the large problem is solved");
        group.bench_function(name, |b| {
            b.iter(|| lambda(black_box(&a_hat), black_box(&q), 2))
        });
    }
    group.finish();
}

criterion_group!(benches, bench, bench_large);
criterion_main!(benches);
