//! Integer least-squares search (Chang, Yang & Zhou 2005 §4): depth-first over the
//! conditional estimates `zc_k = z_hat_k - sum_{j>k} L_jk (zc_j - z_j)`, from the last
//! ambiguity to the first, each level visiting integers in Schnorr-Euchner order (nearest
//! first, then alternating outwards), inside an ellipsoid that shrinks to the `count`-th
//! best squared norm found so far. The first leaf reached is the bootstrapped solution
//! and the next ones its neighbours in the first ambiguity, so the ellipsoid is finite
//! after `count` leaves (search-and-shrink, Chang, Yang & Zhou 2005 §4).
//!
//! The squared norm of a candidate is `sum_k (zc_k - z_k)^2 / d_k`
//! (de Jonge & Tiberius 1996 §4.2), which equals `(z_hat - z)^T Q_z^{-1} (z_hat - z)`.
//!
//! The ellipsoid alone prunes a node only when its own levels exceed the bound. With
//! many ambiguities whose estimates are far from integers the levels below still have
//! their share to add, and the nodes near the top within the bound grow exponentially
//! with the dimension (100 ambiguities of `Q = I` took more than 10^8 nodes; the
//! expected complexity of sphere decoding is exponential, Jalden & Ottersten 2005, IEEE
//! Trans. Signal Process. 53(4)). [`Completion`] bounds from below what the levels below
//! a node must add and prunes the node when that exceeds the ellipsoid (Stojnic, Vikalo &
//! Hassibi 2008), exactly for a diagonal `Q_z`. It only removes subtrees without a leaf
//! inside the ellipsoid: the leaves reached, in the same order, and so the result are
//! those of the search without it.

use super::{AmbiguityError, MAX_SEARCH_NODES, round_fast};
use nalgebra::DMatrix;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Sign of the next step from `round(zc)` towards the second-nearest integer.
fn first_step(y: f64) -> f64 {
    if y > 0.0 { 1.0 } else { -1.0 }
}

/// The `count` integer vectors nearest to `z_hat` in the metric of `L^T D L`, best
/// first, with their squared norms. Integers are returned as whole `f64`s.
pub(crate) fn search(
    l: &DMatrix<f64>,
    d: &[f64],
    z_hat: &[f64],
    count: usize,
) -> Result<Vec<(Vec<f64>, f64)>, AmbiguityError> {
    search_bounded_after(l, d, z_hat, count, BOUNDS_AFTER_NODES)
}

/// [`search`] with [`Completion`] from node `bounds_after` on and its bound 2 from
/// four times as many (never with `u64::MAX`).
pub(crate) fn search_bounded_after(
    l: &DMatrix<f64>,
    d: &[f64],
    z_hat: &[f64],
    count: usize,
    bounds_after: u64,
) -> Result<Vec<(Vec<f64>, f64)>, AmbiguityError> {
    let n = d.len();
    let lv = l.as_slice();
    let mut zc = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut step = vec![0.0; n];
    // above[k]: the squared norm of levels k+1..n (fixed while level k varies).
    let mut above = vec![0.0; n];
    let mut found = Found::with_capacity(count);
    let mut completion: Option<Completion> = None;
    let mut chi2 = f64::INFINITY;
    let mut nodes = 0u64;
    let spectral_after = bounds_after.saturating_mul(4);
    let mut next_event = bounds_after.min(MAX_SEARCH_NODES + 1);

    let mut k = n - 1;
    zc[k] = z_hat[k];
    z[k] = round_fast(zc[k]);
    let mut y = zc[k] - z[k];
    step[k] = first_step(y);
    loop {
        nodes += 1;
        if nodes >= next_event {
            if nodes > MAX_SEARCH_NODES {
                return Err(AmbiguityError::SearchLimit { n });
            }
            next_event = match &mut completion {
                None => {
                    completion = Some(Completion::new(l, d, z_hat, nodes));
                    spectral_after
                }
                Some(c) => {
                    c.add_spectral_bound(l, d);
                    u64::MAX
                }
            }
            .min(MAX_SEARCH_NODES + 1);
        }
        let dist = above[k] + y * y / d[k];
        // Whether level k is done: outside the ellipsoid, or nothing below fits.
        let done = if dist >= chi2 || dist.is_nan() {
            true
        } else if k > 0 {
            k -= 1;
            above[k] = dist;
            let below = &lv[k * n + k + 1..(k + 1) * n];
            let s: f64 = below
                .iter()
                .zip(&zc[k + 1..])
                .zip(&z[k + 1..])
                .map(|((lj, zcj), zj)| lj * (zcj - zj))
                .sum();
            zc[k] = z_hat[k] - s;
            z[k] = round_fast(zc[k]);
            y = zc[k] - z[k];
            step[k] = first_step(y);
            k > 1
                && completion
                    .as_mut()
                    .is_some_and(|c| c.exceeds(k, dist, chi2, &zc, &z, nodes))
        } else {
            chi2 = found.offer(&z, dist);
            z[0] += step[0];
            y = zc[0] - z[0];
            step[0] = -step[0] - first_step(step[0]);
            false
        };
        if done {
            if k == n - 1 {
                break;
            }
            if k > 1
                && let Some(c) = &mut completion
            {
                c.left(k, nodes);
            }
            k += 1;
            z[k] += step[k];
            y = zc[k] - z[k];
            step[k] = -step[k] - first_step(step[k]);
        }
    }
    found.into_sorted()
}

/// Relative allowance for rounding in [`Completion::exceeds`]: the bounds are lowered by
/// far more than the rounding of `n <= 500` terms (about `n * 1.1e-16`) could raise them,
/// so a subtree is pruned only when none of its leaves can enter the ellipsoid.
const ROUNDING_ALLOWANCE: f64 = 1e-10;
/// Nodes per level below a node (on average, over the recent subtrees of its level that
/// were searched) under which the bounds are not evaluated there: an evaluation reads
/// each level below once or twice, and smaller subtrees are searched faster than bounded.
const NODES_PER_LEVEL_WORTH_BOUNDING: u64 = 4;
/// Nodes after which the search uses [`Completion`] (its tables take `O(n^2 log n)`,
/// which problems solved in fewer nodes do not pay for; its bound 2, an SVD, `O(n^3)`,
/// comes after four times as many).
const BOUNDS_AFTER_NODES: u64 = 1 << 16;

/// Lower bounds of the squared norm the levels below a node must add.
///
/// With levels `p..n` fixed at a node of level `p` (residuals `r_i = zc_i - z_i`), level
/// `j < p` has the estimate `x_j = z_hat_j - sum_{i>=p} L_ij r_i` given the fixed levels
/// alone; a completion `z_0..z_{p-1}` with residuals `r_0..r_{p-1}` moves it to
/// `zc_j = x_j - sum_{j<i<p} L_ij r_i`, so `e = x - z = L_p^T r` (`L_p` the leading
/// `p x p` block of `L`), and it adds `C = sum_{j<p} r_j^2 / d_j`. With `f_j` the
/// distance of `x_j` to the nearest integer (`|e_j| >= f_j`) and `B` the budget (the
/// bound minus the node's partial norm), a completion inside the ellipsoid has `C < B`,
/// and then:
///
/// 1. by Cauchy-Schwarz `|zc_j - x_j| < s_jp sqrt(B)` with
///    `s_jp^2 = sum_{j<i<p} L_ij^2 d_i`, so `C >= sum_{j<p} max(0, f_j - s_jp sqrt(B))^2 / d_j`;
/// 2. with `v = D^{-1/2} r` and `u = D^{-1/2} e = P v`, `P = D^{-1/2} L^T D^{1/2}` (unit
///    upper triangular; its leading blocks are those of the full `P`),
///    `C = |v|^2 >= |u|^2 / (1 + nu)^2 >= sum_{j<p} f_j^2 / d_j / (1 + nu)^2` for any
///    `nu >= |P - I|_2`.
///
/// When either bound reaches `B`, no leaf below the node enters the ellipsoid: a lower
/// bound on the unfixed levels prunes the tree as in Stojnic, Vikalo & Hassibi 2008,
/// "Speeding up the sphere decoder with H-infinity and SDP inspired lower bounds", IEEE
/// Trans. Signal Process. 56(2) (these two bounds are derived here). For a diagonal `Q_z`
/// (`L = I`) both are the exact remaining norm, and the search visits `O(n)` nodes per
/// candidate found; for a nearly diagonal one they stay close to it. Strongly correlated
/// levels (large `s_jp`, `nu`) make them weak; they are evaluated only where what they
/// can reach at most ([`Completion::reach`], `O(log n)`) could prune and where the
/// search below a node takes more nodes than an evaluation reads entries
/// ([`NODES_PER_LEVEL_WORTH_BOUNDING`]), so that they cost hard correlated searches
/// (many candidates of 30 GNSS-like ambiguities) 10-20 % more instructions.
struct Completion {
    n: usize,
    /// `L` by rows: `rows[p * n + j] = L_pj` (`j < p`).
    rows: Vec<f64>,
    /// `s[p * n + j] = s_jp` (`j < p`).
    s: Vec<f64>,
    inv_d: Vec<f64>,
    /// `cap[k] = sum_{j<k} 1 / (4 d_j)`.
    cap: Vec<f64>,
    /// `x[k * n + j]`, `j <= k`: the estimate of level `j` given levels `k+1..n` (row
    /// `n - 1` is `z_hat`), for rows `valid..n` on the current path; the others are
    /// rebuilt when a bound needs them (as MLAMBDA keeps its partial sums, Chang, Yang &
    /// Zhou 2005 §4).
    x: Vec<f64>,
    valid: usize,
    /// The node count when the search entered level `k` below a node of level `k + 1`;
    /// eight times the nodes it took below such nodes, a running average (each new
    /// subtree weighs 1/8) over those not pruned, starting high; and eight times
    /// `NODES_PER_LEVEL_WORTH_BOUNDING (k + 1)`, from which the bounds are evaluated
    /// entering level `k`.
    entered: Vec<u64>,
    explored: Vec<u64>,
    worth: Vec<u64>,
    /// For the levels `j < p - 1` in ascending order of `s_jp`, at `p * n..`: `s_jp`,
    /// and the running sums of `1 / d_j`, `s_jp / d_j` and `s_jp^2 / d_j` (bound 1 of
    /// those levels is at most `sum (1/2 - s_jp sqrt(B))^2 / d_j` over the ones with
    /// `s_jp sqrt(B) < 1/2`).
    sorted_s: Vec<f64>,
    sums: [Vec<f64>; 3],
    /// Absolute scale of the rounding of `x`: `1 + max |z_hat_j|`.
    scale: f64,
    /// `max_j s_jn`: the estimates move by at most `s_max sqrt(chi2)` from `z_hat`.
    s_max: f64,
    /// `1 / (1 + nu)^2` of bound 2; 0 until [`Completion::add_spectral_bound`].
    spectral: f64,
}

impl Completion {
    fn new(l: &DMatrix<f64>, d: &[f64], z_hat: &[f64], nodes: u64) -> Self {
        let n = d.len();
        let mut rows = vec![0.0; n * n];
        let mut s = vec![0.0; n * n];
        let mut s_max = 0.0f64;
        for j in 0..n {
            let mut acc = 0.0f64;
            for p in j + 1..n {
                s[p * n + j] = acc.sqrt();
                let lpj = l[(p, j)];
                rows[p * n + j] = lpj;
                acc += lpj * lpj * d[p];
            }
            s_max = s_max.max(acc.sqrt());
        }
        let inv_d: Vec<f64> = d.iter().map(|v| 1.0 / v).collect();
        let mut sorted_s = vec![0.0; n * n];
        let mut sums = [vec![0.0; n * n], vec![0.0; n * n], vec![0.0; n * n]];
        let mut order: Vec<usize> = Vec::with_capacity(n);
        for p in 2..n {
            order.clear();
            order.extend(0..p - 1);
            order.sort_by(|&a, &b| s[p * n + a].total_cmp(&s[p * n + b]));
            let mut acc = [0.0; 3];
            for (i, &j) in order.iter().enumerate() {
                let sj = s[p * n + j];
                acc[0] += inv_d[j];
                acc[1] += sj * inv_d[j];
                acc[2] += sj * sj * inv_d[j];
                sorted_s[p * n + i] = sj;
                for (sum, a) in sums.iter_mut().zip(acc) {
                    sum[p * n + i] = a;
                }
            }
        }
        let mut cap = vec![0.0; n];
        for k in 1..n {
            cap[k] = cap[k - 1] + 0.25 * inv_d[k - 1];
        }
        let mut x = vec![0.0; n * n];
        x[(n - 1) * n..].copy_from_slice(z_hat);
        Self {
            n,
            rows,
            s,
            inv_d,
            cap,
            x,
            valid: n - 1,
            entered: vec![nodes; n],
            explored: vec![u64::MAX; n],
            worth: (0..n)
                .map(|k| 8 * NODES_PER_LEVEL_WORTH_BOUNDING * (k as u64 + 1))
                .collect(),
            sorted_s,
            sums,
            scale: 1.0 + z_hat.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            s_max,
            spectral: 0.0,
        }
    }

    /// Bound 2 with `nu` the largest singular value of `P - I` (computed singular values
    /// are within a small multiple of `n eps |P - I|_2` of the true ones, Golub & Van
    /// Loan 2013, Matrix Computations, 4th ed., §8.6; `1e-12 |P - I|_F` covers that), or
    /// its Frobenius norm should the SVD not converge.
    fn add_spectral_bound(&mut self, l: &DMatrix<f64>, d: &[f64]) {
        let n = self.n;
        let p = DMatrix::from_fn(n, n, |j, i| {
            if i > j {
                l[(i, j)] * (d[i] / d[j]).sqrt()
            } else {
                0.0
            }
        });
        let frobenius = p.norm();
        let nu = p
            .try_svd_unordered(false, false, 5.0 * f64::EPSILON, 100 * n)
            .map_or(frobenius, |svd| {
                svd.singular_values.max() + 1e-12 * frobenius
            });
        self.spectral = 1.0 / ((1.0 + nu) * (1.0 + nu));
    }

    /// The search leaves level `k >= 2` (at node count `nodes`) for the node above.
    fn left(&mut self, k: usize, nodes: u64) {
        let size = nodes - self.entered[k];
        if size > 0 {
            let e = &mut self.explored[k];
            *e = if *e == u64::MAX {
                8 * size
            } else {
                *e - *e / 8 + size
            };
        }
    }

    /// The most bound 1 can take from levels `j < p - 1` with budget `root^2`.
    fn reach(&self, p: usize, root: f64) -> f64 {
        let n = self.n;
        let within = self.sorted_s[p * n..p * n + p - 1].partition_point(|&s| s * root < 0.5);
        if within == 0 {
            return 0.0;
        }
        let at = p * n + within - 1;
        let [a, b, c] = &self.sums;
        (0.25 * a[at] - root * b[at] + root * root * c[at]).max(0.0)
    }

    /// Whether no leaf below the node of level `k + 1` (partial norm `dist`) can have a
    /// squared norm below `chi2`, by bound 1 or 2; the search has just entered level `k`
    /// below it (at node count `nodes`), and `zc`, `z` hold the path, `z_k` the integer
    /// nearest to `zc_k` (so level `k` adds at least `(zc_k - z_k)^2 / d_k`).
    ///
    /// The search calls it on every step down into a level `k >= 2` (the rows below the
    /// node are marked stale here): a level changes only by a step down into it or to
    /// its next integer, and the search steps down from it before its new value is
    /// used below (rows 0 and 1 are never used).
    fn exceeds(
        &mut self,
        k: usize,
        dist: f64,
        chi2: f64,
        zc: &[f64],
        z: &[f64],
        nodes: u64,
    ) -> bool {
        let n = self.n;
        self.entered[k] = nodes;
        self.valid = self.valid.max(k + 1);
        if self.explored[k] < self.worth[k] || !chi2.is_finite() {
            return false;
        }
        let budget = chi2 - dist + ROUNDING_ALLOWANCE * chi2;
        let y = zc[k] - z[k];
        let own = y * y * self.inv_d[k];
        if own >= budget {
            // The search leaves level k at once anyway.
            return false;
        }
        // The most each bound can reach (`f_j <= 1/2`): the rows are rebuilt and the
        // bounds evaluated only when one could reach the budget.
        let p = k + 1;
        let root = budget.sqrt();
        let reach_1 = own + self.reach(p, root);
        let reach_2 = self.spectral * (own + self.cap[k]);
        if reach_1 < budget && reach_2 < budget {
            return false;
        }
        // Rows valid - 1 down to k: x_{i-1, j} = x_{i, j} - L_ij r_i.
        for i in (p..=self.valid).rev() {
            let r = zc[i] - z[i];
            let (below, here) = self.x.split_at_mut(i * n);
            let row = &mut below[(i - 1) * n..(i - 1) * n + i];
            for ((c, &x), &lij) in row.iter_mut().zip(&here[..i]).zip(&self.rows[i * n..]) {
                *c = x - lij * r;
            }
        }
        self.valid = k;
        let x = &self.x[k * n..k * n + p];
        let s = &self.s[p * n..p * n + p];
        let slack = ROUNDING_ALLOWANCE * (self.scale + self.s_max * chi2.sqrt());
        let (mut shifted, mut plain) = (0.0, 0.0);
        for j in (0..p).rev() {
            let f = ((x[j] - round_fast(x[j])).abs() - slack).max(0.0);
            plain += f * f * self.inv_d[j];
            let gap = (f - s[j] * root).max(0.0);
            shifted += gap * gap * self.inv_d[j];
            if shifted >= budget || self.spectral * plain >= budget {
                return true;
            }
            if shifted + self.cap[j] < budget && self.spectral * (plain + self.cap[j]) < budget {
                // Neither bound can reach the budget with what levels below j add.
                return false;
            }
        }
        false
    }
}

/// A squared norm and the slot of its candidate, ordered by the norm (a max-heap entry).
#[derive(Debug, Clone, Copy)]
struct Ranked(f64, usize);

impl PartialEq for Ranked {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Ranked {}

impl PartialOrd for Ranked {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ranked {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The best `count` candidates found so far, the worst on top of a heap (a candidate
/// replaces it in `O(log count)`; a linear scan made a search for a thousand candidates
/// quadratic).
struct Found {
    count: usize,
    candidates: Vec<(Vec<f64>, f64)>,
    worst: BinaryHeap<Ranked>,
}

impl Found {
    fn with_capacity(count: usize) -> Self {
        Self {
            count,
            candidates: Vec::with_capacity(count),
            worst: BinaryHeap::with_capacity(count),
        }
    }

    /// Keep `z` (squared norm `dist`, below the current bound); returns the new bound:
    /// the worst kept squared norm once `count` are kept, infinite before.
    fn offer(&mut self, z: &[f64], dist: f64) -> f64 {
        if self.candidates.len() < self.count {
            self.worst.push(Ranked(dist, self.candidates.len()));
            self.candidates.push((z.to_vec(), dist));
        } else if let Some(Ranked(_, slot)) = self.worst.pop() {
            self.candidates[slot].0.copy_from_slice(z);
            self.candidates[slot].1 = dist;
            self.worst.push(Ranked(dist, slot));
        }
        if self.candidates.len() < self.count {
            f64::INFINITY
        } else {
            self.worst.peek().map_or(f64::INFINITY, |r| r.0)
        }
    }

    /// The kept candidates, best first; an error when fewer than `count` were found.
    fn into_sorted(self) -> Result<Vec<(Vec<f64>, f64)>, AmbiguityError> {
        if self.candidates.len() < self.count {
            return Err(AmbiguityError::Degenerate);
        }
        let mut found = self.candidates;
        found.sort_by(|a, b| a.1.total_cmp(&b.1));
        Ok(found)
    }
}
