//! The baseline-length-constrained integer least-squares problem: the GNSS compass of
//! Teunissen (2010, "Integer least-squares theory for the GNSS compass", J Geod
//! 84:433-447), the constrained LAMBDA (C-LAMBDA) of Park & Teunissen and Giorgi et al.,
//! applied baseline by baseline: the integers `z` minimising
//!
//! `C(z) = ||a_hat - z||^2_{Q_a} + sum_k min_{||b_k|| = l_k} ||b_hat_k(z) - b_k||^2_{W_k}`,
//!
//! with `b_hat_k(z)` baseline `k` given `z` (eq. 2.4-64), `l_k` its known length (from
//! the body geometry `B_0`) and `W_k` the inverse of the `k`-th 3 x 3 diagonal block of
//! `Q_b(z)` (eq. 2.4-65, the same for every `z`).
//!
//! The length score ignores the correlation between baselines: it constrains each
//! baseline's length only, as the single-baseline C-LAMBDA does for its one baseline, and
//! knows nothing of the angles between baselines (for that, the multivariate constrained
//! search of [`super::multivariate`]). It needs no position of the platform (lengths do
//! not depend on the frame) and works with one baseline.
//!
//! Each term is a weighted least-squares problem on a sphere, solved exactly by
//! [`WeightedSphere`]; the integers are searched by the search and shrink shared with the
//! multivariate constraint ([`super::multivariate::search_with_misfit`]), which proves
//! the best when it is exhaustive.

use super::multivariate::{CandidateMisfit, ConstrainedError, ConstrainedFix, search_with_misfit};
use super::{ConstrainedSearch, Searched};
use crate::attitude::{AttitudeError, BodyGeometry};
use crate::baseline::{Conditioned, FloatBaselines};
use crate::relative::resolve::FixMethod;
use nalgebra::{DMatrix, DVector, Matrix3, SymmetricEigen};
use skyforge_orbits::Vec3;

/// Largest ratio of the largest to the smallest weight eigenvalue accepted: beyond it a
/// direction carries no information and the eigenvalues themselves lose their digits.
pub const MAX_WEIGHT_CONDITION: f64 = 1e14;
/// Newton/bisection steps of the secular equation at most (a few suffice; this is the
/// guarantee of termination).
const MAX_SECULAR_STEPS: usize = 200;

/// `min_{||b|| = l} (b_hat - b)^T W (b_hat - b)` for one symmetric positive definite
/// weight `W` and length `l`: a weighted least-squares fit on a sphere (the trust-region
/// subproblem with an equality constraint).
///
/// With `W = U diag(w) U^T` (`w` ascending) and `c = U^T b_hat`, a stationary point is
/// `b = (W + mu I)^{-1} W b_hat`, i.e. `b_i = w_i c_i / (w_i + mu)` in the eigenbasis, with
/// `mu` a root of the secular equation `sum_i (w_i c_i / (w_i + mu))^2 = l^2`; the global
/// minimiser is the one with `W + mu I` positive semidefinite, `mu >= -w_1`. On
/// `mu > -w_1` the left side falls strictly from `+inf` (when `c_1 != 0`) to 0, so that
/// root is unique; it is found by Newton's method on `1/||b(mu)|| - 1/l` (increasing and
/// concave there, so Newton's iterates approach the root from below), safeguarded by a
/// bracket and bisection. When `c_1 = 0` (for every eigenvector of `w_1`) and the other
/// components alone reach no further than `l` at `mu = -w_1` (the "hard case"),
/// `mu = -w_1` and the rest of the length is taken along the eigenvector of `w_1`
/// (either sign: both are minimisers of the same cost; this returns `+`).
#[derive(Debug, Clone, PartialEq)]
pub struct WeightedSphere {
    /// Eigenvectors of `W` (columns), in the order of `weights`.
    basis: Matrix3<f64>,
    /// Eigenvalues of `W`, ascending.
    weights: [f64; 3],
    /// `l` (m).
    length_m: f64,
}

/// The solution of [`WeightedSphere::fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereFit {
    /// The minimiser `b` (`||b|| = l`).
    pub point: Vec3,
    /// `(b_hat - b)^T W (b_hat - b)` at it.
    pub cost: f64,
    /// The Lagrange multiplier `mu`: `W (b - b_hat) + mu b = 0`, `mu >= -w_min`.
    pub multiplier: f64,
}

impl WeightedSphere {
    /// The problem with weight `weight` (symmetric positive definite; its symmetric part is
    /// used) and length `length_m` (positive); `None` when either is not, or when the
    /// weight's condition number exceeds [`MAX_WEIGHT_CONDITION`].
    pub fn from_weight(weight: &Matrix3<f64>, length_m: f64) -> Option<Self> {
        let eig = SymmetricEigen::new((weight + weight.transpose()) * 0.5);
        Self::from_eigen(eig.eigenvectors, eig.eigenvalues.into(), length_m)
    }

    /// The problem with weight `covariance^{-1}` (the covariance symmetric positive
    /// definite; its symmetric part is used), without forming the inverse: the eigenvectors
    /// are shared, the eigenvalues inverted.
    pub fn from_covariance(covariance: &Matrix3<f64>, length_m: f64) -> Option<Self> {
        let eig = SymmetricEigen::new((covariance + covariance.transpose()) * 0.5);
        let v: [f64; 3] = eig.eigenvalues.into();
        if !v.iter().all(|&s| s.is_finite() && s > 0.0) {
            return None;
        }
        Self::from_eigen(eig.eigenvectors, v.map(f64::recip), length_m)
    }

    fn from_eigen(vectors: Matrix3<f64>, values: [f64; 3], length_m: f64) -> Option<Self> {
        let usable = length_m.is_finite()
            && length_m > 0.0
            && values.iter().all(|&w| w.is_finite() && w > 0.0)
            && vectors.iter().all(|v| v.is_finite());
        if !usable {
            return None;
        }
        let mut order = [0, 1, 2];
        order.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
        let weights = order.map(|i| values[i]);
        if weights[2] > MAX_WEIGHT_CONDITION * weights[0] {
            return None;
        }
        let basis = Matrix3::from_columns(&order.map(|i| vectors.column(i).into_owned()));
        Some(Self {
            basis,
            weights,
            length_m,
        })
    }

    /// The length `l` (m).
    pub fn length_m(&self) -> f64 {
        self.length_m
    }

    /// The minimiser over the sphere `||b|| = l` of `(b_hat - b)^T W (b_hat - b)`; `None`
    /// when `b_hat` is not finite.
    pub fn fit(&self, b_hat: &Vec3) -> Option<SphereFit> {
        if !b_hat.iter().all(|v| v.is_finite()) {
            return None;
        }
        let l = self.length_m;
        let w = self.weights;
        let c: [f64; 3] = (self.basis.transpose() * b_hat).into();
        // In the shifted multiplier s = mu + w_1 > 0: b_i = p_i / (d_i + s).
        let p: [f64; 3] = std::array::from_fn(|i| w[i] * c[i]);
        let d: [f64; 3] = std::array::from_fn(|i| w[i] - w[0]);
        let (b, s) = match hard_case(&p, &d, l) {
            Some(b) => (b, 0.0),
            None => {
                let s = secular_root(&p, &d, l)?;
                (std::array::from_fn(|i| shrink(p[i], d[i] + s)), s)
            }
        };
        // Polish the length (a relative change of a few ulp).
        let norm = b.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        let b = b.map(|v| v * (l / norm));
        let cost = (0..3).map(|i| w[i] * (c[i] - b[i]).powi(2)).sum();
        Some(SphereFit {
            point: self.basis * Vec3::from(b),
            cost,
            multiplier: s - w[0],
        })
    }
}

/// `p / e`, zero when `p` is (a component of `b_hat` the weight does not move).
fn shrink(p: f64, e: f64) -> f64 {
    if p == 0.0 { 0.0 } else { p / e }
}

/// The hard case: every component along the smallest weight's eigenvectors (`d_i = 0`) is
/// zero and the others reach at most `l` at `mu = -w_1`; then `b` in the eigenbasis.
fn hard_case(p: &[f64; 3], d: &[f64; 3], l: f64) -> Option<[f64; 3]> {
    if (0..3).any(|i| d[i] == 0.0 && p[i] != 0.0) {
        return None;
    }
    let mut b: [f64; 3] = std::array::from_fn(|i| if d[i] == 0.0 { 0.0 } else { p[i] / d[i] });
    let rest: f64 = b.iter().map(|v| v * v).sum();
    if rest > l * l {
        return None;
    }
    b[0] = (l * l - rest).sqrt();
    Some(b)
}

/// `s > 0` with `sum_i (p_i / (d_i + s))^2 = l^2`, outside the hard case (so the left
/// side exceeds `l^2` as `s` falls to 0). A near-hard case (a tiny `p_1`) has a tiny
/// root, which the bracket's lower end `|p_1| / l` and the geometric bisection reach.
fn secular_root(p: &[f64; 3], d: &[f64; 3], l: f64) -> Option<f64> {
    // sum_i (p_i / (d_i + s))^2 is at least each term and at most ||p||^2 / s^2: a bracket.
    let mut lo = (0..3).map(|i| p[i].abs() / l - d[i]).fold(0.0, f64::max);
    let mut hi = p.iter().map(|v| v * v).sum::<f64>().sqrt() / l;
    if !(hi.is_finite() && hi > 0.0) {
        return None;
    }
    lo = lo.min(hi);
    let mut s = hi;
    for _ in 0..MAX_SECULAR_STEPS {
        // phi(s) = 1/||b(s)|| - 1/l and its derivative.
        let (mut n2, mut dn2) = (0.0, 0.0);
        for i in 0..3 {
            let q = shrink(p[i], d[i] + s);
            n2 += q * q;
            dn2 += q * q / (d[i] + s);
        }
        let n = n2.sqrt();
        let phi = 1.0 / n - 1.0 / l;
        if phi == 0.0 {
            return Some(s);
        }
        if phi > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
        let step = phi * (n2 * n) / dn2;
        let newton = s - step;
        if step.abs() <= 4.0 * f64::EPSILON * s {
            return Some(newton);
        }
        s = if newton >= lo && newton <= hi {
            newton
        } else if lo > 0.0 && hi > 4.0 * lo {
            (lo * hi).sqrt()
        } else {
            0.5 * (lo + hi)
        };
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            return Some(s);
        }
    }
    Some(s)
}

/// The length-constrained misfit of all baselines: one [`WeightedSphere`] per baseline.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthMisfit {
    spheres: Vec<WeightedSphere>,
}

impl LengthMisfit {
    /// The spheres of baselines whose covariance is `covariance` (3m x 3m, baseline 1's
    /// x, y, z first; only its 3 x 3 diagonal blocks are used) and lengths `lengths_m`;
    /// `None` when a block is not positive definite or a length not positive, or the
    /// sizes disagree.
    pub fn new(covariance: &DMatrix<f64>, lengths_m: &[f64]) -> Option<Self> {
        let m = lengths_m.len();
        if covariance.nrows() != 3 * m || covariance.ncols() != 3 * m {
            return None;
        }
        let spheres = lengths_m
            .iter()
            .enumerate()
            .map(|(k, &l)| {
                let block: Matrix3<f64> = covariance.fixed_view::<3, 3>(3 * k, 3 * k).into_owned();
                WeightedSphere::from_covariance(&block, l)
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Self { spheres })
    }

    /// The constrained baselines `b_k` (each `||b_k|| = l_k`) of `b_hat` (vec, 3m).
    pub fn fit(&self, b_hat: &DVector<f64>) -> Option<Vec<SphereFit>> {
        if b_hat.len() != 3 * self.spheres.len() {
            return None;
        }
        self.spheres
            .iter()
            .zip(b_hat.as_slice().chunks_exact(3))
            .map(|(s, b)| s.fit(&Vec3::new(b[0], b[1], b[2])))
            .collect()
    }
}

impl CandidateMisfit for LengthMisfit {
    /// `sum_k min_{||b_k|| = l_k} ||b_hat_k - b_k||^2_{W_k}` of `b_hat` (vec, 3m); `None`
    /// when its size is wrong or a value not finite.
    fn misfit(&self, b_hat: &DVector<f64>) -> Option<f64> {
        if b_hat.len() != 3 * self.spheres.len() {
            return None;
        }
        self.spheres
            .iter()
            .zip(b_hat.as_slice().chunks_exact(3))
            .map(|(s, b)| s.fit(&Vec3::new(b[0], b[1], b[2])).map(|f| f.cost))
            .sum()
    }
}

/// The length-constrained best and second-best integers of the free ambiguities `cond`
/// of `float` (the held ones, `held`, kept at their values), the lengths taken from
/// `geometry` (one per baseline of `float`); `accept_ratio` as in
/// [`search_with_misfit`].
pub fn search(
    float: &FloatBaselines,
    cond: &Conditioned,
    held: &[(usize, i64)],
    geometry: &BodyGeometry,
    accept_ratio: f64,
) -> Result<ConstrainedFix, ConstrainedError> {
    let m = float.model.baseline_count();
    if geometry.len() != m {
        return Err(AttitudeError::BaselineCount {
            geometry: geometry.len(),
            measured: m,
        }
        .into());
    }
    let lengths = geometry.lengths_m();
    search_with_misfit(float, cond, held, geometry, accept_ratio, |covariance| {
        LengthMisfit::new(covariance, &lengths)
    })
}

/// The search under each baseline's length (`constraint = "length"`), any number of
/// baselines.
#[derive(Debug, Clone)]
pub struct LengthSearch {
    geometry: BodyGeometry,
}

impl LengthSearch {
    pub fn new(geometry: BodyGeometry) -> Self {
        Self { geometry }
    }
}

impl ConstrainedSearch for LengthSearch {
    fn search(
        &self,
        float: &FloatBaselines,
        cond: &Conditioned,
        held: &[(usize, i64)],
        _: &Vec3,
        accept_ratio: f64,
    ) -> Searched {
        Searched::of(
            "length",
            search(float, cond, held, &self.geometry, accept_ratio),
        )
    }

    fn method(&self) -> FixMethod {
        FixMethod::Length
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, StandardNormal};

    /// `(b_hat - l u)^T W (b_hat - l u)`.
    fn cost_at(w: &Matrix3<f64>, b_hat: &Vec3, l: f64, u: &Vec3) -> f64 {
        let r = b_hat - u * l;
        r.dot(&(w * r))
    }

    /// Two unit vectors completing `u` to an orthonormal basis.
    fn tangent(u: &Vec3) -> (Vec3, Vec3) {
        let a = if u.x.abs() < 0.6 {
            Vec3::x()
        } else {
            Vec3::y()
        };
        let e1 = (a - u * u.dot(&a)).normalize();
        (e1, u.cross(&e1))
    }

    /// The naive oracle: the cost on a Fibonacci grid of directions, then Newton's method
    /// on the sphere (tangent coordinates of the exponential map, backtracking) from the
    /// best grid points; the least cost found.
    fn oracle(w: &Matrix3<f64>, b_hat: &Vec3, l: f64) -> f64 {
        const GRID: usize = 20_000;
        const STARTS: usize = 100;
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let mut grid: Vec<(f64, Vec3)> = (0..GRID)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / GRID as f64;
                let r = (1.0 - z * z).sqrt();
                let t = golden * i as f64;
                let u = Vec3::new(r * t.cos(), r * t.sin(), z);
                (cost_at(w, b_hat, l, &u), u)
            })
            .collect();
        grid.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::INFINITY;
        for &(mut f, mut u) in &grid[..STARTS] {
            for _ in 0..100 {
                let r = b_hat - u * l;
                let g_e = -2.0 * l * (w * r);
                let (e1, e2) = tangent(&u);
                let g = nalgebra::Vector2::new(e1.dot(&g_e), e2.dot(&g_e));
                let h_e = 2.0 * l * l * w;
                let radial = u.dot(&g_e);
                let h = nalgebra::Matrix2::new(
                    e1.dot(&(h_e * e1)) - radial,
                    e1.dot(&(h_e * e2)),
                    e2.dot(&(h_e * e1)),
                    e2.dot(&(h_e * e2)) - radial,
                );
                let v = match h.cholesky() {
                    Some(c) => -c.solve(&g),
                    None => -g / (h.norm() + g.norm()),
                };
                let mut t = 1.0;
                let mut moved = false;
                for _ in 0..60 {
                    let step = (e1 * v.x + e2 * v.y) * t;
                    let a = step.norm();
                    let candidate = if a == 0.0 {
                        u
                    } else {
                        (u * a.cos() + step * (a.sin() / a)).normalize()
                    };
                    let fc = cost_at(w, b_hat, l, &candidate);
                    if fc < f {
                        (f, u, moved) = (fc, candidate, true);
                        break;
                    }
                    t *= 0.5;
                }
                if !moved {
                    break;
                }
            }
            best = best.min(f);
        }
        best
    }

    fn random_rotation(rng: &mut ChaCha8Rng) -> Matrix3<f64> {
        let q = nalgebra::Quaternion::new(
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
            StandardNormal.sample(rng),
        );
        nalgebra::UnitQuaternion::from_quaternion(q)
            .to_rotation_matrix()
            .into_inner()
    }

    fn random_unit(rng: &mut ChaCha8Rng) -> Vec3 {
        Vec3::from_fn(|_, _| StandardNormal.sample(rng)).normalize()
    }

    /// Checks one fit: the length, the stationarity `W (b - b_hat) + mu b = 0` with
    /// `W + mu I` semidefinite, the cost at the point, and the cost against the oracle.
    fn check(w: &Matrix3<f64>, b_hat: &Vec3, l: f64, what: &str) {
        let sphere = WeightedSphere::from_weight(w, l).unwrap();
        let fit = sphere.fit(b_hat).unwrap();
        let b = fit.point;
        let eig = SymmetricEigen::new(*w).eigenvalues;
        let (w_min, w_max) = (eig.min(), eig.max());
        assert!(
            (b.norm() - l).abs() <= 1e-14 * l,
            "{what}: |b| = {} vs {l}",
            b.norm()
        );
        let residual = w * (b - b_hat) + b * fit.multiplier;
        let scale = w_max * (b_hat.norm() + l) + fit.multiplier.abs() * l;
        assert!(
            residual.norm() <= 1e-9 * scale,
            "{what}: stationarity residual {} (scale {scale})",
            residual.norm()
        );
        assert!(
            fit.multiplier >= -w_min * (1.0 + 1e-9),
            "{what}: mu = {} below -w_min = {}",
            fit.multiplier,
            -w_min
        );
        let direct = cost_at(w, b_hat, 1.0, &b);
        let floor = 1e-12 * w_max * (b_hat.norm() + l).powi(2);
        assert!(
            (fit.cost - direct).abs() <= 1e-9 * direct + floor,
            "{what}: cost {} vs at the point {direct}",
            fit.cost
        );
        let best = oracle(w, b_hat, l);
        assert!(
            (fit.cost - best).abs() <= 1e-9 * best + floor,
            "{what}: cost {} vs oracle {best} (relative {:e})",
            fit.cost,
            (fit.cost - best) / best
        );
    }

    /// Random SPD weights (condition numbers 1..1e6), directions, lengths, and `b_hat`
    /// from far inside the sphere to far outside, against the grid-and-Newton oracle.
    /// Agreement to 1e-9 relative: the attainable precision is about `eps cond(W)` (the
    /// smallest eigenvalue, and `r^T W r` along its eigenvector, carry an absolute error of
    /// `eps w_max`), 2e-10 at 1e6; the largest difference seen on these 300 cases is 1.8e-10.
    #[test]
    fn sphere_fit_matches_the_naive_oracle() {
        let mut rng = ChaCha8Rng::seed_from_u64(20_100_433);
        for case in 0..300 {
            let condition = 10f64.powf(rng.random_range(0.0..6.0));
            let scale = 10f64.powf(rng.random_range(-2.0..6.0));
            let mut w = [
                scale,
                scale * condition.powf(rng.random_range(0.0..1.0)),
                scale * condition,
            ];
            w.swap(0, rng.random_range(0..3));
            let r = random_rotation(&mut rng);
            let weight = r * Matrix3::from_diagonal(&Vec3::from(w)) * r.transpose();
            let l = 10f64.powf(rng.random_range(-1.0..1.0));
            // |b_hat| / l from 1e-3 (deep inside) to 1e3 (far outside).
            let ratio = 10f64.powf(rng.random_range(-3.0..3.0));
            let b_hat = random_unit(&mut rng) * (ratio * l);
            check(&weight, &b_hat, l, &format!("case {case}"));
        }
    }

    /// The hard case and its neighbours: `b_hat` with no component along the smallest
    /// weight's eigenvector (exactly, and 1e-12 off it), repeated eigenvalues, `b_hat = 0`.
    #[test]
    fn hard_and_degenerate_cases_match_the_oracle() {
        let diag = Matrix3::from_diagonal(&Vec3::new(1.0, 4.0, 9.0));
        let cases = [
            (diag, Vec3::new(0.0, 0.1, 0.1), 1.0, "hard case"),
            (
                diag,
                Vec3::new(1e-12, 0.1, 0.1),
                1.0,
                "next to the hard case",
            ),
            (
                diag,
                Vec3::new(-1e-12, 0.1, 0.1),
                1.0,
                "next to it, other side",
            ),
            (
                diag,
                Vec3::new(0.0, 3.0, 0.1),
                1.0,
                "zero component, outside",
            ),
            (diag, Vec3::zeros(), 1.0, "b_hat = 0"),
            (
                Matrix3::identity(),
                Vec3::new(0.3, -0.2, 0.1),
                2.0,
                "W = I inside",
            ),
            (
                Matrix3::identity() * 7.0,
                Vec3::new(3.0, -2.0, 1.0),
                0.5,
                "W = 7 I outside",
            ),
            (Matrix3::identity(), Vec3::zeros(), 2.0, "W = I, b_hat = 0"),
            (
                Matrix3::from_diagonal(&Vec3::new(2.0, 2.0, 5.0)),
                Vec3::new(0.0, 0.0, 0.2),
                1.0,
                "double smallest eigenvalue, hard case",
            ),
            (
                Matrix3::from_diagonal(&Vec3::new(5.0, 2.0, 2.0)),
                Vec3::new(0.1, 0.0, 1e-9),
                1.0,
                "double smallest eigenvalue, near hard",
            ),
        ];
        for (w, b_hat, l, what) in cases {
            check(&w, &b_hat, l, what);
        }
        let hard = WeightedSphere::from_weight(&diag, 1.0)
            .unwrap()
            .fit(&Vec3::new(0.0, 0.1, 0.1))
            .unwrap();
        assert_eq!(hard.multiplier, -1.0);
        assert!(hard.point.x.abs() > 0.9);
    }

    #[test]
    fn covariance_and_weight_give_the_same_fit() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..50 {
            let r = random_rotation(&mut rng);
            let s = Vec3::from_fn(|_, _| 1e-6 * 10f64.powf(rng.random_range(0.0..2.0)));
            let q = r * Matrix3::from_diagonal(&s) * r.transpose();
            let b_hat = random_unit(&mut rng) * rng.random_range(0.9..1.1);
            let from_q = WeightedSphere::from_covariance(&q, 1.0)
                .unwrap()
                .fit(&b_hat);
            let w = q.try_inverse().unwrap();
            let from_w = WeightedSphere::from_weight(&w, 1.0).unwrap().fit(&b_hat);
            let (a, b) = (from_q.unwrap(), from_w.unwrap());
            assert!(
                (a.cost - b.cost).abs() <= 1e-9 * a.cost.max(1e-6),
                "{a:?} {b:?}"
            );
            assert!((a.point - b.point).norm() <= 1e-9);
        }
    }

    #[test]
    fn bad_inputs_are_refused() {
        let w = Matrix3::identity();
        assert!(WeightedSphere::from_weight(&w, 0.0).is_none());
        assert!(WeightedSphere::from_weight(&w, f64::NAN).is_none());
        assert!(
            WeightedSphere::from_weight(&Matrix3::from_diagonal(&Vec3::new(1.0, 1.0, 0.0)), 1.0)
                .is_none()
        );
        assert!(
            WeightedSphere::from_weight(&Matrix3::from_diagonal(&Vec3::new(1.0, 1.0, -1.0)), 1.0)
                .is_none()
        );
        assert!(
            WeightedSphere::from_weight(&Matrix3::from_diagonal(&Vec3::new(1.0, 1.0, 1e15)), 1.0)
                .is_none()
        );
        assert!(WeightedSphere::from_covariance(&Matrix3::zeros(), 1.0).is_none());
        let sphere = WeightedSphere::from_weight(&w, 1.0).unwrap();
        assert!(sphere.fit(&Vec3::new(f64::NAN, 0.0, 0.0)).is_none());
        let q = DMatrix::identity(6, 6) * 1e-6;
        assert!(LengthMisfit::new(&q, &[1.0]).is_none());
        let misfit = LengthMisfit::new(&q, &[1.0, 2.0]).unwrap();
        assert!(misfit.misfit(&DVector::zeros(3)).is_none());
        // Baselines already of the right lengths cost nothing.
        let b = DVector::from_vec(vec![0.0, 1.0, 0.0, 0.0, 0.0, -2.0]);
        assert!(misfit.misfit(&b).unwrap() < 1e-20);
        let fits = misfit.fit(&b).unwrap();
        assert!((fits[1].point - Vec3::new(0.0, 0.0, -2.0)).norm() < 1e-15);
    }
}
