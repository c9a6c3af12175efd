//! Tracking-noise calibration: how the bundled receiver's code and phase noise compare with
//! the loop thermal-noise formulas, measured on signal-level runs (`skyforge calibrate`).

use serde::{Deserialize, Serialize};
use skyforge_gnss::observation::{dll_thermal_chips, pll_thermal_cycles};
use skyforge_gnss::signal::Signal;

/// The loop settings the formulas are evaluated with (the receiver's after pull-in).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoopNoise {
    /// PLL noise bandwidth (Hz).
    pub pll_bandwidth_hz: f64,
    /// DLL noise bandwidth (Hz).
    pub dll_bandwidth_hz: f64,
    /// Early-to-late correlator spacing (chips).
    pub spacing_chips: f64,
    /// Coherent integration (s).
    pub coherent_s: f64,
}

impl LoopNoise {
    /// Thesis eq. 3.2-3: carrier-phase noise (m, 1 sigma) of `signal` at `cn0_dbhz`.
    pub fn phase_sigma_m(&self, signal: Signal, cn0_dbhz: f64) -> f64 {
        pll_thermal_cycles(self.pll_bandwidth_hz, cn0_dbhz, self.coherent_s) * signal.wavelength_m()
    }

    /// Non-coherent early-minus-late DLL noise (m, 1 sigma) of `signal` at `cn0_dbhz`.
    pub fn code_sigma_m(&self, signal: Signal, cn0_dbhz: f64) -> f64 {
        let chips = dll_thermal_chips(
            self.dll_bandwidth_hz,
            self.spacing_chips,
            cn0_dbhz,
            self.coherent_s,
        );
        chips * skyforge_orbits::constants::C_MPS / signal.chip_rate_hz()
    }

    /// The PLL's Doppler (frequency) jitter (Hz, 1 sigma) of `signal` at `cn0_dbhz`, up to
    /// the calibrated factor: its phase jitter (cycles, thesis eq. 3.2-3) times its noise
    /// bandwidth, the rate at which the loop moves its phase. The calibration measures how
    /// the receiver's Doppler compares (`doppler_factor`).
    pub fn doppler_sigma_hz(&self, cn0_dbhz: f64) -> f64 {
        pll_thermal_cycles(self.pll_bandwidth_hz, cn0_dbhz, self.coherent_s) * self.pll_bandwidth_hz
    }

    /// Correlation time of the code noise (s): `1 / (4 Bn)`, the time constant of a
    /// first-order loop of noise bandwidth Bn.
    pub fn code_correlation_s(&self) -> f64 {
        1.0 / (4.0 * self.dll_bandwidth_hz)
    }

    /// Correlation time of the carrier-phase noise (s), as for the code.
    pub fn phase_correlation_s(&self) -> f64 {
        1.0 / (4.0 * self.pll_bandwidth_hz)
    }

    fn check(&self) -> Result<(), String> {
        let positive = [
            ("pll_bandwidth_hz", self.pll_bandwidth_hz),
            ("dll_bandwidth_hz", self.dll_bandwidth_hz),
            ("coherent_s", self.coherent_s),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("{name} = {v}: must be a positive number"));
            }
        }
        if !(self.spacing_chips > 0.0 && self.spacing_chips < 2.0) {
            return Err(format!(
                "spacing_chips = {}: must lie in (0, 2)",
                self.spacing_chips
            ));
        }
        Ok(())
    }
}

/// One signal's measured factors: receiver noise std / formula std.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignalCalibration {
    /// Signal tag (`gps-l1ca`, `bds-b1i`).
    pub signal: String,
    pub loops: LoopNoise,
    /// Measured code-noise std over the formula's, at the C/N0 of each observation.
    pub code_factor: f64,
    /// Measured phase-noise std over the formula's.
    pub phase_factor: f64,
    /// Measured Doppler-noise std over [`LoopNoise::doppler_sigma_hz`] (absent in
    /// calibrations written before it was measured).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub doppler_factor: Option<f64>,
    /// C/N0 range the measurement covered (dB-Hz).
    pub cn0_dbhz: [f64; 2],
    /// Observations the factors were measured on.
    pub samples: usize,
}

/// What `skyforge calibrate` measured, and on what.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Calibration {
    /// The scenario and seed of the signal-level run.
    pub scenario: String,
    pub seed: u64,
    /// Seconds of observations compared.
    pub duration_s: f64,
    pub signals: Vec<SignalCalibration>,
}

impl Calibration {
    /// The calibration of `signal`, if measured.
    pub fn of(&self, signal: Signal) -> Option<&SignalCalibration> {
        self.signals
            .iter()
            .find(|s| s.signal.parse::<Signal>().ok() == Some(signal))
    }

    /// Every signal is known, every factor positive and every loop setting valid.
    pub fn check(&self) -> Result<(), String> {
        for s in &self.signals {
            s.signal
                .parse::<Signal>()
                .map_err(|e| format!("signals: {e}"))?;
            s.loops
                .check()
                .map_err(|e| format!("{}: loops.{e}", s.signal))?;
            for (name, v) in [
                ("code_factor", s.code_factor),
                ("phase_factor", s.phase_factor),
                ("doppler_factor", s.doppler_factor.unwrap_or(1.0)),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(format!(
                        "{}: {name} = {v}: must be a positive number",
                        s.signal
                    ));
                }
            }
        }
        Ok(())
    }
}
