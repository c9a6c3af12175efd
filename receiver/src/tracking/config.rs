//! Settings of the tracking channels (`[tracking]`) and of the carrier stage they run
//! (`[stages] carrier`, `[tracking.ukf]`). The stages import these; nothing here imports
//! a stage.

use super::bit_sync::BitSyncConfig;
use super::discriminators::{FllDiscriminator, PllDiscriminator};
use super::error_budget::LoopOrder;
use skyforge_orbits::check::{Invalid, check_table};

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

/// The range of every `[tracking]` value (docs/limits.md lists them).
mod limits {
    use super::{MAX_CARRIER_BANDWIDTH_HZ, MAX_COHERENT_MS, MAX_DLL_BANDWIDTH_HZ};
    use skyforge_orbits::check::Allowed;

    /// assumed: below 0.1 Hz a PLL cannot follow even a static receiver's oscillator drift.
    pub(super) const PLL_BANDWIDTH_HZ: Allowed =
        Allowed::closed(0.1, MAX_CARRIER_BANDWIDTH_HZ, "Hz");
    /// 0 turns the FLL assist off.
    pub(super) const FLL_BANDWIDTH_HZ: Allowed =
        Allowed::closed(0.0, MAX_CARRIER_BANDWIDTH_HZ, "Hz");
    /// assumed: 0.01 Hz is narrower than any carrier-aided DLL in use (0.05 Hz and up).
    pub(super) const DLL_BANDWIDTH_HZ: Allowed = Allowed::closed(0.01, MAX_DLL_BANDWIDTH_HZ, "Hz");
    /// Above 0: at least one sample; 0.01 chips is one sample of GPS L1 C/A at the
    /// receiver's highest rate (100 MHz). The channel checks the sample at its own rate.
    /// Up to 2 chips, where early and late still see the correlation peak.
    pub(super) const SPACING_CHIPS: Allowed = Allowed::closed(0.01, 2.0, "chips");
    pub(super) const COHERENT_MS: Allowed =
        Allowed::closed(1.0, MAX_COHERENT_MS as f64, "code periods");
    /// At least 20 prompts of 1 ms; assumed: a minute is the longest a C/N0 estimate
    /// stays meaningful on a moving receiver.
    pub(super) const CN0_WINDOW_S: Allowed = Allowed::closed(0.02, 60.0, "s");
    /// assumed: transitions and lock decisions over at most a minute.
    pub(super) const SECONDS: Allowed = Allowed::above(0.0, 60.0, "s");
    /// Infinity keeps the FLL on.
    pub(super) const FLL_ASSIST_S: Allowed = Allowed::closed(0.0, f64::INFINITY, "s");
    /// The lock indicator is cos 2 phi in [-1, 1]: at 0 or below every phase error up to
    /// 45 deg reads as lock, and at 1 no phase error does.
    pub(super) const PLL_LOCK_THRESHOLD: Allowed = Allowed::above(0.0, 0.99, "");
    /// assumed: the strongest GNSS signals received reach about 55 dB-Hz.
    pub(super) const CN0_LOCK_THRESHOLD_DBHZ: Allowed = Allowed::closed(0.0, 60.0, "dB-Hz");
    /// assumed: 1 sigma flags a slip at every other bit, 20 sigma never.
    pub(super) const SLIP_THRESHOLD_SIGMA: Allowed = Allowed::closed(1.0, 20.0, "sigma");
    /// At least one transition decides; assumed: 1000 of them (20 s of alternating bits)
    /// is past any use.
    pub(super) const MIN_TRANSITIONS: Allowed = Allowed::closed(1.0, 1000.0, "transitions");
    /// The winning bin at least as full as the runner-up.
    pub(super) const DOMINANCE: Allowed = Allowed::closed(1.0, 100.0, "");
    /// assumed: 100 windows (2 s) of NH correlation are past any use.
    pub(super) const NH_BITS: Allowed = Allowed::closed(1.0, 100.0, "windows of 20 ms");
    /// The UKF's process noise densities: assumed up to 1e16, a thousand times the largest
    /// the thesis uses (the "traditional" Q_alpha_t of 1e13 that section 3.3.5 compares).
    pub(super) const UKF_Q: Allowed = Allowed::closed(0.0, 1e16, "");
    pub(super) const UKF_KAPPA: Allowed = Allowed::above(0.0, 10.0, "");
    /// Up to the acquisition's widest search (60 kHz).
    pub(super) const UKF_DOPPLER_SIGMA_HZ: Allowed = Allowed::above(0.0, 60e3, "Hz");
    /// assumed: 100 kHz/s is a hundred times a LEO's Doppler rate.
    pub(super) const UKF_RATE_SIGMA_HZPS: Allowed = Allowed::above(0.0, 1e5, "Hz/s");
}

impl TrackingConfig {
    /// Every value in its range ([`limits`]); the error names the field within
    /// `[tracking]`, its value and the range.
    pub(crate) fn check(&self) -> Result<(), Invalid> {
        use limits::*;
        let b = &self.bit_sync;
        let values = [
            (
                "pll_bandwidth_hz",
                Some(self.pll_bandwidth_hz),
                PLL_BANDWIDTH_HZ,
            ),
            (
                "pll_narrow_bandwidth_hz",
                self.pll_narrow_bandwidth_hz,
                PLL_BANDWIDTH_HZ,
            ),
            ("pll_narrowing_s", Some(self.pll_narrowing_s), SECONDS),
            (
                "fll_bandwidth_hz",
                Some(self.fll_bandwidth_hz),
                FLL_BANDWIDTH_HZ,
            ),
            ("fll_assist_s", Some(self.fll_assist_s), FLL_ASSIST_S),
            (
                "dll_bandwidth_hz",
                Some(self.dll_bandwidth_hz),
                DLL_BANDWIDTH_HZ,
            ),
            (
                "dll_narrow_bandwidth_hz",
                self.dll_narrow_bandwidth_hz,
                DLL_BANDWIDTH_HZ,
            ),
            (
                "early_late_spacing_chips",
                Some(self.early_late_spacing_chips),
                SPACING_CHIPS,
            ),
            (
                "narrow_early_late_spacing_chips",
                self.narrow_early_late_spacing_chips,
                SPACING_CHIPS,
            ),
            (
                "coherent_ms",
                Some(f64::from(self.coherent_ms)),
                COHERENT_MS,
            ),
            ("cn0_window_s", Some(self.cn0_window_s), CN0_WINDOW_S),
            (
                "lock_indicator_tau_s",
                Some(self.lock_indicator_tau_s),
                SECONDS,
            ),
            (
                "pll_lock_threshold",
                Some(self.pll_lock_threshold),
                PLL_LOCK_THRESHOLD,
            ),
            (
                "cn0_lock_threshold_dbhz",
                Some(self.cn0_lock_threshold_dbhz),
                CN0_LOCK_THRESHOLD_DBHZ,
            ),
            ("loss_of_lock_s", Some(self.loss_of_lock_s), SECONDS),
            (
                "slip_threshold_sigma",
                Some(self.slip_threshold_sigma),
                SLIP_THRESHOLD_SIGMA,
            ),
            (
                "bit_sync.min_transitions",
                Some(f64::from(b.min_transitions)),
                MIN_TRANSITIONS,
            ),
            ("bit_sync.dominance", Some(b.dominance), DOMINANCE),
            ("bit_sync.nh_bits", Some(b.nh_bits as f64), NH_BITS),
        ];
        let given: Vec<_> = values
            .into_iter()
            .filter_map(|(field, value, allowed)| Some((field, value?, allowed)))
            .collect();
        check_table(&given)?;
        self.ukf.check().map_err(|e| e.within("ukf"))
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
    /// Every value in its range ([`limits`]).
    pub(crate) fn check(&self) -> Result<(), Invalid> {
        use limits::*;
        for (i, q) in self.q.iter().enumerate() {
            UKF_Q.check(&format!("q[{i}]"), *q)?;
        }
        UKF_KAPPA.check("kappa", self.kappa)?;
        UKF_DOPPLER_SIGMA_HZ.check("initial_doppler_sigma_hz", self.initial_doppler_sigma_hz)?;
        UKF_RATE_SIGMA_HZPS.check("initial_rate_sigma_hzps", self.initial_rate_sigma_hzps)
    }
}
