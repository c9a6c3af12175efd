//! The two-component kernel: a signal's data and pilot components in quadrature,
//! `amplitude (d + j p) exp(j 2 pi phase)` (the pilot a quarter cycle ahead, as Galileo
//! E5a-Q is of E5a-I), added to a block in one pass with one phasor recurrence for both,
//! where two calls of [`super::mix_into`] would turn the phasors twice.

use super::{ChannelBlock, Chips, LANES, MixScratch, spread_chips};
use skyforge_gnss::nco::{LanePhasors, turn};

/// Add the channel `ch` (its `chips` the in-phase component's, the data's) and the
/// quadrature component `quadrature` (the pilot's signs, or BeiDou B1C's quadrature
/// sub-chip levels; same code phase and rate, chips aligned) to the block
/// `(out_i, out_q)`. Like [`super::mix_into`], the same IEEE operations on every CPU.
pub fn mix_pair_into(
    out_i: &mut [f32],
    out_q: &mut [f32],
    ch: &ChannelBlock<'_>,
    quadrature: Chips<'_>,
    scratch: &mut MixScratch,
) {
    let n = out_i.len().min(out_q.len());
    spread_chips(n, ch, ch.chips, &mut scratch.amps, &mut scratch.code);
    spread_chips(n, ch, quadrature, &mut scratch.amps, &mut scratch.code_q);
    pulp::Arch::new().dispatch(Kernel {
        out_i: &mut out_i[..n],
        out_q: &mut out_q[..n],
        ch,
        data: &scratch.code,
        pilot: &scratch.code_q,
    });
}

/// [`mix_pair_into`]'s arguments, for the CPU-feature dispatch.
struct Kernel<'a, 'b> {
    out_i: &'a mut [f32],
    out_q: &'a mut [f32],
    ch: &'a ChannelBlock<'b>,
    data: &'a [f32],
    pilot: &'a [f32],
}

impl pulp::WithSimd for Kernel<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        mix_pair(self.out_i, self.out_q, self.ch, self.data, self.pilot);
    }
}

/// `out += (d + j p) * carrier`, with `d` and `p` as long as the outputs.
#[inline(always)]
fn mix_pair(out_i: &mut [f32], out_q: &mut [f32], ch: &ChannelBlock<'_>, d: &[f32], p: &[f32]) {
    let n = out_i.len().min(out_q.len()).min(d.len()).min(p.len());
    let LanePhasors {
        re: mut zr,
        im: mut zi,
        step_re: wr,
        step_im: wi,
    } = LanePhasors::<LANES>::new(ch.carrier_phase_cycles, ch.carrier_cycles_per_sample);
    let (out_i, tail_i) = out_i[..n].as_chunks_mut::<LANES>();
    let (out_q, tail_q) = out_q[..n].as_chunks_mut::<LANES>();
    let (d, tail_d) = d[..n].as_chunks::<LANES>();
    let (p, tail_p) = p[..n].as_chunks::<LANES>();
    for (((oi, oq), d), p) in out_i.iter_mut().zip(out_q.iter_mut()).zip(d).zip(p) {
        let (mut si, mut sq, d, p) = (*oi, *oq, *d, *p);
        for l in 0..LANES {
            si[l] += d[l] * zr[l] - p[l] * zi[l];
            sq[l] += d[l] * zi[l] + p[l] * zr[l];
        }
        (*oi, *oq) = (si, sq);
        (zr, zi) = turn(&zr, &zi, wr, wi);
    }
    let (mut dt, mut pt) = ([0f32; LANES], [0f32; LANES]);
    dt[..tail_d.len()].copy_from_slice(tail_d);
    pt[..tail_p.len()].copy_from_slice(tail_p);
    let (mut ti, mut tq) = ([0f32; LANES], [0f32; LANES]);
    for l in 0..LANES {
        ti[l] = dt[l] * zr[l] - pt[l] * zi[l];
        tq[l] = dt[l] * zi[l] + pt[l] * zr[l];
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
    use super::super::tests::signs;
    use super::*;
    use crate::synth::mix::mix_into;

    /// One pass of the pair kernel against two passes of the one-component kernel, the
    /// second a quarter cycle ahead: the same signal within f32 rounding.
    #[test]
    fn equals_two_components_a_quarter_cycle_apart() {
        let (data, pilot) = (signs(2700, 1), signs(2700, 7));
        let n = 5000;
        let ch = ChannelBlock {
            amplitude: 0.6,
            carrier_phase_cycles: 17.31,
            carrier_cycles_per_sample: -0.0371,
            code_phase_chips: 0.37,
            code_chips_per_sample: 0.5 * (1.0 + 2e-6),
            chips: Chips::Signs(&data),
        };
        let (mut ai, mut aq) = (vec![0.25f32; n], vec![-0.5f32; n]);
        mix_pair_into(
            &mut ai,
            &mut aq,
            &ch,
            Chips::Signs(&pilot),
            &mut MixScratch::default(),
        );
        let (mut bi, mut bq) = (vec![0.25f32; n], vec![-0.5f32; n]);
        let mut scratch = MixScratch::default();
        mix_into(&mut bi, &mut bq, &ch, &mut scratch);
        let quarter = ChannelBlock {
            carrier_phase_cycles: ch.carrier_phase_cycles + 0.25,
            chips: Chips::Signs(&pilot),
            ..ch
        };
        mix_into(&mut bi, &mut bq, &quarter, &mut scratch);
        for k in 0..n {
            assert!((ai[k] - bi[k]).abs() < 2e-4, "{k}: {} vs {}", ai[k], bi[k]);
            assert!((aq[k] - bq[k]).abs() < 2e-4, "{k}: {} vs {}", aq[k], bq[k]);
        }
    }

    /// The dispatched kernel and the same code compiled for baseline x86-64 agree to the
    /// bit.
    #[test]
    fn every_instruction_set_gives_the_same_bits() {
        let (data, pilot) = (signs(1100, 3), signs(1100, 5));
        let ch = ChannelBlock {
            amplitude: 0.37,
            carrier_phase_cycles: 7.3,
            carrier_cycles_per_sample: 0.0123,
            code_phase_chips: 0.42,
            code_chips_per_sample: 0.25 * (1.0 - 1e-6),
            chips: Chips::Signs(&data),
        };
        let n = 4093;
        let (mut ai, mut aq) = (vec![0.5f32; n], vec![-0.25f32; n]);
        let (mut bi, mut bq) = (ai.clone(), aq.clone());
        let mut scratch = MixScratch::default();
        mix_pair_into(&mut ai, &mut aq, &ch, Chips::Signs(&pilot), &mut scratch);
        mix_pair(&mut bi, &mut bq, &ch, &scratch.code, &scratch.code_q);
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&ai), bits(&bi));
        assert_eq!(bits(&aq), bits(&bq));
    }
}
