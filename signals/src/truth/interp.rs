//! Range interpolation between geometry epochs, for sample-rate carrier and code phase.
//!
//! A quintic Hermite polynomial matches range, range rate and range acceleration at both
//! ends of an interval. Its error is bounded by h^6 / 46080 * max|rho^(6)|; for a LEO
//! receiver and h = 1 s that is far below a micrometre (measured in this module's
//! tests against direct light-time solutions: see `interpolation_error_is_sub_millimetre`
//! in `tests/` of this crate).

/// Quintic Hermite interpolant of a range over `[t0_s, t0_s + h_s]`, stored as a
/// deviation from the start value so that 2e7 m ranges keep full precision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuinticHermite {
    t0_s: f64,
    h_s: f64,
    y0: f64,
    /// Coefficients of the deviation in the normalised time u = (t - t0) / h, u^1..u^5.
    c: [f64; 5],
}

impl QuinticHermite {
    /// The interpolant through `(value, first, second derivative)` at `t0_s` and `t1_s`.
    pub fn new(t0_s: f64, t1_s: f64, start: [f64; 3], end: [f64; 3]) -> Self {
        let h = t1_s - t0_s;
        // Normalised end conditions: p(0) = 0, p'(0) = a1, p''(0) = 2 a2; p(1) = d, p'(1) = e1,
        // p''(1) = e2, with p(u) = a1 u + a2 u^2 + a3 u^3 + a4 u^4 + a5 u^5.
        let a1 = start[1] * h;
        let a2 = start[2] * h * h / 2.0;
        let d = end[0] - start[0] - a1 - a2;
        let e1 = end[1] * h - a1 - 2.0 * a2;
        let e2 = end[2] * h * h - 2.0 * a2;
        // Solve [1 1 1; 3 4 5; 6 12 20] [a3 a4 a5] = [d e1 e2].
        let a3 = 10.0 * d - 4.0 * e1 + 0.5 * e2;
        let a4 = -15.0 * d + 7.0 * e1 - e2;
        let a5 = 6.0 * d - 3.0 * e1 + 0.5 * e2;
        Self {
            t0_s,
            h_s: h,
            y0: start[0],
            c: [a1, a2, a3, a4, a5],
        }
    }

    /// Value at `t_s` minus the start value (keeps precision for large ranges).
    pub fn deviation(&self, t_s: f64) -> f64 {
        let u = (t_s - self.t0_s) / self.h_s;
        u * (self.c[0] + u * (self.c[1] + u * (self.c[2] + u * (self.c[3] + u * self.c[4]))))
    }

    /// Value at `t_s`.
    pub fn value(&self, t_s: f64) -> f64 {
        self.y0 + self.deviation(t_s)
    }

    /// First derivative at `t_s`.
    pub fn rate(&self, t_s: f64) -> f64 {
        let u = (t_s - self.t0_s) / self.h_s;
        let c = &self.c;
        (c[0] + u * (2.0 * c[1] + u * (3.0 * c[2] + u * (4.0 * c[3] + u * 5.0 * c[4])))) / self.h_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn reproduces_any_quintic(c in proptest::array::uniform6(-10.0f64..10.0), t0 in -50.0f64..50.0, h in 0.1f64..5.0) {
            let p = |t: f64| c.iter().rev().fold(0.0, |acc, ci| acc * (t - t0) + ci);
            let dp = |t: f64| (1..6).rev().fold(0.0, |acc, i| acc * (t - t0) + i as f64 * c[i]);
            let ddp = |t: f64| (2..6).rev().fold(0.0, |acc, i| acc * (t - t0) + (i * (i - 1)) as f64 * c[i]);
            let t1 = t0 + h;
            let q = QuinticHermite::new(t0, t1, [p(t0), dp(t0), ddp(t0)], [p(t1), dp(t1), ddp(t1)]);
            for k in 0..=10 {
                let t = t0 + h * k as f64 / 10.0;
                let scale = 1.0 + p(t).abs() + c.iter().map(|x| x.abs()).sum::<f64>() * (1.0 + h).powi(5);
                prop_assert!((q.value(t) - p(t)).abs() < 1e-9 * scale);
                prop_assert!((q.rate(t) - dp(t)).abs() < 1e-8 * scale / h.min(1.0));
            }
        }
    }
}
