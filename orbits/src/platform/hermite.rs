//! Piecewise cubic Hermite interpolation of 3-vectors.
//!
//! On `[t_k, t_k+1]`, with `s = (t - t_k)/h`, the value is
//! `h00(s) y_k + h h10(s) m_k + h01(s) y_k+1 + h h11(s) m_k+1` with the standard Hermite
//! basis `h00 = 2s^3 - 3s^2 + 1`, `h10 = s^3 - 2s^2 + s`, `h01 = -2s^3 + 3s^2`,
//! `h11 = s^3 - s^2`; the curve is C1 and reproduces cubics exactly. Slopes `m` are given
//! (e.g. trajectory velocities) or estimated at each node as the derivative of the
//! Lagrange polynomial through the five nearest nodes (fourth-order accurate, valid for
//! uneven spacing); with fewer nodes all of them are used. Outside the nodes the curve
//! continues along a straight line with the end slope (C1), so a caller may reach a little
//! beyond the data (e.g. for finite-difference stencils at the edges).

use crate::Vec3;

/// A cubic Hermite interpolant of 3-vectors over strictly increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct Hermite3 {
    t_s: Vec<f64>,
    y: Vec<Vec3>,
    dy: Vec<Vec3>,
}

/// Number of nodes in the slope-estimation stencil.
const STENCIL: usize = 5;

impl Hermite3 {
    /// Interpolant with given slopes. `t_s` strictly increasing, all lengths equal, >= 2.
    pub fn with_slopes(t_s: Vec<f64>, y: Vec<Vec3>, dy: Vec<Vec3>) -> Self {
        Self { t_s, y, dy }
    }

    /// Interpolant with slopes estimated from the values (five-point Lagrange derivative).
    pub fn with_estimated_slopes(t_s: Vec<f64>, y: Vec<Vec3>) -> Self {
        let n = t_s.len();
        let m = STENCIL.min(n);
        let dy = (0..n)
            .map(|i| {
                let first = i.saturating_sub(m / 2).min(n - m);
                let nodes = first..first + m;
                nodes
                    .clone()
                    .map(|j| lagrange_derivative_weight(&t_s, nodes.clone(), i, j) * y[j])
                    .sum()
            })
            .collect();
        Self { t_s, y, dy }
    }

    /// First and last time.
    pub fn span(&self) -> (f64, f64) {
        (self.t_s[0], self.t_s[self.t_s.len() - 1])
    }

    /// Value and derivative at `t_s`; outside the span, the straight-line continuation
    /// with the end slope.
    pub fn eval(&self, t_s: f64) -> (Vec3, Vec3) {
        let (first, last) = self.span();
        let n = self.t_s.len();
        if t_s < first {
            return (self.y[0] + (t_s - first) * self.dy[0], self.dy[0]);
        }
        if t_s > last {
            return (
                self.y[n - 1] + (t_s - last) * self.dy[n - 1],
                self.dy[n - 1],
            );
        }
        let t = t_s;
        let k = self
            .t_s
            .partition_point(|&x| x <= t)
            .saturating_sub(1)
            .min(n - 2);
        let h = self.t_s[k + 1] - self.t_s[k];
        let s = (t - self.t_s[k]) / h;
        let (s2, s3) = (s * s, s * s * s);
        let (y0, y1, m0, m1) = (self.y[k], self.y[k + 1], self.dy[k], self.dy[k + 1]);
        let value = (2.0 * s3 - 3.0 * s2 + 1.0) * y0
            + h * (s3 - 2.0 * s2 + s) * m0
            + (3.0 * s2 - 2.0 * s3) * y1
            + h * (s3 - s2) * m1;
        let rate = (6.0 * s2 - 6.0 * s) / h * (y0 - y1)
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (3.0 * s2 - 2.0 * s) * m1;
        (value, rate)
    }
}

/// `L_j'(t_i)`: derivative at node `i` of the Lagrange basis polynomial of node `j` over
/// `nodes` (both `i` and `j` in `nodes`).
fn lagrange_derivative_weight(t: &[f64], nodes: std::ops::Range<usize>, i: usize, j: usize) -> f64 {
    if i == j {
        nodes.filter(|&k| k != i).map(|k| 1.0 / (t[i] - t[k])).sum()
    } else {
        nodes
            .filter(|&k| k != i && k != j)
            .map(|k| (t[i] - t[k]) / (t[j] - t[k]))
            .product::<f64>()
            / (t[j] - t[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn cubic(t: f64) -> Vec3 {
        Vec3::new(1.0 + 2.0 * t - t * t + 0.5 * t * t * t, -3.0 * t, 7.0)
    }
    fn cubic_rate(t: f64) -> Vec3 {
        Vec3::new(2.0 - 2.0 * t + 1.5 * t * t, -3.0, 0.0)
    }

    #[test]
    fn reproduces_a_cubic_with_exact_or_estimated_slopes() {
        let t: Vec<f64> = vec![0.0, 0.4, 1.0, 1.3, 2.5, 3.0, 4.1];
        let y: Vec<Vec3> = t.iter().map(|&x| cubic(x)).collect();
        let dy: Vec<Vec3> = t.iter().map(|&x| cubic_rate(x)).collect();
        let exact = Hermite3::with_slopes(t.clone(), y.clone(), dy);
        // A five-point Lagrange derivative is exact for polynomials up to degree 4.
        let est = Hermite3::with_estimated_slopes(t, y);
        for k in 0..=100 {
            let x = 4.1 * f64::from(k) / 100.0;
            for h in [&exact, &est] {
                let (v, r) = h.eval(x);
                assert!((v - cubic(x)).norm() < 1e-12, "{x}");
                assert!((r - cubic_rate(x)).norm() < 1e-11, "{x}");
            }
        }
        // Straight-line continuation outside the nodes.
        assert_eq!(
            exact.eval(-1.0),
            (cubic(0.0) - cubic_rate(0.0), cubic_rate(0.0))
        );
        let (v, r) = exact.eval(5.1);
        assert!((v - cubic(4.1) - cubic_rate(4.1)).norm() < 1e-12 && r == cubic_rate(4.1));
    }

    #[test]
    fn two_nodes_give_a_straight_line() {
        let h = Hermite3::with_estimated_slopes(
            vec![1.0, 3.0],
            vec![Vec3::zeros(), Vec3::new(2.0, 4.0, 6.0)],
        );
        let (v, r) = h.eval(2.5);
        assert!((v - Vec3::new(1.5, 3.0, 4.5)).norm() < 1e-15);
        assert!((r - Vec3::new(1.0, 2.0, 3.0)).norm() < 1e-15);
    }

    proptest! {
        #[test]
        fn interpolates_the_nodes(
            ys in prop::collection::vec((-1e3f64..1e3, -1e3f64..1e3, -1e3f64..1e3), 2..12),
            steps in prop::collection::vec(0.1f64..10.0, 12),
        ) {
            let mut t = vec![0.0];
            for s in steps.iter().take(ys.len() - 1) {
                let last = t[t.len() - 1];
                t.push(last + s);
            }
            let y: Vec<Vec3> = ys.iter().map(|&(a, b, c)| Vec3::new(a, b, c)).collect();
            let h = Hermite3::with_estimated_slopes(t.clone(), y.clone());
            for (ti, yi) in t.iter().zip(&y) {
                prop_assert!((h.eval(*ti).0 - yi).norm() < 1e-9);
            }
        }
    }
}
