//! The two-way fixed-effects least-squares fit `y_j = a_g(j) + c_k(j) + e_j` of error
//! samples `y_j`, each in one group `g` (a satellite, or a carrier-phase arc) and at one
//! epoch `k`: `a_g` is the group's offset (a satellite's bias, an arc's ambiguity) and
//! `c_k` the epoch's common term (the clock difference between estimate and truth).
//!
//! Exact least squares, not alternating means: eliminating `c_k = mean over epoch k of
//! (y - a)` leaves normal equations `M a = b` with, per epoch holding groups `G_k`
//! (`n_k = |G_k|`), `M[g][g] += 1 - 1/n_k`, `M[g][h] -= 1/n_k` and
//! `b[g] += y_gk - mean_k(y)` (a weighted graph Laplacian). Its null space is one constant
//! per connected set of groups (groups linked by sharing epochs), so one reference group
//! per set (the one with most samples) is pinned to 0 and the rest solved by Cholesky.
//!
//! The residual variance is `SSR / dof` with `dof = N - K - G + C` (samples, epochs,
//! groups, connected sets: the rank of the design), unbiased for independent errors of
//! equal variance. Per group, `sum of squared residuals / n_g * N / dof` rescales by the
//! same factor (exact when every group loses the same share of its degrees of freedom).

use nalgebra::{DMatrix, DVector};

/// One error sample: its group, its epoch and its value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub group: usize,
    pub epoch: usize,
    pub value: f64,
}

/// The least-squares fit of [`fit`].
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Offset of each group, 0 for the reference group of its connected set (`NaN` for a
    /// group without samples).
    pub group_offset: Vec<f64>,
    /// Connected set of each group.
    pub group_set: Vec<usize>,
    /// The reference group of each connected set.
    pub set_reference: Vec<usize>,
    /// Common term of each epoch (`NaN` for an epoch without samples).
    pub epoch_term: Vec<f64>,
    /// Residual of each sample, in input order.
    pub residual: Vec<f64>,
    /// Degrees of freedom of the residuals.
    pub dof: usize,
}

impl Fit {
    /// Residual standard deviation over all samples, `sqrt(SSR / dof)`; `None` without
    /// degrees of freedom.
    pub fn std(&self) -> Option<f64> {
        (self.dof > 0).then(|| (self.ssr() / self.dof as f64).sqrt())
    }

    /// Standard deviation of the residuals of the samples `in_group` selects (a group or a
    /// union of groups), rescaled by `N / dof` (see the module documentation).
    pub fn std_of(&self, samples: &[Sample], in_group: impl Fn(usize) -> bool) -> Option<f64> {
        if self.dof == 0 {
            return None;
        }
        let (mut ss, mut n) = (0.0, 0usize);
        for (s, r) in samples.iter().zip(&self.residual) {
            if in_group(s.group) {
                ss += r * r;
                n += 1;
            }
        }
        let scale = self.residual.len() as f64 / self.dof as f64;
        (n > 0).then(|| (ss / n as f64 * scale).sqrt())
    }

    fn ssr(&self) -> f64 {
        self.residual.iter().map(|r| r * r).sum()
    }
}

/// Union-find root of `x`.
fn root(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Fit `samples` (groups `< n_groups`, epochs `< n_epochs`; at most one sample per group
/// and epoch). `None` if the normal equations are not positive definite, which a
/// connected set with its reference pinned cannot be, barring non-finite input.
pub fn fit(samples: &[Sample], n_groups: usize, n_epochs: usize) -> Option<Fit> {
    let mut by_epoch: Vec<Vec<usize>> = vec![Vec::new(); n_epochs];
    let mut count = vec![0usize; n_groups];
    for (j, s) in samples.iter().enumerate() {
        by_epoch[s.epoch].push(j);
        count[s.group] += 1;
    }
    // Connected sets of groups.
    let mut parent: Vec<usize> = (0..n_groups).collect();
    for js in &by_epoch {
        for w in js.windows(2) {
            let (a, b) = (
                root(&mut parent, samples[w[0]].group),
                root(&mut parent, samples[w[1]].group),
            );
            parent[a] = b;
        }
    }
    let roots: Vec<usize> = (0..n_groups).map(|g| root(&mut parent, g)).collect();
    let mut set_of_root = vec![usize::MAX; n_groups];
    let mut set_reference: Vec<usize> = Vec::new();
    for g in (0..n_groups).filter(|&g| count[g] > 0) {
        let r = roots[g];
        if set_of_root[r] == usize::MAX {
            set_of_root[r] = set_reference.len();
            set_reference.push(g);
        }
        let s = set_of_root[r];
        if count[g] > count[set_reference[s]] {
            set_reference[s] = g;
        }
    }
    let group_set: Vec<usize> = roots.iter().map(|&r| set_of_root[r]).collect();
    // Unknowns: every group with samples that is not a reference.
    let mut unknown = vec![usize::MAX; n_groups];
    let mut n_unknown = 0;
    for g in 0..n_groups {
        if count[g] > 0 && !set_reference.contains(&g) {
            unknown[g] = n_unknown;
            n_unknown += 1;
        }
    }
    let mut m = DMatrix::<f64>::zeros(n_unknown, n_unknown);
    let mut b = DVector::<f64>::zeros(n_unknown);
    for js in by_epoch.iter().filter(|js| js.len() > 1) {
        let n = js.len() as f64;
        let mean = js.iter().map(|&j| samples[j].value).sum::<f64>() / n;
        for &j in js {
            let u = unknown[samples[j].group];
            if u == usize::MAX {
                continue;
            }
            b[u] += samples[j].value - mean;
            for &l in js {
                let v = unknown[samples[l].group];
                if v != usize::MAX {
                    m[(u, v)] += if l == j { 1.0 - 1.0 / n } else { -1.0 / n };
                }
            }
        }
    }
    let a = if n_unknown > 0 {
        m.cholesky()?.solve(&b)
    } else {
        b
    };
    let group_offset: Vec<f64> = (0..n_groups)
        .map(|g| match (count[g], unknown[g]) {
            (0, _) => f64::NAN,
            (_, usize::MAX) => 0.0,
            (_, u) => a[u],
        })
        .collect();
    let mut epoch_term = vec![f64::NAN; n_epochs];
    let mut residual = vec![0.0; samples.len()];
    for (k, js) in by_epoch.iter().enumerate().filter(|(_, js)| !js.is_empty()) {
        let c = js
            .iter()
            .map(|&j| samples[j].value - group_offset[samples[j].group])
            .sum::<f64>()
            / js.len() as f64;
        epoch_term[k] = c;
        for &j in js {
            residual[j] = samples[j].value - group_offset[samples[j].group] - c;
        }
    }
    let epochs_used = by_epoch.iter().filter(|js| !js.is_empty()).count();
    let groups_used = count.iter().filter(|&&c| c > 0).count();
    let dof = (samples.len() + set_reference.len()).saturating_sub(epochs_used + groups_used);
    Some(Fit {
        group_offset,
        group_set,
        set_reference,
        epoch_term,
        residual,
        dof,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// Standard normal by Box-Muller.
    fn normal(rng: &mut ChaCha8Rng) -> f64 {
        use rand::Rng;
        let u1: f64 = rng.random::<f64>().max(1e-300);
        let u2: f64 = rng.random();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }

    /// Unbalanced panel: 6 groups over 200 epochs, each present on its own span.
    fn panel(sigma: f64, seed: u64) -> (Vec<Sample>, [f64; 6], Vec<f64>) {
        let offsets = [3.0, -1.5, 7.25, 0.5, -4.0, 2.0];
        let spans = [(0, 200), (0, 120), (30, 200), (50, 90), (80, 200), (0, 60)];
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let clock: Vec<f64> = (0..200).map(|k| 100.0 * (k as f64 * 0.1).sin()).collect();
        let mut samples = Vec::new();
        for (k, &ck) in clock.iter().enumerate() {
            for (g, &(a, b)) in spans.iter().enumerate() {
                if (a..b).contains(&k) {
                    samples.push(Sample {
                        group: g,
                        epoch: k,
                        value: offsets[g] + ck + sigma * normal(&mut rng),
                    });
                }
            }
        }
        (samples, offsets, clock)
    }

    #[test]
    fn noiseless_offsets_and_epoch_terms_are_recovered_up_to_one_constant() {
        let (samples, offsets, clock) = panel(0.0, 1);
        let f = fit(&samples, 6, 200).unwrap();
        assert_eq!(f.set_reference, vec![0]);
        for g in 0..6 {
            assert!((f.group_offset[g] - (offsets[g] - offsets[0])).abs() < 1e-9);
        }
        for (c, ck) in f.epoch_term.iter().zip(&clock) {
            assert!((c - (ck + offsets[0])).abs() < 1e-9);
        }
        assert!(f.residual.iter().all(|r| r.abs() < 1e-9));
        let n = samples.len();
        assert_eq!(f.dof, n - 200 - 6 + 1);
    }

    /// Over many draws the variance estimate is unbiased (mean of SSR/dof within 3 standard
    /// errors of sigma^2), where the naive SSR/N is biased low by dof/N.
    #[test]
    fn residual_variance_is_unbiased() {
        let sigma = 0.5;
        let draws = 200;
        let mut sum = 0.0;
        let mut naive = 0.0;
        let mut dof = 0;
        for seed in 0..draws {
            let (samples, _, _) = panel(sigma, seed);
            let f = fit(&samples, 6, 200).unwrap();
            sum += f.std().unwrap().powi(2);
            naive += f.ssr() / samples.len() as f64;
            dof = f.dof;
        }
        let mean = sum / draws as f64;
        // Var of one estimate: 2 sigma^4 / dof.
        let se = (2.0 / dof as f64 / draws as f64).sqrt() * sigma * sigma;
        assert!((mean - sigma * sigma).abs() < 3.0 * se, "{mean}");
        assert!(naive / (draws as f64) < sigma * sigma - 3.0 * se);
    }

    #[test]
    fn separate_sets_get_their_own_reference_and_lonely_epochs_no_dof() {
        // Groups 0,1 share epochs 0..3; group 2 alone at epochs 3..5.
        let mut samples = Vec::new();
        for k in 0..3 {
            samples.push(Sample {
                group: 0,
                epoch: k,
                value: 1.0 + k as f64,
            });
            samples.push(Sample {
                group: 1,
                epoch: k,
                value: 3.0 + k as f64,
            });
        }
        for k in 3..5 {
            samples.push(Sample {
                group: 2,
                epoch: k,
                value: 10.0,
            });
        }
        let f = fit(&samples, 4, 5).unwrap();
        assert_eq!(f.set_reference.len(), 2);
        assert_eq!(f.group_set[0], f.group_set[1]);
        assert_ne!(f.group_set[0], f.group_set[2]);
        assert!((f.group_offset[1] - f.group_offset[0] - 2.0).abs() < 1e-12);
        assert!(f.group_offset[3].is_nan());
        // 8 samples - 5 epochs - 3 groups + 2 sets.
        assert_eq!(f.dof, 2);
        assert!(f.residual.iter().all(|r| r.abs() < 1e-12));
    }
}
