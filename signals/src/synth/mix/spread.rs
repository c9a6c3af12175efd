//! Code spreading: the chip amplitude under each sample of a block.
//!
//! Sample `i` carries chip `(x0 + i d) >> 32`, with the code phase `x0` and its step `d`
//! in 32.32 fixed point (chips): 2^-32 chip resolution, and over a 1100-chip block an
//! accumulated step rounding below 2^-33 x 4096 = 5e-7 chip, about 1.5e-4 m of code at
//! L1 C/A. Chips beyond the ones given repeat the last, as does a non-positive code rate.
//!
//! Two paths compute exactly that, so every CPU gives the same bits:
//! - the definition, sample by sample;
//! - with AVX-512, 16 samples at a time: their chips lie within a window of 16 chips from
//!   the first one's whenever a sample advances the code by at most one chip, so one
//!   permutation of the window's amplitudes spreads them (no chip-by-chip loop, no
//!   gather).

/// Samples per step of the vector path.
const LANES: usize = 16;

/// `2^32`, the fixed-point scale.
const SCALE: f64 = 4_294_967_296.0;

/// A block's code phase in fixed point.
#[derive(Debug, Clone, Copy)]
struct Phase {
    /// Phase of the first sample (chips from the first given chip, 32.32).
    x0: u64,
    /// Phase step per sample (chips, 32.32).
    d: u64,
}

impl Phase {
    /// From the first sample's phase (in [0, 1)) and the step per sample (chips); `None`
    /// when the `n` samples' phases do not fit the fixed point.
    fn new(code_phase_chips: f64, chips_per_sample: f64, n: usize) -> Option<Self> {
        let x0 = (code_phase_chips.clamp(0.0, 1.0) * SCALE).floor();
        let d = (chips_per_sample.max(0.0) * SCALE).round();
        let last = x0 + d * n as f64;
        (last < 2f64.powi(62)).then_some(Self {
            x0: x0 as u64,
            d: d as u64,
        })
    }

    /// The chip under sample `i`.
    #[inline(always)]
    fn chip(self, i: usize) -> u64 {
        (self.x0 + i as u64 * self.d) >> 32
    }
}

/// Fill `code[..n]` with the amplitude of the chip under each sample; `amps` holds each
/// chip's amplitude (`amplitude * sign`) followed by [`PAD`] copies of the last.
pub(super) fn spread(code: &mut [f32], amps: &[f32], code_phase_chips: f64, chips_per_sample: f64) {
    let n = code.len();
    let chips = amps.len().saturating_sub(PAD);
    let Some(phase) = Phase::new(code_phase_chips, chips_per_sample, n) else {
        code.fill(amps.first().copied().unwrap_or(0.0));
        return;
    };
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if let Some(simd) = pulp::x86::V4::try_new() {
        // The window may not reach past the padding: every sample within the given chips.
        let covered = n == 0 || phase.chip(n - 1) < chips as u64;
        if covered && phase.d <= 1 << 32 {
            done = simd.vectorize(
                #[inline(always)]
                || v4::spread(simd, code, amps, phase),
            );
        }
    }
    let last = chips.saturating_sub(1) as u64;
    for (i, c) in code.iter_mut().enumerate().skip(done) {
        *c = amps[phase.chip(i).min(last) as usize];
    }
}

/// Copies of the last chip after the given ones (the vector path's window).
pub(super) const PAD: usize = LANES;

#[cfg(target_arch = "x86_64")]
mod v4 {
    use super::{LANES, Phase};
    use core::arch::x86_64::{__m512, __m512i};
    use pulp::cast;
    use pulp::x86::V4;

    /// Dword indices of the low halves of two vectors of 8 qwords (`permutex2var`).
    const LOW_DWORDS: [u32; 16] = [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30];

    /// The whole chunks of `code`; returns the samples done. Needs `phase.d <= 2^32` and
    /// `amps` covering every sample's chip plus [`super::PAD`].
    #[inline(always)]
    pub(super) fn spread(simd: V4, code: &mut [f32], amps: &[f32], phase: Phase) -> usize {
        let f = simd.avx512f;
        // Lane l's offset from the chunk's first sample: l d.
        let lo: __m512i = cast(core::array::from_fn::<u64, 8, _>(|l| l as u64 * phase.d));
        let hi: __m512i = cast(core::array::from_fn::<u64, 8, _>(|l| {
            (l + 8) as u64 * phase.d
        }));
        let pick: __m512i = cast(LOW_DWORDS);
        let (chunks, _) = code.as_chunks_mut::<LANES>();
        for (j, out) in chunks.iter_mut().enumerate() {
            let base = phase.x0 + (j * LANES) as u64 * phase.d;
            let first = (base >> 32) as usize;
            let Some(window) = amps.get(first..first + LANES) else {
                return j * LANES;
            };
            let window: [f32; LANES] = core::array::from_fn(|l| window[l]);
            // (frac(base) + l d) >> 32: the lane's chip counted from the first's (< 16).
            let frac = f._mm512_set1_epi64((base & 0xffff_ffff) as i64);
            let a = f._mm512_srli_epi64::<32>(f._mm512_add_epi64(frac, lo));
            let b = f._mm512_srli_epi64::<32>(f._mm512_add_epi64(frac, hi));
            let index = f._mm512_permutex2var_epi32(a, pick, b);
            let w: __m512 = cast(window);
            *out = cast(f._mm512_permutexvar_ps(index, w));
        }
        chunks.len() * LANES
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, with no vector path.
    fn definition(n: usize, amps: &[f32], p0: f64, dp: f64) -> Vec<f32> {
        let phase = Phase::new(p0, dp, n).unwrap();
        let last = (amps.len() - PAD - 1) as u64;
        (0..n)
            .map(|i| amps[phase.chip(i).min(last) as usize])
            .collect()
    }

    fn amps(chips: usize) -> Vec<f32> {
        let mut x: u32 = 777;
        let mut v: Vec<f32> = (0..chips)
            .map(|k| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                (k as f32 + 1.0) * if x >> 31 == 0 { 1.0 } else { -1.0 }
            })
            .collect();
        let last = *v.last().unwrap();
        v.extend([last; PAD]);
        v
    }

    #[test]
    fn the_vector_path_gives_the_definition() {
        // Short and long chips, a sample per chip exactly, more samples than chips given.
        for (p0, dp, n, chips) in [
            (0.0, 0.25, 4092, 1024),
            (0.5, 0.393_461_5, 2600, 1100),
            (0.999, 1.0, 3001, 3002),
            (0.3, 0.02, 20_000, 402),
            (0.7, 1.3, 1000, 1302),
            (0.1, 0.0, 50, 1),
            (0.2, 0.25, 1000, 100),
        ] {
            let a = amps(chips);
            let mut got = vec![0f32; n];
            spread(&mut got, &a, p0, dp);
            assert_eq!(got, definition(n, &a, p0, dp), "dp {dp}, n {n}");
        }
    }

    #[test]
    fn each_sample_carries_the_chip_under_its_code_phase() {
        let (p0, dp, n) = (0.37, 1.023e6 / 2.6e6 * (1.0 + 3e-6), 2600);
        let a = amps(1100);
        let mut code = vec![0f32; n];
        spread(&mut code, &a, p0, dp);
        let mut edge = 0;
        for (i, &c) in code.iter().enumerate() {
            let x = p0 + i as f64 * dp;
            if c != a[x.floor() as usize] {
                // Only within the fixed point's rounding of a chip edge.
                assert!((x - x.round()).abs() < 1e-6, "sample {i}");
                edge += 1;
            }
        }
        assert!(edge <= 2, "{edge} chip-edge disagreements");
    }
}
