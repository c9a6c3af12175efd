//! Word parity: the (32, 26) Hamming code of IS-GPS-200 table 20-XIV, with the D29*/D30*
//! chaining between words and the solved non-information bits of words 2 and 10
//! (IS-GPS-200 20.3.5.2).
//!
//! Word layout used throughout: a `u32` whose bit 29 is D1 (first transmitted) and bit 0
//! is D30; 24-bit source data have d1 at bit 23 and d24 at bit 0.

/// Source-bit lists of the six parity equations (IS-GPS-200 table 20-XIV), D25..D30, and
/// whether the equation starts from D29* (`true`) or D30* (`false`) of the previous word.
const EQUATIONS: [(bool, &[u32]); 6] = [
    (true, &[1, 2, 3, 5, 6, 10, 11, 12, 13, 14, 17, 18, 20, 23]),
    (false, &[2, 3, 4, 6, 7, 11, 12, 13, 14, 15, 18, 19, 21, 24]),
    (true, &[1, 3, 4, 5, 7, 8, 12, 13, 14, 15, 16, 19, 20, 22]),
    (false, &[2, 4, 5, 6, 8, 9, 13, 14, 15, 16, 17, 20, 21, 23]),
    (
        false,
        &[1, 3, 5, 6, 7, 9, 10, 14, 15, 16, 17, 18, 21, 22, 24],
    ),
    (true, &[3, 5, 6, 8, 9, 10, 11, 13, 15, 19, 22, 23, 24]),
];

/// Mask over 24-bit source data (d1 at bit 23) of a list of source-bit numbers.
const fn mask(bits: &[u32]) -> u32 {
    let mut m = 0;
    let mut k = 0;
    while k < bits.len() {
        m |= 1 << (24 - bits[k]);
        k += 1;
    }
    m
}

/// The equations as (uses D29*, mask) pairs.
const MASKS: [(bool, u32); 6] = {
    let mut out = [(false, 0u32); 6];
    let mut j = 0;
    while j < 6 {
        out[j] = (EQUATIONS[j].0, mask(EQUATIONS[j].1));
        j += 1;
    }
    out
};

/// 24 data bits set.
const DATA_MASK: u32 = 0x00FF_FFFF;

/// Encode 24 source bits into a transmitted 30-bit word, given the previous transmitted
/// word (only its D29, D30 are used): D1..D24 are d1..d24 complemented when D30* = 1,
/// D25..D30 are the parity bits of table 20-XIV.
pub fn encode_word(source: u32, previous_word: u32) -> u32 {
    let d29_star = (previous_word >> 1) & 1;
    let d30_star = previous_word & 1;
    let source = source & DATA_MASK;
    let parity = MASKS.iter().fold(0, |acc, &(uses_d29, m)| {
        let seed = if uses_d29 { d29_star } else { d30_star };
        (acc << 1) | (((source & m).count_ones() & 1) ^ seed)
    });
    let data = if d30_star == 1 {
        !source & DATA_MASK
    } else {
        source
    };
    (data << 6) | parity
}

/// Encode a word whose source bits 23 and 24 are the non-information bits "t": they are
/// chosen so that the transmitted D29 = D30 = 0 (IS-GPS-200 20.3.5.2, words 2 and 10),
/// which makes the next word start from D29* = D30* = 0.
///
/// d24 enters the D29 and D30 equations and d23 only the D30 equation, so D29 fixes d24
/// and then D30 fixes d23.
pub(crate) fn encode_word_solving_t(source: u32, previous_word: u32) -> u32 {
    let mut source = source & (DATA_MASK & !0b11);
    if encode_word(source, previous_word) & 0b10 != 0 {
        source ^= 0b01;
    }
    if encode_word(source, previous_word) & 0b01 != 0 {
        source ^= 0b10;
    }
    encode_word(source, previous_word)
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::TSUI_PARITY_MATRIX;
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn masks_match_the_published_parity_matrix() {
        // An independent transcription of table 20-XIV.
        for (row, &(_, m)) in TSUI_PARITY_MATRIX.iter().zip(MASKS.iter()) {
            let from_book = u32::from_str_radix(row, 2).unwrap_or(u32::MAX);
            assert_eq!(m, from_book, "{row}");
        }
    }

    proptest! {
        #[test]
        fn t_bits_zero_d29_d30(source in 0u32..(1 << 24), prev in 0u32..4) {
            let w = encode_word_solving_t(source, prev);
            prop_assert_eq!(w & 0b11, 0);
            // Information bits are untouched (up to the D30* complement).
            let data = (w >> 6) ^ if prev & 1 == 1 { DATA_MASK } else { 0 };
            prop_assert_eq!(data >> 2, (source & DATA_MASK) >> 2);
        }
    }
}
