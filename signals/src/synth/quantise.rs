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

use super::format::SampleFormat;

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

/// Quantises blocks of I/Q (or real) samples into a file container.
#[derive(Debug, Clone)]
pub struct Quantiser {
    format: SampleFormat,
    /// `None` for float output.
    bits: Option<u8>,
    scale: f32,
    max_level: f32,
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
        let (scale, max_level) = match bits {
            None => (1.0, f32::INFINITY),
            Some(b) => {
                let max_level = if b <= 4 {
                    ((1u32 << b) - 1) as f32
                } else {
                    ((1u32 << (b - 1)) - 1) as f32
                };
                (noise_level(b) / noise_sigma, max_level)
            }
        };
        Ok(Self {
            format,
            bits,
            scale,
            max_level,
            clipped: 0,
        })
    }

    /// Components clipped so far.
    pub fn clipped(&self) -> u64 {
        self.clipped
    }

    /// The output level of one input component.
    fn level(&mut self, x: f32) -> f32 {
        let Some(bits) = self.bits else { return x };
        let y = x * self.scale;
        let q = if bits <= 4 {
            2.0 * (y * 0.5).floor() + 1.0
        } else {
            y.round()
        };
        if q.abs() > self.max_level {
            // 1- and 2-bit words saturate by design; clipping is counted from 4 bits up.
            self.clipped += u64::from(bits >= 4);
            q.signum() * self.max_level
        } else {
            q
        }
    }

    /// Append the block to `out` in the container's byte layout (interleaved I/Q for
    /// complex formats; only `i` for real IF).
    pub fn write(&mut self, i: &[f32], q: &[f32], out: &mut Vec<u8>) {
        out.reserve(i.len() * self.format.bytes_per_sample());
        match self.format {
            SampleFormat::Ci8 => {
                for (&a, &b) in i.iter().zip(q) {
                    out.push(self.level(a) as i8 as u8);
                    out.push(self.level(b) as i8 as u8);
                }
            }
            SampleFormat::Ri8 => {
                for &a in i {
                    out.push(self.level(a) as i8 as u8);
                }
            }
            SampleFormat::Ci16 => {
                for (&a, &b) in i.iter().zip(q) {
                    out.extend_from_slice(&(self.level(a) as i16).to_le_bytes());
                    out.extend_from_slice(&(self.level(b) as i16).to_le_bytes());
                }
            }
            SampleFormat::Cf32 => {
                for (&a, &b) in i.iter().zip(q) {
                    out.extend_from_slice(&a.to_le_bytes());
                    out.extend_from_slice(&b.to_le_bytes());
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
