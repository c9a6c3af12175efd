//! LNAV word parity check (IS-GPS-200 20.3.5.2, table 20-XIV).
//!
//! A transmitted word is D1..D30 (here bit 29 of a `u32` is D1, bit 0 is D30). The source
//! bits are d_i = D_i xor D30* (D30* = last bit of the previous word); the parity bits are
//! D25..D30 = (D29* or D30*) xor the XOR of listed source bits. Because every term flips
//! together when the whole stream is complemented, the check and the recovered source bits
//! do not depend on the stream polarity, provided D29*, D30* come from the same stream.

use skyforge_gnss::navmsg::gps_lnav::parity::encode_word;

/// The 24 source bits (d1 at bit 23) of transmitted word `word` if its parity holds given
/// `d29_star`, `d30_star` (the last two bits of the previous word), else `None`: the
/// source bits re-encoded with table 20-XIV must give the received word.
pub(crate) fn check_word(word: u32, d29_star: u8, d30_star: u8) -> Option<u32> {
    let flip = if d30_star & 1 == 1 { 0x00FF_FFFF } else { 0 };
    let source = ((word >> 6) & 0x00FF_FFFF) ^ flip;
    let previous = (u32::from(d29_star & 1) << 1) | u32::from(d30_star & 1);
    (encode_word(source, previous) == word & 0x3FFF_FFFF).then_some(source)
}

/// Source words of a subframe given as bits: `bits[0]`, `bits[1]` are D29, D30 of the
/// previous word, then the 300 bits of the subframe. `Err` holds the mask of words that
/// failed (bit k = word k + 1).
pub(crate) fn check_subframe(bits: &[u8]) -> Result<[u32; 10], u16> {
    let mut out = [0u32; 10];
    let mut failed = 0u16;
    for (k, slot) in out.iter_mut().enumerate() {
        let start = 2 + 30 * k;
        let word = bits.get(start..start + 30).map_or(0, |w| {
            w.iter().fold(0u32, |acc, &b| (acc << 1) | u32::from(b & 1))
        });
        let prev = |k: usize| bits.get(k).copied().unwrap_or(0);
        let (d29, d30) = (prev(start - 2), prev(start - 1));
        match check_word(word, d29, d30) {
            Some(s) => *slot = s,
            None => failed |= 1 << k,
        }
    }
    if failed == 0 { Ok(out) } else { Err(failed) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use skyforge_gnss::navmsg::gps_lnav::fixtures::TSUI_PARITY_MATRIX;

    /// Encode by brute force: the parity bits that make `check_word` accept, computed
    /// independently from the equations as a matrix over GF(2) (the H matrix printed in
    /// Tsui, "Fundamentals of GPS receivers", eq. 5.3, rows D25..D30 over d1..d24).
    fn encode(source: u32, d29: u8, d30: u8) -> u32 {
        let seeds = [d29, d30, d29, d30, d30, d29];
        let mut parity = 0;
        for (row, seed) in TSUI_PARITY_MATRIX.iter().zip(seeds) {
            let m = u32::from_str_radix(row, 2).unwrap_or(0);
            parity = (parity << 1) | (((source & m).count_ones() + u32::from(seed)) & 1);
        }
        let data = if d30 == 1 {
            !source & 0x00FF_FFFF
        } else {
            source
        };
        (data << 6) | parity
    }

    proptest! {
        #[test]
        fn valid_words_pass_and_single_errors_fail(
            source in 0u32..(1 << 24), d29 in 0u8..2, d30 in 0u8..2, flip in 0u32..30
        ) {
            let w = encode(source, d29, d30);
            prop_assert_eq!(check_word(w, d29, d30), Some(source));
            prop_assert_eq!(check_word(w ^ (1 << flip), d29, d30), None);
            // The complemented stream (word and previous bits) decodes to the same source.
            prop_assert_eq!(check_word(!w & 0x3FFF_FFFF, d29 ^ 1, d30 ^ 1), Some(source));
        }
    }
}
