//! The observation noise model of thesis eqs. 2.4-9..2.4-13: a standard deviation per
//! antenna, per signal and per observation type, scaled by an elevation factor.

pub use skyforge_gnss::observation::ElevationNoise;
use skyforge_gnss::signal::Signal;

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
