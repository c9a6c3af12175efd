//! Integer least-squares search (Chang, Yang & Zhou 2005 §4): depth-first over the
//! conditional estimates `zc_k = z_hat_k - sum_{j>k} L_jk (zc_j - z_j)`, from the last
//! ambiguity to the first, each level visiting integers in Schnorr-Euchner order (nearest
//! first, then alternating outwards), inside an ellipsoid that shrinks to the `count`-th
//! best squared norm found so far.
//!
//! The squared norm of a candidate is `sum_k (zc_k - z_k)^2 / d_k`
//! (de Jonge & Tiberius 1996 §4.2), which equals `(z_hat - z)^T Q_z^{-1} (z_hat - z)`.

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
    let n = d.len();
    let lv = l.as_slice();
    let mut zc = vec![0.0; n];
    let mut z = vec![0.0; n];
    let mut step = vec![0.0; n];
    // above[k]: the squared norm of levels k+1..n (fixed while level k varies).
    let mut above = vec![0.0; n];
    let mut found = Found::with_capacity(count);
    let mut chi2 = f64::INFINITY;
    let mut nodes = 0u64;

    let mut k = n - 1;
    zc[k] = z_hat[k];
    z[k] = round_fast(zc[k]);
    let mut y = zc[k] - z[k];
    step[k] = first_step(y);
    loop {
        nodes += 1;
        if nodes > MAX_SEARCH_NODES {
            return Err(AmbiguityError::SearchLimit);
        }
        let dist = above[k] + y * y / d[k];
        if dist < chi2 {
            if k > 0 {
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
            } else {
                chi2 = found.offer(&z, dist);
                z[0] += step[0];
                y = zc[0] - z[0];
                step[0] = -step[0] - first_step(step[0]);
            }
        } else {
            if k == n - 1 {
                break;
            }
            k += 1;
            z[k] += step[k];
            y = zc[k] - z[k];
            step[k] = -step[k] - first_step(step[k]);
        }
    }
    found.into_sorted()
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
