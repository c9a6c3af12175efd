//! The observation noise model of thesis eqs. 2.4-9/2.4-10: a standard deviation that
//! grows towards the horizon. The observation-level model draws noise from it; the
//! receiver's relative positioning weighs double differences with it.

use serde::Deserialize;

/// Thesis eqs. 2.4-9/2.4-10: `sigma0 [1 + a0 exp(-elev / elev0)]` for one observation type.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElevationNoise {
    /// Zenith standard deviation (m).
    pub sigma0_m: f64,
    /// Amplification at the horizon, `a0` (dimensionless, >= 0).
    pub a0: f64,
    /// Elevation scale `elev0` (degrees, > 0).
    pub elev0_deg: f64,
}

impl ElevationNoise {
    /// The elevation factor `nu = 1 + a0 exp(-elev / elev0)` of eqs. 2.4-12/2.4-13.
    pub fn factor(&self, elevation_rad: f64) -> f64 {
        1.0 + self.a0 * (-elevation_rad / self.elev0_deg.to_radians()).exp()
    }

    /// Standard deviation (m) at `elevation_rad`.
    pub fn sigma_m(&self, elevation_rad: f64) -> f64 {
        self.sigma0_m * self.factor(elevation_rad)
    }

    /// The domain of eqs. 2.4-9/2.4-10: `sigma0_m` finite and above 0, `a0` finite and at
    /// least 0, `elev0_deg` finite and above 0. The error names the field of `key` (the
    /// table, e.g. `relative.phase`), its value and what is allowed.
    pub fn check(&self, key: &str) -> Result<(), String> {
        let (finite, a0) = (|v: f64| v.is_finite(), self.a0);
        let problem = if !(finite(self.sigma0_m) && self.sigma0_m > 0.0) {
            Some(("sigma0_m", self.sigma0_m, "above 0"))
        } else if !(finite(a0) && a0 >= 0.0) {
            Some(("a0", a0, "0 or more"))
        } else if !(finite(self.elev0_deg) && self.elev0_deg > 0.0) {
            Some(("elev0_deg", self.elev0_deg, "above 0"))
        } else {
            None
        };
        match problem {
            Some((field, v, allowed)) => Err(format!(
                "{key}.{field} = {v}: must be a finite number {allowed}"
            )),
            None => Ok(()),
        }
    }

    /// A constant standard deviation, independent of elevation (what T-1.2-2 prescribes).
    pub fn constant(sigma_m: f64) -> Self {
        Self {
            sigma0_m: sigma_m,
            a0: 0.0,
            elev0_deg: 10.0,
        }
    }
}

/// Thesis eq. 3.2-3: thermal-noise phase jitter of a PLL (cycles, 1 sigma) of noise
/// bandwidth `bn_hz` and coherent integration `t_coh_s` at `cn0_dbhz`.
pub fn pll_thermal_cycles(bn_hz: f64, cn0_dbhz: f64, t_coh_s: f64) -> f64 {
    let cn0 = 10f64.powf(cn0_dbhz / 10.0);
    (bn_hz / cn0 * (1.0 + 1.0 / (2.0 * t_coh_s * cn0))).sqrt() / std::f64::consts::TAU
}

/// Thermal-noise jitter (chips, 1 sigma) of a non-coherent early-minus-late power DLL with
/// a wide front end (Kaplan & Hegarty, Understanding GPS, 2nd ed., eq. 5.23):
/// `sqrt(Bn D / (2 C/N0) (1 + 2 / ((2 - D) T C/N0)))`, `D` the early-to-late spacing.
pub fn dll_thermal_chips(bn_hz: f64, spacing_chips: f64, cn0_dbhz: f64, t_coh_s: f64) -> f64 {
    let cn0 = 10f64.powf(cn0_dbhz / 10.0);
    let d = spacing_chips;
    (bn_hz * d / (2.0 * cn0) * (1.0 + 2.0 / ((2.0 - d) * t_coh_s * cn0))).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elevation_factor_follows_eq_2_4_10() {
        let n = ElevationNoise {
            sigma0_m: 0.003,
            a0: 10.0,
            elev0_deg: 10.0,
        };
        // At the zenith the exponential is exp(-9) = 1.2e-4; at the horizon nu = 1 + a0.
        assert!((n.factor(0.0) - 11.0).abs() < 1e-12);
        let zenith = 1.0 + 10.0 * (-9.0f64).exp();
        assert!((n.factor(90f64.to_radians()) - zenith).abs() < 1e-12);
        assert!((n.sigma_m(0.0) - 0.033).abs() < 1e-12);
        assert_eq!(ElevationNoise::constant(0.001).sigma_m(0.1), 0.001);
    }
}
