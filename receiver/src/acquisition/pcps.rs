//! Parallel code-phase search (PCPS): for every Doppler bin, the circular correlation of
//! one code period of carrier-wiped samples with the code replica, computed as
//! `IFFT(FFT(x) . conj(FFT(c)))` (the parallel code phase search of Borre et al., *A
//! Software-Defined GPS and Galileo Receiver*, 2007, ch. 6); `K` consecutive periods
//! summed coherently, `N` such sums added in power, and a CFAR decision
//! ([`super::cfar`]) against the noise power estimated from the correlation surface
//! itself.
//!
//! The FFT length: a code period (1 ms at a multiple of 1.023 Mchip/s) holds samples in
//! multiples of 1023 = 3 x 11 x 31, a length whose transforms cost four times those of a
//! length with only the factors 2, 3 and 5 (`cargo bench -p skyforge-receiver --bench
//! acquisition -- fft_forward`). Where the period is such a length the circular
//! correlation is an FFT of it; otherwise the same correlation is computed exactly as a
//! linear one in the next 5-smooth length of at least twice the period: the samples
//! zero-padded, the replica periodically extended to negative lags at the buffer's end
//! ([`fft_length`]).
//!
//! Conventions: samples are complex baseband (or complex IF) `x(t) = c(t - tau) exp(j 2 pi
//! (f_carrier + f_d) t) + noise`, `t = 0` at the first sample given. The search removes
//! `carrier_offset_hz` (the IF) and reports `f_d`. The code phase is the sample offset,
//! in `[0, period)`, at which a code period (chip 0) starts in the buffer. Code Doppler
//! is ignored within a correlation (1 ms).

use super::AcquisitionError;
use super::cfar;
use super::replica::{mean_edge_delay_samples, sample_code, wipe_carrier};
use crate::replica::{replica_chips, subchips};
use num_complex::Complex32;
use rayon::prelude::*;
use rustfft::{Fft, FftPlanner};
use skyforge_gnss::signal::Signal;
use std::sync::Arc;

/// How correlations handle sign changes between code periods (GPS data bits every
/// 20 ms; BeiDou D1 NH chips every 1 ms, D2 bits every 2 ms).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BitTransition {
    /// Circular correlation of one period of samples: cheapest; a sign change inside
    /// the block splits the peak between Doppler bins (up to total loss at mid-block).
    #[default]
    Ignore,
    /// Each correlation takes two periods of samples against one replica period
    /// zero-padded to two (an FFT twice as long and one more period of samples): every
    /// lag then integrates exactly one code period that starts at a code boundary, so
    /// sign changes, which happen only at code boundaries, never fall inside it.
    AlignedWindows,
}

/// The Doppler interval searched: `centre_hz +/- half_width_hz` (assisted search is a
/// different centre, e.g. predicted from an almanac).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DopplerWindow {
    pub centre_hz: f64,
    pub half_width_hz: f64,
}

/// Search parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PcpsConfig {
    pub signal: Signal,
    /// Complex sample rate (Hz); any rate at or above the chip rate.
    pub sample_rate_hz: f64,
    /// Carrier frequency removed before the Doppler search (the IF of complex-IF input,
    /// 0 for baseband) (Hz).
    pub carrier_offset_hz: f64,
    /// Code periods (1 ms each) summed coherently, `K >= 1`.
    pub coherent_periods: usize,
    /// Coherent sums added non-coherently (in power), `N >= 1`.
    pub noncoherent: usize,
    /// Doppler interval searched.
    pub window: DopplerWindow,
    /// Doppler bin spacing (Hz); `None` = `2 / (3 T_coh)`.
    pub doppler_step_hz: Option<f64>,
    /// False-alarm probability over the whole search (all cells of one PRN).
    pub pfa: f64,
    pub bit_transition: BitTransition,
}

impl PcpsConfig {
    /// Cold start: 1 ms coherent, no non-coherent sum, +/-10 kHz, default step,
    /// `P_fa = 1e-3`, baseband input.
    pub fn cold(signal: Signal, sample_rate_hz: f64) -> Self {
        Self {
            signal,
            sample_rate_hz,
            carrier_offset_hz: 0.0,
            coherent_periods: 1,
            noncoherent: 1,
            window: DopplerWindow {
                centre_hz: 0.0,
                half_width_hz: 10e3,
            },
            doppler_step_hz: None,
            pfa: 1e-3,
            bit_transition: BitTransition::Ignore,
        }
    }

    /// Coherent integration time `T_coh = K T_code` (s).
    pub fn coherent_s(&self) -> f64 {
        self.coherent_periods as f64 * self.signal.code_period_s()
    }

    /// Doppler bin spacing (Hz): the configured one or `2 / (3 T_coh)`.
    pub fn doppler_step(&self) -> f64 {
        self.doppler_step_hz
            .unwrap_or(2.0 / (3.0 * self.coherent_s()))
    }
}

/// The conjugated spectra of one PRN's replicas, computed once and reused by searches:
/// the code, and for a signal with a pilot the pilot's code beside the data code (the
/// search adds both components' powers: twice the signal power for twice the noise).
#[derive(Debug, Clone)]
pub struct PreparedCode {
    pub prn: u8,
    spectra_conj: Vec<Vec<Complex32>>,
}

/// The search statistic over (Doppler bin, code lag): `sum_N |sum_K R|^2` (raw, not yet
/// normalised by the noise power).
#[derive(Debug, Clone)]
pub struct Surface {
    /// Centre of every Doppler bin (Hz), ascending.
    pub doppler_hz: Vec<f64>,
    /// Code lags per bin (samples per code period).
    pub lags: usize,
    /// Bin-major: `power[j * lags + lag]`.
    pub power: Vec<f32>,
    /// Non-coherent sums in every cell.
    pub noncoherent: usize,
}

impl Surface {
    /// (bin, lag, value) of the largest cell.
    pub fn peak(&self) -> (usize, usize, f32) {
        let (idx, val) =
            self.power
                .iter()
                .copied()
                .enumerate()
                .fold((0, f32::NEG_INFINITY), |best, (i, v)| {
                    if v > best.1 { (i, v) } else { best }
                });
        let lags = self.lags.max(1);
        (idx / lags, idx % lags, val)
    }

    /// Noise power of one coherent correlation, `E|R|^2` without signal: the mean cell
    /// value divided by the non-coherent count, over every bin but excluding the lags
    /// within `guard_lags` (circularly) of `peak_lag`, where the signal's correlation
    /// main lobe lies in all Doppler bins.
    pub fn noise_power(&self, peak_lag: usize, guard_lags: usize) -> f64 {
        let lags = self.lags.max(1);
        let near = |lag: usize| {
            let d = lag.abs_diff(peak_lag);
            d.min(lags - d.min(lags)) <= guard_lags
        };
        let (mut sum, mut count) = (0.0_f64, 0usize);
        for row in self.power.chunks(lags) {
            for (lag, &v) in row.iter().enumerate() {
                if !near(lag) {
                    sum += f64::from(v);
                    count += 1;
                }
            }
        }
        if count == 0 {
            sum = self.power.iter().map(|&v| f64::from(v)).sum();
            count = self.power.len().max(1);
        }
        sum / count as f64 / self.noncoherent.max(1) as f64
    }
}

/// The outcome of one PRN's search.
#[derive(Debug, Clone, PartialEq)]
pub struct Acquisition {
    pub signal: Signal,
    pub prn: u8,
    /// Peak statistic above the CFAR threshold.
    pub detected: bool,
    /// Code phase (samples, in `[0, period)`): the peak lag refined by a triangle fit,
    /// less the apex offset of the sampled replica (see [`Pcps::apex_offset_samples`]).
    pub code_phase_samples: f64,
    /// The same in chips.
    pub code_phase_chips: f64,
    /// Lag of the largest cell (samples).
    pub peak_lag: usize,
    /// Doppler (Hz) refined by parabolic interpolation of the correlation amplitude
    /// between the peak bin and its neighbours.
    pub doppler_hz: f64,
    /// Centre of the peak bin (Hz).
    pub doppler_bin_hz: f64,
    /// Peak statistic normalised by the noise power: `Gamma(N, 1)` distributed without
    /// signal.
    pub peak_metric: f64,
    /// CFAR threshold on `peak_metric`.
    pub threshold: f64,
    /// Estimated noise power of one coherent correlation (surface units).
    pub noise_power: f64,
    /// Cells searched (bins x lags).
    pub cells: usize,
}

/// A planned search: FFTs, bins and sample counts for one configuration.
pub struct Pcps {
    config: PcpsConfig,
    period_samples: usize,
    /// Samples one correlation reads: a period, two with aligned windows.
    window_samples: usize,
    fft_len: usize,
    forward: Arc<dyn Fft<f32>>,
    inverse: Arc<dyn Fft<f32>>,
    doppler_hz: Vec<f64>,
    apex_offset_samples: f64,
}

impl std::fmt::Debug for Pcps {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pcps")
            .field("config", &self.config)
            .field("period_samples", &self.period_samples)
            .field("fft_len", &self.fft_len)
            .field("bins", &self.doppler_hz.len())
            .finish()
    }
}

fn bad(name: &'static str, value: f64, allowed: &'static str) -> AcquisitionError {
    AcquisitionError::BadParameter {
        name,
        value,
        allowed,
    }
}

impl Pcps {
    /// Check `config` and plan its FFTs and Doppler bins.
    pub fn new(config: PcpsConfig) -> Result<Self, AcquisitionError> {
        if !config.signal.is_received() {
            return Err(AcquisitionError::NotTracked(config.signal));
        }
        let fs = config.sample_rate_hz;
        if !(fs.is_finite() && fs >= config.signal.chip_rate_hz()) {
            return Err(bad(
                "sample rate (Hz)",
                fs,
                "finite and at least the chip rate",
            ));
        }
        // BOC(1,1)'s main peak is 2/3 chip wide: at two samples per half-chip the nearest
        // lag is within 1/8 chip of its apex (at most 4.1 dB down, 1 - 3/8 in amplitude).
        if config.signal.replica_boc11() && fs < 4.0 * config.signal.chip_rate_hz() {
            return Err(bad(
                "sample rate (Hz)",
                fs,
                "at least two samples per BOC(1,1) half-chip (4.092 Msps)",
            ));
        }
        if config.coherent_periods == 0 {
            return Err(bad("coherent periods", 0.0, ">= 1"));
        }
        if config.noncoherent == 0 {
            return Err(bad("non-coherent sums", 0.0, ">= 1"));
        }
        let step = config.doppler_step();
        if !(step.is_finite() && step > 0.0) {
            return Err(bad("Doppler step (Hz)", step, "finite and > 0"));
        }
        if !(config.pfa > 0.0 && config.pfa < 1.0) {
            return Err(bad("false-alarm probability", config.pfa, "0 < p < 1"));
        }
        if !config.carrier_offset_hz.is_finite() {
            return Err(bad(
                "carrier offset (Hz)",
                config.carrier_offset_hz,
                "finite",
            ));
        }
        let doppler_hz = doppler_bins(config.window, step)?;
        let period_samples = (fs * config.signal.code_period_s()).round() as usize;
        let window_samples = match config.bit_transition {
            BitTransition::Ignore => period_samples,
            BitTransition::AlignedWindows => 2 * period_samples,
        };
        let fft_len = fft_length(period_samples, config.bit_transition);
        let mut planner = FftPlanner::new();
        Ok(Self {
            config,
            period_samples,
            window_samples,
            fft_len,
            forward: planner.plan_fft_forward(fft_len),
            inverse: planner.plan_fft_inverse(fft_len),
            doppler_hz,
            apex_offset_samples: 0.5
                - mean_edge_delay_samples(replica_rate_hz(config.signal), fs, period_samples),
        })
    }

    /// The configuration searched.
    pub fn config(&self) -> &PcpsConfig {
        &self.config
    }

    /// Samples per code period (code lags searched).
    pub fn period_samples(&self) -> usize {
        self.period_samples
    }

    /// How far (samples) the correlation apex lies after the true code phase, removed
    /// from the reported phase: `0.5 - d`, `d` the replica's mean chip-edge delay
    /// ([`mean_edge_delay_samples`]). A band-limited (zero-phase) or integrate-and-dump
    /// signal is best matched by a replica that changes chip half a sample after the true
    /// edge; the replica changes `d` after it (0 at an integer number of samples per chip,
    /// about 0.5 otherwise), so the apex sits `0.5 - d` late. For point-sampled,
    /// unfiltered input at an integer rate the phase is only known to one sample and the
    /// reported value is the middle of that interval.
    pub fn apex_offset_samples(&self) -> f64 {
        self.apex_offset_samples
    }

    /// Doppler bin centres (Hz).
    pub fn doppler_bins_hz(&self) -> &[f64] {
        &self.doppler_hz
    }

    /// Samples one search reads from the start of the buffer:
    /// `K N` periods, plus one with [`BitTransition::AlignedWindows`].
    pub fn samples_needed(&self) -> usize {
        let blocks = self.config.coherent_periods * self.config.noncoherent;
        (blocks - 1) * self.period_samples + self.window_samples
    }

    /// Length of the FFTs a correlation runs ([`fft_length`]).
    pub fn fft_len(&self) -> usize {
        self.fft_len
    }

    /// The replica spectrum of `prn`: one code period sampled at the sample rate,
    /// zero-padded to the FFT length, transformed, conjugated and scaled by `1/len`.
    pub fn prepare(&self, prn: u8) -> Result<PreparedCode, AcquisitionError> {
        let signal = self.config.signal;
        let mut codes = vec![signal.code(prn)?];
        if signal.has_pilot() {
            codes.push(signal.pilot(prn)?.primary);
        }
        Ok(PreparedCode {
            prn,
            spectra_conj: codes
                .iter()
                .map(|c| self.spectrum_conj(&replica_chips(signal, c)))
                .collect(),
        })
    }

    /// One code period of replica `chips` ([`replica_chips`]) sampled, zero-padded,
    /// transformed, conjugated, scaled. A circular correlation in a buffer longer than the
    /// period also needs the code at negative lags: chips `1..P` again at its end.
    fn spectrum_conj(&self, chips: &[i8]) -> Vec<Complex32> {
        let code = sample_code(
            chips,
            replica_rate_hz(self.config.signal),
            self.config.sample_rate_hz,
            self.period_samples,
        );
        let mut buf = vec![Complex32::default(); self.fft_len];
        for (b, &c) in buf.iter_mut().zip(&code) {
            *b = Complex32::new(c, 0.0);
        }
        let p = self.period_samples;
        if self.config.bit_transition == BitTransition::Ignore && self.fft_len > p {
            let tail = self.fft_len - p;
            for (b, &c) in buf[tail + 1..].iter_mut().zip(&code[1..]) {
                *b = Complex32::new(c, 0.0);
            }
        }
        self.forward.process(&mut buf);
        let scale = 1.0 / self.fft_len as f32;
        for b in &mut buf {
            *b = b.conj() * scale;
        }
        buf
    }

    /// The search surface of `code` over the configured window.
    pub fn surface(
        &self,
        samples: &[Complex32],
        code: &PreparedCode,
    ) -> Result<Surface, AcquisitionError> {
        self.surface_in(samples, code, &self.doppler_hz)
    }

    fn surface_in(
        &self,
        samples: &[Complex32],
        code: &PreparedCode,
        doppler_hz: &[f64],
    ) -> Result<Surface, AcquisitionError> {
        let needed = self.samples_needed();
        if samples.len() < needed {
            return Err(AcquisitionError::TooFewSamples {
                needed,
                got: samples.len(),
            });
        }
        let lags = self.period_samples;
        let (k, n) = (self.config.coherent_periods, self.config.noncoherent);
        let components = code.spectra_conj.len();
        let fs = self.config.sample_rate_hz;
        // Samples one correlation wipes (the FFT may be one shorter than aligned windows).
        let read = self.window_samples.min(self.fft_len);
        let mut power = vec![0f32; doppler_hz.len() * lags];
        let scratch_len = self
            .forward
            .get_inplace_scratch_len()
            .max(self.inverse.get_inplace_scratch_len());
        power
            .par_chunks_mut(lags)
            .zip(doppler_hz.par_iter())
            .for_each_init(
                || {
                    (
                        vec![Complex32::default(); self.fft_len],
                        vec![Complex32::default(); self.fft_len],
                        vec![Complex32::default(); scratch_len],
                        vec![Complex32::default(); lags * components],
                    )
                },
                |(wiped, buf, scratch, coh), (row, &doppler)| {
                    let freq = self.config.carrier_offset_hz + doppler;
                    for q in 0..n {
                        coh.fill(Complex32::default());
                        for m in 0..k {
                            let start = (q * k + m) * lags;
                            let block = &samples[start..start + read];
                            wipe_carrier(block, start as u64, fs, freq, &mut wiped[..read]);
                            wiped[read..].fill(Complex32::default());
                            self.forward.process_with_scratch(wiped, scratch);
                            for (spectrum, coh) in
                                code.spectra_conj.iter().zip(coh.chunks_mut(lags))
                            {
                                for ((x, w), c) in buf.iter_mut().zip(wiped.iter()).zip(spectrum) {
                                    *x = w * c;
                                }
                                self.inverse.process_with_scratch(buf, scratch);
                                for (a, b) in coh.iter_mut().zip(buf.iter()) {
                                    *a += b;
                                }
                            }
                        }
                        for coh in coh.chunks(lags) {
                            for (r, c) in row.iter_mut().zip(coh.iter()) {
                                *r += c.norm_sqr();
                            }
                        }
                    }
                },
            );
        Ok(Surface {
            doppler_hz: doppler_hz.to_vec(),
            lags,
            power,
            noncoherent: n * components,
        })
    }

    /// Search `code` over the configured Doppler window.
    pub fn search(
        &self,
        samples: &[Complex32],
        code: &PreparedCode,
    ) -> Result<Acquisition, AcquisitionError> {
        let surface = self.surface(samples, code)?;
        self.decide(&surface, code.prn)
    }

    /// Search `code` over another Doppler window (assisted search) with this plan's
    /// step and integration.
    pub fn search_window(
        &self,
        samples: &[Complex32],
        code: &PreparedCode,
        window: DopplerWindow,
    ) -> Result<Acquisition, AcquisitionError> {
        let bins = doppler_bins(window, self.config.doppler_step())?;
        let surface = self.surface_in(samples, code, &bins)?;
        self.decide(&surface, code.prn)
    }

    /// Prepare and search each PRN in turn (each search parallel over Doppler bins).
    pub fn search_prns(
        &self,
        samples: &[Complex32],
        prns: &[u8],
    ) -> Result<Vec<Acquisition>, AcquisitionError> {
        prns.iter()
            .map(|&prn| self.search(samples, &self.prepare(prn)?))
            .collect()
    }

    /// Peak, refinement and CFAR decision on a surface.
    pub fn decide(&self, surface: &Surface, prn: u8) -> Result<Acquisition, AcquisitionError> {
        let signal = self.config.signal;
        let fs = self.config.sample_rate_hz;
        let samples_per_chip = fs / signal.chip_rate_hz();
        let guard = (1.5 * samples_per_chip).ceil() as usize + 1;
        let (bin, lag, peak) = surface.peak();
        let lag = if signal.replica_boc11() {
            main_peak_lag(surface, bin, lag, samples_per_chip / 2.0)
        } else {
            lag
        };
        let noise = surface.noise_power(lag, guard);
        let cells = surface.power.len();
        let threshold = cfar::search_threshold(surface.noncoherent, cells, self.config.pfa)?;
        let peak_metric = if noise > 0.0 {
            f64::from(peak) / noise
        } else {
            0.0
        };
        let lags = surface.lags;
        let amp = |j: usize, l: usize| f64::from(surface.power[j * lags + l]).max(0.0).sqrt();
        let step = if surface.doppler_hz.len() > 1 {
            surface.doppler_hz[1] - surface.doppler_hz[0]
        } else {
            0.0
        };
        let doppler_offset = if bin > 0 && bin + 1 < surface.doppler_hz.len() {
            parabola_vertex(amp(bin - 1, lag), amp(bin, lag), amp(bin + 1, lag)) * step
        } else {
            0.0
        };
        let prev = (lag + lags - 1) % lags;
        let next = (lag + 1) % lags;
        let lag_offset = triangle_vertex(amp(bin, prev), amp(bin, lag), amp(bin, next));
        let code_phase_samples =
            (lag as f64 + lag_offset - self.apex_offset_samples).rem_euclid(lags as f64);
        Ok(Acquisition {
            signal,
            prn,
            detected: peak_metric > threshold,
            code_phase_samples,
            code_phase_chips: code_phase_samples / samples_per_chip,
            peak_lag: lag,
            doppler_hz: surface.doppler_hz[bin] + doppler_offset,
            doppler_bin_hz: surface.doppler_hz[bin],
            peak_metric,
            threshold,
            noise_power: noise,
            cells,
        })
    }
}

/// The FFT length of a correlation of one code period of `period` samples: the period
/// itself when a circular correlation ([`BitTransition::Ignore`]) fits a 5-smooth
/// length, else the least 5-smooth length of at least `2 period - 1`, the least in which
/// the linear correlation of a period (of samples, or of replica with aligned windows)
/// at lags `0..period` does not wrap onto itself.
pub fn fft_length(period: usize, bits: BitTransition) -> usize {
    if bits == BitTransition::Ignore && is_5_smooth(period) {
        return period;
    }
    let mut n = 2 * period.max(1) - 1;
    while !is_5_smooth(n) {
        n += 1;
    }
    n
}

/// Whether `n`'s prime factors are all 2, 3 or 5.
fn is_5_smooth(mut n: usize) -> bool {
    if n == 0 {
        return false;
    }
    for p in [2, 3, 5] {
        while n.is_multiple_of(p) {
            n /= p;
        }
    }
    n == 1
}

/// Replica chips per second: the chip rate, twice it for BOC(1,1) half-chips.
fn replica_rate_hz(signal: Signal) -> f64 {
    signal.chip_rate_hz() * subchips(signal) as f64
}

/// BOC(1,1) side-peak check: the correlation has side peaks of half the main peak's
/// amplitude half a chip either side of it, so noise can lift one above the main peak.
/// Of the peak `lag` and the lags `half_chip` samples either side, the main peak is the
/// one that best matches the peak's magnitudes `1/2, 1, 1/2` at half-chip steps: the
/// largest `|R(c)| + (|R(c - h)| + |R(c + h)|) / 2` (ideally 3/2 at the main peak, 1 at
/// a side peak; a side peak wins only above 3/2 of the main peak with the other side
/// peak at half of it).
fn main_peak_lag(surface: &Surface, bin: usize, lag: usize, half_chip: f64) -> usize {
    let lags = surface.lags;
    let h = (half_chip.round() as usize).clamp(1, lags / 4);
    let amp = |l: usize| {
        f64::from(surface.power[bin * lags + l % lags])
            .max(0.0)
            .sqrt()
    };
    let score = |c: usize| amp(c) + 0.5 * (amp(c + lags - h) + amp(c + h));
    [lag, (lag + lags - h) % lags, (lag + h) % lags]
        .into_iter()
        .map(|c| (c, score(c)))
        .fold((lag, f64::NEG_INFINITY), |best, (c, s)| {
            if s > best.1 { (c, s) } else { best }
        })
        .0
}

/// Bin centres `centre + j step`, `|j| <= ceil(half_width / step)`.
fn doppler_bins(w: DopplerWindow, step: f64) -> Result<Vec<f64>, AcquisitionError> {
    if !(w.half_width_hz.is_finite() && w.half_width_hz >= 0.0) {
        return Err(bad(
            "Doppler half-width (Hz)",
            w.half_width_hz,
            "finite and >= 0",
        ));
    }
    if !w.centre_hz.is_finite() {
        return Err(bad("Doppler centre (Hz)", w.centre_hz, "finite"));
    }
    let half_bins = (w.half_width_hz / step - 1e-9).ceil().max(0.0);
    if half_bins > 1e6 {
        return Err(bad(
            "Doppler bins either side",
            half_bins,
            "at most 1e6 (widen the step)",
        ));
    }
    let half_bins = half_bins as i64;
    Ok((-half_bins..=half_bins)
        .map(|j| w.centre_hz + j as f64 * step)
        .collect())
}

/// Offset (in bin spacings, within +/-0.5) of the vertex of the parabola through
/// `(-1, a)`, `(0, b)`, `(1, c)`, `b` the largest.
fn parabola_vertex(a: f64, b: f64, c: f64) -> f64 {
    let den = a - 2.0 * b + c;
    if den >= 0.0 {
        return 0.0;
    }
    (0.5 * (a - c) / den).clamp(-0.5, 0.5)
}

/// Offset (in lags, within +/-0.5) of the apex of a symmetric triangle through
/// `(-1, a)`, `(0, b)`, `(1, c)`, `b` the largest: the correlation main lobe of a
/// rectangular-chip code is a triangle, `R(u) = A - s |u - d|`.
fn triangle_vertex(a: f64, b: f64, c: f64) -> f64 {
    let d = if c >= a {
        if b - a <= 0.0 {
            return 0.0;
        }
        (c - a) / (2.0 * (b - a))
    } else {
        if b - c <= 0.0 {
            return 0.0;
        }
        (c - a) / (2.0 * (b - c))
    };
    d.clamp(-0.5, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertex_fits_recover_exact_shapes() {
        // Parabola y = 3 - (x - 0.3)^2.
        let p = |x: f64| 3.0 - (x - 0.3) * (x - 0.3);
        assert!((parabola_vertex(p(-1.0), p(0.0), p(1.0)) - 0.3).abs() < 1e-12);
        // Triangle y = 5 - 2 |x - d|.
        for d in [-0.4, -0.1, 0.0, 0.25, 0.5] {
            let t = |x: f64| 5.0 - 2.0 * (x - d).abs();
            assert!((triangle_vertex(t(-1.0), t(0.0), t(1.0)) - d).abs() < 1e-12);
        }
    }

    /// Galileo E1 (BOC(1,1)): a side peak half a chip from the main peak, lifted above it
    /// by noise, is not taken; the main peak's lag is. Below two samples per half-chip the
    /// search is refused.
    #[test]
    fn a_boc11_side_peak_above_the_main_peak_is_not_taken() {
        // 8 samples per chip: half a chip is 4 lags.
        let fs = 8.184e6;
        let pcps = Pcps::new(PcpsConfig::cold(Signal::GalE1, fs)).unwrap();
        let lags = pcps.period_samples();
        assert_eq!(lags, 32_736);
        let boc = |x: f64| {
            let x = x.abs();
            if x <= 0.5 {
                1.0 - 3.0 * x
            } else {
                (x - 1.0).min(0.0)
            }
        };
        let main = 1000;
        for (side, lifted) in [(4usize, 1.05), (lags - 4, 1.02)] {
            let power: Vec<f32> = (0..lags)
                .map(|l| {
                    let d = (l as f64 - main as f64) / 8.0;
                    let a = if l == (main + side) % lags {
                        lifted
                    } else {
                        boc(d)
                    };
                    (a * a + 1e-4) as f32
                })
                .collect();
            let surface = Surface {
                doppler_hz: vec![0.0],
                lags,
                power,
                noncoherent: 2,
            };
            let acq = pcps.decide(&surface, 11).unwrap();
            assert_eq!(acq.peak_lag, main, "side peak at {side}");
            assert!((acq.code_phase_samples - main as f64).abs() < 1.0);
        }
        assert!(Pcps::new(PcpsConfig::cold(Signal::GalE1, 4.0e6)).is_err());
    }

    #[test]
    fn fft_lengths_avoid_the_factor_31() {
        use BitTransition::{AlignedWindows, Ignore};
        assert_eq!(fft_length(4096, Ignore), 4096);
        assert_eq!(fft_length(4092, Ignore), 8192);
        assert_eq!(fft_length(20_460, Ignore), 40_960);
        assert_eq!(fft_length(20_460, AlignedWindows), 40_960);
        assert_eq!(fft_length(4096, AlignedWindows), 8192);
        for p in [1usize, 7, 1023, 2600, 16_368, 20_460] {
            for bits in [Ignore, AlignedWindows] {
                let n = fft_length(p, bits);
                assert!(is_5_smooth(n), "{p}: {n}");
                assert!(n == p || n >= 2 * p - 1, "{p}: {n}");
                assert!(n < 3 * p.max(2), "{p}: {n}");
            }
        }
    }

    /// Oracle: the search surface at one Doppler bin (0 Hz, nothing to wipe) is the
    /// correlation summed sample by sample, circular over one period
    /// ([`BitTransition::Ignore`]) or one period of replica sliding over two of samples
    /// ([`BitTransition::AlignedWindows`]), whether the FFT is the period's length or the
    /// longer 5-smooth one.
    #[test]
    fn surfaces_match_the_correlation_summed_sample_by_sample() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let cases = [
            (Signal::GpsL1Ca, 1.023e6, BitTransition::Ignore, 2048),
            (Signal::GpsL1Ca, 1.024e6, BitTransition::Ignore, 1024),
            (Signal::BdsB1I, 2.046e6, BitTransition::AlignedWindows, 4096),
            (
                Signal::GpsL1Ca,
                1.024e6,
                BitTransition::AlignedWindows,
                2048,
            ),
        ];
        for (signal, fs, bits, fft_len) in cases {
            let mut config = PcpsConfig::cold(signal, fs);
            config.window.half_width_hz = 0.0;
            config.bit_transition = bits;
            let pcps = Pcps::new(config).unwrap();
            assert_eq!(pcps.fft_len(), fft_len);
            let p = pcps.period_samples();
            let x: Vec<Complex32> = (0..pcps.samples_needed())
                .map(|_| Complex32::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)))
                .collect();
            let code = pcps.prepare(9).unwrap();
            let surface = pcps.surface(&x, &code).unwrap();
            let chips = replica_chips(signal, &signal.code(9).unwrap());
            let c = sample_code(&chips, replica_rate_hz(signal), fs, p);
            let mut largest = 0.0_f64;
            let direct: Vec<f64> = (0..p)
                .map(|lag| {
                    let r: num_complex::Complex64 = (0..p)
                        .map(|n| {
                            let xi = match bits {
                                BitTransition::Ignore => x[(n + lag) % p],
                                BitTransition::AlignedWindows => x[n + lag],
                            };
                            num_complex::Complex64::new(xi.re.into(), xi.im.into())
                                * f64::from(c[n])
                        })
                        .sum();
                    largest = largest.max(r.norm_sqr());
                    r.norm_sqr()
                })
                .collect();
            for (lag, (d, s)) in direct.iter().zip(&surface.power).enumerate() {
                let err = (d - f64::from(*s)).abs();
                assert!(
                    err < 1e-4 * largest,
                    "{signal:?} {bits:?} lag {lag}: {d} vs {s}"
                );
            }
        }
    }

    #[test]
    fn default_step_and_bins_cover_the_window() {
        let pcps = Pcps::new(PcpsConfig::cold(Signal::GpsL1Ca, 4.092e6)).unwrap();
        assert!((pcps.config().doppler_step() - 2000.0 / 3.0).abs() < 1e-9);
        let bins = pcps.doppler_bins_hz();
        assert_eq!(bins.len(), 31);
        assert!(bins[0] <= -10e3 + 1e-6 && *bins.last().unwrap() >= 10e3 - 1e-6);
        assert_eq!(pcps.period_samples(), 4092);
        assert_eq!(pcps.samples_needed(), 4092);
    }

    #[test]
    fn bad_configurations_are_refused() {
        let mut c = PcpsConfig::cold(Signal::BdsB1I, 2.0e6);
        assert!(matches!(
            Pcps::new(c),
            Err(AcquisitionError::BadParameter { .. })
        ));
        c.sample_rate_hz = 4.092e6;
        c.noncoherent = 0;
        assert!(Pcps::new(c).is_err());
        c.noncoherent = 1;
        c.pfa = 1.0;
        assert!(Pcps::new(c).is_err());
        c.pfa = 1e-3;
        let pcps = Pcps::new(c).unwrap();
        let code = pcps.prepare(7).unwrap();
        let short = vec![Complex32::default(); 100];
        assert_eq!(
            pcps.search(&short, &code).unwrap_err(),
            AcquisitionError::TooFewSamples {
                needed: 4092,
                got: 100
            }
        );
    }
}
