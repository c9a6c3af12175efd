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
    let mut found: Vec<(Vec<f64>, f64)> = Vec::with_capacity(count);
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
                if found.len() < count {
                    found.push((z.clone(), dist));
                    if found.len() == count {
                        chi2 = worst(&found).1;
                    }
                } else {
                    let (w, _) = worst(&found);
                    found[w].0.copy_from_slice(&z);
                    found[w].1 = dist;
                    chi2 = worst(&found).1;
                }
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
    if found.len() < count {
        return Err(AmbiguityError::Degenerate);
    }
    found.sort_by(|a, b| a.1.total_cmp(&b.1));
    Ok(found)
}

/// Index and squared norm of the worst stored candidate.
fn worst(found: &[(Vec<f64>, f64)]) -> (usize, f64) {
    found
        .iter()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |acc, (i, c)| {
            if c.1 > acc.1 { (i, c.1) } else { acc }
        })
}
