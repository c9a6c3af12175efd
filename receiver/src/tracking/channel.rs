//! The channel tracker: one satellite on one antenna, from the acquisition hand-over to
//! per-integration records of code phase, carrier phase, Doppler, prompt, C/N0, lock and
//! slip flags and data bits.
//!
//! Processing runs code period by code period (1 ms for GPS C/A and BeiDou B1I): each
//! period is correlated in one call of the kernel, with the NCO state at its first sample.
//! A period that straddles two input blocks is gathered in a buffer first, so how the
//! caller cuts its samples into blocks does not change any result.
//!
//! A signal with a pilot (GPS L5, Galileo E5a and E1) is tracked on its pilot: the loops
//! close on the pilot code's early, prompt and late taps (turned back a quarter cycle, the
//! pilot's lead on the data component, or for E1, whose pilot is sent in phase with the
//! opposite sign, negated; so the carrier phase is the data component's), a
//! fourth tap reads the data code's prompt, and "bit synchronisation" is the search for
//! the pilot's secondary code, which also gives the symbol edge and the carrier loop's
//! polarity; after it the pilot's secondary code is wiped off the loop taps, the data
//! secondary code and the polarity off the symbols.
//!
//! Loops: FLL-assisted PLL of 2nd or 3rd order (Costas by default) and a 1st-order
//! normalised early-minus-late envelope DLL with carrier aiding, updated at the end of
//! every coherent integration. After bit synchronisation (and Neumann-Hoffman wipe-off on
//! BeiDou D1) integrations grow to `coherent_ms` periods, never crossing a bit edge, as
//! far as the PLL bandwidth in use allows (`Bn T <= 0.1`).
//!
//! Galileo E1 is correlated with BOC(1,1) replicas ([`crate::replica`]), 4 ms per code
//! period and symbol, its DLL with the BOC(1,1) discriminator and early-late spacings
//! capped for BOC(1,1)'s narrow peak ([`BOC11_MAX_SPACING_CHIPS`]). BeiDou B1C likewise,
//! 10 ms per period and symbol, on its pilot's BOC(1,1) part in quadrature; its 1800-chip
//! secondary code lasts one B-CNAV1 frame, so its symbols are handed on from a code start
//! (a frame start) on ([`DataModulation::frame_is_pilot_secondary`]).

use num_complex::Complex;
use skyforge_gnss::codes::neumann_hoffman;

use super::TrackingError;
use super::bit_sync::BitSynchroniser;
use super::carrier::{self, CarrierTracker, IntegrationEnd};
use super::config::TrackingConfig;
use super::correlator::{Correlator, NcoState, TapSet};
use super::discriminators::{dll_envelope_boc11_chips, dll_envelope_chips};
use super::lock::{Cn0Estimator, LossOfLockTimer, PllLockIndicator};
use super::loop_filter::{aided_code_rate, dll_rate_correction};
use crate::replica::{B1C_PILOT_BOC11_SHARE_DB, BOC61_SHARE_DB, SignalCodes, subchips};
use skyforge_gnss::signal::{DataModulation, Signal};

/// Largest PLL `Bn T` (noise bandwidth x coherent integration) an integration may reach.
/// The digital loop (bilinear filter, zero-delay NCO) realises its design noise bandwidth
/// within 4 % up to 0.1, 7-12 % high at 0.15 and is unstable from about 0.3 (impulse
/// response of the closed loop; at 0.5, a 25 Hz loop at 20 ms, tracking broke up).
const MAX_BN_T: f64 = 0.1;

/// What acquisition hands over to a tracking channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Handover {
    /// The signal.
    pub signal: Signal,
    /// Satellite PRN.
    pub prn: u8,
    /// Sample index the code phase refers to.
    pub sample_index: u64,
    /// Samples from `sample_index` to the start of the next code period (chip 0), in
    /// `[0, samples per code period)`; fractional samples allowed.
    pub code_phase_samples: f64,
    /// Carrier Doppler (Hz).
    pub doppler_hz: f64,
    /// Doppler rate (Hz/s) if known (e.g. from assistance), else 0.
    pub doppler_rate_hzps: f64,
}

/// Front-end description of the samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrontEnd {
    /// Sample rate (Hz).
    pub sample_rate_hz: f64,
    /// Intermediate frequency of the carrier (Hz); 0 for complex baseband.
    pub if_hz: f64,
}

/// A carrier loop whose Doppler runs beyond this (Hz) has diverged: the channel is lost
/// (the code period, and with it the sample buffer, would grow without bound).
pub const MAX_TRACKED_DOPPLER_HZ: f64 = 100e3;

/// A data bit decided after bit synchronisation (sign ambiguous by the Costas half cycle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DataBit {
    /// +1 or -1.
    pub value: i8,
    /// Sum of the in-phase prompts over the bit (secondary code removed).
    pub soft: f64,
    /// First sample of the bit's first code period.
    pub first_sample_index: u64,
}

/// One coherent integration of a channel. Phases and rates are the NCO's at
/// `sample_index`, the first sample of the integration, where the prompt replica code
/// phase is `code_phase_chips` (the code epoch is `code_phase_chips / code rate * fs`
/// samples earlier).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackingRecord {
    /// First sample of the integration.
    pub sample_index: u64,
    /// Prompt code phase at `sample_index` (chips into the code period, `[0, chips per
    /// sample)`).
    pub code_phase_chips: f64,
    /// Code periods in the integration.
    pub integration_periods: u32,
    /// Integration length (s).
    pub integration_s: f64,
    /// Accumulated carrier phase of the replica at `sample_index` (cycles, integer part
    /// kept): the integral of the NCO Doppler since the first code epoch after hand-over (IF
    /// excluded); grows with positive Doppler (RINEX sign is the opposite).
    pub carrier_phase_cycles: f64,
    /// Carrier Doppler of the NCO during the integration (Hz).
    pub doppler_hz: f64,
    /// Doppler rate estimate of the loop filter (Hz/s; 0 for a 2nd-order PLL).
    pub doppler_rate_hzps: f64,
    /// Code rate of the NCO during the integration (chips/s).
    pub code_rate_chips_per_s: f64,
    /// Early, prompt and late correlations (secondary code removed after sync).
    pub early: Complex<f64>,
    /// Prompt correlation.
    pub prompt: Complex<f64>,
    /// Late correlation.
    pub late: Complex<f64>,
    /// PLL discriminator output (cycles).
    pub phase_error_cycles: f64,
    /// DLL discriminator output (chips).
    pub code_error_chips: f64,
    /// C/N0 estimate (dB-Hz) of the whole signal, once the estimator window has filled;
    /// for a signal with a pilot, the pilot's estimate plus 3.01 dB (the ICDs split the
    /// power equally between the two components), for Galileo E1 plus 0.41 dB more (the
    /// BOC(6,1) part its BOC(1,1) replica does not see, [`BOC61_SHARE_DB`]); for BeiDou
    /// B1C, whose pilot's BOC(1,1) part carries 29/44 of the power, plus 1.81 dB
    /// ([`B1C_PILOT_BOC11_SHARE_DB`]).
    pub cn0_dbhz: Option<f64>,
    /// PLL lock indicator: the smoothed `cos 2 phi` estimate, corrected for the noise bias
    /// `SNR / (1 + SNR)` of one prompt with the C/N0 estimate.
    pub pll_lock_indicator: f64,
    /// Phase lock (indicator and C/N0 above their thresholds).
    pub locked: bool,
    /// Bit synchronisation established.
    pub bit_synced: bool,
    /// A cycle slip was detected in or before this integration (half-cycle sign reversal
    /// inside a bit, or the lock indicator dropping out of lock).
    pub cycle_slip: bool,
    /// Loss of lock declared: the channel stops.
    pub loss_of_lock: bool,
    /// Continuous lock time without slip (s).
    pub lock_time_s: f64,
    /// A data bit completed in this integration.
    pub bit: Option<DataBit>,
}

/// NCO state at the start of an integration.
#[derive(Debug, Clone, Copy, PartialEq)]
struct IntegrationStart {
    sample_index: u64,
    code_phase_chips: f64,
    carrier_phase_cycles: f64,
    doppler_hz: f64,
    code_rate: f64,
}

/// Per-bit accumulation after bit sync.
#[derive(Debug, Clone, Copy, PartialEq)]
struct BitAccumulator {
    first_sample_index: u64,
    prompts: [f64; neumann_hoffman::NH20_LENGTH],
    count: usize,
}

/// Power of a pilot signal over its pilot alone: the two components carry half each.
const PILOT_SHARE_DB: f64 = 3.010_299_956_639_812;

/// The widest early-late spacing (chips) of a BOC(1,1) replica's DLL: its envelope
/// discriminator is right while early and late stay on the main peak, within its zeros
/// at +-1/3 chip; 0.3 leaves the hand-over +-0.18 chip to pull in from.
pub const BOC11_MAX_SPACING_CHIPS: f64 = 0.3;
/// The widest narrow (after bit sync) spacing of a BOC(1,1) DLL (chips): GNSS-SDR's E1
/// early-late spacing, 0.15 chip (`Galileo_E1_DLL_PLL_VEML_Tracking`).
pub const BOC11_MAX_NARROW_SPACING_CHIPS: f64 = 0.15;

/// The spacing `d` (chips) a channel of `signal` uses: at most `boc_cap` for a BOC(1,1)
/// replica.
fn spacing_for(signal: Signal, d: f64, boc_cap: f64) -> f64 {
    if signal.replica_boc11() {
        d.min(boc_cap)
    } else {
        d
    }
}

/// One satellite's tracking channel.
#[derive(Debug)]
pub struct ChannelTracker {
    signal: Signal,
    prn: u8,
    modulation: DataModulation,
    front_end: FrontEnd,
    config: TrackingConfig,
    codes: SignalCodes,
    correlator: Correlator,
    /// DLL bandwidth and early-late spacing in use (wide until bit sync).
    dll_bandwidth_hz: f64,
    early_late_spacing_chips: f64,
    carrier: Box<dyn CarrierTracker>,
    // NCO state at `next_index`, the first sample of the next code period.
    next_index: u64,
    code_phase_chips: f64,
    carrier_phase_cycles: f64,
    if_phase_cycles: f64,
    doppler_hz: f64,
    code_rate: f64,
    period_index: u64,
    time_s: f64,
    pending: Vec<Complex<f32>>,
    expected_block: Option<u64>,
    // Integration in progress.
    start: Option<IntegrationStart>,
    acc: [Complex<f64>; 3],
    acc_periods: u32,
    acc_s: f64,
    // Lock and sync.
    lock_indicator: PllLockIndicator,
    cn0: Cn0Estimator,
    loss_timer: LossOfLockTimer,
    locked: bool,
    ever_locked: bool,
    lock_time_s: f64,
    slip_pending: bool,
    lost: bool,
    sync: BitSynchroniser,
    synced_at_s: Option<f64>,
    /// Data bits are handed on: from bit sync, or for B1C from the first frame start.
    framed: bool,
    bit: Option<BitAccumulator>,
    last_cn0_dbhz: Option<f64>,
}

impl ChannelTracker {
    /// A channel started from an acquisition hand-over.
    pub fn new(
        handover: Handover,
        front_end: FrontEnd,
        config: TrackingConfig,
    ) -> Result<Self, TrackingError> {
        config.check()?;
        let codes = SignalCodes::of(handover.signal, handover.prn)?;
        Self::with_codes(handover, front_end, config, codes)
    }

    /// [`Self::new`] with the PRN's codes given (Galileo E1's from tables the caller read,
    /// [`SignalCodes::galileo_e1`]).
    pub fn with_codes(
        handover: Handover,
        front_end: FrontEnd,
        config: TrackingConfig,
        codes: SignalCodes,
    ) -> Result<Self, TrackingError> {
        config.check()?;
        if !(front_end.sample_rate_hz.is_finite()
            && front_end.sample_rate_hz > 0.0
            && front_end.if_hz.is_finite())
        {
            return Err(TrackingError::InvalidConfig(format!(
                "sample rate must be positive and IF finite: {front_end:?}"
            )));
        }
        let signal = handover.signal;
        let fs = front_end.sample_rate_hz;
        if codes.data.len() != signal.code_length() {
            return Err(TrackingError::InvalidConfig(format!(
                "{} chips of code, {} has {}",
                codes.data.len(),
                signal.name(),
                signal.code_length()
            )));
        }
        if fs < signal.chip_rate_hz() * subchips(signal) as f64 {
            return Err(TrackingError::InvalidConfig(format!(
                "sample rate {fs} Hz is too low for {}",
                signal.name()
            )));
        }
        let spacing = spacing_for(
            signal,
            config.early_late_spacing_chips,
            BOC11_MAX_SPACING_CHIPS,
        );
        let correlator = correlator(signal, &codes, spacing)?;
        let carrier = carrier::build(&config, handover.doppler_hz, handover.doppler_rate_hzps)?;
        let code_rate = aided_code_rate(
            signal.chip_rate_hz(),
            handover.doppler_hz,
            signal.carrier_hz(),
        );
        let dp = code_rate / fs;
        let samples_per_period = signal.code_length() as f64 / dp;
        if !(handover.code_phase_samples.is_finite()
            && (0.0..samples_per_period + 1.0).contains(&handover.code_phase_samples))
        {
            return Err(TrackingError::InvalidConfig(format!(
                "hand-over code phase {} samples outside one code period ({samples_per_period})",
                handover.code_phase_samples
            )));
        }
        // The first code period starts between samples; begin at the first sample after it.
        let lead = handover.code_phase_samples.ceil();
        let modulation = signal.data_modulation(handover.prn).ok_or_else(|| {
            TrackingError::InvalidConfig(format!("{} is not tracked", signal.name()))
        })?;
        let sync = match &codes.pilot {
            Some(pilot) if signal.has_pilot() => {
                BitSynchroniser::for_pilot(modulation, pilot.secondary.clone(), config.bit_sync)
            }
            _ => BitSynchroniser::new(modulation, config.bit_sync),
        };
        Ok(Self {
            signal,
            prn: handover.prn,
            modulation,
            front_end,
            config,
            codes,
            correlator,
            dll_bandwidth_hz: config.dll_bandwidth_hz,
            early_late_spacing_chips: spacing,
            carrier,
            next_index: handover.sample_index + lead as u64,
            code_phase_chips: (lead - handover.code_phase_samples) * dp,
            carrier_phase_cycles: 0.0,
            if_phase_cycles: ((handover.sample_index as f64 + lead) * front_end.if_hz / fs)
                .rem_euclid(1.0),
            doppler_hz: handover.doppler_hz,
            code_rate,
            period_index: 0,
            time_s: 0.0,
            pending: Vec::new(),
            expected_block: None,
            start: None,
            acc: [Complex::new(0.0, 0.0); 3],
            acc_periods: 0,
            acc_s: 0.0,
            lock_indicator: PllLockIndicator::new(config.lock_indicator_tau_s),
            cn0: Cn0Estimator::new(
                ((config.cn0_window_s / signal.code_period_s()).round() as usize).max(20),
                signal.code_period_s(),
            ),
            loss_timer: LossOfLockTimer::new(config.loss_of_lock_s),
            locked: false,
            ever_locked: false,
            lock_time_s: 0.0,
            slip_pending: false,
            lost: false,
            sync,
            synced_at_s: None,
            framed: false,
            bit: None,
            last_cn0_dbhz: None,
        })
    }

    /// The tracked signal.
    pub fn signal(&self) -> Signal {
        self.signal
    }

    /// The tracked PRN.
    pub fn prn(&self) -> u8 {
        self.prn
    }

    /// The data modulation of this PRN.
    pub fn data_modulation(&self) -> DataModulation {
        self.modulation
    }

    /// True once loss of lock has been declared; the channel then ignores further samples.
    pub fn is_lost(&self) -> bool {
        self.lost
    }

    /// Bit-edge phase once bit sync is established: bits start at code periods whose index
    /// since hand-over modulo the bit length equals it.
    pub fn bit_edge_phase(&self) -> Option<u32> {
        self.sync.edge_phase()
    }

    /// A signal tracked on its pilot whose secondary code is found: the carrier loop's
    /// polarity is known ([`Self::pilot_inverted`]) without the data.
    pub fn pilot_synchronised(&self) -> bool {
        self.sync.pilot_wipe(0).is_some()
    }

    /// For a signal tracked on its pilot, once its secondary code is found: whether the
    /// carrier loop holds the carrier half a cycle off (the code arrived inverted). The
    /// data bits are handed on corrected; the carrier phase is not.
    pub fn pilot_inverted(&self) -> bool {
        self.sync.pilot_inverted()
    }

    /// Track over one block of samples whose first sample has index `first_sample_index`.
    /// The first block may start anywhere (samples before the hand-over are skipped, a
    /// later start moves the NCOs forward); later blocks must follow on without a gap.
    pub fn process(
        &mut self,
        samples: &[Complex<f32>],
        first_sample_index: u64,
    ) -> Result<Vec<TrackingRecord>, TrackingError> {
        match self.expected_block {
            Some(expected) if expected != first_sample_index => {
                return Err(TrackingError::NonContiguous {
                    expected,
                    got: first_sample_index,
                });
            }
            Some(_) => {}
            None => self.skip_to(first_sample_index),
        }
        let end = first_sample_index + samples.len() as u64;
        self.expected_block = Some(end);
        let mut records = Vec::new();
        while !self.lost {
            let n = self.period_length();
            let period_end = self.next_index + n as u64;
            // First sample of this period not yet held in `pending`.
            let have = self.next_index + self.pending.len() as u64;
            let from = (have.max(first_sample_index) - first_sample_index) as usize;
            if period_end > end {
                if have < end {
                    self.pending.extend_from_slice(&samples[from..]);
                }
                break;
            }
            let to = (period_end - first_sample_index) as usize;
            let nco = self.nco();
            let corr = if self.pending.is_empty() {
                self.correlator.correlate(&samples[from..to], &nco)
            } else {
                self.pending.extend_from_slice(&samples[from..to]);
                self.correlator.correlate(&self.pending, &nco)
            };
            // A pilot in quadrature leads the data component by a quarter cycle: turn its
            // taps back. E1-C is sent as -e_C beside e_B: negate its taps.
            let (corr, data) = match corr {
                [e, p, l, d] if self.signal.pilot_in_quadrature() => {
                    ([e, p, l].map(|c| Complex::new(c.im, -c.re)), *d)
                }
                [e, p, l, d] => ([e, p, l].map(|c| -c), *d),
                _ => ([corr[0], corr[1], corr[2]], corr[1]),
            };
            self.pending.clear();
            if let Some(record) = self.finish_period(corr, data, n) {
                records.push(record);
            }
        }
        Ok(records)
    }

    /// NCO state at `next_index`.
    fn nco(&self) -> NcoState {
        let fs = self.front_end.sample_rate_hz;
        NcoState {
            carrier_phase_cycles: self.if_phase_cycles + self.carrier_phase_cycles.fract(),
            carrier_cycles_per_sample: (self.front_end.if_hz + self.doppler_hz) / fs,
            code_phase_chips: self.code_phase_chips,
            code_chips_per_sample: self.code_rate / fs,
        }
    }

    /// Samples in the code period starting at `next_index`.
    fn period_length(&self) -> usize {
        let dp = self.code_rate / self.front_end.sample_rate_hz;
        ((self.signal.code_length() as f64 - self.code_phase_chips) / dp).ceil() as usize
    }

    /// Move the NCOs over one code period of `n` samples at the current rates.
    fn advance(&mut self, n: usize) {
        let fs = self.front_end.sample_rate_hz;
        let dp = self.code_rate / fs;
        self.code_phase_chips += n as f64 * dp - self.signal.code_length() as f64;
        self.carrier_phase_cycles += n as f64 * self.doppler_hz / fs;
        self.if_phase_cycles =
            (self.if_phase_cycles + n as f64 * self.front_end.if_hz / fs).rem_euclid(1.0);
        self.next_index += n as u64;
        self.period_index += 1;
        self.time_s += n as f64 / fs;
    }

    /// Before the first block: move on to the first code period starting at or after
    /// `index` (open loop, at the hand-over rates).
    fn skip_to(&mut self, index: u64) {
        while self.next_index < index {
            let n = self.period_length();
            self.advance(n);
        }
    }

    /// Fold one code period's correlations (early, prompt, late of the tracked code, and
    /// the data code's prompt, the same as the prompt without a pilot) into the
    /// integration; returns the record when the integration completes.
    fn finish_period(
        &mut self,
        corr: [Complex<f64>; 3],
        data: Complex<f64>,
        n: usize,
    ) -> Option<TrackingRecord> {
        let k = self.period_index;
        let ppb = u64::from(self.modulation.periods_per_bit());
        let edge = self.sync.edge_phase().map(u64::from);
        // Position in the bit (after sync) and secondary-code wipe-off.
        let position = edge.map(|e| (k + ppb - e % ppb) % ppb);
        let data_chip = match (self.modulation.data_secondary_code(), position) {
            (Some(code), Some(pos)) => f64::from(code[pos as usize % code.len()]),
            _ => 1.0,
        };
        let (corr, data) = match self.sync.pilot_wipe(k) {
            Some(wipe) => {
                let polarity = if self.sync.pilot_inverted() {
                    -1.0
                } else {
                    1.0
                };
                (corr.map(|c| c * wipe), data * data_chip * polarity)
            }
            None => (corr.map(|c| c * data_chip), data * data_chip),
        };
        if self.start.is_none() {
            self.start = Some(IntegrationStart {
                sample_index: self.next_index,
                code_phase_chips: self.code_phase_chips,
                carrier_phase_cycles: self.carrier_phase_cycles,
                doppler_hz: self.doppler_hz,
                code_rate: self.code_rate,
            });
        }
        let period_start = self.next_index;
        self.advance(n);
        for (a, c) in self.acc.iter_mut().zip(corr) {
            *a += c;
        }
        self.acc_periods += 1;
        self.acc_s += n as f64 / self.front_end.sample_rate_hz;

        // C/N0 from every code period's prompt, whatever the coherent integration: at long
        // integrations the prompt SNR is so high that M2M4 would count the small amplitude
        // changes from code tracking as noise.
        self.cn0.push(corr[1]);
        let mut bit = None;
        match position {
            None => {
                if self.locked && self.sync.feed(k, corr[1].re).is_some() {
                    self.synced_at_s = Some(self.time_s);
                }
            }
            Some(pos) => {
                self.framed |= !self.modulation.frame_is_pilot_secondary()
                    || self.sync.secondary_chip(k) == Some(0);
                if self.framed {
                    bit = self.accumulate_bit(pos, ppb, data.re, period_start);
                }
            }
        }
        let complete = match position {
            None => true,
            Some(pos) => self.acc_periods >= self.coherent_periods(ppb as u32) || pos + 1 == ppb,
        };
        complete.then(|| self.close_integration(bit))
    }

    /// Code periods per coherent integration after bit sync: `coherent_ms`, at most one
    /// bit, and no longer than keeps the PLL's `Bn T` within [`MAX_BN_T`] at its current
    /// bandwidth, so integrations grow as the PLL narrows.
    fn coherent_periods(&self, periods_per_bit: u32) -> u32 {
        let stable = match self.carrier.loop_bandwidth_hz() {
            // Saturating float-to-int cast: a huge quotient still ends at coherent_ms below.
            Some(bn) => ((MAX_BN_T / (bn * self.signal.code_period_s())).floor() as u32).max(1),
            None => u32::MAX,
        };
        self.config.coherent_ms.min(periods_per_bit).min(stable)
    }

    /// After bit sync: switch the DLL to its narrow bandwidth and spacing, if configured
    /// (once; the new spacing takes effect from the next integration).
    fn narrow_dll(&mut self) {
        if self.synced_at_s.is_none() {
            return;
        }
        if let Some(bn) = self.config.dll_narrow_bandwidth_hz {
            self.dll_bandwidth_hz = bn;
        }
        // Never closer than one sample: early and late inside one sample step of the
        // correlation staircase leave the discriminator a dead zone.
        let chips_per_sample = self.signal.chip_rate_hz() / self.front_end.sample_rate_hz;
        if let Some(d) = self
            .config
            .narrow_early_late_spacing_chips
            .map(|d| spacing_for(self.signal, d, BOC11_MAX_NARROW_SPACING_CHIPS))
            .map(|d| d.max(chips_per_sample))
            && d != self.early_late_spacing_chips
        {
            // The codes were valid when the channel was made.
            if let Ok(c) = correlator(self.signal, &self.codes, d) {
                self.correlator = c;
                self.early_late_spacing_chips = d;
            }
        }
    }

    /// After sync: add a period's in-phase prompt to the bit; returns the bit at its end.
    fn accumulate_bit(
        &mut self,
        pos: u64,
        ppb: u64,
        prompt_i: f64,
        period_start: u64,
    ) -> Option<DataBit> {
        if pos == 0 {
            self.bit = Some(BitAccumulator {
                first_sample_index: period_start,
                prompts: [0.0; neumann_hoffman::NH20_LENGTH],
                count: 0,
            });
        }
        let acc = self.bit.as_mut()?;
        acc.prompts[acc.count] = prompt_i;
        acc.count += 1;
        if pos + 1 != ppb {
            return None;
        }
        let acc = self.bit.take()?;
        let prompts = &acc.prompts[..acc.count];
        let soft: f64 = prompts.iter().sum();
        if self.half_cycle_slip(prompts) {
            self.slip_pending = true;
        }
        Some(DataBit {
            value: if soft >= 0.0 { 1 } else { -1 },
            soft,
            first_sample_index: acc.first_sample_index,
        })
    }

    /// A sign reversal inside one bit: some split into a leading and a trailing part
    /// whose sums have opposite signs, each beyond `slip_threshold_sigma` noise standard
    /// deviations (from the C/N0 estimate and the bit's mean amplitude).
    fn half_cycle_slip(&self, prompts: &[f64]) -> bool {
        let Some(cn0_dbhz) = self.last_cn0_dbhz.filter(|c| c.is_finite()) else {
            return false;
        };
        let m = prompts.len();
        if m < 2 {
            return false;
        }
        let amplitude = prompts.iter().map(|p| p.abs()).sum::<f64>() / m as f64;
        let snr_period = 10f64.powf(cn0_dbhz / 10.0) * self.signal.code_period_s();
        // In-phase noise of one period: amplitude / sqrt(2 SNR).
        let sigma = amplitude / (2.0 * snr_period).sqrt();
        let k = self.config.slip_threshold_sigma;
        let total: f64 = prompts.iter().sum();
        let mut head = 0.0;
        for (j, p) in prompts[..m - 1].iter().enumerate() {
            head += p;
            let tail = total - head;
            let (nh, nt) = ((j + 1) as f64, (m - j - 1) as f64);
            if head * tail < 0.0
                && head.abs() > k * sigma * nh.sqrt()
                && tail.abs() > k * sigma * nt.sqrt()
            {
                return true;
            }
        }
        false
    }

    /// End of a coherent integration: discriminators, loop filters, lock detectors, record.
    fn close_integration(&mut self, bit: Option<DataBit>) -> TrackingRecord {
        let [early, prompt, late] = self.acc;
        let t = self.acc_s;
        let start = self.start.take().unwrap_or(IntegrationStart {
            sample_index: self.next_index,
            code_phase_chips: self.code_phase_chips,
            carrier_phase_cycles: self.carrier_phase_cycles,
            doppler_hz: self.doppler_hz,
            code_rate: self.code_rate,
        });
        let periods = self.acc_periods;
        self.acc = [Complex::new(0.0, 0.0); 3];
        self.acc_periods = 0;
        self.acc_s = 0.0;

        // Carrier loop.
        let step = self.carrier.close(&IntegrationEnd {
            prompt,
            integration_s: t,
            time_s: self.time_s,
            synced_at_s: self.synced_at_s,
            cn0_dbhz: self.last_cn0_dbhz,
            nco_doppler_hz: self.doppler_hz,
            nco_start_phase_cycles: start.carrier_phase_cycles,
        });
        let phase_error = step.phase_error_cycles;
        self.doppler_hz = step.doppler_hz;
        let diverged = self.doppler_hz.is_nan() || self.doppler_hz.abs() > MAX_TRACKED_DOPPLER_HZ;
        self.carrier_phase_cycles += step.phase_step_cycles;

        // Code loop, carrier aided.
        let code_error = if self.signal.replica_boc11() {
            dll_envelope_boc11_chips(early, late, self.early_late_spacing_chips)
        } else {
            dll_envelope_chips(early, late, self.early_late_spacing_chips)
        };
        self.code_rate = aided_code_rate(
            self.signal.chip_rate_hz(),
            self.doppler_hz,
            self.signal.carrier_hz(),
        ) + dll_rate_correction(self.dll_bandwidth_hz, code_error);
        // After this integration's discriminator used the spacing it was correlated with.
        self.narrow_dll();

        // Lock detectors (on the tracked component).
        let cn0 = self.cn0.cn0_dbhz().or(self.last_cn0_dbhz);
        self.last_cn0_dbhz = cn0;
        // Noise pulls the `cos 2 phi` estimate down to `SNR / (1 + SNR)` of a prompt in
        // perfect lock; undo that with the C/N0 estimate so one threshold serves every
        // C/N0 and integration time.
        let raw = self.lock_indicator.update(prompt, t);
        let indicator = match cn0.map(|c| 10f64.powf(c / 10.0) * t) {
            Some(snr) if snr.is_finite() && snr > 0.0 => raw * (1.0 + 1.0 / snr),
            _ => raw,
        };
        let locked = indicator >= self.config.pll_lock_threshold
            && cn0.is_none_or(|c| c >= self.config.cn0_lock_threshold_dbhz);
        if self.locked && !locked {
            self.slip_pending = true;
        }
        self.locked = locked;
        // Pull-in (the FLL-assist time) does not count towards loss of lock.
        self.ever_locked |= locked;
        let judged = self.ever_locked || self.time_s > self.config.fll_assist_s;
        self.lost = diverged || (judged && self.loss_timer.update(locked, t));
        let cycle_slip = std::mem::take(&mut self.slip_pending);
        self.lock_time_s = if locked && !cycle_slip {
            self.lock_time_s + t
        } else {
            0.0
        };

        TrackingRecord {
            sample_index: start.sample_index,
            code_phase_chips: start.code_phase_chips,
            integration_periods: periods,
            integration_s: t,
            carrier_phase_cycles: start.carrier_phase_cycles,
            doppler_hz: start.doppler_hz,
            doppler_rate_hzps: self.carrier.rate_hzps(),
            code_rate_chips_per_s: start.code_rate,
            early,
            prompt,
            late,
            phase_error_cycles: phase_error,
            code_error_chips: code_error,
            cn0_dbhz: cn0.map(|c| {
                if self.signal == Signal::BdsB1C {
                    c + B1C_PILOT_BOC11_SHARE_DB
                } else if self.signal.replica_boc11() {
                    c + PILOT_SHARE_DB + BOC61_SHARE_DB
                } else if self.signal.has_pilot() {
                    c + PILOT_SHARE_DB
                } else {
                    c
                }
            }),
            pll_lock_indicator: indicator,
            locked,
            bit_synced: self.sync.edge_phase().is_some(),
            cycle_slip,
            loss_of_lock: self.lost,
            lock_time_s: self.lock_time_s,
            bit,
        }
    }
}

/// The correlator of `signal` with `codes`: early, prompt and late of its code, or, for a
/// signal with a pilot, of the pilot code with the data code's prompt beside them
/// (BOC(1,1) replicas for Galileo E1).
fn correlator(
    signal: Signal,
    codes: &SignalCodes,
    spacing_chips: f64,
) -> Result<Correlator, TrackingError> {
    match &codes.pilot {
        Some(pilot) if signal.replica_boc11() => {
            Correlator::pilot_and_data_boc11(&pilot.primary, &codes.data, spacing_chips)
        }
        Some(pilot) => Correlator::pilot_and_data(&pilot.primary, &codes.data, spacing_chips),
        None => Correlator::new(
            &codes.data,
            TapSet::Three {
                early_late_spacing_chips: spacing_chips,
            },
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::super::discriminators::{FllDiscriminator, PllDiscriminator};
    use super::super::error_budget::LoopOrder;
    use super::*;

    fn handover() -> Handover {
        Handover {
            signal: Signal::GpsL1Ca,
            prn: 3,
            sample_index: 0,
            code_phase_samples: 100.0,
            doppler_hz: 1000.0,
            doppler_rate_hzps: 0.0,
        }
    }

    const FRONT_END: FrontEnd = FrontEnd {
        sample_rate_hz: 4.092e6,
        if_hz: 0.0,
    };

    #[test]
    fn config_reads_from_json_with_defaults() {
        let config: TrackingConfig = serde_json::from_str(
            r#"{"pll_order": "second", "pll_bandwidth_hz": 10.0,
                "pll_discriminator": "four_quadrant", "fll_discriminator": "atan2",
                "bit_sync": {"nh_bits": 3}}"#,
        )
        .expect("valid JSON config");
        assert_eq!(config.pll_order, LoopOrder::Second);
        assert_eq!(config.pll_discriminator, PllDiscriminator::FourQuadrant);
        assert_eq!(config.fll_discriminator, FllDiscriminator::Atan2);
        assert_eq!(config.bit_sync.nh_bits, 3);
        assert_eq!(config.bit_sync.min_transitions, 8);
        assert_eq!(
            config.dll_bandwidth_hz,
            TrackingConfig::default().dll_bandwidth_hz
        );
        assert!(serde_json::from_str::<TrackingConfig>(r#"{"pll_bw": 1.0}"#).is_err());
    }

    #[test]
    fn bad_settings_are_rejected_with_their_name() {
        let bad = [
            TrackingConfig {
                pll_bandwidth_hz: 0.0,
                ..TrackingConfig::default()
            },
            TrackingConfig {
                coherent_ms: 21,
                ..TrackingConfig::default()
            },
            TrackingConfig {
                early_late_spacing_chips: 2.5,
                ..TrackingConfig::default()
            },
            TrackingConfig {
                pll_narrow_bandwidth_hz: Some(f64::NAN),
                ..TrackingConfig::default()
            },
            TrackingConfig {
                fll_bandwidth_hz: -1.0,
                ..TrackingConfig::default()
            },
            // Issue #11: a 1 MHz PLL grew a tracking buffer without bound.
            TrackingConfig {
                pll_bandwidth_hz: 1e6,
                ..TrackingConfig::default()
            },
            TrackingConfig {
                dll_narrow_bandwidth_hz: Some(50.0),
                ..TrackingConfig::default()
            },
        ];
        for config in bad {
            let err = ChannelTracker::new(handover(), FRONT_END, config).map(|_| ());
            assert!(
                matches!(err, Err(TrackingError::InvalidConfig(_))),
                "{config:?}"
            );
        }
        let low_rate = FrontEnd {
            sample_rate_hz: 1e6,
            if_hz: 0.0,
        };
        assert!(ChannelTracker::new(handover(), low_rate, TrackingConfig::default()).is_err());
        let far = Handover {
            code_phase_samples: 5000.0,
            ..handover()
        };
        assert!(ChannelTracker::new(far, FRONT_END, TrackingConfig::default()).is_err());
        let no_code = Handover {
            prn: 0,
            ..handover()
        };
        assert_eq!(
            ChannelTracker::new(no_code, FRONT_END, TrackingConfig::default()).map(|_| ()),
            Err(TrackingError::UnknownPrn(
                skyforge_gnss::signal::UnknownPrn {
                    signal: Signal::GpsL1Ca,
                    prn: 0,
                    max: 63
                }
            ))
        );
    }

    #[test]
    fn the_first_period_starts_at_the_hand_over_code_epoch() {
        let ch = ChannelTracker::new(handover(), FRONT_END, TrackingConfig::default())
            .expect("valid channel");
        assert_eq!(ch.next_index, 100);
        assert!(ch.code_phase_chips.abs() < 1e-12);
        let dp = ch.code_rate / FRONT_END.sample_rate_hz;
        // 1023 chips at a code rate raised by the Doppler: just under 4092 samples.
        assert_eq!(ch.period_length(), (1023.0 / dp).ceil() as usize);
        assert_eq!(ch.data_modulation(), DataModulation::GpsLnav);
    }
}
