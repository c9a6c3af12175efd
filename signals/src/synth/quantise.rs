//! Front-end quantisation to 1, 2, 4, 8 or 16 bits (or float), with a fixed scale set the
//! way an ideal AGC would set it from the known noise level, and a clipping count.
//!
//! Levels: 1, 2 and 4 bits are mid-rise with odd integer levels (+-1; +-1, +-3; +-1..+-15);
//! 8 and 16 bits are mid-tread, symmetric (+-127; +-32767). The scale maps the noise
//! standard deviation per component to `NOISE_LEVEL[bits]` output units: the 2-bit
//! threshold then sits at 1 sigma (the classic optimum), and 4/8/16 bits clip beyond about
//! 3.75, 5 and 8 sigma. Because the scale comes from the scenario, not from measured
//! blocks, the output does not depend on block size. The clip count counts components
//! beyond the top level for 4, 8 and 16 bits (1- and 2-bit words saturate by design).

use skyforge_gnss::sample_format::SampleFormat;

/// Word lengths the quantiser supports.
pub const SUPPORTED_BITS: [u8; 5] = [1, 2, 4, 8, 16];

/// Output units per noise standard deviation for each word length.
fn noise_level(bits: u8) -> f32 {
    match bits {
        1 => 1.0,
        2 => 2.0,
        4 => 4.0,
        8 => 25.4,
        _ => 4096.0,
    }
}

/// Error configuring the quantiser.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuantiseError {
    #[error(
        "quantisation to {bits} bits is not supported; allowed: 1, 2, 4, 8, 16 (or float output)"
    )]
    Bits { bits: u8 },
    #[error("{bits}-bit samples do not fit the {format:?} container")]
    Container { bits: u8, format: SampleFormat },
    #[error("the noise standard deviation must be positive and finite, got {sigma}")]
    Sigma { sigma: f32 },
}

/// Components quantised per inner loop: fixed-size arrays the compiler vectorises.
const CHUNK: usize = 64;

/// How one component maps to an output level.
#[derive(Debug, Clone, Copy)]
enum Rule {
    /// Float output: no quantisation.
    Float,
    /// 1, 2, 4 bits: odd levels `2 floor(y / 2) + 1`, saturating at `+-max`; clipping is
    /// counted only for 4 bits.
    MidRise { max: i32, count: bool },
    /// 8, 16 bits: `round(y)` (half away from zero), saturating at `+-max`.
    MidTread { max: i32 },
}

/// 1.5 2^23: adding it to |y| < 2^22 leaves round-half-even(y) in the low mantissa
/// bits, with plain float adds (no rounding or conversion instruction needed, so the
/// loops vectorise on baseline x86-64).
const MAGIC: f32 = 12_582_912.0;

/// `(round-half-even(y) as i32, as f32)` for |y| < 2^22.
#[inline(always)]
fn round_even(y: f32) -> (i32, f32) {
    let big = y + MAGIC;
    (
        big.to_bits().wrapping_sub(MAGIC.to_bits()) as i32,
        big - MAGIC,
    )
}

/// `round(y)` with halves away from zero, for |y| < 2^22.
#[inline(always)]
fn round_half_away(y: f32) -> i32 {
    let (r, rf) = round_even(y);
    // y - rf is exact; a tie rounded towards zero moves one step outwards.
    let d = y - rf;
    r + i32::from(d == 0.5 && y > 0.0) - i32::from(d == -0.5 && y < 0.0)
}

/// `floor(h)` for |h| < 2^22.
#[inline(always)]
fn floor_i32(h: f32) -> i32 {
    let (r, rf) = round_even(h);
    r - i32::from(rf > h)
}

/// 1, 2, 4 bits: the odd level `2 floor(y / 2) + 1` saturated at `+-max`, and whether
/// it saturated.
#[inline(always)]
fn mid_rise(y: f32, max: i32) -> (i32, bool) {
    // Clamping keeps the cast exact; anything clamped is beyond max anyway.
    let bound = (max + 1) as f32;
    let q = 2 * floor_i32((y * 0.5).clamp(-bound, bound)) + 1;
    (q.clamp(-max, max), q > max || q < -max)
}

/// 8, 16 bits: `round(y)` saturated at `+-max`, and whether it saturated.
#[inline(always)]
fn mid_tread(y: f32, max: i32) -> (i32, bool) {
    let top = max as f32;
    (round_half_away(y.clamp(-top, top)), y.abs() >= top + 0.5)
}

/// [`Quantiser::write`]'s arguments, for the CPU-feature dispatch.
struct Write<'a> {
    quantiser: &'a mut Quantiser,
    i: &'a [f32],
    q: &'a [f32],
    out: &'a mut [u8],
}

impl pulp::WithSimd for Write<'_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        self.quantiser.write_block(self.i, self.q, self.out);
    }
}

/// Quantises blocks of I/Q (or real) samples into a file container.
#[derive(Debug, Clone)]
pub struct Quantiser {
    format: SampleFormat,
    rule: Rule,
    scale: f32,
    clipped: u64,
}

impl Quantiser {
    /// A quantiser for `format` at `bits` (ignored for `cf32`), for input whose noise has
    /// standard deviation `noise_sigma` per component.
    pub fn new(
        format: SampleFormat,
        bits: Option<u8>,
        noise_sigma: f32,
    ) -> Result<Self, QuantiseError> {
        if !(noise_sigma.is_finite() && noise_sigma > 0.0) {
            return Err(QuantiseError::Sigma { sigma: noise_sigma });
        }
        let bits = match (format.max_bits(), bits) {
            (None, _) => None,
            (Some(max), Some(b)) => {
                if !SUPPORTED_BITS.contains(&b) {
                    return Err(QuantiseError::Bits { bits: b });
                }
                if b > max {
                    return Err(QuantiseError::Container { bits: b, format });
                }
                Some(b)
            }
            (Some(max), None) => Some(max),
        };
        let (rule, scale) = match bits {
            None => (Rule::Float, 1.0),
            Some(b) if b <= 4 => (
                Rule::MidRise {
                    max: (1 << b) - 1,
                    count: b >= 4,
                },
                noise_level(b) / noise_sigma,
            ),
            Some(b) => (
                Rule::MidTread {
                    max: (1 << (b - 1)) - 1,
                },
                noise_level(b) / noise_sigma,
            ),
        };
        Ok(Self {
            format,
            rule,
            scale,
            clipped: 0,
        })
    }

    /// Components clipped so far.
    pub fn clipped(&self) -> u64 {
        self.clipped
    }

    /// Levels of one chunk of input components (`x.len() <= CHUNK`) into `levels`.
    #[inline(always)]
    fn chunk_levels(&mut self, x: &[f32], levels: &mut [i32; CHUNK]) {
        let scale = self.scale;
        let mut clipped = 0u32;
        // One loop per rule, so that each one vectorises.
        match self.rule {
            Rule::Float => {}
            Rule::MidRise { max, count } => {
                for (l, &v) in levels.iter_mut().zip(x) {
                    let (q, clip) = mid_rise(v * scale, max);
                    *l = q;
                    clipped += u32::from(clip);
                }
                clipped *= u32::from(count);
            }
            Rule::MidTread { max } => {
                for (l, &v) in levels.iter_mut().zip(x) {
                    let (q, clip) = mid_tread(v * scale, max);
                    *l = q;
                    clipped += u32::from(clip);
                }
            }
        }
        self.clipped += u64::from(clipped);
    }

    /// Append the block to `out` in the container's byte layout (interleaved I/Q for
    /// complex formats; only `i` for real IF).
    pub fn write(&mut self, i: &[f32], q: &[f32], out: &mut Vec<u8>) {
        let start = out.len();
        out.resize(start + self.bytes(i, q), 0);
        self.write_into(i, q, &mut out[start..]);
    }

    /// [`Self::write`] to the front of `out`, which must hold [`Self::bytes`] of them.
    /// Runs with the widest vector instructions the CPU has; integer results, so
    /// identical on every path.
    pub fn write_into(&mut self, i: &[f32], q: &[f32], out: &mut [u8]) {
        pulp::Arch::new().dispatch(Write {
            quantiser: self,
            i,
            q,
            out,
        });
    }

    /// Bytes [`Self::write`] appends for `i` and `q`.
    pub fn bytes(&self, i: &[f32], q: &[f32]) -> usize {
        self.samples(i, q) * self.format.bytes_per_sample()
    }

    /// Samples of a block: complex formats take `i` and `q` pairs, real IF `i` alone.
    fn samples(&self, i: &[f32], q: &[f32]) -> usize {
        if self.format.is_complex() {
            i.len().min(q.len())
        } else {
            i.len()
        }
    }

    /// [`Self::write`], compiled once per instruction set. The ci8 and ci16 loops are
    /// written apart on purpose: one loop for both with a packing closure made the
    /// synthesis bar 3 % slower (scripts/bench-synth-bar.sh, 2026-11-28).
    #[inline(always)]
    fn write_block(&mut self, i: &[f32], q: &[f32], out: &mut [u8]) {
        let n = self.samples(i, q);
        let per = self.format.bytes_per_sample();
        let out = &mut out[..n * per];
        let (mut li, mut lq) = ([0i32; CHUNK], [0i32; CHUNK]);
        match self.format {
            SampleFormat::Ci8 => {
                for ((ci, cq), bytes) in i[..n]
                    .chunks(CHUNK)
                    .zip(q[..n].chunks(CHUNK))
                    .zip(out.chunks_mut(2 * CHUNK))
                {
                    self.chunk_levels(ci, &mut li);
                    self.chunk_levels(cq, &mut lq);
                    for ((b, &a), &c) in bytes.chunks_exact_mut(2).zip(&li).zip(&lq) {
                        b[0] = a as i8 as u8;
                        b[1] = c as i8 as u8;
                    }
                }
            }
            SampleFormat::Ri8 => {
                for (ci, bytes) in i[..n].chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
                    self.chunk_levels(ci, &mut li);
                    for (b, &a) in bytes.iter_mut().zip(&li) {
                        *b = a as i8 as u8;
                    }
                }
            }
            SampleFormat::Ci16 => {
                for ((ci, cq), bytes) in i[..n]
                    .chunks(CHUNK)
                    .zip(q[..n].chunks(CHUNK))
                    .zip(out.chunks_mut(4 * CHUNK))
                {
                    self.chunk_levels(ci, &mut li);
                    self.chunk_levels(cq, &mut lq);
                    for ((b, &a), &c) in bytes.chunks_exact_mut(4).zip(&li).zip(&lq) {
                        b[..2].copy_from_slice(&(a as i16).to_le_bytes());
                        b[2..].copy_from_slice(&(c as i16).to_le_bytes());
                    }
                }
            }
            SampleFormat::Cf32 => {
                for ((&a, &b), bytes) in i[..n].iter().zip(&q[..n]).zip(out.chunks_exact_mut(8)) {
                    bytes[..4].copy_from_slice(&a.to_le_bytes());
                    bytes[4..].copy_from_slice(&b.to_le_bytes());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    impl Quantiser {
        /// The output level of one input component, through the block path.
        fn level(&mut self, x: f32) -> f32 {
            let mut l = [0; CHUNK];
            self.chunk_levels(&[x], &mut l);
            l[0] as f32
        }
    }

    /// The levels by their definition, with the standard library's rounding.
    fn definition(bits: u8, y: f32) -> (f32, bool) {
        let max = if bits <= 4 {
            ((1u32 << bits) - 1) as f32
        } else {
            ((1u32 << (bits - 1)) - 1) as f32
        };
        let q = if bits <= 4 {
            2.0 * (y * 0.5).floor() + 1.0
        } else {
            y.round()
        };
        if q.abs() > max {
            (q.signum() * max, bits >= 4)
        } else {
            (q, false)
        }
    }

    #[test]
    fn block_path_matches_the_definition_including_halves_and_clipping() {
        // Halves, near-halves, integers, large values and a long pseudo-random sweep.
        let mut xs: Vec<f32> = Vec::new();
        for k in -70_000..70_000 {
            let h = k as f32 * 0.5;
            xs.extend([h, h.next_up(), h.next_down()]);
        }
        xs.extend([1e9, -1e9, 3.4e38, -3.4e38, 0.0, -0.0]);
        let mut x: u32 = 99;
        xs.extend((0..100_000).map(|_| {
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (x as i32) as f32 * 1e-5
        }));
        for (bits, format) in [
            (1, SampleFormat::Ci8),
            (2, SampleFormat::Ci8),
            (4, SampleFormat::Ci8),
            (8, SampleFormat::Ci8),
            (16, SampleFormat::Ci16),
        ] {
            let mut q = Quantiser::new(format, Some(bits), noise_level(bits)).unwrap();
            let mut want_clipped = 0;
            for &x in &xs {
                let (want, clip) = definition(bits, x);
                want_clipped += u64::from(clip);
                assert_eq!(q.level(x), want, "{bits} bits, x = {x}");
            }
            assert_eq!(q.clipped(), want_clipped, "{bits} bits");
            // The same through write(), in blocks that are not a multiple of the chunk.
            let mut q = Quantiser::new(format, Some(bits), noise_level(bits)).unwrap();
            let mut out = Vec::new();
            for block in xs.chunks(1000) {
                q.write(block, block, &mut out);
            }
            assert_eq!(q.clipped(), 2 * want_clipped);
            let per = format.bytes_per_sample();
            for (k, &x) in xs.iter().enumerate().step_by(97) {
                let b = &out[k * per..(k + 1) * per];
                let got = if per == 2 {
                    f32::from(b[1] as i8)
                } else {
                    f32::from(i16::from_le_bytes([b[2], b[3]]))
                };
                assert_eq!(got, definition(bits, x).0);
            }
        }
    }

    #[test]
    fn levels_are_odd_for_short_words_and_symmetric_for_long_ones() {
        let mut q2 = Quantiser::new(SampleFormat::Ci8, Some(2), 1.0).unwrap();
        // sigma maps to 2 units: thresholds at 0 and +-1 sigma.
        let got: Vec<f32> = [-5.0, -0.8, -0.2, 0.2, 0.8, 5.0]
            .iter()
            .map(|&x| q2.level(x))
            .collect();
        assert_eq!(got, [-3.0, -1.0, -1.0, 1.0, 1.0, 3.0]);
        assert_eq!(q2.clipped(), 0);
        let mut q1 = Quantiser::new(SampleFormat::Ci8, Some(1), 1.0).unwrap();
        assert_eq!((q1.level(-0.01), q1.level(0.01)), (-1.0, 1.0));
        let mut q8 = Quantiser::new(SampleFormat::Ci8, Some(8), 1.0).unwrap();
        assert_eq!(q8.level(100.0), 127.0);
        assert_eq!(q8.level(-100.0), -127.0);
        assert_eq!(q8.clipped(), 2);
        assert_eq!(q8.level(1.0), 25.0);
        let mut q16 = Quantiser::new(SampleFormat::Ci16, Some(16), 2.0).unwrap();
        assert_eq!(q16.level(1.0), 2048.0);
    }

    #[test]
    fn rejects_what_cannot_be_represented() {
        assert_eq!(
            Quantiser::new(SampleFormat::Ci8, Some(3), 1.0).unwrap_err(),
            QuantiseError::Bits { bits: 3 }
        );
        assert!(matches!(
            Quantiser::new(SampleFormat::Ci8, Some(16), 1.0),
            Err(QuantiseError::Container { bits: 16, .. })
        ));
        assert!(Quantiser::new(SampleFormat::Ci8, Some(8), 0.0).is_err());
        assert!(Quantiser::new(SampleFormat::Ci8, Some(8), f32::NAN).is_err());
    }

    #[test]
    fn byte_layouts() {
        let (i, q) = ([1.0f32, -2.0], [0.5f32, 3.0]);
        let mut out = Vec::new();
        Quantiser::new(SampleFormat::Ci16, Some(16), 4096.0)
            .unwrap()
            .write(&i, &q, &mut out);
        // I, Q interleaved; 0.5 rounds away from zero to 1.
        assert_eq!(out, [1, 0, 1, 0, 254, 255, 3, 0]);
        let mut out = Vec::new();
        Quantiser::new(SampleFormat::Cf32, None, 1.0)
            .unwrap()
            .write(&i, &q, &mut out);
        assert_eq!(out.len(), 16);
        assert_eq!(f32::from_le_bytes(out[12..16].try_into().unwrap()), 3.0);
        let mut out = Vec::new();
        Quantiser::new(SampleFormat::Ri8, Some(8), 25.4)
            .unwrap()
            .write(&i, &q, &mut out);
        assert_eq!(out, [1, (-2i8) as u8]);
    }

    #[test]
    fn gaussian_noise_through_two_bits_hits_the_textbook_occupancy() {
        // With the threshold at 1 sigma, |level| = 3 occurs with probability 2 Q(1) = 0.3173.
        let mut x: u64 = 7;
        let mut normal = || {
            // Box-Muller on a 64-bit LCG: independent of the crate's noise generator.
            let mut u = || {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64
            };
            let (u1, u2) = (u(), u());
            ((-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()) as f32
        };
        let mut q = Quantiser::new(SampleFormat::Ci8, Some(2), 1.0).unwrap();
        let n = 200_000;
        let outer = (0..n).filter(|_| q.level(normal()).abs() == 3.0).count() as f64 / n as f64;
        assert!((outer - 0.3173).abs() < 0.005, "{outer}");
    }
}
