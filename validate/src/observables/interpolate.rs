//! Truth observations at an arbitrary time: cubic (4-point Lagrange) interpolation over
//! neighbouring truth epochs.
//!
//! Error: for nodes `t0 < t1 < t2 < t3` spaced `h` and `t` in `[t0, t3]`, the
//! interpolation remainder is `f''''(xi) / 4! * prod(t - t_j)`, so
//! `|error| <= max|f''''| * h^4 * K / 24` with `K = 9/16` in the middle interval and
//! `K = 1` in an end interval ([`error_bound`]). For a static ground receiver the
//! geometric range to a GPS satellite has `|f''''| ~ a n^4 ~ 1e-8 m/s^4` (orbit radius
//! `a = 26,560 km`, mean motion `n = 1.46e-4 rad/s`), so at 1 Hz the bound is ~1e-9 m; for
//! a LEO platform (`~ 1e-5 m/s^4`) it is ~1e-6 m. Both are far below what is compared.
//! The truth's receiver-clock term (a random walk for a TCXO) is not smooth, but it is the
//! same for every satellite at one time tag and leaves with the per-epoch clock term.
//! The truth file's rounding (1 mm, 0.001 cycle) passes through weights whose absolute sum
//! is at most 1.25, i.e. <= 0.4 mm std in the pseudorange.

/// A truth observable of one satellite: times (s) in increasing order and values.
#[derive(Debug, Clone, Default)]
pub struct Series {
    pub t_s: Vec<f64>,
    pub value: Vec<f64>,
}

impl Series {
    /// Append a sample (`t_s` after every earlier one).
    pub fn push(&mut self, t_s: f64, value: f64) {
        self.t_s.push(t_s);
        self.value.push(value);
    }

    /// The value at `t_s` from the 4 samples around it (the bracketing interval in the
    /// middle where the series allows). `None` outside the series, with fewer than 4
    /// samples, or when the 4 samples span more than `max_span_s` (a gap).
    pub fn at(&self, t_s: f64, max_span_s: f64) -> Option<f64> {
        let n = self.t_s.len();
        if n < 4 || !(self.t_s[0]..=self.t_s[n - 1]).contains(&t_s) {
            return None;
        }
        // First sample after t_s (the bracket is [i - 1, i]).
        let i = self.t_s.partition_point(|&x| x <= t_s).clamp(1, n - 1);
        let first = i.saturating_sub(2).min(n - 4);
        let ts = &self.t_s[first..first + 4];
        if ts[3] - ts[0] > max_span_s {
            return None;
        }
        Some(lagrange4(ts, &self.value[first..first + 4], t_s))
    }
}

/// The cubic through the four points `(ts[j], ys[j])`, evaluated at `t`.
pub fn lagrange4(ts: &[f64], ys: &[f64], t: f64) -> f64 {
    let mut sum = 0.0;
    for j in 0..4 {
        let mut w = 1.0;
        for m in 0..4 {
            if m != j {
                w *= (t - ts[m]) / (ts[j] - ts[m]);
            }
        }
        sum += w * ys[j];
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The remainder bound `max|f''''| * |prod(t - t_j)| / 24` of [`lagrange4`] at `t`.
    fn error_bound(ts: &[f64], t: f64, max_fourth_derivative: f64) -> f64 {
        let prod: f64 = ts.iter().map(|&x| (t - x).abs()).product();
        max_fourth_derivative * prod / 24.0
    }

    /// Range (m) from a ground site on the equator (radius 6378 km) to a satellite in a
    /// circular equatorial orbit of radius `a` moving at `n` rad/s relative to the site,
    /// overhead at `t_zenith`.
    fn range(a: f64, n: f64, t_zenith: f64, t: f64) -> f64 {
        let r = 6_378e3;
        let th = n * (t - t_zenith);
        (a * a + r * r - 2.0 * a * r * th.cos()).sqrt()
    }

    /// max |f''''| of `f` on `[t0, t1]`, by central differences on an `h` grid, times 1.5.
    fn max_fourth(f: impl Fn(f64) -> f64, t0: f64, t1: f64, h: f64) -> f64 {
        let n = ((t1 - t0) / h) as usize;
        (0..=n)
            .map(|k| {
                let t = t0 + k as f64 * h;
                let d4 =
                    f(t - 2.0 * h) - 4.0 * f(t - h) + 6.0 * f(t) - 4.0 * f(t + h) + f(t + 2.0 * h);
                (d4 / h.powi(4)).abs()
            })
            .fold(0.0, f64::max)
            * 1.5
    }

    /// The largest interpolation error over 600 s of 1 Hz samples of `f`, each error
    /// checked against the remainder bound plus the rounding of values of size `f`.
    fn worst_error(f: impl Fn(f64) -> f64 + Copy, max4: f64) -> f64 {
        let mut s = Series::default();
        for k in 0..600 {
            s.push(k as f64, f(k as f64));
        }
        let mut worst = 0.0f64;
        for k in 0..5990 {
            let t = 0.1 * k as f64 + 0.0371;
            let err = (s.at(t, 3.5).unwrap() - f(t)).abs();
            let i = (t.floor() as usize).clamp(1, 597);
            let first = (i - 1).min(596);
            let ts: Vec<f64> = (first..first + 4).map(|x| x as f64).collect();
            let rounding = 8.0 * f64::EPSILON * f(t).abs();
            let bound = error_bound(&ts, t, max4) + rounding;
            assert!(err <= bound, "t {t}: error {err} bound {bound}");
            worst = worst.max(err);
        }
        worst
    }

    #[test]
    fn interpolating_a_gps_range_at_1_hz_is_exact_to_rounding() {
        let f = |t| range(26_560e3, 1.458e-4 - 7.292e-5, 250.0, t);
        let max4 = max_fourth(f, 0.0, 600.0, 10.0);
        assert!(max4 < 1e-7, "{max4}");
        let worst = worst_error(f, max4);
        assert!(worst < 5e-8, "{worst}");
    }

    /// An overhead LEO pass (500 km, 7.6 km/s) seen from the ground is the hardest smooth
    /// case: |f''''| ~ 3 v^4 / rho^3 ~ 0.08 m/s^4, a bound of a few mm, which holds.
    #[test]
    fn interpolating_an_overhead_leo_pass_stays_inside_the_remainder_bound() {
        let f = |t| range(6_878e3, 1.1e-3, 300.0, t);
        let max4 = max_fourth(f, 0.0, 600.0, 1.0);
        assert!(max4 > 0.01 && max4 < 1.0, "{max4}");
        let worst = worst_error(f, max4);
        assert!(
            worst > 1e-6,
            "a bound this loose would not test anything: {worst}"
        );
    }

    #[test]
    fn outside_the_series_or_across_a_gap_there_is_no_value() {
        let mut s = Series::default();
        for t in [0.0, 1.0, 2.0, 3.0, 10.0, 11.0, 12.0, 13.0] {
            s.push(t, t * t);
        }
        assert_eq!(s.at(-0.5, 3.5), None);
        assert_eq!(s.at(13.5, 3.5), None);
        assert_eq!(s.at(6.0, 3.5), None);
        assert!((s.at(1.5, 3.5).unwrap() - 2.25).abs() < 1e-12);
        assert!((s.at(12.5, 3.5).unwrap() - 156.25).abs() < 1e-9);
        assert!((s.at(13.0, 3.5).unwrap() - 169.0).abs() < 1e-9);
    }

    proptest! {
        /// A cubic polynomial is reproduced exactly (up to rounding) anywhere in the nodes.
        #[test]
        fn cubics_are_reproduced(c in prop::array::uniform4(-1e3..1e3f64), t0 in -1e4..1e4f64,
                                 u in 0.0..3.0f64) {
            let f = |t: f64| c[0] + c[1] * t + c[2] * t * t + c[3] * t * t * t;
            let ts: Vec<f64> = (0..4).map(|j| t0 + j as f64).collect();
            let ys: Vec<f64> = ts.iter().map(|&t| f(t)).collect();
            let t = t0 + u;
            let scale = ys.iter().fold(1.0f64, |m, y| m.max(y.abs()));
            prop_assert!((lagrange4(&ts, &ys, t) - f(t)).abs() <= 1e-9 * scale);
        }
    }
}
