//! The 24 source bits of the ten words of one subframe, filled field by field with the
//! ICD's word and bit numbers, then parity-encoded.

use super::WORDS_PER_SUBFRAME;
use super::parity::{encode_word, encode_word_solving_t};
use super::scale::Scale;

/// Source data of one subframe: 24 bits per word, word 1 first, d1 at bit 23.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct DataWords([u32; WORDS_PER_SUBFRAME]);

impl DataWords {
    /// Write `len` bits of `value` (right-aligned) at ICD word `word` (1-10), bits
    /// `first_bit` (1-24) onwards.
    pub fn put(&mut self, word: usize, first_bit: u32, len: u32, value: u32) {
        debug_assert!((1..=WORDS_PER_SUBFRAME).contains(&word));
        debug_assert!(first_bit >= 1 && len >= 1 && first_bit + len - 1 <= 24);
        debug_assert!(len == 32 || value >> len == 0, "value wider than field");
        let mask = if len >= 32 { u32::MAX } else { (1 << len) - 1 };
        let shift = 24 - (first_bit - 1 + len);
        let w = &mut self.0[word - 1];
        *w = (*w & !(mask << shift)) | ((value & mask) << shift);
    }

    /// Write the quantised integer `n` of field `scale` at `word`, `first_bit`.
    pub fn put_field(&mut self, word: usize, first_bit: u32, scale: &Scale, n: i64) {
        self.put(word, first_bit, scale.bits, scale.bits_of(n));
    }

    /// Write a 32-bit field split as 8 MSBs at bits 17-24 of `word` and 24 LSBs filling
    /// `word + 1` (the layout of M0, e, sqrt A, OMEGA0, i0, omega in table 20-II).
    pub fn put_split32(&mut self, word: usize, scale: &Scale, n: i64) {
        let bits = scale.bits_of(n);
        self.put(word, 17, 8, bits >> 24);
        self.put(word + 1, 1, 24, bits & 0x00FF_FFFF);
    }

    /// Fill `len` bits with alternating ones and zeros, starting with a one (reserved
    /// fields and dummy pages; IS-GPS-200 20.3.3.5.1.2 for dummy almanac pages).
    pub fn put_alternating(&mut self, word: usize, first_bit: u32, len: u32) {
        let pattern = 0x00AA_AAAA >> (24 - len);
        self.put(word, first_bit, len, pattern);
    }

    /// A cursor writing consecutive fields from `word`, `first_bit` on, flowing into the
    /// next word after bit 24 (for the NMCT, special message and page 25 layouts).
    pub fn cursor(&mut self, word: usize, first_bit: u32) -> Cursor<'_> {
        Cursor {
            words: self,
            word,
            bit: first_bit,
        }
    }

    /// Transmitted words: parity per table 20-XIV chained from D29* = D30* = 0 (the
    /// previous subframe's word 10 ends with 00), with the t bits of words 2 and 10
    /// solved so that they end with D29 = D30 = 0.
    pub fn encode(&self) -> [u32; WORDS_PER_SUBFRAME] {
        let mut out = [0u32; WORDS_PER_SUBFRAME];
        let mut previous = 0;
        for (k, (&source, slot)) in self.0.iter().zip(out.iter_mut()).enumerate() {
            let word = if k == 1 || k == 9 {
                encode_word_solving_t(source, previous)
            } else {
                encode_word(source, previous)
            };
            *slot = word;
            previous = word;
        }
        out
    }
}

/// Sequential writer over the data bits of consecutive words.
#[derive(Debug)]
pub(crate) struct Cursor<'a> {
    words: &'a mut DataWords,
    word: usize,
    bit: u32,
}

impl Cursor<'_> {
    /// Append the `len` low bits of `value`, most significant first.
    pub fn push(&mut self, len: u32, value: u32) {
        for k in (0..len).rev() {
            self.words.put(self.word, self.bit, 1, (value >> k) & 1);
            self.bit += 1;
            if self.bit > 24 {
                self.word += 1;
                self.bit = 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn put_uses_icd_bit_numbers() {
        let mut d = DataWords::default();
        d.put(1, 1, 8, 0x8B);
        d.put(3, 23, 2, 0b10);
        d.put(10, 1, 22, 0x3F_FFFF);
        assert_eq!(d.0[0], 0x8B_0000);
        assert_eq!(d.0[2], 0b10);
        assert_eq!(d.0[9], 0xFF_FFFC);
        d.put(1, 1, 8, 0x01);
        assert_eq!(d.0[0], 0x01_0000);
        d.put_alternating(2, 1, 24);
        assert_eq!(d.0[1], 0xAA_AAAA);
        d.put_alternating(4, 9, 4);
        assert_eq!(d.0[3], 0b1010 << 12);
        let mut d = DataWords::default();
        let mut c = d.cursor(3, 21);
        c.push(6, 0b110011);
        c.push(2, 0b11);
        assert_eq!((d.0[2], d.0[3]), (0b1100, 0b1111 << 20));
    }
}
