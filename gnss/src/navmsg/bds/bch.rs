//! Error-correction coding of D1/D2 words: BCH(15,11,1) and the bit interleaving of words
//! 2-10 (BDS-SIS-ICD-B1I-3.0 §5.1.3).
//!
//! - Word 1: the first 15 bits (preamble, Rev) are sent as they are; the last 11
//!   information bits (FraID, SOW MSBs) form one BCH(15,11) codeword.
//! - Words 2-10: the 22 information bits are split into two 11-bit groups, each
//!   BCH(15,11)-encoded; the two codewords are then interleaved bit by bit, first
//!   codeword first: c1[0] c2[0] c1[1] c2[1] ... c1[14] c2[14].
//! - Codeword c(x) = m(x) x^4 + (m(x) x^4 mod g(x)), g(x) = x^4 + x + 1, sent
//!   highest degree first (11 information bits, then the 4 parity bits, x^3 first).
//!   Checked in the tests against words broadcast by C06 and C01 (GNSSTk test vectors).

/// Number of information bits of one BCH codeword.
const K_INFO: u32 = 11;
/// Low terms of the generator polynomial g(x) = x^4 + x + 1 (the x^4 term is implicit).
const G_LOW: u32 = 0b0011;

/// The 4 parity bits of an 11-bit information group (bit 10 sent first): the remainder of
/// m(x) x^4 divided by g(x), from the ICD's feedback shift register (§5.1.3).
fn parity(info11: u32) -> u32 {
    let mut reg = 0u32;
    for k in (0..K_INFO).rev() {
        let feedback = ((info11 >> k) & 1) ^ ((reg >> 3) & 1);
        reg = (reg << 1) & 0xF;
        if feedback == 1 {
            reg ^= G_LOW;
        }
    }
    reg
}

/// The 15-bit codeword of an 11-bit information group (bit 14 sent first).
pub(super) fn codeword(info11: u32) -> u32 {
    let info = info11 & 0x7FF;
    (info << 4) | parity(info)
}

/// Word 1 from its 26 information bits (bit 25 sent first): 15 bits uncoded, then one
/// codeword.
pub(super) fn encode_word1(info26: u32) -> u32 {
    (((info26 >> K_INFO) & 0x7FFF) << 15) | codeword(info26 & 0x7FF)
}

/// Words 2-10 from their 22 information bits (bit 21 sent first): two codewords,
/// interleaved bit by bit.
pub(super) fn encode_word(info22: u32) -> u32 {
    let c1 = codeword((info22 >> K_INFO) & 0x7FF);
    let c2 = codeword(info22 & 0x7FF);
    (0..15).rev().fold(0u32, |w, k| {
        (((w << 1) | ((c1 >> k) & 1)) << 1) | ((c2 >> k) & 1)
    })
}

/// All ten transmitted words of a subframe from its information words (word 1: 26 bits,
/// words 2-10: 22 bits each, right-aligned). Each output word holds 30 bits, bit 29 first.
pub(super) fn encode_subframe(info: &[u32; 10]) -> [u32; 10] {
    let mut out = [0u32; 10];
    out[0] = encode_word1(info[0]);
    for (o, &i) in out.iter_mut().zip(info.iter()).skip(1) {
        *o = encode_word(i);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::navmsg::bds::test_decoder::{bch_correct, bch_syndrome, deinterleave};
    use proptest::prelude::*;

    #[test]
    fn every_codeword_has_zero_syndrome_and_every_single_error_is_corrected() {
        for info in 0..(1u32 << 11) {
            let c = codeword(info);
            assert_eq!(c >> 4, info, "systematic: information bits first");
            assert_eq!(bch_syndrome(c), 0, "info {info:#x}");
            for bit in 0..15 {
                let bad = c ^ (1 << bit);
                assert_ne!(bch_syndrome(bad), 0, "single error at {bit} undetected");
                assert_eq!(bch_correct(bad), Some(c), "single error at {bit}");
            }
        }
    }

    /// Hand-computed example: m(x) = x^9 + x^8 -> m x^4 mod g = x (parity 0010); this is
    /// also the first codeword of word 2 of a C06 subframe 1 (SOW 345600).
    #[test]
    fn parity_of_a_hand_computed_example() {
        assert_eq!(parity(0b011_0000_0000), 0b0010);
        // The all-ones word is a codeword (g(1) != 0), as the all-ones D2 grid words
        // broadcast by C01 show (0x3FFFFFFF).
        assert_eq!(codeword(0x7FF), 0x7FFF);
        assert_eq!(encode_word(0x3F_FFFF), 0x3FFF_FFFF);
    }

    proptest! {
        #[test]
        fn interleaving_round_trips(info in 0u32..(1 << 22)) {
            let w = encode_word(info);
            prop_assert!(w < (1 << 30));
            let (c1, c2) = deinterleave(w);
            prop_assert_eq!(c1, codeword(info >> 11));
            prop_assert_eq!(c2, codeword(info & 0x7FF));
        }

        #[test]
        fn word1_keeps_15_bits_uncoded(info in 0u32..(1 << 26)) {
            let w = encode_word1(info);
            prop_assert_eq!(w >> 15, info >> 11);
            prop_assert_eq!(bch_syndrome(w & 0x7FFF), 0);
        }
    }
}
