//! What the time differences use: the signal, the elevation mask, the longest gap and
//! the phase noise.

use super::error::TdcpError;
use skyforge_gnss::signal::Signal;

/// Settings of [`super::time_differences`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TdcpConfig {
    /// The signal differenced; `None`: per satellite the first signal (in [`Signal`]
    /// order) with code and phase at both epochs.
    pub signal: Option<Signal>,
    /// Satellites below this elevation at `t2` are not used (deg, in `[-90, 90)`).
    pub elevation_mask_deg: f64,
    /// Longest time between the two epochs (s, > 0): beyond it the atmosphere's change is
    /// no longer negligible and lock is less likely kept.
    pub max_gap_s: f64,
    /// Standard deviation of one carrier-phase measurement (m, > 0), white per epoch.
    pub sigma_phase_m: f64,
    /// Scale `sigma_phase_m` by `1 / sin(elevation)` (elevation at `t2`).
    pub elevation_weighting: bool,
}

impl Default for TdcpConfig {
    /// Any signal, 10 deg mask, 5 s longest gap, 3 mm phase noise (assumed: a tracking
    /// loop near 45 dB-Hz), no elevation weighting.
    fn default() -> Self {
        Self {
            signal: None,
            elevation_mask_deg: 10.0,
            max_gap_s: 5.0,
            sigma_phase_m: 0.003,
            elevation_weighting: false,
        }
    }
}

impl TdcpConfig {
    /// `Ok` when every value is in its range, else the first one that is not (its field,
    /// value and allowed range).
    pub fn check(&self) -> Result<(), TdcpError> {
        let bad = |field, value: f64, allowed| TdcpError::Config {
            field,
            value: value.to_string(),
            allowed,
        };
        let mask = self.elevation_mask_deg;
        if !(-90.0..90.0).contains(&mask) {
            return Err(bad("elevation_mask_deg", mask, "-90 <= mask < 90 (deg)"));
        }
        if !(self.max_gap_s.is_finite() && self.max_gap_s > 0.0) {
            return Err(bad("max_gap_s", self.max_gap_s, "finite and > 0 (s)"));
        }
        if !(self.sigma_phase_m.is_finite() && self.sigma_phase_m > 0.0) {
            let allowed = "finite and > 0 (m)";
            return Err(bad("sigma_phase_m", self.sigma_phase_m, allowed));
        }
        Ok(())
    }
}
