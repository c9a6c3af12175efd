//! Settings of the acquisition stage (`[stages] acquisition`, `[acquisition]`): which
//! stage searches and how. The stages import these; nothing here imports a stage.

/// The acquisition stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AcquisitionMethod {
    /// Parallel code-phase search over Doppler bins (default).
    #[default]
    Pcps,
    /// PCPS, then the Doppler refined by the PMF-FFT fine estimator of thesis sections
    /// 3.3.1-3.3.2 (eqs. 3.3-13, 3.3-14).
    PmfFft,
}

/// How satellites are searched.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AcquisitionSettings {
    /// The stage: PCPS alone or with the PMF-FFT fine Doppler.
    pub method: AcquisitionMethod,
    /// Code periods summed coherently.
    pub coherent_ms: usize,
    /// Coherent sums added in power.
    pub noncoherent: usize,
    /// False-alarm probability per satellite search.
    pub pfa: f64,
    /// Half-width of the Doppler window of a search without assistance (Hz).
    pub cold_half_width_hz: f64,
    /// Seconds between searches for satellites not tracked.
    pub reacquire_interval_s: f64,
}

impl Default for AcquisitionSettings {
    /// 1 ms coherent x 2 non-coherent (enough above about 38 dB-Hz), P_fa 1e-3, +/-10 kHz
    /// (a ground receiver with a 1 ppm oscillator), a new search every 10 s.
    fn default() -> Self {
        Self {
            method: AcquisitionMethod::Pcps,
            coherent_ms: 1,
            noncoherent: 2,
            pfa: 1e-3,
            cold_half_width_hz: 10e3,
            reacquire_interval_s: 10.0,
        }
    }
}
