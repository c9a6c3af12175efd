//! Sample containers and their decoders: interleaved little-endian complex `ci8`, `ci16`,
//! `cf32`, and real `ri8`.
//!
//! Full scale: integer containers are scaled so that their full scale `2^(bits-1)` maps to
//! 1.0 (`ci8`/`ri8`: `v / 128`, `ci16`: `v / 32768`; exact in f32); `cf32` components are
//! passed through unchanged (their scale is whatever the writer used: SkyForge's float
//! output has noise of standard deviation 1 per component).

use super::error::InputError;
use num_complex::Complex32;

/// The sample containers (shared with the synthesiser that writes them).
pub use skyforge_gnss::sample_format::SampleFormat;

/// The format named by a command-line `--format` value (a SigMF `core:datatype` or a
/// shorter spelling); `origin` (where the name came from) goes into the error message.
pub fn parse_format(name: &str, origin: &str) -> Result<SampleFormat, InputError> {
    SampleFormat::from_name(name).ok_or_else(|| InputError::UnknownDatatype {
        origin: origin.to_owned(),
        found: name.to_owned(),
    })
}

/// Samples per inner loop of the integer decoders.
const CHUNK: usize = 64;

/// Decodes interleaved `ci8` bytes into `out`, scaled by 1/128; returns the number of
/// samples decoded (`min(bytes.len() / 2, out.len())`).
pub fn decode_ci8(bytes: &[u8], out: &mut [Complex32]) -> usize {
    const SCALE: f32 = 1.0 / 128.0;
    let n = (bytes.len() / 2).min(out.len());
    // Components are converted as a flat run first (which vectorises), then paired.
    let mut flat = [0.0f32; 2 * CHUNK];
    for (o, b) in out[..n]
        .chunks_mut(CHUNK)
        .zip(bytes[..2 * n].chunks(2 * CHUNK))
    {
        for (f, &v) in flat.iter_mut().zip(b) {
            *f = f32::from(v as i8) * SCALE;
        }
        for (c, p) in o.iter_mut().zip(flat.as_chunks::<2>().0) {
            *c = Complex32::new(p[0], p[1]);
        }
    }
    n
}

/// Decodes interleaved little-endian `ci16` bytes into `out`, scaled by 1/32768; returns
/// the number of samples decoded.
pub fn decode_ci16(bytes: &[u8], out: &mut [Complex32]) -> usize {
    const SCALE: f32 = 1.0 / 32768.0;
    let n = (bytes.len() / 4).min(out.len());
    // As in decode_ci8: a flat run of components, then pairs.
    let mut flat = [0.0f32; 2 * CHUNK];
    for (o, b) in out[..n]
        .chunks_mut(CHUNK)
        .zip(bytes[..4 * n].chunks(4 * CHUNK))
    {
        for (f, w) in flat.iter_mut().zip(b.as_chunks::<2>().0) {
            *f = f32::from(i16::from_le_bytes(*w)) * SCALE;
        }
        for (c, p) in o.iter_mut().zip(flat.as_chunks::<2>().0) {
            *c = Complex32::new(p[0], p[1]);
        }
    }
    n
}

/// Decodes interleaved little-endian `cf32` bytes into `out` unchanged; returns the number
/// of samples decoded.
pub fn decode_cf32(bytes: &[u8], out: &mut [Complex32]) -> usize {
    let n = (bytes.len() / 8).min(out.len());
    for (o, b) in out[..n].iter_mut().zip(bytes.chunks_exact(8)) {
        *o = Complex32::new(
            f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            f32::from_le_bytes([b[4], b[5], b[6], b[7]]),
        );
    }
    n
}

/// Decodes real `ri8` bytes into `out`, scaled by 1/128; returns the number of samples
/// decoded.
pub fn decode_ri8(bytes: &[u8], out: &mut [f32]) -> usize {
    const SCALE: f32 = 1.0 / 128.0;
    let n = bytes.len().min(out.len());
    for (o, &b) in out[..n].iter_mut().zip(bytes) {
        *o = f32::from(b as i8) * SCALE;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn zeros(n: usize) -> Vec<Complex32> {
        vec![Complex32::new(0.0, 0.0); n]
    }

    #[test]
    fn names_round_trip_and_unknown_names_list_the_allowed_ones() {
        for f in SampleFormat::ALL {
            assert_eq!(parse_format(f.sigmf_datatype(), "x").unwrap(), f);
        }
        assert_eq!(
            parse_format("CI16", "--format").unwrap(),
            SampleFormat::Ci16
        );
        assert_eq!(
            parse_format("cf32", "--format").unwrap(),
            SampleFormat::Cf32
        );
        let e = parse_format("ci16_be", "--format").unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "--format: unknown sample datatype \"ci16_be\"; allowed: {}",
                super::super::error::ALLOWED_DATATYPES
            )
        );
    }

    #[test]
    fn extreme_codes_map_to_the_documented_full_scale() {
        let mut out = zeros(2);
        assert_eq!(decode_ci8(&[0x80, 0x7f, 0x01, 0xff], &mut out), 2);
        assert_eq!(out[0], Complex32::new(-1.0, 127.0 / 128.0));
        assert_eq!(out[1], Complex32::new(1.0 / 128.0, -1.0 / 128.0));
        assert_eq!(decode_ci16(&[0x00, 0x80, 0xff, 0x7f], &mut out), 1);
        assert_eq!(out[0], Complex32::new(-1.0, 32767.0 / 32768.0));
        let mut real = [0.0f32; 3];
        assert_eq!(decode_ri8(&[0x80, 0x00, 0x40], &mut real), 3);
        assert_eq!(real, [-1.0, 0.0, 0.5]);
    }

    #[test]
    fn partial_trailing_bytes_are_not_decoded() {
        let mut out = zeros(4);
        assert_eq!(decode_ci16(&[1, 0, 2, 0, 3, 0], &mut out), 1);
        assert_eq!(decode_cf32(&[0; 15], &mut out), 1);
        // The output length limits too.
        assert_eq!(decode_ci8(&[1; 20], &mut out), 4);
    }

    proptest! {
        #[test]
        fn ci8_decodes_what_was_encoded(v in prop::collection::vec(any::<(i8, i8)>(), 0..300)) {
            let bytes: Vec<u8> = v.iter().flat_map(|&(i, q)| [i as u8, q as u8]).collect();
            let mut out = zeros(v.len());
            prop_assert_eq!(decode_ci8(&bytes, &mut out), v.len());
            for (o, &(i, q)) in out.iter().zip(&v) {
                prop_assert_eq!(o.re * 128.0, f32::from(i));
                prop_assert_eq!(o.im * 128.0, f32::from(q));
            }
        }

        #[test]
        fn ci16_decodes_what_was_encoded(v in prop::collection::vec(any::<(i16, i16)>(), 0..300)) {
            let bytes: Vec<u8> = v
                .iter()
                .flat_map(|&(i, q)| [i.to_le_bytes(), q.to_le_bytes()].concat())
                .collect();
            let mut out = zeros(v.len());
            prop_assert_eq!(decode_ci16(&bytes, &mut out), v.len());
            for (o, &(i, q)) in out.iter().zip(&v) {
                prop_assert_eq!(o.re * 32768.0, f32::from(i));
                prop_assert_eq!(o.im * 32768.0, f32::from(q));
            }
        }

        #[test]
        fn cf32_decodes_what_was_encoded(
            v in prop::collection::vec((-1e30f32..1e30, -1e30f32..1e30), 0..300)
        ) {
            let bytes: Vec<u8> = v
                .iter()
                .flat_map(|&(i, q)| [i.to_le_bytes(), q.to_le_bytes()].concat())
                .collect();
            let mut out = zeros(v.len());
            prop_assert_eq!(decode_cf32(&bytes, &mut out), v.len());
            for (o, &(i, q)) in out.iter().zip(&v) {
                prop_assert_eq!((o.re, o.im), (i, q));
            }
        }

        #[test]
        fn ri8_decodes_what_was_encoded(v in prop::collection::vec(any::<i8>(), 0..300)) {
            let bytes: Vec<u8> = v.iter().map(|&x| x as u8).collect();
            let mut out = vec![0.0f32; v.len()];
            prop_assert_eq!(decode_ri8(&bytes, &mut out), v.len());
            for (o, &x) in out.iter().zip(&v) {
                prop_assert_eq!(*o * 128.0, f32::from(x));
            }
        }

        #[test]
        fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
            let mut out = zeros(64);
            let mut real = vec![0.0f32; 64];
            decode_ci8(&bytes, &mut out);
            decode_ci16(&bytes, &mut out);
            decode_cf32(&bytes, &mut out);
            decode_ri8(&bytes, &mut real);
        }
    }
}
