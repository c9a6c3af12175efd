//! A first-order Gauss-Markov process made smooth enough for a signal to follow it.
//!
//! The process `x' = -x / tau + w` is sampled exactly at nodes `t_k = t_0 + k dt`
//! (Gelb, *Applied Optimal Estimation*, Table 4.4-1: `x_{k+1} = phi x_k + sqrt(1 - phi^2)
//! sigma w_k`, `phi = exp(-dt / tau)`, `x_0 ~ N(0, sigma^2)`: stationary from the first
//! node). A first-order Gauss-Markov path has no derivative, but a range that a carrier
//! follows must have a Doppler and a Doppler rate, so the nodes are the control points of
//! a uniform cubic B-spline (de Boor, *A Practical Guide to Splines*, ch. IX): twice
//! continuously differentiable, local (four nodes per point) and cheap. The spline
//! averages neighbouring nodes, which lowers the variance at a node by the factor
//! `(18 + 16 phi + 2 phi^2) / 36`; the control points are scaled by its inverse root so
//! that the value at every node has exactly the variance `sigma^2`. Correlation over
//! lags much longer than `dt` is the process's `exp(-lag / tau)`; shorter lags are
//! smoother than the process (how smooth is the node spacing's choice).

use rand::Rng;
use rand_distr::StandardNormal;

/// One smoothed first-order Gauss-Markov path over a fixed span.
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothGaussMarkov {
    t0_s: f64,
    dt_s: f64,
    /// Control points (already scaled), `nodes[k]` at `t0_s + k dt_s`.
    nodes: Vec<f64>,
}

/// Variance of the spline at a node over the variance of its control points, for
/// neighbouring-node correlation `phi`.
pub fn node_variance_factor(phi: f64) -> f64 {
    (18.0 + 16.0 * phi + 2.0 * phi * phi) / 36.0
}

impl SmoothGaussMarkov {
    /// A path with standard deviation `sigma`, correlation time `tau_s`, nodes every
    /// `dt_s` from `t0_s`, `n_nodes` of them (at least 5), drawn from `rng`.
    pub fn draw(
        sigma: f64,
        tau_s: f64,
        t0_s: f64,
        dt_s: f64,
        n_nodes: usize,
        rng: &mut impl Rng,
    ) -> Self {
        let phi = (-dt_s / tau_s).exp();
        let drive = (1.0 - phi * phi).sqrt();
        let scale = sigma / node_variance_factor(phi).sqrt();
        let mut x: f64 = rng.sample(StandardNormal);
        let mut nodes = Vec::with_capacity(n_nodes.max(5));
        for _ in 0..n_nodes.max(5) {
            nodes.push(scale * x);
            let w: f64 = rng.sample(StandardNormal);
            x = phi * x + drive * w;
        }
        Self { t0_s, dt_s, nodes }
    }

    /// A path that is zero everywhere (a component switched off).
    pub fn zero(t0_s: f64, dt_s: f64) -> Self {
        Self {
            t0_s,
            dt_s,
            nodes: vec![0.0; 5],
        }
    }

    /// Value and first derivative (per second) at `t_s`. Outside the span the first or
    /// last polynomial piece is extended.
    pub fn value_and_rate(&self, t_s: f64) -> (f64, f64) {
        let last = self.nodes.len() - 3;
        let x = (t_s - self.t0_s) / self.dt_s;
        let k = (x.floor().max(1.0) as usize).min(last - 1);
        let u = x - k as f64;
        let c = &self.nodes[k - 1..k + 3];
        let v = 1.0 - u;
        let (u2, u3) = (u * u, u * u * u);
        let value = (v * v * v * c[0]
            + (3.0 * u3 - 6.0 * u2 + 4.0) * c[1]
            + (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) * c[2]
            + u3 * c[3])
            / 6.0;
        let rate = (-3.0 * v * v * c[0]
            + (9.0 * u2 - 12.0 * u) * c[1]
            + (-9.0 * u2 + 6.0 * u + 3.0) * c[2]
            + 3.0 * u2 * c[3])
            / (6.0 * self.dt_s);
        (value, rate)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::errors::seed::{Stream, stream_rng};

    /// The spline as the weighted sum of its four control points, written independently
    /// from the basis functions' definition (de Boor's recurrence for the uniform cubic).
    fn basis(u: f64) -> [f64; 4] {
        let b = |t: f64| {
            // The centred uniform cubic B-spline on [-2, 2].
            let a = t.abs();
            if a < 1.0 {
                (4.0 - 6.0 * a * a + 3.0 * a * a * a) / 6.0
            } else if a < 2.0 {
                (2.0 - a).powi(3) / 6.0
            } else {
                0.0
            }
        };
        [b(u + 1.0), b(u), b(u - 1.0), b(u - 2.0)]
    }

    #[test]
    fn the_spline_matches_its_basis_and_its_rate_the_finite_difference() {
        let mut rng = stream_rng(1, Stream::Named("gm-spline"), 0);
        let p = SmoothGaussMarkov::draw(3.0, 50.0, -20.0, 10.0, 30, &mut rng);
        for t in [-5.0, 0.0, 3.7, 41.2, 99.99, 150.0] {
            let x: f64 = (t - p.t0_s) / p.dt_s;
            let k = x.floor() as usize;
            let w = basis(x - k as f64);
            let oracle: f64 = (0..4).map(|j| w[j] * p.nodes[k - 1 + j]).sum();
            let (v, r) = p.value_and_rate(t);
            assert!((v - oracle).abs() < 1e-12, "{t}: {v} vs {oracle}");
            let h = 1e-4;
            let fd = (p.value_and_rate(t + h).0 - p.value_and_rate(t - h).0) / (2.0 * h);
            assert!((r - fd).abs() < 1e-7, "{t}: rate {r} vs {fd}");
        }
    }

    #[test]
    fn the_path_is_continuous_in_value_and_rate_across_nodes() {
        let mut rng = stream_rng(2, Stream::Named("gm-spline"), 0);
        let p = SmoothGaussMarkov::draw(30.0, 200.0, 0.0, 100.0, 40, &mut rng);
        for k in 2..30 {
            let t = k as f64 * 100.0;
            let (a, ra) = p.value_and_rate(t - 1e-9);
            let (b, rb) = p.value_and_rate(t + 1e-9);
            assert!((a - b).abs() < 1e-8 && (ra - rb).abs() < 1e-8, "node {k}");
        }
    }

    /// Over many independent paths: the variance at nodes is sigma^2 and between them
    /// within 3 % of it (4.5 standard errors of 4000 draws), and the correlation between
    /// nodes `m` apart is the spline's of the process: `phi^m ((4 + phi + 1/phi) / 6)^2`
    /// over the node variance factor (exp(-1) x 1.029 at lag tau, nodes tau / 20 apart).
    #[test]
    fn variance_and_correlation_time_are_the_process_s() {
        let (sigma, tau, dt) = (2.0, 200.0, 10.0);
        let n = 4000;
        let (mut s_node, mut s_mid, mut s_lag) = (0.0, 0.0, 0.0);
        for i in 0..n {
            let mut rng = stream_rng(3, Stream::Named("gm-stats"), i);
            let p = SmoothGaussMarkov::draw(sigma, tau, 0.0, dt, 60, &mut rng);
            let a = p.value_and_rate(100.0).0;
            s_node += a * a;
            let m = p.value_and_rate(105.0).0;
            s_mid += m * m;
            s_lag += a * p.value_and_rate(100.0 + tau).0;
        }
        let var = sigma * sigma;
        // Standard error of a variance estimate from n Gaussian draws: var * sqrt(2 / n).
        let se = var * (2.0 / n as f64).sqrt();
        assert!(
            (s_node / n as f64 - var).abs() < 4.5 * se,
            "node {}",
            s_node / n as f64
        );
        // Between nodes the spline averages more: slightly below sigma^2, within 3 %.
        let mid = s_mid / n as f64;
        assert!(
            mid < var * 1.01 + 4.5 * se && mid > var * 0.97 - 4.5 * se,
            "mid {mid}"
        );
        // The correlation at lag tau; its standard error is sqrt((1 + rho^2) / n).
        let phi = (-dt / tau).exp();
        let expected = phi.powf(tau / dt) * ((4.0 + phi + 1.0 / phi) / 6.0).powi(2)
            / node_variance_factor(phi);
        let rho = s_lag / n as f64 / var;
        let se_rho = (1.0 + expected * expected).sqrt() / (n as f64).sqrt();
        assert!(
            (rho - expected).abs() < 4.5 * se_rho,
            "rho {rho} vs {expected}"
        );
    }

    #[test]
    fn node_variance_factor_is_one_for_a_rigid_path() {
        assert!((node_variance_factor(1.0) - 1.0).abs() < 1e-15);
        // Independent nodes: (1 + 16 + 1) / 36.
        assert!((node_variance_factor(0.0) - 0.5).abs() < 1e-15);
    }
}
