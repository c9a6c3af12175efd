//! PMF-FFT acquisition of thesis section 3.3.1 with the fine Doppler estimator of
//! section 3.3.2: `P` partial matched filters of `L` chips each (`M = P L` chips, the
//! 1023-chip C/A code followed by one zero chip for `M = 1024`), their outputs
//! zero-padded to an `N = 2P` point FFT (thesis eq. 3.3-5/3.3-7), the coarse Doppler
//! `p / (2 M Tc)` of the largest bin `p`, and the fine offset `delta` from that bin and its
//! two neighbours (eq. 3.3-13), `fd = (p + delta) / (2 M Tc)` (eq. 3.3-14).
//!
//! The input is the code-wiped chip-rate sequence `x'[n]` of eq. 3.3-15 (the code phase
//! is known, e.g. from [`super::pcps`]); [`despread_to_chips`] makes it from samples at
//! any rate. The estimator's noise theory is in [`theory`].

pub mod theory;

use super::AcquisitionError;
use super::replica::wipe_carrier;
use num_complex::Complex32;
use rustfft::{Fft, FftPlanner};
use std::f64::consts::PI;
use std::sync::Arc;

/// Thesis eq. 3.3-13: the fractional bin offset `delta` of the spectral peak from the
/// energies `|Y[p-1]|^2`, `|Y[p]|^2`, `|Y[p+1]|^2`:
/// `delta = (pi^4 + 32)(E+ - E-) / (64 (E+ + E-) + 16 pi^2 E0)`.
pub fn fine_offset(e_minus: f64, e_peak: f64, e_plus: f64) -> f64 {
    let den = 64.0 * (e_plus + e_minus) + 16.0 * PI * PI * e_peak;
    if den > 0.0 {
        (PI.powi(4) + 32.0) * (e_plus - e_minus) / den
    } else {
        0.0
    }
}

/// One PMF-FFT Doppler estimate, in units of the chip period `Tc`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PmfEstimate {
    /// Peak bin `p`, signed: `[-P, P)` (bin `k >= P` is `k - 2P`).
    pub peak_bin: i64,
    /// Fine offset `delta` (eq. 3.3-13), in bins.
    pub delta: f64,
    /// `|Y[p]|^2`.
    pub peak_energy: f64,
    /// Coarse estimate `fd Tc = p / (2M)` (thesis section 3.3.1).
    pub coarse_fd_tc: f64,
    /// Fine estimate `fd Tc = (p + delta) / (2M)` (eq. 3.3-14).
    pub fine_fd_tc: f64,
}

impl PmfEstimate {
    /// Coarse Doppler (Hz) for chip rate `chip_rate_hz = 1/Tc`.
    pub fn coarse_doppler_hz(&self, chip_rate_hz: f64) -> f64 {
        self.coarse_fd_tc * chip_rate_hz
    }

    /// Fine Doppler (Hz) for chip rate `chip_rate_hz = 1/Tc`.
    pub fn fine_doppler_hz(&self, chip_rate_hz: f64) -> f64 {
        self.fine_fd_tc * chip_rate_hz
    }
}

/// Work buffers of one thread, so repeated estimates do not allocate.
#[derive(Debug, Clone)]
pub struct PmfScratch {
    y: Vec<Complex32>,
    fft: Vec<Complex32>,
}

/// A PMF-FFT of `M` chips in `P` filters of `L` chips, `N = 2P`.
pub struct PmfFft {
    m: usize,
    l: usize,
    p: usize,
    fft: Arc<dyn Fft<f32>>,
}

impl std::fmt::Debug for PmfFft {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PmfFft")
            .field("m", &self.m)
            .field("l", &self.l)
            .field("p", &self.p)
            .finish()
    }
}

impl PmfFft {
    /// `m_chips = M` chips in filters of `l_chips = L`; `L` must divide `M` with `P >= 2`.
    pub fn new(m_chips: usize, l_chips: usize) -> Result<Self, AcquisitionError> {
        if l_chips == 0 || !m_chips.is_multiple_of(l_chips) || m_chips / l_chips < 2 {
            return Err(AcquisitionError::BadParameter {
                name: "PMF length L (chips)",
                value: l_chips as f64,
                allowed: "a divisor of M with M / L >= 2",
            });
        }
        let p = m_chips / l_chips;
        Ok(Self {
            m: m_chips,
            l: l_chips,
            p,
            fft: FftPlanner::new().plan_fft_forward(2 * p),
        })
    }

    /// `M` (chips).
    pub fn m(&self) -> usize {
        self.m
    }

    /// `L` (chips per partial matched filter).
    pub fn l(&self) -> usize {
        self.l
    }

    /// `P = M / L` (filters).
    pub fn p(&self) -> usize {
        self.p
    }

    /// Buffers for the spectrum and estimate functions.
    pub fn scratch(&self) -> PmfScratch {
        PmfScratch {
            y: vec![Complex32::default(); 2 * self.p],
            fft: vec![Complex32::default(); self.fft.get_inplace_scratch_len()],
        }
    }

    /// The `P` partial matched filter outputs of eq. 3.3-16,
    /// `(1/P)(1/L) sum_{n=iL}^{(i+1)L-1} x[n]`, from exactly `M` chip-rate samples.
    pub fn filter_outputs(
        &self,
        chips: &[Complex32],
        out: &mut [Complex32],
    ) -> Result<(), AcquisitionError> {
        if chips.len() != self.m {
            return Err(AcquisitionError::TooFewSamples {
                needed: self.m,
                got: chips.len(),
            });
        }
        if out.len() != self.p {
            return Err(AcquisitionError::BadParameter {
                name: "filter output slots",
                value: out.len() as f64,
                allowed: "exactly P = M / L",
            });
        }
        let scale = 1.0 / self.m as f32;
        for (o, filter) in out.iter_mut().zip(chips.chunks_exact(self.l)) {
            let sum: Complex32 = filter.iter().sum();
            *o = sum * scale;
        }
        Ok(())
    }

    /// Thesis eq. 3.3-16: `Y[k] = (1/P) sum_i ((1/L) sum_{n=iL}^{(i+1)L-1} x[n])
    /// exp(-j 2 pi k i / N)`, `k = 0..N`, from exactly `M` chip-rate samples.
    pub fn spectrum<'a>(
        &self,
        chips: &[Complex32],
        scratch: &'a mut PmfScratch,
    ) -> Result<&'a [Complex32], AcquisitionError> {
        let (head, _) = scratch.y.split_at_mut(self.p);
        self.filter_outputs(chips, head)?;
        Ok(self.transform(scratch))
    }

    /// The spectrum from the `P` filter outputs (as [`Self::filter_outputs`] makes them).
    pub fn spectrum_of_filters<'a>(
        &self,
        filters: &[Complex32],
        scratch: &'a mut PmfScratch,
    ) -> Result<&'a [Complex32], AcquisitionError> {
        if filters.len() != self.p {
            return Err(AcquisitionError::TooFewSamples {
                needed: self.p,
                got: filters.len(),
            });
        }
        scratch.y[..self.p].copy_from_slice(filters);
        Ok(self.transform(scratch))
    }

    /// Zero-pad the filter outputs in `scratch.y[..P]` to `N = 2P` and transform.
    fn transform<'a>(&self, scratch: &'a mut PmfScratch) -> &'a [Complex32] {
        scratch.y[self.p..].fill(Complex32::default());
        self.fft
            .process_with_scratch(&mut scratch.y, &mut scratch.fft);
        &scratch.y
    }

    /// The coarse and fine Doppler estimates from `M` chip-rate samples.
    pub fn estimate(
        &self,
        chips: &[Complex32],
        scratch: &mut PmfScratch,
    ) -> Result<PmfEstimate, AcquisitionError> {
        Ok(self.peak(self.spectrum(chips, scratch)?))
    }

    /// The coarse and fine Doppler estimates from the `P` filter outputs.
    pub fn estimate_filters(
        &self,
        filters: &[Complex32],
        scratch: &mut PmfScratch,
    ) -> Result<PmfEstimate, AcquisitionError> {
        Ok(self.peak(self.spectrum_of_filters(filters, scratch)?))
    }

    /// Peak bin, eq. 3.3-13 and eq. 3.3-14 on a spectrum of `N = 2P` bins.
    fn peak(&self, y: &[Complex32]) -> PmfEstimate {
        let n = y.len().max(1);
        let energy = |k: usize| y.get(k % n).map_or(0.0, |v| f64::from(v.norm_sqr()));
        let k = (0..n)
            .max_by(|&a, &b| energy(a).total_cmp(&energy(b)))
            .unwrap_or(0);
        let delta = fine_offset(energy(k + n - 1), energy(k), energy(k + 1));
        let peak_bin = if k < self.p {
            k as i64
        } else {
            k as i64 - n as i64
        };
        let two_m = 2.0 * self.m as f64;
        PmfEstimate {
            peak_bin,
            delta,
            peak_energy: energy(k),
            coarse_fd_tc: peak_bin as f64 / two_m,
            fine_fd_tc: (peak_bin as f64 + delta) / two_m,
        }
    }
}

/// Where the code lies in a block of samples, for [`despread_to_chips`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChipTiming {
    /// Complex sample rate (Hz).
    pub sample_rate_hz: f64,
    /// Carrier removed (IF plus any Doppler already known) (Hz); phase zero at sample 0.
    pub carrier_hz: f64,
    /// Chip rate `1/Tc` (Hz).
    pub chip_rate_hz: f64,
    /// Sample position (fractional) where chip 0 of a code period starts.
    pub code_start_sample: f64,
}

/// The chip-rate sequence `x'[n]` (thesis eq. 3.3-15) of `m_chips` chips from samples:
/// carrier wiped, multiplied by `code` and averaged over each chip's samples; chips
/// past the end of `code` are zero (the zero appended to the 1023-chip C/A code to make
/// `M = 1024`, thesis section 3.3.1).
pub fn despread_to_chips(
    samples: &[Complex32],
    timing: ChipTiming,
    code: &[i8],
    m_chips: usize,
) -> Result<Vec<Complex32>, AcquisitionError> {
    let spc = timing.sample_rate_hz / timing.chip_rate_hz;
    if !(spc.is_finite() && spc >= 1.0) {
        return Err(AcquisitionError::BadParameter {
            name: "samples per chip",
            value: spc,
            allowed: "finite and >= 1",
        });
    }
    let start = timing.code_start_sample;
    if !(start.is_finite() && start >= 0.0) {
        return Err(AcquisitionError::BadParameter {
            name: "code start sample",
            value: start,
            allowed: "finite and >= 0",
        });
    }
    let first = start.ceil() as usize;
    let end = (start + m_chips as f64 * spc).ceil() as usize;
    if samples.len() < end {
        return Err(AcquisitionError::TooFewSamples {
            needed: end,
            got: samples.len(),
        });
    }
    let mut wiped = vec![Complex32::default(); end - first];
    wipe_carrier(
        &samples[first..end],
        first as u64,
        timing.sample_rate_hz,
        timing.carrier_hz,
        &mut wiped,
    );
    let mut chips = vec![Complex32::default(); m_chips];
    for (j, out) in chips.iter_mut().enumerate() {
        let Some(&c) = code.get(j) else {
            continue;
        };
        let lo = ((start + j as f64 * spc).ceil() as usize).max(first) - first;
        let hi = ((start + (j + 1) as f64 * spc).ceil() as usize).min(end) - first;
        if hi > lo {
            let sum: Complex32 = wiped[lo..hi].iter().sum();
            *out = sum * (f32::from(c) / (hi - lo) as f32);
        }
    }
    Ok(chips)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tone(m: usize, fd_tc: f64, phase: f64) -> Vec<Complex32> {
        (0..m)
            .map(|n| {
                let a = 2.0 * PI * fd_tc * n as f64 + phase;
                Complex32::new(a.cos() as f32, a.sin() as f32)
            })
            .collect()
    }

    #[test]
    fn spectrum_matches_the_closed_form_of_eq_3_3_9() {
        // Thesis eq. 3.3-9: |Y[k]| = (1/M) |sin(pi(p+d)/(2P)) / sin(pi(p+d)/(2M))
        //   * sin(pi(p+d-k)/2) / sin(pi(p+d-k)/(2P))|.
        let pmf = PmfFft::new(1024, 64).unwrap();
        let (m, p) = (1024.0, 16.0);
        let mut s = pmf.scratch();
        for (pb, d) in [(0.0, 0.3), (3.0, -0.2), (-7.0, 0.45)] {
            let fd_tc = (pb + d) / (2.0 * m);
            let y = pmf
                .spectrum(&tone(1024, fd_tc, 0.7), &mut s)
                .unwrap()
                .to_vec();
            for (k, yk) in y.iter().enumerate() {
                let kk = if k < 16 { k as f64 } else { k as f64 - 32.0 };
                let a = (PI / (2.0 * p) * (pb + d)).sin() / (PI / (2.0 * m) * (pb + d)).sin();
                let x = pb + d - kk;
                let b = (PI / 2.0 * x).sin() / (PI / (2.0 * p) * x).sin();
                let expect = (a * b).abs() / m;
                assert!(
                    (f64::from(yk.norm()) - expect).abs() < 2e-6,
                    "p {pb} d {d} k {k}: {} vs {expect}",
                    yk.norm()
                );
            }
        }
    }

    #[test]
    fn noiseless_fine_estimate_is_exact_at_bin_centres_and_beats_coarse_elsewhere() {
        let pmf = PmfFft::new(1024, 64).unwrap();
        let mut s = pmf.scratch();
        for pb in [-12i64, -1, 0, 5, 15] {
            for d in [-0.45, -0.3, -0.1, 0.0, 0.2, 0.4] {
                let fd_tc = (pb as f64 + d) / 2048.0;
                let e = pmf.estimate(&tone(1024, fd_tc, -1.1), &mut s).unwrap();
                let coarse = (e.coarse_fd_tc - fd_tc).abs();
                let fine = (e.fine_fd_tc - fd_tc).abs();
                if d == 0.0 {
                    assert_eq!(e.peak_bin, pb);
                    assert!(fine < 1e-9, "p {pb}: {fine}");
                } else {
                    assert!(fine < 0.1 * coarse, "p {pb} d {d}: {fine} vs {coarse}");
                }
            }
        }
    }

    #[test]
    fn estimating_from_filter_outputs_equals_estimating_from_chips() {
        let pmf = PmfFft::new(1024, 128).unwrap();
        let x = tone(1024, 2.3 / 2048.0, 0.4);
        let mut f = vec![Complex32::default(); pmf.p()];
        pmf.filter_outputs(&x, &mut f).unwrap();
        let mut s = pmf.scratch();
        let a = pmf.estimate(&x, &mut s).unwrap();
        let b = pmf.estimate_filters(&f, &mut s).unwrap();
        assert_eq!(a, b);
        assert!(pmf.estimate_filters(&f[1..], &mut s).is_err());
    }

    #[test]
    fn fine_offset_is_odd_and_zero_for_a_symmetric_peak() {
        assert_eq!(fine_offset(1.0, 4.0, 1.0), 0.0);
        let a = fine_offset(0.2, 3.0, 1.1);
        assert!((a + fine_offset(1.1, 3.0, 0.2)).abs() < 1e-15 && a > 0.0);
    }

    #[test]
    fn despreading_samples_gives_the_chip_rate_tone() {
        // 4 samples per chip, IF 250 kHz, residual Doppler fd: x'[n] ~ exp(j 2 pi fd n Tc).
        let (rc, fs, f_if, fd) = (1.023e6, 4.092e6, 250e3, 1500.0);
        let code: Vec<i8> = (0..1023)
            .map(|k| if (k * 7) % 5 < 2 { 1 } else { -1 })
            .collect();
        let start = 37.0;
        let samples: Vec<Complex32> = (0..5000)
            .map(|i| {
                let t = i as f64 / fs;
                let chip = ((i as f64 - start) / 4.0).floor();
                let c = if chip >= 0.0 {
                    code[chip as usize % 1023]
                } else {
                    1
                };
                let ph = 2.0 * PI * (f_if + fd) * t;
                Complex32::new(ph.cos() as f32, ph.sin() as f32) * f32::from(c)
            })
            .collect();
        let timing = ChipTiming {
            sample_rate_hz: fs,
            carrier_hz: f_if,
            chip_rate_hz: rc,
            code_start_sample: start,
        };
        let chips = despread_to_chips(&samples, timing, &code, 1024).unwrap();
        assert_eq!(chips[1023], Complex32::default());
        let pmf = PmfFft::new(1024, 64).unwrap();
        let e = pmf.estimate(&chips, &mut pmf.scratch()).unwrap();
        assert!(
            (e.fine_doppler_hz(rc) - fd).abs() < 15.0,
            "{}",
            e.fine_doppler_hz(rc)
        );
        assert!(despread_to_chips(&samples[..4000], timing, &code, 1024).is_err());
    }

    #[test]
    fn filter_length_must_divide_m() {
        assert!(PmfFft::new(1024, 100).is_err());
        assert!(PmfFft::new(1024, 1024).is_err());
        assert_eq!(PmfFft::new(1024, 256).unwrap().p(), 4);
    }
}
