//! The AVX-512 correlator: each tap's replica is spread 16 samples at a time by one
//! permutation of a 16-chip window of its code (`skyforge_gnss::spread`) inside the
//! accumulation loop, so no replica buffer is written or read and no loop runs over
//! chips. The carrier is the portable kernel's: 16 interleaved phasor lanes from
//! [`CarrierStart`], each sample multiplied by `conj(z)`.
//!
//! Applies when a sample advances the code by at most one chip (every signal at or above
//! its chip rate); [`correlate`] answers `None` otherwise and the portable kernel runs.

use core::arch::x86_64::{__m512, __m512i};
use num_complex::Complex;
use pulp::cast;
use pulp::x86::V4;
use skyforge_gnss::spread::v4::Window;
use skyforge_gnss::spread::{CodePhase, LANES};

use super::{CarrierStart, MAX_TAPS, Replica};

/// 2^32 - 1: the fraction of a 32.32 phase.
const FRACTION: u64 = 0xffff_ffff;

/// One tap's walk through its code: the window's first chip and the phase within it.
#[derive(Debug, Clone, Copy)]
struct Walk<'a> {
    /// One code period, then its first [`LANES`] chips again (any window fits).
    table: &'a [f32],
    /// Code length (chips).
    len: usize,
    /// The current chunk's first chip (below `len`).
    pos: usize,
    /// Phase into that chip (32.32, below 2^32).
    frac: u64,
}

impl<'a> Walk<'a> {
    fn new(table: &'a [f32], len: usize, phase_chips: f64) -> Self {
        let first = phase_chips.floor();
        Self {
            table,
            len,
            pos: (first.rem_euclid(len as f64) as usize).min(len - 1),
            frac: 0,
        }
    }

    /// The window of the current chunk.
    #[inline(always)]
    fn window(&self) -> __m512 {
        let w = &self.table[self.pos..self.pos + LANES];
        cast(core::array::from_fn::<f32, LANES, _>(|l| w[l]))
    }

    /// Move on by `step` (32.32 chips).
    #[inline(always)]
    fn advance(&mut self, step: u64) {
        let x = self.frac + step;
        self.pos += (x >> 32) as usize;
        self.frac = x & FRACTION;
        while self.pos >= self.len {
            self.pos -= self.len;
        }
    }
}

/// The correlation sums of `T` taps with AVX-512, or `None` where this path does not apply
/// (no AVX-512, more than one chip per sample, a block beyond the fixed point).
/// `tables[t]` is tap `t`'s code period followed by its first [`LANES`] chips.
pub(super) fn correlate<const T: usize>(
    samples: &[Complex<f32>],
    tables: [&[f32]; T],
    replica: &Replica<'_>,
    carrier: CarrierStart,
) -> Option<[Complex<f64>; MAX_TAPS]> {
    let simd = V4::try_new()?;
    let len = replica.code.len();
    let mut walks = [Walk::new(tables[0], len, 0.0); T];
    let mut d = 0;
    for (t, walk) in walks.iter_mut().enumerate() {
        let p = replica.p0_chips + replica.offsets[t];
        *walk = Walk::new(tables[t], len, p);
        let phase = CodePhase::new(p - p.floor(), replica.dp, samples.len())?;
        if !phase.windowed() {
            return None;
        }
        walk.frac = phase.x0;
        d = phase.d;
    }
    Some(simd.vectorize(
        #[inline(always)]
        || accumulate(simd, samples, walks, d, carrier),
    ))
}

/// Even (real) and odd (imaginary) float indices of 16 interleaved complex values.
const REAL: [u32; LANES] = [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30];
const IMAG: [u32; LANES] = [1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31];

/// The per-chunk loop: carrier wipe-off, phasor step, then per tap one window
/// permutation and two fused multiply-adds.
#[inline(always)]
fn accumulate<const T: usize>(
    simd: V4,
    samples: &[Complex<f32>],
    mut walks: [Walk<'_>; T],
    d: u64,
    carrier: CarrierStart,
) -> [Complex<f64>; MAX_TAPS] {
    let f = simd.avx512f;
    let window = Window::new(d);
    let step = LANES as u64 * d;
    let (real, imag): (__m512i, __m512i) = (cast(REAL), cast(IMAG));
    let (wr, wi) = (f._mm512_set1_ps(carrier.wr), f._mm512_set1_ps(carrier.wi));
    let (mut zr, mut zi): (__m512, __m512) = (cast(carrier.zr), cast(carrier.zi));
    let mut acc_r = [f._mm512_setzero_ps(); T];
    let mut acc_i = [f._mm512_setzero_ps(); T];
    let (chunks, tail) = samples.as_chunks::<LANES>();
    for x in chunks {
        let [lo, hi]: [__m512; 2] = cast(*x);
        let re = f._mm512_permutex2var_ps(lo, real, hi);
        let im = f._mm512_permutex2var_ps(lo, imag, hi);
        // x conj(z), then the carrier rotation z w.
        let br = f._mm512_fmadd_ps(re, zr, f._mm512_mul_ps(im, zi));
        let bi = f._mm512_fmsub_ps(im, zr, f._mm512_mul_ps(re, zi));
        let r = f._mm512_fmsub_ps(zr, wr, f._mm512_mul_ps(zi, wi));
        zi = f._mm512_fmadd_ps(zr, wi, f._mm512_mul_ps(zi, wr));
        zr = r;
        for t in 0..T {
            let code = window.spread(simd, walks[t].frac, walks[t].window());
            acc_r[t] = f._mm512_fmadd_ps(code, br, acc_r[t]);
            acc_i[t] = f._mm512_fmadd_ps(code, bi, acc_i[t]);
            walks[t].advance(step);
        }
    }
    let (zr, zi): ([f32; LANES], [f32; LANES]) = (cast(zr), cast(zi));
    let mut out = [Complex::new(0.0, 0.0); MAX_TAPS];
    for t in 0..T {
        let (mut re, mut im): ([f32; LANES], [f32; LANES]) = (cast(acc_r[t]), cast(acc_i[t]));
        let w = walks[t];
        for (l, x) in tail.iter().enumerate() {
            let chip = w.table[w.pos + ((w.frac + l as u64 * d) >> 32) as usize];
            re[l] += chip * (x.re * zr[l] + x.im * zi[l]);
            im[l] += chip * (x.im * zr[l] - x.re * zi[l]);
        }
        out[t] = super::lane_sums(&re, &im);
    }
    out
}
