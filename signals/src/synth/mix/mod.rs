//! The per-channel mixing kernel: adds `amplitude * chip_sign(code phase) *
//! exp(j 2 pi carrier phase)` to a block of complex samples held as separate I and Q
//! arrays (so the compiler vectorises the inner loops).
//!
//! Within a block the code and carrier phases are linear in the sample index; the caller
//! re-anchors them every block from the f64 truth, so nothing accumulates across blocks.
//!
//! Code: sample `i` carries chip `floor(p0 + i dp)`, in 32.32 fixed point ([`spread`]).
//!
//! Carrier: `LANES` interleaved phasor recurrences, z[i + LANES] = z[i] w^LANES, started
//! from exact values; over a 4096-sample block the f32 recurrence drifts by about 1e-4
//! rad (1e-5 m at L1), measured in this module's tests.

mod pair;
mod spread;

pub use pair::mix_pair_into;

use skyforge_gnss::nco::{LanePhasors, turn};

/// Phasor recurrences run side by side: two AVX-512 registers of f32 (four AVX2 ones),
/// so that two independent multiply-add chains hide each other's latency.
pub(super) const LANES: usize = 32;

/// One channel over one block.
#[derive(Debug, Clone, Copy)]
pub struct ChannelBlock<'a> {
    /// Signal amplitude (same units as the noise the caller adds).
    pub amplitude: f32,
    /// Carrier phase at the first sample (cycles; only the fraction matters).
    pub carrier_phase_cycles: f64,
    /// Carrier phase increment per sample (cycles): (IF + Doppler) / fs.
    pub carrier_cycles_per_sample: f64,
    /// Code phase at the first sample, in chips from `chip_signs[0]` (in [0, 1)).
    pub code_phase_chips: f64,
    /// Code phase increment per sample (chips): code rate / fs.
    pub code_chips_per_sample: f64,
    /// Each chip from the block's first chip on, with data bits and any secondary code
    /// already applied; must cover the whole block.
    pub chips: Chips<'a>,
}

/// The chips of a block: signs of a binary code, or levels of a multi-level waveform
/// (Galileo E1's CBOC sub-chips, several components summed).
#[derive(Debug, Clone, Copy)]
pub enum Chips<'a> {
    /// +1/-1 per chip.
    Signs(&'a [i8]),
    /// Any amplitude per chip, relative to the channel's.
    Levels(&'a [f32]),
}

impl ChannelBlock<'_> {
    /// Number of chips a block of `n` samples touches (the length `chip_signs` needs).
    pub fn chips_needed(code_phase_chips: f64, code_chips_per_sample: f64, n: usize) -> usize {
        (code_phase_chips + code_chips_per_sample * n as f64).floor() as usize + 1
    }
}

/// Reusable per-thread buffers of the kernel.
#[derive(Debug, Default)]
pub struct MixScratch {
    /// The code amplitude under each sample.
    code: Vec<f32>,
    /// The second component's code amplitude under each sample ([`mix_pair_into`]).
    code_q: Vec<f32>,
    /// Each chip's amplitude, then [`spread::PAD`] copies of the last.
    amps: Vec<f32>,
}

/// Add one channel to the block `(out_i, out_q)`.
///
/// The kernel runs with the widest vector instructions the CPU has (AVX-512, AVX2 or
/// baseline SSE2, detected at run time). No fused multiply-adds and no reassociation, so
/// every path computes the same IEEE operations per sample: the output is bit-identical
/// across CPUs.
pub fn mix_into(
    out_i: &mut [f32],
    out_q: &mut [f32],
    ch: &ChannelBlock<'_>,
    scratch: &mut MixScratch,
) {
    let n = out_i.len().min(out_q.len());
    spread_code(n, ch, scratch);
    pulp::Arch::new().dispatch(Kernel {
        out_i: &mut out_i[..n],
        out_q: &mut out_q[..n],
        ch,
        code: &scratch.code,
    });
}

/// `scratch.code[..n]`: the amplitude of the chip under each of `n` samples.
fn spread_code(n: usize, ch: &ChannelBlock<'_>, scratch: &mut MixScratch) {
    spread_chips(n, ch, ch.chips, &mut scratch.amps, &mut scratch.code);
}

/// `code[..n]`: the amplitude `ch.amplitude * sign` (or `* level`) of the chip of `chips`
/// under each of `n` samples at `ch`'s code phase and rate (`amps` is a buffer).
fn spread_chips(
    n: usize,
    ch: &ChannelBlock<'_>,
    chips: Chips<'_>,
    amps: &mut Vec<f32>,
    code: &mut Vec<f32>,
) {
    amps.clear();
    match chips {
        Chips::Signs(signs) => amps.extend(signs.iter().map(|&s| ch.amplitude * f32::from(s))),
        Chips::Levels(levels) => amps.extend(levels.iter().map(|&l| ch.amplitude * l)),
    }
    let last = amps.last().copied().unwrap_or(0.0);
    amps.extend([last; spread::PAD]);
    code.resize(n, 0.0);
    spread::spread(
        &mut code[..n],
        amps,
        ch.code_phase_chips,
        ch.code_chips_per_sample,
    );
}

/// [`mix_into`]'s arguments, for the CPU-feature dispatch.
struct Kernel<'a, 'b> {
    out_i: &'a mut [f32],
    out_q: &'a mut [f32],
    ch: &'a ChannelBlock<'b>,
    code: &'a [f32],
}

impl pulp::WithSimd for Kernel<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        mix(self.out_i, self.out_q, self.ch, self.code);
    }
}

/// The kernel itself, compiled once per instruction set: `out += code * carrier`, with
/// `code` as long as the outputs.
#[inline(always)]
fn mix(out_i: &mut [f32], out_q: &mut [f32], ch: &ChannelBlock<'_>, code: &[f32]) {
    let n = out_i.len().min(out_q.len()).min(code.len());

    // Lane l starts at phase p0 + l dp; every step advances all lanes by LANES dp.
    let LanePhasors {
        re: mut zr,
        im: mut zi,
        step_re: wr,
        step_im: wi,
    } = LanePhasors::<LANES>::new(ch.carrier_phase_cycles, ch.carrier_cycles_per_sample);

    let (out_i, tail_i) = out_i[..n].as_chunks_mut::<LANES>();
    let (out_q, tail_q) = out_q[..n].as_chunks_mut::<LANES>();
    let (code, tail_c) = code[..n].as_chunks::<LANES>();
    for ((oi, oq), c) in out_i.iter_mut().zip(out_q.iter_mut()).zip(code) {
        // Whole-array loads and stores: the compiler need not prove the three blocks
        // apart to use vector instructions.
        let (mut si, mut sq, c) = (*oi, *oq, *c);
        for l in 0..LANES {
            si[l] += c[l] * zr[l];
            sq[l] += c[l] * zi[l];
        }
        (*oi, *oq) = (si, sq);
        (zr, zi) = turn(&zr, &zi, wr, wi);
    }
    // The tail through fixed-size arrays, so that no lane is indexed with a run-time
    // bound (that would keep the phasor lanes in memory through the loop above).
    let mut c = [0f32; LANES];
    c[..tail_c.len()].copy_from_slice(tail_c);
    let (mut ti, mut tq) = ([0f32; LANES], [0f32; LANES]);
    for l in 0..LANES {
        ti[l] = c[l] * zr[l];
        tq[l] = c[l] * zi[l];
    }
    for (o, t) in tail_i.iter_mut().zip(&ti) {
        *o += t;
    }
    for (o, t) in tail_q.iter_mut().zip(&tq) {
        *o += t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Direct f64 evaluation of the same signal, sample by sample.
    fn reference(ch: &ChannelBlock<'_>, n: usize) -> (Vec<f64>, Vec<f64>) {
        (0..n)
            .map(|i| {
                let chip =
                    (ch.code_phase_chips + i as f64 * ch.code_chips_per_sample).floor() as usize;
                let Chips::Signs(signs) = ch.chips else {
                    unreachable!("the tests mix signs")
                };
                let a = f64::from(ch.amplitude) * f64::from(signs[chip]);
                let p = std::f64::consts::TAU
                    * (ch.carrier_phase_cycles + i as f64 * ch.carrier_cycles_per_sample);
                (a * p.cos(), a * p.sin())
            })
            .unzip()
    }

    /// A fixed pseudo-random +-1 sequence (LCG from `seed`), independent of the code
    /// generators.
    pub(super) fn signs(n: usize, seed: u32) -> Vec<i8> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                if x >> 31 == 0 { 1 } else { -1 }
            })
            .collect()
    }

    #[test]
    fn matches_direct_evaluation_over_a_block() {
        let n = 4092;
        let chips = signs(1100, 12345);
        for (carrier, code0, f_over_fs) in [
            (0.3, 0.0, 0.2443),
            (12345.678, 0.71, -0.0107),
            (-3.9, 0.999, 0.0),
        ] {
            let ch = ChannelBlock {
                amplitude: 0.7,
                carrier_phase_cycles: carrier,
                carrier_cycles_per_sample: f_over_fs,
                code_phase_chips: code0,
                code_chips_per_sample: 1.023e6 / 4.092e6 * (1.0 + 3e-6),
                chips: Chips::Signs(&chips),
            };
            assert!(ChannelBlock::chips_needed(code0, ch.code_chips_per_sample, n) <= chips.len());
            let (mut oi, mut oq) = (vec![0f32; n], vec![0f32; n]);
            mix_into(&mut oi, &mut oq, &ch, &mut MixScratch::default());
            let (ri, rq) = reference(&ch, n);
            let mut worst_phase: f64 = 0.0;
            let mut sign_errors = 0;
            for i in 0..n {
                let (a, b) = (f64::from(oi[i]), f64::from(oq[i]));
                // Samples whose chip sign differs from the reference (only possible right
                // at a chip edge, from rounding) are counted, not compared.
                if a * ri[i] + b * rq[i] < 0.0 {
                    sign_errors += 1;
                    continue;
                }
                let dphi = (b * ri[i] - a * rq[i]).atan2(a * ri[i] + b * rq[i]);
                worst_phase = worst_phase.max(dphi.abs());
                assert!(((a * a + b * b).sqrt() - 0.7).abs() < 1e-3);
            }
            assert!(sign_errors <= 2, "{sign_errors} chip-edge disagreements");
            assert!(worst_phase < 3e-4, "carrier phase error {worst_phase} rad");
        }
    }

    #[test]
    fn every_instruction_set_gives_the_same_bits() {
        // The dispatched kernel (AVX-512 / AVX2 where the CPU has them) against the same
        // code compiled for baseline x86-64.
        let chips = signs(1100, 12345);
        let ch = ChannelBlock {
            amplitude: 0.37,
            carrier_phase_cycles: 7.3,
            carrier_cycles_per_sample: 0.0123,
            code_phase_chips: 0.42,
            code_chips_per_sample: 0.25 * (1.0 - 1e-6),
            chips: Chips::Signs(&chips),
        };
        let n = 4093;
        let (mut ai, mut aq) = (vec![0.5f32; n], vec![-0.25f32; n]);
        let (mut bi, mut bq) = (ai.clone(), aq.clone());
        mix_into(&mut ai, &mut aq, &ch, &mut MixScratch::default());
        let mut scratch = MixScratch::default();
        spread_code(n, &ch, &mut scratch);
        mix(&mut bi, &mut bq, &ch, &scratch.code);
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&ai), bits(&bi));
        assert_eq!(bits(&aq), bits(&bq));
    }

    /// Multi-level chips: each sample is the channel's amplitude times its chip's level
    /// times the carrier, as directly evaluated.
    #[test]
    fn levels_weight_each_chip() {
        let levels: Vec<f32> = signs(400, 99)
            .iter()
            .enumerate()
            .map(|(k, &s)| f32::from(s) * [0.25, 1.5, 0.8][k % 3])
            .collect();
        let ch = ChannelBlock {
            amplitude: 0.5,
            carrier_phase_cycles: 0.1,
            carrier_cycles_per_sample: 0.013,
            code_phase_chips: 0.3,
            code_chips_per_sample: 0.6,
            chips: Chips::Levels(&levels),
        };
        let n = 600;
        let (mut oi, mut oq) = (vec![0f32; n], vec![0f32; n]);
        mix_into(&mut oi, &mut oq, &ch, &mut MixScratch::default());
        for i in 0..n {
            let chip = (0.3 + 0.6 * i as f64).floor() as usize;
            let a = 0.5 * f64::from(levels[chip]);
            let p = std::f64::consts::TAU * (0.1 + 0.013 * i as f64);
            assert!((f64::from(oi[i]) - a * p.cos()).abs() < 1e-4, "{i}");
            assert!((f64::from(oq[i]) - a * p.sin()).abs() < 1e-4, "{i}");
        }
    }

    #[test]
    fn adds_to_what_is_already_there() {
        let chips = signs(40, 12345);
        let ch = ChannelBlock {
            amplitude: 1.0,
            carrier_phase_cycles: 0.0,
            carrier_cycles_per_sample: 0.0,
            code_phase_chips: 0.0,
            code_chips_per_sample: 0.25,
            chips: Chips::Signs(&chips),
        };
        let (mut oi, mut oq) = (vec![2f32; 100], vec![0f32; 100]);
        mix_into(&mut oi, &mut oq, &ch, &mut MixScratch::default());
        for i in 0..100 {
            assert_eq!(oi[i], 2.0 + f32::from(chips[i / 4]));
            assert_eq!(oq[i], 0.0);
        }
    }
}
