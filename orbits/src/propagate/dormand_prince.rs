//! Adaptive Dormand-Prince 5(4) integrator with error control and 4th-order dense output.
//!
//! The method is RK5(4)7M of Dormand & Prince, "A family of embedded Runge-Kutta formulae",
//! J. Comp. Appl. Math. 6 (1980) 19-26, as tabulated in Hairer, Norsett & Wanner, *Solving
//! Ordinary Differential Equations I* (2nd ed.), table II.5.2. It is FSAL: the derivative
//! at the end of an accepted step is the first stage of the next one, so an accepted step
//! costs six derivative evaluations.
//!
//! Error control: the embedded 4th-order solution gives a per-component error estimate
//! `err_i`, scaled by `sc_i = abs_tol_i + rel_tol * max(|y0_i|, |y1_i|)`; the step is
//! accepted when the RMS of `err_i / sc_i` is <= 1. The next step size follows the PI
//! controller of Hairer, Norsett & Wanner (section II.4, "stabilized step size control",
//! beta = 0.04), bounded to a factor in [0.2, 10] (no growth right after a rejection) and
//! to `[h_min_s, h_max_s]`.
//!
//! Dense output: the continuous extension of order 4 of Hairer, Norsett & Wanner (section
//! II.6, the `dopri5` dense output); one extra linear combination of the stages per step,
//! no extra derivative evaluation.

/// The integrated state: 6 `f64` (position then velocity for orbits).
pub type State6 = nalgebra::Vector6<f64>;

// Butcher tableau (HNW table II.5.2). Stage 2 (c2 = a21 = 1/5) is written out in
// `DormandPrince::attempt`; the others are (c_i, [a_i1, a_i2, ...]).
const C2: f64 = 1.0 / 5.0;
const A21: f64 = 1.0 / 5.0;
const STAGES_3_TO_6: [(f64, &[f64]); 4] = [
    (3.0 / 10.0, &[3.0 / 40.0, 9.0 / 40.0]),
    (4.0 / 5.0, &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0]),
    (
        8.0 / 9.0,
        &[
            19372.0 / 6561.0,
            -25360.0 / 2187.0,
            64448.0 / 6561.0,
            -212.0 / 729.0,
        ],
    ),
    (
        1.0,
        &[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ],
    ),
];
// 5th-order weights b_i (= a_7i, FSAL; b2 = b7 = 0).
const B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
// Error weights e_i = b_i - b*_i with the 4th-order weights
// b* = (5179/57600, 0, 7571/16695, 393/640, -92097/339200, 187/2100, 1/40).
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
// Dense-output weights d_i (HNW section II.6, continuous extension of order 4; d2 = 0).
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

// PI step-size control (HNW II.4): h_new = h * SAFETY * err^-ALPHA * err_old^BETA.
const SAFETY: f64 = 0.9;
const BETA: f64 = 0.04;
const ALPHA: f64 = 0.2 - 0.75 * BETA;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;

/// Tolerances and step-size limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Relative tolerance (applied to every component).
    pub rel_tol: f64,
    /// Absolute tolerance per component (same units as the state).
    pub abs_tol: State6,
    /// Smallest allowed step (s); a smaller one is a [`StepUnderflow`].
    pub h_min_s: f64,
    /// Largest allowed step (s).
    pub h_max_s: f64,
    /// First trial step (s); `None` selects it automatically (HNW II.4 starting step).
    pub h_initial_s: Option<f64>,
}

/// The tolerance cannot be met with a step of at least `h_min_s` (or the derivative is
/// not finite).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("step size underflow at t = {t_s} s")]
pub struct StepUnderflow {
    /// Time at which the step failed (s).
    pub t_s: f64,
}

/// One accepted step `[t_start_s, t_start_s + h_s]` with its dense-output polynomial.
#[derive(Debug, Clone, PartialEq)]
pub struct DenseStep {
    t_start_s: f64,
    h_s: f64,
    /// `y(theta) = c0 + theta (c1 + (1-theta) (c2 + theta (c3 + (1-theta) c4)))`.
    coeffs: [State6; 5],
}

impl DenseStep {
    /// Start of the step (s).
    pub fn t_start_s(&self) -> f64 {
        self.t_start_s
    }
    /// End of the step (s).
    pub fn t_end_s(&self) -> f64 {
        self.t_start_s + self.h_s
    }
    /// Step size (s).
    #[cfg(test)]
    pub fn h_s(&self) -> f64 {
        self.h_s
    }
    /// The state at the end of the step (the 5th-order solution).
    pub fn end_state(&self) -> State6 {
        self.coeffs[0] + self.coeffs[1]
    }
    /// Interpolated state at `t_s` (4th order inside the step; outside it the polynomial
    /// is extrapolated, which is only accurate a small fraction of a step away).
    pub fn state_at(&self, t_s: f64) -> State6 {
        let theta = (t_s - self.t_start_s) / self.h_s;
        let theta1 = 1.0 - theta;
        let [c0, c1, c2, c3, c4] = &self.coeffs;
        c0 + (c1 + (c2 + (c3 + c4 * theta1) * theta) * theta1) * theta
    }
}

/// An adaptive Dormand-Prince 5(4) integrator that owns the current time and state.
#[derive(Debug, Clone, PartialEq)]
pub struct DormandPrince {
    settings: Settings,
    t_s: f64,
    y: State6,
    /// Derivative at `(t_s, y)` (first stage of the next step, FSAL).
    dy: State6,
    /// Next trial step size (s).
    h_s: f64,
    /// Error norm of the last accepted step (PI controller memory).
    err_old: f64,
}

impl DormandPrince {
    /// Start at `(t0_s, y0)` for the system `dy/dt = f(t, y)`.
    pub fn new<F>(f: &mut F, t0_s: f64, y0: State6, settings: Settings) -> Self
    where
        F: FnMut(f64, &State6) -> State6,
    {
        let dy = f(t0_s, &y0);
        let h_s = match settings.h_initial_s {
            Some(h) => h,
            None => initial_step(f, t0_s, &y0, &dy, &settings),
        }
        .clamp(settings.h_min_s, settings.h_max_s);
        Self {
            settings,
            t_s: t0_s,
            y: y0,
            dy,
            h_s,
            err_old: 1e-4,
        }
    }

    /// Current time (s): the end of the last accepted step.
    pub fn t_s(&self) -> f64 {
        self.t_s
    }

    /// Take one accepted step (retrying with smaller steps as the error control demands)
    /// and return it with its dense output.
    pub fn step<F>(&mut self, f: &mut F) -> Result<DenseStep, StepUnderflow>
    where
        F: FnMut(f64, &State6) -> State6,
    {
        let mut h = self.h_s;
        let mut rejected = false;
        loop {
            if h.is_nan() || h < self.settings.h_min_s {
                return Err(StepUnderflow { t_s: self.t_s });
            }
            let trial = self.attempt(f, h);
            let err = self.error_norm(&trial.y1, &trial.err);
            if err.is_finite() && err <= 1.0 {
                let err_pi = err.max(1e-10);
                let fac_max = if rejected { 1.0 } else { FAC_MAX };
                let fac = (SAFETY * err_pi.powf(-ALPHA) * self.err_old.powf(BETA))
                    .clamp(FAC_MIN, fac_max);
                self.err_old = err.max(1e-4);
                let step = self.dense_step(h, &trial);
                self.t_s += h;
                self.y = trial.y1;
                self.dy = trial.k[6];
                self.h_s = (h * fac).clamp(self.settings.h_min_s, self.settings.h_max_s);
                return Ok(step);
            }
            rejected = true;
            let fac = if err.is_finite() {
                (SAFETY * err.powf(-0.2)).max(FAC_MIN)
            } else {
                0.1
            };
            h *= fac;
        }
    }

    /// One trial step of size `h` from the current state.
    fn attempt<F>(&self, f: &mut F, h: f64) -> Trial
    where
        F: FnMut(f64, &State6) -> State6,
    {
        let (t, y) = (self.t_s, &self.y);
        // Filled stage by stage: each stage reads only the ones before it.
        let mut k = [self.dy; 7];
        k[1] = f(t + C2 * h, &(y + k[0] * (h * A21)));
        for (i, (c, a)) in STAGES_3_TO_6.iter().enumerate() {
            k[i + 2] = f(t + c * h, &(y + weighted_sum(&k, a) * h));
        }
        let y1 = y + weighted_sum(&k, &B) * h;
        k[6] = f(t + h, &y1);
        let err = weighted_sum(&k, &E) * h;
        Trial { k, y1, err }
    }

    /// RMS of the error scaled by the mixed tolerance.
    fn error_norm(&self, y1: &State6, err: &State6) -> f64 {
        let s = &self.settings;
        let sum: f64 = (0..6)
            .map(|i| {
                let sc = s.abs_tol[i] + s.rel_tol * self.y[i].abs().max(y1[i].abs());
                (err[i] / sc).powi(2)
            })
            .sum();
        (sum / 6.0).sqrt()
    }

    /// The dense-output polynomial of an accepted trial step.
    fn dense_step(&self, h: f64, trial: &Trial) -> DenseStep {
        let [k1, .., k7] = &trial.k;
        let c0 = self.y;
        let c1 = trial.y1 - self.y;
        let c2 = k1 * h - c1;
        let c3 = c1 - k7 * h - c2;
        let c4 = weighted_sum(&trial.k, &D) * h;
        DenseStep {
            t_start_s: self.t_s,
            h_s: h,
            coeffs: [c0, c1, c2, c3, c4],
        }
    }
}

/// Stages, solution and error estimate of one trial step.
struct Trial {
    k: [State6; 7],
    y1: State6,
    err: State6,
}

/// `sum_i w_i k_i` over the stages with a non-zero weight, added in stage order.
fn weighted_sum(k: &[State6; 7], w: &[f64]) -> State6 {
    let mut terms = k
        .iter()
        .zip(w)
        .filter(|&(_, &w)| w != 0.0)
        .map(|(k, &w)| k * w);
    let first = terms.next().unwrap_or_else(State6::zeros);
    terms.fold(first, |sum, term| sum + term)
}

/// Starting step size (HNW II.4, "starting step size"): balance an explicit Euler step's
/// second-derivative error against the tolerance.
fn initial_step<F>(f: &mut F, t0: f64, y0: &State6, dy0: &State6, s: &Settings) -> f64
where
    F: FnMut(f64, &State6) -> State6,
{
    let scale = State6::from_fn(|i, _| s.abs_tol[i] + s.rel_tol * y0[i].abs());
    let rms = |v: &State6| (v.component_div(&scale).norm_squared() / 6.0).sqrt();
    let d0 = rms(y0);
    let d1 = rms(dy0);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let dy1 = f(t0 + h0, &(y0 + dy0 * h0));
    let d2 = rms(&(dy1 - dy0)) / h0;
    let dmax = d1.max(d2);
    let h1 = if dmax <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / dmax).powf(0.2)
    };
    (100.0 * h0).min(h1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three independent harmonic oscillators x_i'' = -w_i^2 x_i.
    const W: [f64; 3] = [1.0, 0.7, 1.9];

    fn oscillator(_t: f64, y: &State6) -> State6 {
        State6::new(
            y[3],
            y[4],
            y[5],
            -W[0] * W[0] * y[0],
            -W[1] * W[1] * y[1],
            -W[2] * W[2] * y[2],
        )
    }

    /// Exact solution with x(0) = 1, x'(0) = 0.
    fn exact(t: f64) -> State6 {
        State6::new(
            (W[0] * t).cos(),
            (W[1] * t).cos(),
            (W[2] * t).cos(),
            -W[0] * (W[0] * t).sin(),
            -W[1] * (W[1] * t).sin(),
            -W[2] * (W[2] * t).sin(),
        )
    }

    fn settings(rel_tol: f64, abs_tol: f64, h_initial_s: Option<f64>) -> Settings {
        Settings {
            rel_tol,
            abs_tol: State6::repeat(abs_tol),
            h_min_s: 1e-12,
            h_max_s: 1e3,
            h_initial_s,
        }
    }

    #[test]
    fn oscillator_matches_analytical_solution_at_steps_and_mid_steps() {
        let mut f = oscillator;
        let mut dp = DormandPrince::new(&mut f, 0.0, exact(0.0), settings(1e-10, 1e-10, None));
        let mut worst_end = 0.0_f64;
        let mut worst_mid = 0.0_f64;
        let mut steps = 0;
        while dp.t_s() < 50.0 {
            let step = dp.step(&mut f).unwrap();
            steps += 1;
            worst_end = worst_end.max((step.end_state() - exact(step.t_end_s())).amax());
            let t_mid = step.t_start_s() + 0.5 * step.h_s();
            worst_mid = worst_mid.max((step.state_at(t_mid) - exact(t_mid)).amax());
            // theta = 1 up to the rounding of (t_start + h - t_start) / h.
            let d = (step.state_at(step.t_end_s()) - step.end_state()).amax();
            assert!(d < 1e-12, "{d:e}");
        }
        // ~ 8 periods: the global error stays a small multiple of the tolerance per step
        // times the number of steps.
        assert!(steps > 50, "{steps} steps");
        assert!(worst_end < 1e-8, "end-of-step error {worst_end:e}");
        assert!(worst_mid < 1e-8, "mid-step error {worst_mid:e}");
    }

    #[test]
    fn dense_output_local_error_is_fifth_order_in_h() {
        // Single steps of h and h/2 from the exact state; the interpolation error at the
        // mid-step of a 4th-order continuous extension scales as h^5 (ratio 32).
        let mid_error = |h: f64| {
            let mut f = oscillator;
            let mut dp = DormandPrince::new(&mut f, 0.3, exact(0.3), settings(1.0, 1.0, Some(h)));
            let step = dp.step(&mut f).unwrap();
            assert_eq!(step.h_s(), h, "step must be accepted as given");
            let t_mid = 0.3 + 0.37 * h;
            (step.state_at(t_mid) - exact(t_mid)).norm()
        };
        let ratio = mid_error(0.2) / mid_error(0.1);
        assert!((20.0..50.0).contains(&ratio), "ratio {ratio}");
    }

    #[test]
    fn step_end_local_error_is_sixth_order_in_h() {
        let end_error = |h: f64| {
            let mut f = oscillator;
            let mut dp = DormandPrince::new(&mut f, 0.0, exact(0.0), settings(1.0, 1.0, Some(h)));
            let step = dp.step(&mut f).unwrap();
            (step.end_state() - exact(h)).norm()
        };
        let ratio = end_error(0.2) / end_error(0.1);
        assert!((45.0..90.0).contains(&ratio), "ratio {ratio}");
    }

    #[test]
    fn rejects_too_large_first_step_and_meets_tolerance() {
        let mut f = oscillator;
        let mut dp = DormandPrince::new(&mut f, 0.0, exact(0.0), settings(1e-9, 1e-12, Some(5.0)));
        let step = dp.step(&mut f).unwrap();
        assert!(step.h_s() < 5.0);
        assert!((step.end_state() - exact(step.t_end_s())).amax() < 1e-8);
    }

    #[test]
    fn non_finite_derivative_is_a_step_underflow() {
        let mut f = |t: f64, y: &State6| if t > 0.5 { y * f64::NAN } else { *y };
        let mut dp =
            DormandPrince::new(&mut f, 0.0, State6::repeat(1.0), settings(1e-9, 1e-9, None));
        let mut result = Ok(());
        for _ in 0..10_000 {
            if let Err(e) = dp.step(&mut f) {
                result = Err(e);
                break;
            }
        }
        let err = result.unwrap_err();
        assert!(err.t_s <= 0.5 + 1e-9, "{err:?}");
    }
}
