//! The observation noise model of thesis eqs. 2.4-9/2.4-10: a standard deviation that
//! grows towards the horizon. The observation-level model draws noise from it; the
//! receiver's relative positioning weighs double differences with it.

use serde::Deserialize;
use skyforge_orbits::check::{Allowed, Invalid};

/// Zenith standard deviation of noise drawn at the observation level (m): 0 is
/// noiseless; assumed: 100 m, beyond any receiver's code noise (a few metres at 30 dB-Hz).
pub const NOISE_SIGMA0_M: Allowed = Allowed::closed(0.0, 100.0, "m");
/// Zenith standard deviation of a weighting model (m): above 0 (a weight of infinity
/// makes the normal equations singular), up to [`NOISE_SIGMA0_M`]'s 100 m.
pub const WEIGHT_SIGMA0_M: Allowed = Allowed::above(0.0, 100.0, "m");
/// The amplification at the horizon, `a0`: assumed up to 100 (the thesis's models use
/// about 10).
const A0: Allowed = Allowed::closed(0.0, 100.0, "");
/// The elevation scale `elev0` (deg).
const ELEV0_DEG: Allowed = Allowed::above(0.0, 90.0, "deg");

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

    /// The domain of eqs. 2.4-9/2.4-10 within plausible ranges: `sigma0_m` in `sigma0`
    /// ([`NOISE_SIGMA0_M`] for drawn noise, [`WEIGHT_SIGMA0_M`] for weights), `a0` in
    /// [`A0`], `elev0_deg` in [`ELEV0_DEG`]. The error names the field of `key` (the
    /// table, e.g. `relative.phase`), its value and the range.
    pub fn check(&self, key: &str, sigma0: Allowed) -> Result<(), Invalid> {
        sigma0
            .check("sigma0_m", self.sigma0_m)
            .and_then(|()| A0.check("a0", self.a0))
            .and_then(|()| ELEV0_DEG.check("elev0_deg", self.elev0_deg))
            .map_err(|e| e.within(key))
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
