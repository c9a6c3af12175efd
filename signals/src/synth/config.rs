//! `[signal]`: what the synthesiser writes.

use super::filter::FilterConfig;
use crate::errors::link_budget::LinkBudgetConfig;
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::check::Invalid;
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::BTreeMap;

/// Synthesis block length (s): blocks are 1 ms, the C/A code period.
pub const BLOCK_S: f64 = 1e-3;

/// Fraction of a signal's main-lobe width (2 x chip rate) the recorded band may cut off.
pub const MAIN_LOBE_MARGIN: f64 = 0.05;

/// The lowest sample rate any signal can use: the GPS C/A main lobe with the margin.
pub const MIN_SAMPLE_RATE_HZ: f64 = 2.0 * (1.0 - MAIN_LOBE_MARGIN) * 1.023e6;

/// `[signal]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignalConfig {
    /// Complex (or real, for `ri8`) sample rate (Hz); a multiple of 1 kHz.
    #[serde(default = "default_fs")]
    pub sample_rate_hz: f64,
    /// Intermediate frequency (Hz); 0 for complex baseband.
    #[serde(default)]
    pub if_hz: f64,
    #[serde(default = "default_format")]
    pub format: SampleFormat,
    /// Quantisation word length: 1, 2, 4, 8 or 16 (default: the container's); ignored for cf32.
    #[serde(default)]
    pub bits: Option<u8>,
    /// C/N0 of every satellite (dB-Hz), unless `link_budget` or `cn0_by_satellite_dbhz`
    /// says otherwise.
    #[serde(default = "default_cn0")]
    pub cn0_dbhz: f64,
    /// `[signal.cn0_by_satellite_dbhz]`: fixed C/N0 of named satellites (`G05 = 40.0`),
    /// overriding `cn0_dbhz` and the link budget.
    #[serde(default)]
    pub cn0_by_satellite_dbhz: BTreeMap<String, f64>,
    /// `[signal.link_budget]`: C/N0 of each link from transmitter EIRP, free-space loss,
    /// the antenna gain pattern and the system noise temperature.
    #[serde(default)]
    pub link_budget: Option<LinkBudgetConfig>,
    /// `[signal.filter]`: an optional band-limiting front-end filter.
    #[serde(default)]
    pub filter: Option<FilterConfig>,
    /// Rate of the signal truth written beside the samples (Hz): a divisor of 1000, or 0
    /// for none.
    #[serde(default = "default_truth_rate")]
    pub truth_rate_hz: u32,
    /// The signals synthesised, one per enabled constellation, each recorded on its own
    /// (`["gps-l5", "bds-b1i"]`); empty (the default): each constellation's first signal
    /// ([`Signal::of_system`]: GPS L1 C/A, BeiDou B1I, Galileo E5a).
    #[serde(default)]
    pub signals: Vec<Signal>,
    /// How the signals are recorded: one recording per signal (the default) or one per
    /// band, the signals that share a carrier in one.
    #[serde(default)]
    pub recordings: RecordingLayout,
}

/// `[signal] recordings`: which signals share a recording.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RecordingLayout {
    /// One recording per signal (`"per-signal"`).
    #[default]
    PerSignal,
    /// One recording per band (`"per-band"`): the signals on one carrier (GPS L1 C/A and
    /// Galileo E1 at 1575.42 MHz, GPS L5 and Galileo E5a at 1176.45 MHz) summed in one
    /// recording, as a receiver's front end takes them; signals on other carriers get
    /// recordings of their own.
    PerBand,
}

impl RecordingLayout {
    /// Whether signals `a` and `b` go into one recording.
    pub fn together(self, a: Signal, b: Signal) -> bool {
        self == Self::PerBand && (a.carrier_hz() - b.carrier_hz()).abs() < 1.0
    }
}

/// Checks a C/N0 value.
fn check_cn0(field: &str, cn0: f64) -> Result<(), Invalid> {
    if !(cn0.is_finite() && (10.0..=70.0).contains(&cn0)) {
        return Err(Invalid::new(field, cn0, "must be in [10, 70] dB-Hz"));
    }
    Ok(())
}

impl Default for SignalConfig {
    /// Every key at its documented default.
    fn default() -> Self {
        Self {
            sample_rate_hz: default_fs(),
            if_hz: 0.0,
            format: default_format(),
            bits: None,
            cn0_dbhz: default_cn0(),
            cn0_by_satellite_dbhz: BTreeMap::new(),
            link_budget: None,
            filter: None,
            truth_rate_hz: default_truth_rate(),
            signals: Vec::new(),
            recordings: RecordingLayout::default(),
        }
    }
}

fn default_fs() -> f64 {
    4.092e6
}
fn default_format() -> SampleFormat {
    SampleFormat::Ci8
}
fn default_cn0() -> f64 {
    45.0
}
fn default_truth_rate() -> u32 {
    1000
}

impl SignalConfig {
    /// Checks: the rate gives whole samples per block; the IF lies inside Nyquist; C/N0
    /// is plausible. Whether the band holds each signal is [`Self::check_band`].
    pub fn check(&self) -> Result<(), Invalid> {
        let fs = self.sample_rate_hz;
        let per_block = fs * BLOCK_S;
        if !(fs.is_finite()
            && fs >= MIN_SAMPLE_RATE_HZ
            && (per_block - per_block.round()).abs() < 1e-6
            && fs <= 1e9)
        {
            return Err(Invalid::new(
                "sample_rate_hz",
                fs,
                format!(
                    "must be at least {MIN_SAMPLE_RATE_HZ:e} (the C/A main lobe, see check_band), at most 1e9, and a multiple of 1000"
                ),
            ));
        }
        let nyquist = fs / 2.0;
        if !(self.if_hz.is_finite() && self.if_hz.abs() < nyquist)
            || (!self.format.is_complex() && self.if_hz <= 0.0)
        {
            return Err(Invalid::new(
                "if_hz",
                self.if_hz,
                format!(
                    "must lie inside Nyquist (|IF| < {nyquist} Hz), and be > 0 for real (ri8) output"
                ),
            ));
        }
        if let Some(b) = self.bits {
            if !super::quantise::SUPPORTED_BITS.contains(&b) {
                return Err(Invalid::new("bits", b, "must be one of 1, 2, 4, 8, 16"));
            }
            if self.format.max_bits().is_some_and(|max| b > max) {
                return Err(Invalid::new(
                    "bits",
                    b,
                    format!("does not fit the {:?} container", self.format),
                ));
            }
        }
        check_cn0("cn0_dbhz", self.cn0_dbhz)?;
        for (sat, &cn0) in &self.cn0_by_satellite_dbhz {
            let field = format!("cn0_by_satellite_dbhz.{sat}");
            if sat.parse::<SatId>().is_err() {
                return Err(Invalid::new(
                    field,
                    format!("{sat:?}"),
                    "keys must be satellites such as G05 or C23",
                ));
            }
            check_cn0(&field, cn0)?;
        }
        if let Some(budget) = &self.link_budget {
            budget.check().map_err(|e| e.within("link_budget"))?;
        }
        if let Some(filter) = &self.filter {
            filter
                .check(fs, self.if_hz, self.format.is_complex())
                .map_err(|e| e.within("filter"))?;
        }
        if self.truth_rate_hz != 0 && 1000 % self.truth_rate_hz != 0 {
            return Err(Invalid::new(
                "truth_rate_hz",
                self.truth_rate_hz,
                "must divide 1000 (1 ms blocks), or be 0",
            ));
        }
        Ok(())
    }

    /// The recorded band must hold the main lobes of signal `name` (outermost null
    /// `lobe_hz` about the carrier, [`Signal::main_lobe_half_width_hz`]: the chip rate for
    /// BPSK) to within [`MAIN_LOBE_MARGIN`]: complex samples need `|IF| + (1 - margin) x
    /// lobe <= fs/2`, real samples `(1 - margin) x lobe < IF < fs/2 - (1 - margin) x lobe`.
    /// (The margin lets the common 4 Msps B1I recordings through: they keep 97.8 % of the
    /// main lobe.)
    pub fn check_band(&self, name: &str, lobe_hz: f64) -> Result<(), Invalid> {
        let half = (1.0 - MAIN_LOBE_MARGIN) * lobe_hz;
        let (fs, f_if) = (self.sample_rate_hz, self.if_hz);
        let nyquist = fs / 2.0;
        if self.format.is_complex() {
            if f_if.abs() + half > nyquist {
                let need = 2.0 * (f_if.abs() + half);
                return Err(Invalid::new(
                    "sample_rate_hz",
                    fs,
                    format!(
                        "is below the {name} signal bandwidth: its main lobe (+-{lobe_hz:e} Hz about IF {f_if} Hz, {}% margin) needs at least {need:e} complex samples/s",
                        MAIN_LOBE_MARGIN * 100.0
                    ),
                ));
            }
        } else if f_if - half <= 0.0 || f_if + half >= nyquist {
            return Err(Invalid::new(
                "if_hz",
                f_if,
                format!(
                    "puts the {name} main lobe (+-{lobe_hz:e} Hz, {}% margin) outside 0..{nyquist} Hz for real samples at {fs:e}/s: the IF must lie in {half:e}..{:e} Hz",
                    MAIN_LOBE_MARGIN * 100.0,
                    nyquist - half
                ),
            ));
        }
        Ok(())
    }

    /// The signals `system`'s satellites transmit: those `signals` lists for it, or the
    /// system's first when `signals` is empty ([`Self::check_signals`] makes sure every
    /// enabled system has one).
    pub fn signals_of(&self, system: System) -> Vec<Signal> {
        if self.signals.is_empty() {
            return vec![Signal::of_system(system)];
        }
        self.signals
            .iter()
            .copied()
            .filter(|s| s.system() == system)
            .collect()
    }

    /// Checks `signals` against the enabled constellations `enabled`: each listed signal
    /// is one SkyForge transmits ([`Signal::TRANSMITTED`]; Galileo E1 with the user's code
    /// tables, `skyforge_gnss::codes::e1_codes`), of an enabled constellation, listed once,
    /// and every enabled constellation has one (a constellation may transmit
    /// several: GPS L1 C/A and L5, one recording each).
    pub fn check_signals(&self, enabled: &[System]) -> Result<(), Invalid> {
        let transmitted = || {
            Signal::TRANSMITTED
                .iter()
                .map(|s| s.tag())
                .collect::<Vec<_>>()
                .join(", ")
        };
        for (i, s) in self.signals.iter().enumerate() {
            let field = format!("signals[{i}]");
            if !s.is_transmitted() {
                return Err(Invalid::new(
                    field,
                    s.tag(),
                    format!("is not a signal SkyForge transmits ({})", transmitted()),
                ));
            }
            if !enabled.contains(&s.system()) {
                return Err(Invalid::new(
                    field,
                    s.tag(),
                    format!(
                        "{} is not enabled under [gnss] in this scenario",
                        s.system().name()
                    ),
                ));
            }
            if self.signals[..i].contains(s) {
                return Err(Invalid::new(field, s.tag(), "is listed twice"));
            }
            if *s == Signal::GalE1
                && let Err(e) = skyforge_gnss::codes::e1_codes()
            {
                return Err(Invalid::new(field, s.tag(), e.to_string()));
            }
        }
        if let Some(missing) = enabled.iter().find(|&&sys| self.signals_of(sys).is_empty()) {
            return Err(Invalid::new(
                "signals",
                format!(
                    "[{}]",
                    self.signals
                        .iter()
                        .map(|s| format!("{:?}", s.tag()))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                format!(
                    "lists no signal of {}, which is enabled (add one, or disable it under [gnss])",
                    missing.name()
                ),
            ));
        }
        Ok(())
    }

    /// The C/N0 (dB-Hz) of satellite `sat`'s fixed setting, or `None` when the link budget
    /// decides.
    pub fn fixed_cn0_dbhz(&self, sat: SatId) -> Option<f64> {
        self.cn0_by_satellite_dbhz
            .iter()
            .find(|(k, _)| k.parse::<SatId>().is_ok_and(|s| s == sat))
            .map(|(_, &v)| v)
            .or_else(|| self.link_budget.is_none().then_some(self.cn0_dbhz))
    }

    /// Blocks between signal-truth records (0: none).
    pub fn truth_every_blocks(&self) -> u64 {
        1000u32.checked_div(self.truth_rate_hz).map_or(0, u64::from)
    }

    /// Samples per 1 ms block.
    pub fn samples_per_block(&self) -> usize {
        (self.sample_rate_hz * BLOCK_S).round() as usize
    }

    /// Bytes of one 1 ms block in the container format.
    pub fn block_bytes(&self) -> usize {
        self.samples_per_block() * self.format.bytes_per_sample()
    }
}
