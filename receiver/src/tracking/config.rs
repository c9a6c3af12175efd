//! Settings of the tracking channels (`[tracking]`) and of the carrier stage they run
//! (`[stages] carrier`, `[tracking.ukf]`). The stages import these; nothing here imports
//! a stage.

use super::TrackingError;
use super::bit_sync::BitSyncConfig;
use super::discriminators::{FllDiscriminator, PllDiscriminator};
use super::error_budget::LoopOrder;

/// Thesis section 3.3.5: the proposed process noise densities (Q_theta, Q_omega, Q_alpha,
/// Q_alpha_t) of eq. 3.3-59.
pub const THESIS_PROPOSED_Q: [f64; 4] = [1e-10, 1e-4, 1e2, 1e8];
/// Thesis section 3.3.5: the sigma-point spread kappa.
pub const THESIS_KAPPA: f64 = 0.5;

/// Longest coherent integration after bit sync (code periods): one GPS or D1 bit.
pub const MAX_COHERENT_MS: u32 = 20;

/// Highest PLL and FLL noise bandwidth (Hz): `Bn T` stays below 0.1 at 1 ms; wider loops
/// are unstable in a digital receiver.
pub const MAX_CARRIER_BANDWIDTH_HZ: f64 = 100.0;

/// Highest DLL noise bandwidth (Hz).
pub const MAX_DLL_BANDWIDTH_HZ: f64 = 20.0;

/// Tracking loop configuration.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct TrackingConfig {
    /// PLL order (2nd or 3rd).
    pub pll_order: LoopOrder,
    /// PLL noise bandwidth Bn (Hz).
    pub pll_bandwidth_hz: f64,
    /// PLL noise bandwidth after bit sync (Hz), for the longer coherent integrations;
    /// `None` keeps `pll_bandwidth_hz`. A narrow PLL pulls in poorly from the hand-over
    /// Doppler, so pull-in runs at `pll_bandwidth_hz`.
    pub pll_narrow_bandwidth_hz: Option<f64>,
    /// Time (s) over which the PLL bandwidth moves geometrically from
    /// `pll_bandwidth_hz` to `pll_narrow_bandwidth_hz` after bit sync: a sudden switch
    /// leaves the lightly damped 3rd-order loop (complex poles at damping 0.21 with the
    /// Kaplan coefficients) ringing on the wide loop's rate noise.
    pub pll_narrowing_s: f64,
    /// PLL discriminator (Costas unless the signal is data-free).
    pub pll_discriminator: PllDiscriminator,
    /// FLL-assist noise bandwidth (Hz); 0 disables the FLL.
    pub fll_bandwidth_hz: f64,
    /// FLL discriminator.
    pub fll_discriminator: FllDiscriminator,
    /// Seconds of FLL assistance after hand-over (pull-in); infinity keeps it on. A strong
    /// FLL holds the frequency so firmly that a narrow PLL pulls the phase in only after
    /// the assistance ends.
    pub fll_assist_s: f64,
    /// DLL noise bandwidth Bn (Hz).
    pub dll_bandwidth_hz: f64,
    /// Early-to-late correlator spacing (chips).
    pub early_late_spacing_chips: f64,
    /// DLL noise bandwidth after bit sync (Hz); `None` keeps `dll_bandwidth_hz`. The
    /// carrier-aided DLL then only follows the code-carrier divergence, so a narrow loop
    /// costs no dynamics and cuts the code noise (sigma^2 ~ Bn d).
    pub dll_narrow_bandwidth_hz: Option<f64>,
    /// Early-to-late spacing after bit sync (chips), at least one sample; `None` keeps
    /// `early_late_spacing_chips`. Pull-in runs with the wide spacing, whose linear range
    /// covers the hand-over code error (half a sample or more).
    pub narrow_early_late_spacing_chips: Option<f64>,
    /// Coherent integration after bit sync (code periods, 1..=20; never beyond a bit, and
    /// shorter while the PLL bandwidth times the integration would exceed 0.1).
    pub coherent_ms: u32,
    /// C/N0 estimator window (s) over the 1 ms prompts; at least 20 of them.
    pub cn0_window_s: f64,
    /// Time constant of the PLL lock indicator (s).
    pub lock_indicator_tau_s: f64,
    /// PLL lock threshold on the `cos 2 phi` indicator.
    pub pll_lock_threshold: f64,
    /// C/N0 below which the channel counts as unlocked (dB-Hz).
    pub cn0_lock_threshold_dbhz: f64,
    /// Time continuously out of lock before loss of lock is declared (s), counted from the
    /// end of the FLL-assisted pull-in or from the first lock.
    pub loss_of_lock_s: f64,
    /// Half-cycle slip test: both parts of a bit split by a sign reversal must exceed this
    /// many noise standard deviations.
    pub slip_threshold_sigma: f64,
    /// Bit synchronisation thresholds.
    pub bit_sync: BitSyncConfig,
    /// The carrier tracking stage (chosen by the configuration's `[stages] carrier`).
    #[serde(skip)]
    pub carrier: CarrierMethod,
    /// Settings of the UKF carrier stage (`[tracking.ukf]`).
    pub ukf: UkfSettings,
}

impl Default for TrackingConfig {
    fn default() -> Self {
        Self {
            pll_order: LoopOrder::Third,
            pll_bandwidth_hz: 15.0,
            pll_narrow_bandwidth_hz: None,
            pll_narrowing_s: 1.0,
            pll_discriminator: PllDiscriminator::Costas,
            fll_bandwidth_hz: 10.0,
            fll_discriminator: FllDiscriminator::CrossDot,
            fll_assist_s: 0.5,
            dll_bandwidth_hz: 2.0,
            early_late_spacing_chips: 1.0,
            dll_narrow_bandwidth_hz: Some(0.25),
            narrow_early_late_spacing_chips: Some(0.5),
            coherent_ms: 1,
            cn0_window_s: 1.0,
            lock_indicator_tau_s: 0.05,
            pll_lock_threshold: 0.6,
            cn0_lock_threshold_dbhz: 25.0,
            loss_of_lock_s: 0.5,
            slip_threshold_sigma: 4.0,
            bit_sync: BitSyncConfig::default(),
            carrier: CarrierMethod::default(),
            ukf: UkfSettings::default(),
        }
    }
}

impl TrackingConfig {
    pub(crate) fn check(&self) -> Result<(), TrackingError> {
        let positive = [
            ("pll_bandwidth_hz", self.pll_bandwidth_hz),
            ("dll_bandwidth_hz", self.dll_bandwidth_hz),
            ("early_late_spacing_chips", self.early_late_spacing_chips),
            ("cn0_window_s", self.cn0_window_s),
            ("pll_narrowing_s", self.pll_narrowing_s),
            ("lock_indicator_tau_s", self.lock_indicator_tau_s),
            ("loss_of_lock_s", self.loss_of_lock_s),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(TrackingError::InvalidConfig(format!(
                    "{name} must be positive and finite, got {v}"
                )));
            }
        }
        let narrow = [
            ("pll_narrow_bandwidth_hz", self.pll_narrow_bandwidth_hz),
            ("dll_narrow_bandwidth_hz", self.dll_narrow_bandwidth_hz),
            (
                "narrow_early_late_spacing_chips",
                self.narrow_early_late_spacing_chips,
            ),
        ];
        for (name, v) in narrow {
            if let Some(v) = v
                && !(v.is_finite() && v > 0.0)
            {
                return Err(TrackingError::InvalidConfig(format!(
                    "{name} must be positive and finite, got {v}"
                )));
            }
        }
        for (name, v, max) in [
            (
                "pll_bandwidth_hz",
                Some(self.pll_bandwidth_hz),
                MAX_CARRIER_BANDWIDTH_HZ,
            ),
            (
                "pll_narrow_bandwidth_hz",
                self.pll_narrow_bandwidth_hz,
                MAX_CARRIER_BANDWIDTH_HZ,
            ),
            (
                "fll_bandwidth_hz",
                Some(self.fll_bandwidth_hz),
                MAX_CARRIER_BANDWIDTH_HZ,
            ),
            (
                "dll_bandwidth_hz",
                Some(self.dll_bandwidth_hz),
                MAX_DLL_BANDWIDTH_HZ,
            ),
            (
                "dll_narrow_bandwidth_hz",
                self.dll_narrow_bandwidth_hz,
                MAX_DLL_BANDWIDTH_HZ,
            ),
        ] {
            if let Some(v) = v
                && v > max
            {
                return Err(TrackingError::InvalidConfig(format!(
                    "{name} must be at most {max} Hz, got {v}"
                )));
            }
        }
        if !(self.fll_bandwidth_hz >= 0.0 && self.fll_assist_s >= 0.0) {
            return Err(TrackingError::InvalidConfig(format!(
                "fll_bandwidth_hz and fll_assist_s must be >= 0, got {} and {}",
                self.fll_bandwidth_hz, self.fll_assist_s
            )));
        }
        self.ukf.check()?;
        if !(1..=MAX_COHERENT_MS).contains(&self.coherent_ms) {
            return Err(TrackingError::InvalidConfig(format!(
                "coherent_ms must be 1..=20, got {}",
                self.coherent_ms
            )));
        }
        for d in [
            Some(self.early_late_spacing_chips),
            self.narrow_early_late_spacing_chips,
        ]
        .into_iter()
        .flatten()
        {
            if d > 2.0 {
                return Err(TrackingError::InvalidConfig(format!(
                    "early-late spacing must be at most 2 chips, got {d}"
                )));
            }
        }
        Ok(())
    }
}

/// Which carrier tracking stage a channel runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CarrierMethod {
    /// Second/third-order PLL with FLL assist during pull-in (default).
    #[default]
    FllPll,
    /// The UKF of thesis section 3.3.4 (eqs. 3.3-57..3.3-73).
    Ukf,
}

/// Settings of the UKF stage (`[tracking.ukf]`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct UkfSettings {
    /// Process noise spectral densities (Q_theta, Q_omega, Q_alpha, Q_alpha_t) of eq.
    /// 3.3-59 (rad^2/s, rad^2/s^3, rad^2/s^5, rad^2/s^7). Default: the thesis's proposed
    /// values (section 3.3.5).
    pub q: [f64; 4],
    /// Sigma-point spread kappa (eqs. 3.3-65..3.3-67); the thesis uses 0.5.
    pub kappa: f64,
    /// 1-sigma Doppler uncertainty at the hand-over (Hz).
    pub initial_doppler_sigma_hz: f64,
    /// 1-sigma Doppler-rate uncertainty at the hand-over (Hz/s).
    pub initial_rate_sigma_hzps: f64,
}

impl Default for UkfSettings {
    fn default() -> Self {
        Self {
            q: THESIS_PROPOSED_Q,
            kappa: THESIS_KAPPA,
            // assumed: a uniform error over one 500 Hz acquisition bin (144 Hz), as
            // validate's T-3.3-S gives the coarse estimate.
            initial_doppler_sigma_hz: 144.0,
            // assumed: LEO-sized dynamics, as T-3.3-S.
            initial_rate_sigma_hzps: 2500.0,
        }
    }
}

impl UkfSettings {
    /// Every value finite, the spread and uncertainties positive, Q non-negative.
    pub(crate) fn check(&self) -> Result<(), TrackingError> {
        let q_ok = self.q.iter().all(|q| q.is_finite() && *q >= 0.0);
        let positive = [
            self.kappa,
            self.initial_doppler_sigma_hz,
            self.initial_rate_sigma_hzps,
        ]
        .iter()
        .all(|v| v.is_finite() && *v > 0.0);
        if q_ok && positive {
            Ok(())
        } else {
            Err(TrackingError::InvalidConfig(format!(
                "ukf: q must be finite and >= 0, kappa and the initial uncertainties finite and > 0, got {self:?}"
            )))
        }
    }
}
