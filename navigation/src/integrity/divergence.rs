//! Code-carrier divergence (CCD) of one station's track of one satellite.

/// The divergence rate of smoothed code minus carrier by a geometric moving average, the
/// LAAS/GBAS ground monitor's estimator (Simili & Pervan 2006; paper 002 names the
/// "sliding geometric mean" and leaves out its equation):
/// `z_k = rho_bar_k - lambda phi_k`,
/// `d_k = (tau - T) / tau d_{k-1} + (z_k - z_{k-1}) / tau`, starting at `d = 0`.
///
/// The paper's divergence reaches its maximum about 100 s after a cycle slip and "grows
/// gradually (combined effect of CCD smoothing and code smoothing)": of code minus
/// carrier, only the smoothed code makes a slip grow gradually (with raw code the
/// estimator jumps at the slip), so `z` is taken on the smoothed pseudorange.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Divergence {
    tau_s: f64,
    last_z_m: f64,
    rate_mps: f64,
}

impl Divergence {
    /// An estimator with time constant `tau_s`, started on code minus carrier `z_m`.
    pub fn start(tau_s: f64, z_m: f64) -> Self {
        Self {
            tau_s,
            last_z_m: z_m,
            rate_mps: 0.0,
        }
    }

    /// The divergence rate (m/s).
    pub fn rate_mps(&self) -> f64 {
        self.rate_mps
    }

    /// Take code minus carrier `z_m` after `dt_s` and return the divergence rate (m/s).
    pub fn update(&mut self, z_m: f64, dt_s: f64) -> f64 {
        let a = (dt_s / self.tau_s).min(1.0);
        self.rate_mps = (1.0 - a) * self.rate_mps + (z_m - self.last_z_m) / self.tau_s;
        self.last_z_m = z_m;
        self.rate_mps
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_steady_divergence_is_estimated_at_its_rate() {
        // z growing at 0.01 m/s: d converges to 0.01 m/s with time constant tau.
        let mut d = Divergence::start(200.0, 0.0);
        let mut last = 0.0;
        for k in 1..=2000 {
            last = d.update(0.01 * k as f64, 1.0);
        }
        assert!((last - 0.01).abs() < 1e-6, "{last}");
        // After exactly tau seconds, 1 - (1 - 1/tau)^tau of the rate: about 63 %.
        let mut d = Divergence::start(200.0, 0.0);
        let at_tau = (1..=200).map(|k| d.update(0.01 * k as f64, 1.0)).last();
        let want = 0.01 * (1.0 - (1.0 - 1.0 / 200.0f64).powi(200));
        assert!((at_tau.unwrap() - want).abs() < 1e-12);
    }

    #[test]
    fn a_step_in_z_decays_geometrically() {
        let mut d = Divergence::start(100.0, 0.0);
        let first = d.update(-1.0, 1.0);
        assert!((first + 0.01).abs() < 1e-15);
        let next = d.update(-1.0, 1.0);
        assert!((next - first * 0.99).abs() < 1e-15);
        assert_eq!(d.rate_mps(), next);
    }
}
