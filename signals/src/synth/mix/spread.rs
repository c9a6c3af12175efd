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
//!   permutation of the window's amplitudes spreads them (`skyforge_gnss::spread`, which
//!   the receiver's correlators share).

use skyforge_gnss::spread::{CodePhase, LANES};

/// Fill `code[..n]` with the amplitude of the chip under each sample; `amps` holds each
/// chip's amplitude (`amplitude * sign`) followed by [`PAD`] copies of the last.
pub(super) fn spread(code: &mut [f32], amps: &[f32], code_phase_chips: f64, chips_per_sample: f64) {
    let n = code.len();
    let chips = amps.len().saturating_sub(PAD);
    let Some(phase) = CodePhase::new(code_phase_chips, chips_per_sample, n) else {
        code.fill(amps.first().copied().unwrap_or(0.0));
        return;
    };
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if let Some(simd) = pulp::x86::V4::try_new() {
        // The window may not reach past the padding: every sample within the given chips.
        let covered = n == 0 || phase.chip(n - 1) < chips as u64;
        if covered && phase.windowed() {
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
    use super::{CodePhase, LANES};
    use core::arch::x86_64::__m512;
    use pulp::cast;
    use pulp::x86::V4;
    use skyforge_gnss::spread::v4::Window;

    /// The whole chunks of `code`; returns the samples done. Needs `phase.d <= 2^32` and
    /// `amps` covering every sample's chip plus [`super::PAD`].
    #[inline(always)]
    pub(super) fn spread(simd: V4, code: &mut [f32], amps: &[f32], phase: CodePhase) -> usize {
        let spreader = Window::new(phase.d);
        let (chunks, _) = code.as_chunks_mut::<LANES>();
        for (j, out) in chunks.iter_mut().enumerate() {
            let base = phase.x0 + (j * LANES) as u64 * phase.d;
            let first = (base >> 32) as usize;
            let Some(window) = amps.get(first..first + LANES) else {
                return j * LANES;
            };
            let window: [f32; LANES] = core::array::from_fn(|l| window[l]);
            let w: __m512 = cast(window);
            *out = cast(spreader.spread(simd, base & 0xffff_ffff, w));
        }
        chunks.len() * LANES
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition, with no vector path.
    fn definition(n: usize, amps: &[f32], p0: f64, dp: f64) -> Vec<f32> {
        let phase = CodePhase::new(p0, dp, n).unwrap();
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
