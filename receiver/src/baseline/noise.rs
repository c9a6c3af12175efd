//! The observation noise model of thesis eqs. 2.4-9..2.4-13: a standard deviation per
//! antenna, per signal and per observation type, scaled by an elevation factor.

use serde::Deserialize;
use skyforge_signals::signal::Signal;

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

    /// A constant standard deviation, independent of elevation (what T-1.2-2 prescribes).
    pub fn constant(sigma_m: f64) -> Self {
        Self {
            sigma0_m: sigma_m,
            a0: 0.0,
            elev0_deg: 10.0,
        }
    }
}

/// The whole model: phase and code per eqs. 2.4-9/2.4-10, the antenna factors `sigma_m` of
/// eq. 2.4-11 and the signal factors `sigma_f` of eqs. 2.4-29 and 2.4-40/2.4-41.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseModel {
    pub phase: ElevationNoise,
    pub code: ElevationNoise,
    /// `sigma_m` per antenna, master first; an antenna without an entry has factor 1.
    pub antenna_factors: Vec<f64>,
    /// `sigma_f` per signal; a signal without an entry has factor 1.
    pub signal_factors: Vec<(Signal, f64)>,
}

impl NoiseModel {
    /// Equal antennas and signals.
    pub fn new(phase: ElevationNoise, code: ElevationNoise) -> Self {
        Self {
            phase,
            code,
            antenna_factors: Vec::new(),
            signal_factors: Vec::new(),
        }
    }

    /// `sigma_m` of antenna `index` (0 is the master).
    pub fn antenna_factor(&self, index: usize) -> f64 {
        self.antenna_factors.get(index).copied().unwrap_or(1.0)
    }

    /// `sigma_f` of `signal`.
    pub fn signal_factor(&self, signal: Signal) -> f64 {
        self.signal_factors
            .iter()
            .find(|(s, _)| *s == signal)
            .map_or(1.0, |(_, f)| *f)
    }
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
