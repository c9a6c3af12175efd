//! `[signal.filter]`: an optional band-limiting front-end filter, a linear-phase FIR
//! (Kaiser-windowed sinc) centred on the IF and applied zero-phase, so filtered samples stay
//! aligned with the unfiltered signal and with the truth.
//!
//! Design (Oppenheim & Schafer, Discrete-Time Signal Processing, 3rd ed., sec. 7.5.3):
//! ideal low-pass of cutoff `bandwidth / 2`, `h_lp[j] = 2 f_c sinc(2 f_c j)` for
//! `j = -M..=M` (`M = (taps - 1) / 2`, `f_c` in cycles per sample), times the Kaiser window
//! `I0(beta sqrt(1 - (j/M)^2)) / I0(beta)`. The Kaiser window is used because one parameter
//! sets the stopband attenuation independently of the length (a Blackman window is fixed at
//! about 74 dB, with a transition band 9.19 pi / M wide against 7.2 pi / M for this 60 dB
//! Kaiser design, O&S table 7.2 and eq. 7.63): `beta` is chosen for
//! [`STOPBAND_ATTENUATION_DB`] (eq. 7.62), and the length then sets the transition width
//! (eq. 7.63). The low-pass is moved to the IF: complex taps `h_lp[j] e^{i 2 pi f_IF j / fs}`
//! for complex samples, real taps `2 h_lp[j] cos(2 pi f_IF j / fs)` for a real IF; the
//! gain at the IF is then normalised to exactly 1.

use skyforge_orbits::check::Invalid;
use std::f64::consts::PI;

/// Stopband attenuation the filter keeps (dB). Window designs have equal ripple `10^(-A/20)`
/// in both bands; normalising the gain at the IF to 1 can double it in the passband, so the
/// passband stays within 0.2 % (0.017 dB) of 1. 60 dB puts out-of-band noise and
/// interference below the 8-bit quantisation floor (about 50 dB below full scale).
pub const STOPBAND_ATTENUATION_DB: f64 = 60.0;

/// Largest accepted filter length (taps).
pub const MAX_TAPS: usize = 1023;

/// Attenuation the Kaiser formulas are evaluated for (dB): 1 dB above the claim, because
/// `beta` from eq. 7.62 for exactly 60 dB reaches only 59.9 dB (measured).
const DESIGN_ATTENUATION_DB: f64 = STOPBAND_ATTENUATION_DB + 1.0;

/// `[signal.filter]`: an optional band-limiting front-end filter.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FilterConfig {
    /// Two-sided passband width (Hz), centred on the IF (on 0 Hz at complex baseband); the
    /// -6 dB points lie at IF +- bandwidth / 2.
    pub bandwidth_hz: f64,
    /// Filter length (odd). Default 63: at 4.092 Msps it gives a 244 kHz transition band
    /// (12 % of a 2.046 MHz passband) at 60 dB, costs 32 multiply pairs per component and
    /// sample (far above real time), and its 31-sample margins add 1.5 % to a 1 ms block.
    #[serde(default = "default_taps")]
    pub taps: usize,
}

fn default_taps() -> usize {
    63
}

impl FilterConfig {
    /// Checks against the sample stream: `taps` odd in 3..=1023; the bandwidth in
    /// `(0, fs]` for complex samples, and for a real IF the passband
    /// `IF +- bandwidth / 2` inside `(0, fs / 2)`.
    pub fn check(&self, sample_rate_hz: f64, if_hz: f64, complex: bool) -> Result<(), Invalid> {
        if self.taps.is_multiple_of(2) || !(3..=MAX_TAPS).contains(&self.taps) {
            return Err(Invalid::new(
                "taps",
                self.taps,
                format!("must be odd, from 3 to {MAX_TAPS}"),
            ));
        }
        let bw = self.bandwidth_hz;
        if complex {
            if !(bw.is_finite() && bw > 0.0 && bw <= sample_rate_hz) {
                return Err(Invalid::new(
                    "bandwidth_hz",
                    bw,
                    format!("must be > 0 and at most the sample rate ({sample_rate_hz} Hz)"),
                ));
            }
        } else if !(bw.is_finite()
            && bw > 0.0
            && if_hz - bw / 2.0 > 0.0
            && if_hz + bw / 2.0 < sample_rate_hz / 2.0)
        {
            return Err(Invalid::new(
                "bandwidth_hz",
                bw,
                format!(
                    "must be > 0 and keep the passband IF +- bandwidth/2 (IF = {if_hz} Hz) inside (0, {}) Hz for real samples",
                    sample_rate_hz / 2.0
                ),
            ));
        }
        Ok(())
    }
}

/// How the taps act on the I/Q components.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Real IF: real taps on I only.
    Real,
    /// Complex samples, IF 0: real taps on I and Q separately.
    ComplexBaseband,
    /// Complex samples, IF not 0: complex taps.
    ComplexShifted,
}

/// Outputs filtered per pass over the taps: the output and input chunks stay in L1.
const CHUNK: usize = 512;

/// Linear-phase FIR applied zero-phase: output sample `k` is
/// `sum_{j=-M..=M} h[j] x[k - j]` (`M` = [`BandFilter::half`]), so a block rendered with
/// `half()` extra samples on each side filters to output aligned with the unfiltered
/// signal (no group delay). Taps are conjugate-symmetric (`h[-j] = conj(h[j])`), hence a
/// real frequency response: zero phase wherever it is positive.
#[derive(Debug, Clone)]
pub struct BandFilter {
    kind: Kind,
    /// `Re h[j]`, `j = 0..=M`.
    re: Vec<f32>,
    /// `Im h[j]`, `j = 0..=M` (all 0 unless `ComplexShifted`).
    im: Vec<f32>,
    sample_rate_hz: f64,
    if_hz: f64,
}

impl BandFilter {
    /// Designs the filter for a checked configuration ([`FilterConfig::check`] runs again).
    pub fn new(
        cfg: &FilterConfig,
        sample_rate_hz: f64,
        if_hz: f64,
        complex: bool,
    ) -> Result<Self, Invalid> {
        cfg.check(sample_rate_hz, if_hz, complex)?;
        let m = (cfg.taps - 1) / 2;
        let lowpass = kaiser_lowpass(cfg.bandwidth_hz / 2.0 / sample_rate_hz, m);
        let kind = match (complex, if_hz == 0.0) {
            (false, _) => Kind::Real,
            (true, true) => Kind::ComplexBaseband,
            (true, false) => Kind::ComplexShifted,
        };
        let w_if = 2.0 * PI * if_hz / sample_rate_hz;
        let (mut re, mut im): (Vec<f64>, Vec<f64>) = lowpass
            .iter()
            .enumerate()
            .map(|(j, &h)| {
                let (s, c) = (w_if * j as f64).sin_cos();
                match kind {
                    Kind::Real => (2.0 * h * c, 0.0),
                    Kind::ComplexBaseband => (h, 0.0),
                    Kind::ComplexShifted => (h * c, h * s),
                }
            })
            .unzip();
        // Gain at the IF: H = re[0] + 2 sum_j (re[j] cos(w j) + im[j] sin(w j)), real.
        let gain = response(&re, &im, w_if);
        for x in re.iter_mut().chain(im.iter_mut()) {
            *x /= gain;
        }
        Ok(Self {
            kind,
            re: re.iter().map(|&x| x as f32).collect(),
            im: im.iter().map(|&x| x as f32).collect(),
            sample_rate_hz,
            if_hz,
        })
    }

    /// `(taps - 1) / 2`: extra samples needed before and after a block.
    pub fn half(&self) -> usize {
        self.re.len() - 1
    }

    /// Width of the transition band (Hz) from the Kaiser design formula (Oppenheim &
    /// Schafer eq. 7.63, `order = taps - 1 = (A - 8) / (2.285 dw)`, A = 61 dB): the
    /// response is within 0.2 % (0.017 dB) of 1 for offsets from the IF up to
    /// `(bandwidth - width) / 2`, and at least [`STOPBAND_ATTENUATION_DB`] down beyond
    /// `(bandwidth + width) / 2` (tested for 15 to 1023 taps).
    pub fn transition_width_hz(&self) -> f64 {
        let order = (2 * self.half()) as f64;
        let dw = (DESIGN_ATTENUATION_DB - 8.0) / (2.285 * order);
        dw * self.sample_rate_hz / (2.0 * PI)
    }

    /// Filter: inputs have `n + 2 half()` samples (block plus margins), outputs `n` samples.
    /// Complex samples use the complex taps; for a real IF only `in_i` is filtered into
    /// `out_i`, and `in_q` / `out_q` are neither read nor written (they may be empty).
    ///
    /// # Panics
    /// When the slice lengths do not match (`in_i.len() != out_i.len() + 2 half()`, and the
    /// same for Q with complex samples): a programming error, not an input error.
    pub fn apply(&self, in_i: &[f32], in_q: &[f32], out_i: &mut [f32], out_q: &mut [f32]) {
        let m = self.half();
        assert_eq!(
            in_i.len(),
            out_i.len() + 2 * m,
            "filter input/output lengths"
        );
        if self.kind != Kind::Real {
            assert_eq!(
                in_q.len(),
                out_q.len() + 2 * m,
                "filter input/output lengths"
            );
            assert_eq!(out_i.len(), out_q.len(), "filter I/Q lengths");
        }
        let n = out_i.len();
        let mut k0 = 0;
        while k0 < n {
            let len = CHUNK.min(n - k0);
            let oi = &mut out_i[k0..k0 + len];
            let xi = &in_i[k0..k0 + len + 2 * m];
            match self.kind {
                Kind::Real => self.real_taps(xi, oi),
                Kind::ComplexBaseband => {
                    self.real_taps(xi, oi);
                    let xq = &in_q[k0..k0 + len + 2 * m];
                    self.real_taps(xq, &mut out_q[k0..k0 + len]);
                }
                Kind::ComplexShifted => {
                    let xq = &in_q[k0..k0 + len + 2 * m];
                    self.complex_taps(xi, xq, oi, &mut out_q[k0..k0 + len]);
                }
            }
            k0 += len;
        }
    }

    /// `out[k] = re[0] x[k+M] + sum_j re[j] (x[k+M-j] + x[k+M+j])`, one tap pair per pass
    /// (contiguous loops that vectorise); the summation order per sample is fixed, so the
    /// result does not depend on how the stream is split into blocks.
    fn real_taps(&self, x: &[f32], out: &mut [f32]) {
        let (m, n) = (self.half(), out.len());
        let h0 = self.re[0];
        for (o, &xc) in out.iter_mut().zip(&x[m..m + n]) {
            *o = h0 * xc;
        }
        for (j, &h) in self.re.iter().enumerate().skip(1) {
            let (lo, hi) = (&x[m - j..m - j + n], &x[m + j..m + j + n]);
            for k in 0..n {
                out[k] += h * (lo[k] + hi[k]);
            }
        }
    }

    /// Complex taps in conjugate pairs: with `h[j] = a + i b`, `h[-j] = a - i b`,
    /// `x- = x[k-j]`, `x+ = x[k+j]`:
    /// `h[j] x- + h[-j] x+ = a (x- + x+) + i b (x- - x+)`.
    fn complex_taps(&self, xi: &[f32], xq: &[f32], oi: &mut [f32], oq: &mut [f32]) {
        let (m, n) = (self.half(), oi.len());
        let h0 = self.re[0];
        for (o, &x) in oi.iter_mut().zip(&xi[m..m + n]) {
            *o = h0 * x;
        }
        for (o, &x) in oq.iter_mut().zip(&xq[m..m + n]) {
            *o = h0 * x;
        }
        for (j, (&a, &b)) in self.re.iter().zip(&self.im).enumerate().skip(1) {
            // Equal-length slices: the indexed loop below needs no bounds checks.
            let (il, ih) = (&xi[m - j..m - j + n], &xi[m + j..m + j + n]);
            let (ql, qh) = (&xq[m - j..m - j + n], &xq[m + j..m + j + n]);
            let (oi, oq) = (&mut oi[..n], &mut oq[..n]);
            for k in 0..n {
                oi[k] += a * (il[k] + ih[k]) - b * (ql[k] - qh[k]);
                oq[k] += a * (ql[k] + qh[k]) + b * (il[k] - ih[k]);
            }
        }
    }

    /// Power gain on white noise, `sum_j |h[j]|^2` (per component for complex noise with
    /// independent I and Q), so the renderer can keep the noise sigma/AGC right.
    pub fn noise_power_gain(&self) -> f64 {
        let pair: f64 = self
            .re
            .iter()
            .zip(&self.im)
            .skip(1)
            .map(|(&a, &b)| f64::from(a).powi(2) + f64::from(b).powi(2))
            .sum();
        f64::from(self.re[0]).powi(2) + 2.0 * pair
    }

    /// Response at a frequency offset `f_hz` from the IF, of the taps as applied:
    /// (linear amplitude, phase rad). The phase is 0 where the response is positive (the
    /// whole passband) and pi where a stopband lobe is negative.
    pub fn response_at(&self, f_hz: f64) -> (f64, f64) {
        let w = 2.0 * PI * (self.if_hz + f_hz) / self.sample_rate_hz;
        let h = response(&self.re, &self.im, w);
        (h.abs(), if h < 0.0 { PI } else { 0.0 })
    }
}

/// `H(w) = sum_j h[j] e^{-i w j}` of conjugate-symmetric taps given for `j >= 0`:
/// `re[0] + 2 sum_{j>=1} (re[j] cos(w j) + im[j] sin(w j))`, real.
fn response<T: Copy + Into<f64>>(re: &[T], im: &[T], w_rad_per_sample: f64) -> f64 {
    let pairs: f64 = re
        .iter()
        .zip(im)
        .enumerate()
        .skip(1)
        .map(|(j, (&a, &b))| {
            let (s, c) = (w_rad_per_sample * j as f64).sin_cos();
            a.into() * c + b.into() * s
        })
        .sum();
    re[0].into() + 2.0 * pairs
}

/// Kaiser-windowed ideal low-pass of cutoff `fc` (cycles per sample), taps `j = 0..=m`
/// (the other half mirrors them). `beta = 0.1102 (A - 8.7)` for A > 50 dB
/// (Oppenheim & Schafer eq. 7.62).
fn kaiser_lowpass(fc: f64, m: usize) -> Vec<f64> {
    let beta = 0.1102 * (DESIGN_ATTENUATION_DB - 8.7);
    let i0_beta = bessel_i0(beta);
    (0..=m)
        .map(|j| {
            let ideal = if j == 0 {
                2.0 * fc
            } else {
                (2.0 * PI * fc * j as f64).sin() / (PI * j as f64)
            };
            let r = j as f64 / m as f64;
            ideal * bessel_i0(beta * (1.0 - r * r).max(0.0).sqrt()) / i0_beta
        })
        .collect()
}

/// Modified Bessel function of the first kind, order 0: `sum_k ((x/2)^k / k!)^2`
/// (Abramowitz & Stegun 9.6.12), to full f64 precision for the window's `x <= 10`.
fn bessel_i0(x: f64) -> f64 {
    let (mut sum, mut term, mut k) = (1.0, 1.0, 1.0);
    while term > 1e-17 * sum {
        term *= (x / (2.0 * k)).powi(2);
        sum += term;
        k += 1.0;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest passband deviation from unit amplitude gain (0.2 %, 0.017 dB).
    const PASSBAND_RIPPLE: f64 = 2e-3;
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::StandardNormal;

    const FS: f64 = 4.092e6;

    fn filter(bw: f64, taps: usize, if_hz: f64, complex: bool) -> BandFilter {
        let cfg = FilterConfig {
            bandwidth_hz: bw,
            taps,
        };
        match BandFilter::new(&cfg, FS, if_hz, complex) {
            Ok(f) => f,
            Err(e) => panic!("valid filter rejected: {e}"),
        }
    }

    fn noise(n: usize, seed: u64) -> Vec<f32> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        (0..n)
            .map(|_| rng.sample::<f32, _>(StandardNormal))
            .collect()
    }

    /// Filters a whole stream: output `k` belongs to input `k + half`.
    fn run(f: &BandFilter, xi: &[f32], xq: &[f32]) -> (Vec<f32>, Vec<f32>) {
        let n = xi.len() - 2 * f.half();
        let (mut oi, mut oq) = (vec![0f32; n], vec![0f32; n]);
        if f.kind == Kind::Real {
            f.apply(xi, &[], &mut oi, &mut []);
        } else {
            f.apply(xi, xq, &mut oi, &mut oq);
        }
        (oi, oq)
    }

    #[test]
    fn bessel_i0_matches_tabulated_values() {
        // Abramowitz & Stegun table 9.8: I0(1) = 1.266065878, I0(5) = 27.23987182.
        assert!((bessel_i0(1.0) - 1.266_065_878).abs() < 1e-9);
        assert!((bessel_i0(5.0) - 27.239_871_82).abs() < 1e-7);
        assert_eq!(bessel_i0(0.0), 1.0);
    }

    /// Passband ripple and stopband attenuation at the edges the design formula claims,
    /// for complex baseband, complex at an IF, and a real IF; several lengths.
    #[test]
    fn response_meets_the_kaiser_design() {
        for (bw, taps, if_hz, complex) in [
            (2.046e6, 63, 0.0, true),
            (2.046e6, 63, 0.6e6, true),
            (1.0e6, 31, 0.0, true),
            (1.2e6, 127, 1.023e6, false),
            (0.5e6, 255, 1.3e6, false),
            (2.046e6, 15, 0.0, true),
            (2.046e6, 511, 0.0, true),
            (3.0e6, 1023, 0.2e6, true),
        ] {
            let f = filter(bw, taps, if_hz, complex);
            let dw = f.transition_width_hz();
            let (pass, stop) = ((bw - dw) / 2.0, (bw + dw) / 2.0);
            assert!(pass > 0.0, "design case too narrow for its length");
            let (gain_if, phase_if) = f.response_at(0.0);
            assert!(
                (gain_if - 1.0).abs() < 1e-6 && phase_if == 0.0,
                "IF gain {gain_if}"
            );
            for k in 0..=8000 {
                let off = -FS / 2.0 + FS * f64::from(k) / 8000.0;
                let (amp, phase) = f.response_at(off);
                // A real IF also passes the image at -IF: judge only the upper half there.
                if !complex && if_hz + off <= 0.0 {
                    continue;
                }
                if off.abs() <= pass {
                    assert!(
                        (amp - 1.0).abs() <= PASSBAND_RIPPLE && phase == 0.0,
                        "{bw} {taps} {if_hz}: passband {off} Hz: {amp} {phase}"
                    );
                } else if off.abs() >= stop && (complex || if_hz + off < FS / 2.0) {
                    assert!(
                        20.0 * amp.log10() <= -STOPBAND_ATTENUATION_DB,
                        "{bw} {taps} {if_hz}: stopband {off} Hz: {} dB",
                        20.0 * amp.log10()
                    );
                }
            }
            // The -6 dB points at IF +- bandwidth / 2 (an ideal low-pass windowed
            // symmetrically is at half amplitude at its cutoff).
            for edge in [-bw / 2.0, bw / 2.0] {
                let (amp, _) = f.response_at(edge);
                assert!((amp - 0.5).abs() < 0.01, "edge {edge}: {amp}");
            }
        }
    }

    /// Time-domain filtering of tones agrees with the frequency response (amplitude and
    /// phase), in the passband and the stopband: `apply` and `response_at` describe the
    /// same filter, and a passband tone comes out undelayed.
    #[test]
    fn tones_come_out_scaled_by_the_response_without_delay() {
        for (if_hz, complex) in [(0.0, true), (0.7e6, true), (1.1e6, false)] {
            let f = filter(1.5e6, 63, if_hz, complex);
            let m = f.half();
            for off in [0.0, 0.2e6, -0.55e6, 0.69e6, 1.2e6, -1.4e6] {
                let fr = (if_hz + off) / FS;
                let n = 2000;
                let phase = |k: usize| 2.0 * PI * fr * k as f64 + 0.3;
                let xi: Vec<f32> = (0..n + 2 * m).map(|k| phase(k).cos() as f32).collect();
                let xq: Vec<f32> = (0..n + 2 * m).map(|k| phase(k).sin() as f32).collect();
                let (oi, oq) = run(&f, &xi, &xq);
                let (amp, ph) = f.response_at(off);
                for k in 0..n {
                    let want = amp * (phase(k + m) + ph).cos();
                    assert!(
                        (f64::from(oi[k]) - want).abs() < 2e-5,
                        "IF {if_hz}, offset {off}: I[{k}] {} vs {want}",
                        oi[k]
                    );
                    if complex {
                        let want = amp * (phase(k + m) + ph).sin();
                        assert!((f64::from(oq[k]) - want).abs() < 2e-5);
                    }
                }
                if off.abs() < 0.5e6 {
                    // Passband: the output is the input itself to the ripple (no delay).
                    for k in 0..n {
                        assert!(
                            (oi[k] - xi[k + m]).abs() < PASSBAND_RIPPLE as f32,
                            "delayed at {off}"
                        );
                    }
                }
            }
        }
    }

    /// Noise power gain against a measurement on white noise, and against Parseval:
    /// `sum |h|^2 = (1/fs) integral |H|^2 df`, which for this design lies between the ideal
    /// filter's `bandwidth / fs` with the passband shrunk by the transition width and the
    /// ideal value itself (the transition band, |H| < 1, loses power; ripple 0.2 %). A real
    /// IF's filter passes both sides: twice that.
    #[test]
    fn noise_power_gain_matches_white_noise() {
        let n = 400_000;
        for (bw, if_hz, complex, ideal) in [
            (2.046e6, 0.0, true, 2.046e6 / FS),
            (1.0e6, 0.5e6, true, 1.0e6 / FS),
            (1.0e6, 1.0e6, false, 2.0 * 1.0e6 / FS),
        ] {
            let f = filter(bw, 63, if_hz, complex);
            let g = f.noise_power_gain();
            let lower = ideal * (bw - f.transition_width_hz()) / bw;
            assert!(
                lower <= g && g <= ideal * 1.002,
                "gain {g} vs ideal {ideal} (lower bound {lower})"
            );
            let (xi, xq) = (noise(n + 2 * f.half(), 1), noise(n + 2 * f.half(), 2));
            let (oi, oq) = run(&f, &xi, &xq);
            let power = |x: &[f32]| x.iter().map(|&v| f64::from(v).powi(2)).sum::<f64>();
            let p_in = power(&xi[f.half()..f.half() + n]);
            assert!((power(&oi) / p_in / g - 1.0).abs() < 0.02, "I power");
            if complex {
                let p_in = power(&xq[f.half()..f.half() + n]);
                assert!((power(&oq) / p_in / g - 1.0).abs() < 0.02, "Q power");
            }
        }
    }

    #[test]
    fn check_rejects_what_the_design_cannot_do() {
        let cfg = |bw, taps| FilterConfig {
            bandwidth_hz: bw,
            taps,
        };
        assert!(cfg(2e6, 63).check(FS, 0.0, true).is_ok());
        assert!(cfg(FS, 63).check(FS, 0.0, true).is_ok());
        assert!(cfg(1.0e6, 63).check(FS, 1.0e6, false).is_ok());
        for (c, if_hz, complex, field) in [
            (cfg(2e6, 64), 0.0, true, "taps"),
            (cfg(2e6, 1), 0.0, true, "taps"),
            (cfg(2e6, 1025), 0.0, true, "taps"),
            (cfg(0.0, 63), 0.0, true, "bandwidth_hz"),
            (cfg(f64::NAN, 63), 0.0, true, "bandwidth_hz"),
            (cfg(FS * 1.01, 63), 0.0, true, "bandwidth_hz"),
            (cfg(2.1e6, 63), 1.0e6, false, "bandwidth_hz"),
            (cfg(2.0e6, 63), 1.1e6, false, "bandwidth_hz"),
        ] {
            let e = c.check(FS, if_hz, complex).err();
            assert_eq!(e.map(|e| e.field), Some(field.to_string()), "{c:?}");
            assert!(BandFilter::new(&c, FS, if_hz, complex).is_err());
        }
    }

    #[test]
    fn taps_default_to_63() -> Result<(), serde_json::Error> {
        let cfg: FilterConfig = serde_json::from_str(r#"{"bandwidth_hz": 2e6}"#)?;
        assert_eq!(cfg.taps, 63);
        assert!(serde_json::from_str::<FilterConfig>(r#"{"bandwidth_hz": 2e6, "x": 1}"#).is_err());
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// Filtering blocks (each with its margins) gives bit-identical output to filtering
        /// the whole stream at once, for any split and every filter kind.
        #[test]
        fn block_split_independence(
            cuts in proptest::collection::vec(1usize..1500, 1..6),
            kind in 0usize..3,
            taps in (1usize..40).prop_map(|h| 2 * h + 1),
        ) {
            let (if_hz, complex) = [(0.0, true), (0.4e6, true), (1.0e6, false)][kind];
            let f = filter(1.2e6, taps, if_hz, complex);
            let m = f.half();
            let total: usize = cuts.iter().sum();
            let (xi, xq) = (noise(total + 2 * m, 3), noise(total + 2 * m, 4));
            let (whole_i, whole_q) = run(&f, &xi, &xq);
            let mut start = 0;
            for len in cuts {
                let span = start..start + len + 2 * m;
                let (bi, bq) = run(&f, &xi[span.clone()], &xq[span]);
                prop_assert_eq!(&bi[..], &whole_i[start..start + len]);
                if complex {
                    prop_assert_eq!(&bq[..], &whole_q[start..start + len]);
                }
                start += len;
            }
        }
    }
}
