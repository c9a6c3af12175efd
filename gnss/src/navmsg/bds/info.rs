//! The 224 information bits of a subframe, written field after field in transmission
//! order. In the ICD's bit-allocation figures (BDS-SIS-ICD-B1I-3.0 §5.2.3, §5.3.2) a field
//! that does not fit in a word continues in the next one after the parity bits; counting
//! information bits only, every subframe is therefore a plain sequence of fields.

use super::bch;

/// Information bits of word 1 (preamble 11, Rev 4, FraID 3, SOW MSBs 8).
const WORD1_INFO: usize = 26;
/// Information bits of words 2-10.
const WORD_INFO: usize = 22;
/// Information bits of a subframe: 26 + 9 x 22.
pub(super) const SUBFRAME_INFO: usize = WORD1_INFO + 9 * WORD_INFO;

/// Preamble 11100010010 (BDS-SIS-ICD-B1I-3.0 §5.2.3).
pub(super) const PREAMBLE: u64 = 0b111_0001_0010;

/// A subframe being written: information words and the number of bits written so far.
#[derive(Debug, Clone)]
pub(super) struct InfoBits {
    words: [u32; 10],
    cursor: usize,
}

impl InfoBits {
    /// A subframe starting with the common header: preamble (11), Rev (4, zero),
    /// FraID (3), SOW (20 bits: 8 MSBs in word 1, 12 LSBs at the start of word 2).
    pub(super) fn with_header(fra_id: u32, sow: u32) -> Self {
        let mut s = Self {
            words: [0; 10],
            cursor: 0,
        };
        s.put(11, PREAMBLE);
        s.skip(4);
        s.put(3, u64::from(fra_id));
        s.put(20, u64::from(sow));
        s
    }

    /// Append the `len` low bits of `value`, most significant first.
    pub(super) fn put(&mut self, len: usize, value: u64) {
        for k in (0..len).rev() {
            self.push_bit(((value >> k) & 1) as u32);
        }
    }

    /// Append a two's-complement signed value on `len` bits.
    pub(super) fn put_signed(&mut self, len: usize, value: i64) {
        self.put(len, value as u64);
    }

    /// Append `len` zero bits (reserved bits, "Rev").
    pub(super) fn skip(&mut self, len: usize) {
        self.cursor += len;
    }

    /// Append `len` one bits.
    pub(super) fn ones(&mut self, len: usize) {
        for _ in 0..len {
            self.push_bit(1);
        }
    }

    /// Number of information bits written so far.
    pub(super) fn len(&self) -> usize {
        self.cursor
    }

    fn push_bit(&mut self, bit: u32) {
        let c = self.cursor;
        if c < SUBFRAME_INFO {
            let (word, pos, width) = if c < WORD1_INFO {
                (0, c, WORD1_INFO)
            } else {
                let k = c - WORD1_INFO;
                (1 + k / WORD_INFO, k % WORD_INFO, WORD_INFO)
            };
            self.words[word] |= bit << (width - 1 - pos);
        }
        self.cursor += 1;
    }

    /// The ten transmitted words (BCH-encoded, interleaved; bit 29 first). Unwritten bits
    /// at the end are reserved zeros.
    pub(super) fn encode(&self) -> [u32; 10] {
        debug_assert!(self.cursor <= SUBFRAME_INFO, "subframe overflow");
        bch::encode_subframe(&self.words)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::navmsg::bds::test_decoder::{logical_bits, read_u};

    #[test]
    fn header_sits_where_the_icd_puts_it() {
        let words = InfoBits::with_header(3, 345_606).encode();
        let bits = logical_bits(&words).expect("valid codewords");
        assert_eq!(read_u(&bits, &[(1, 11)]), 0b111_0001_0010);
        assert_eq!(read_u(&bits, &[(12, 4)]), 0);
        assert_eq!(read_u(&bits, &[(16, 3)]), 3);
        assert_eq!(read_u(&bits, &[(19, 8), (31, 12)]), 345_606);
    }

    #[test]
    fn fields_continue_after_the_parity_bits() {
        let mut s = InfoBits::with_header(1, 0);
        s.skip(6); // fill word 2 up to bit 48 of the information stream
        s.put(8, 0xA5); // 4 bits at the end of word 2, 4 at the start of word 3
        assert_eq!(s.len(), 38 + 6 + 8);
        let bits = logical_bits(&s.encode()).expect("valid codewords");
        // ICD positions: word 2 = bits 31-60 (information 31-52), word 3 starts at 61.
        assert_eq!(read_u(&bits, &[(49, 4), (61, 4)]), 0xA5);
    }
}
