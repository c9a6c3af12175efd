//! I/NAV page parts and their channel coding (Galileo OS SIS ICD Issue 2.1 §4.1.4, §4.3.2).
//!
//! A nominal page (§4.3.2, nominal page bits allocation) is an even part and an odd part,
//! 1 s each on E1-B, each the 10 symbols of the synchronisation pattern followed by 240
//! encoded symbols: 114 bits and 6 zero tail bits, convolutionally encoded (rate 1/2,
//! K = 7, G2 inverted, `conv_k7`) from the zero state and block-interleaved (§4.1.4.2: 30
//! columns where the data is written, 8 rows where it is read).
//!
//! Even part: even/odd = 0, page type = 0 (nominal), word bits 1-112. Odd part:
//! even/odd = 1, page type = 0, word bits 113-128, OSNMA (40), SAR (22), spare (2), the
//! CRC-24Q of the 196 bits before it in the two parts (§4.3.2: even/odd, page type and
//! data of both parts, OSNMA, SAR and spare; §5.1.9.4 checksum), and on E1-B the
//! secondary synchronisation pattern (8, §5.1.9.5), which the CRC does not cover.
//! SkyForge sends OSNMA, SAR and spare as zeros (no authentication, no return link
//! message).

use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;
use crate::navmsg::field::push_bits;

/// The I/NAV synchronisation pattern (§4.3.2), sent first in each page part, not encoded.
pub const INAV_SYNC: [u8; 10] = [0, 1, 0, 1, 1, 0, 0, 0, 0, 0];
/// Symbols per page part, synchronisation pattern included.
pub const PART_SYMBOLS: usize = INAV_SYNC.len() + ENCODED_SYMBOLS;
/// Symbols per page (even part, then odd part).
pub const PAGE_SYMBOLS: usize = 2 * PART_SYMBOLS;
/// Bits per page part before the tail.
pub const PART_BITS: usize = 114;
/// Bits per page part, tail included.
const CODED_BITS: usize = PART_BITS + 6;
/// Encoded symbols per page part.
const ENCODED_SYMBOLS: usize = 2 * CODED_BITS;
/// Word bits in the even part (the rest are in the odd part).
const EVEN_WORD_BITS: usize = 112;
/// Bits of the odd part before its CRC: even/odd, page type, word bits 113-128, OSNMA,
/// SAR, spare.
const ODD_BITS_BEFORE_CRC: usize = 2 + 16 + 40 + 22 + 2;
/// Block interleaver: columns written, rows read (§4.1.4.2).
const COLUMNS: usize = 30;
const ROWS: usize = 8;
/// The three secondary synchronisation patterns SSP1, SSP2, SSP3 (§5.1.9.5), MSB first.
pub const SSP: [u8; 3] = [0b0000_0100, 0b0010_1011, 0b0010_1111];

/// The even and odd page parts (114 bits each, before the tail) that carry the 128-bit
/// `word`, the odd one ending with secondary synchronisation pattern `ssp`.
pub(super) fn parts(word: &[u8], ssp: u8) -> [Vec<u8>; 2] {
    let mut even = vec![0, 0];
    even.extend_from_slice(&word[..EVEN_WORD_BITS]);
    let mut odd = vec![1, 0];
    odd.extend_from_slice(&word[EVEN_WORD_BITS..]);
    odd.resize(ODD_BITS_BEFORE_CRC, 0);
    let crc = crc24q_bits(&[&even[..], &odd[..]].concat());
    push_bits(&mut odd, i64::from(crc), 24);
    push_bits(&mut odd, i64::from(ssp), 8);
    [even, odd]
}

/// Whether the CRC of the odd part matches the two parts (114 bits each).
pub(super) fn crc_holds(even: &[u8], odd: &[u8]) -> bool {
    crc24q_bits(&[even, &odd[..ODD_BITS_BEFORE_CRC + 24]].concat()) == 0
}

/// The 250 channel symbols of a page part from its 114 bits.
pub(super) fn encode_part(bits: &[u8]) -> [u8; PART_SYMBOLS] {
    let mut coded = bits.to_vec();
    coded.resize(CODED_BITS, 0);
    let encoded = ConvK7::GALILEO.encode(&coded);
    let mut out = [0u8; PART_SYMBOLS];
    out[..INAV_SYNC.len()].copy_from_slice(&INAV_SYNC);
    for (j, &s) in encoded.iter().enumerate() {
        out[INAV_SYNC.len() + interleaved_index(j)] = s;
    }
    out
}

/// Where encoded symbol `j` is sent: written column by column (8 per column), read row by
/// row (30 per row).
pub(super) fn interleaved_index(j: usize) -> usize {
    (j % ROWS) * COLUMNS + j / ROWS
}

/// The 114 bits of a page part (tail dropped) from its 240 received soft symbols after the
/// synchronisation pattern (positive = 0).
pub(super) fn decode_symbols(soft: &[f32]) -> Vec<u8> {
    let deinterleaved: Vec<f32> = (0..ENCODED_SYMBOLS)
        .map(|j| soft[interleaved_index(j)])
        .collect();
    let mut bits = ConvK7::GALILEO.decode_soft(&deinterleaved, true);
    bits.truncate(PART_BITS);
    bits
}

/// The 128-bit word of a page's two parts.
pub(super) fn word(even: &[u8], odd: &[u8]) -> Vec<u8> {
    [&even[2..], &odd[2..2 + 16]].concat()
}
