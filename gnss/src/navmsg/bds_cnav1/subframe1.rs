//! Subframe 1 of B-CNAV1 (BDS-SIS-ICD-B1C-1.0 6.2.2.1, Table 6-1, Figure 6-2): the 6-bit
//! PRN as a BCH(21, 6) word and the 8-bit SOH as a BCH(51, 8) word, 72 symbols.
//!
//! The encoders are k-stage shift registers: the k information bits go out first (gate 1)
//! and then the register, closed by g(x), runs on (gate 2). SkyForge reads Figure 6-2 as
//! the recurrence sum g_i s_(j+i) = 0 over the output sequence s, with g(x) = x^6 + x^4 +
//! x^2 + x + 1 for (21, 6) and x^8 + x^7 + x^4 + x^3 + x^2 + x + 1 for (51, 8); the
//! words have minimum distances 8 and 24, so the codes correct the t = 3 and t = 11
//! errors Table 6-1 states (see the tests). Decoding is maximum likelihood over the 64 or
//! 256 words.

/// Symbols of the PRN word and of the SOH word.
pub(super) const PRN_SYMBOLS: usize = 21;
pub(super) const SOH_SYMBOLS: usize = 51;

/// The word of `k` information bits `value` (MSB first) under the recurrence with
/// taps `taps` (the i with g_i = 1, i < k), `n` symbols long.
fn word(value: u32, k: usize, n: usize, taps: &[usize]) -> Vec<u8> {
    let mut s: Vec<u8> = (0..k).map(|i| ((value >> (k - 1 - i)) & 1) as u8).collect();
    while s.len() < n {
        let j = s.len() - k;
        s.push(taps.iter().fold(0, |acc, &t| acc ^ s[j + t]));
    }
    s
}

/// BCH(21, 6) word of a PRN (its 6 low bits).
pub(super) fn prn_word(prn: u8) -> Vec<u8> {
    word(u32::from(prn & 0x3F), 6, PRN_SYMBOLS, &[0, 1, 2, 4])
}

/// BCH(51, 8) word of an SOH count.
pub(super) fn soh_word(soh: u8) -> Vec<u8> {
    word(u32::from(soh), 8, SOH_SYMBOLS, &[0, 1, 2, 3, 4, 7])
}

/// The most likely SOH count of 51 soft symbols (positive = logic 0) and its normalised
/// correlation (1 for a noiseless word).
pub(super) fn decode_soh(soft: &[f32]) -> (u8, f32) {
    let norm: f32 = soft
        .iter()
        .map(|x| x.abs())
        .sum::<f32>()
        .max(f32::MIN_POSITIVE);
    (0..=255u8)
        .map(|v| {
            let c: f32 = soh_word(v)
                .iter()
                .zip(soft)
                .map(|(&b, &x)| if b == 0 { x } else { -x })
                .sum();
            (v, c / norm)
        })
        .fold(
            (0, f32::NEG_INFINITY),
            |best, c| if c.1 > best.1 { c } else { best },
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn min_distance(words: impl Iterator<Item = Vec<u8>>) -> usize {
        words
            .map(|w| w.iter().filter(|&&b| b == 1).count())
            .filter(|&d| d > 0)
            .min()
            .unwrap()
    }

    #[test]
    fn the_words_correct_the_errors_table_6_1_states() {
        // A linear code corrects t errors when its minimum distance is at least 2t + 1.
        assert!(min_distance((0..64).map(prn_word)) > 2 * 3);
        assert!(min_distance((0..=255).map(soh_word)) > 2 * 11);
        assert_eq!(prn_word(0b10_0011)[..6], [1, 0, 0, 0, 1, 1]);
        assert_eq!(soh_word(0x81)[..8], [1, 0, 0, 0, 0, 0, 0, 1]);
    }

    #[test]
    fn soh_decodes_through_eleven_errors() {
        for soh in [0u8, 17, 199] {
            let mut soft: Vec<f32> = soh_word(soh)
                .iter()
                .map(|&b| 1.0 - 2.0 * f32::from(b))
                .collect();
            for k in 0..11 {
                soft[4 * k + 1] = -soft[4 * k + 1];
            }
            assert_eq!(decode_soh(&soft).0, soh);
        }
    }
}
