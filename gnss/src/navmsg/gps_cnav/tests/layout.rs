//! Message layouts, header and CRC.

use super::super::layout::{self, HEADER, all_fields};
use super::super::{CnavDecodeError, decode_message};
use super::{WEEK, encoder, epoch, realistic, soft, uint, window};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;

#[test]
fn every_message_type_is_300_bits_with_header_and_crc() {
    let header: u32 = HEADER.iter().map(|f| f.bits).sum();
    assert_eq!(header, 38);
    for t in [10, 11, 30, 33] {
        let payload: u32 = layout::layout(t).unwrap().iter().map(|f| f.bits).sum();
        assert_eq!(header + payload + 24, 300, "message type {t}");
    }
    assert!(layout::layout(0).is_none() && layout::layout(12).is_none());
}

/// Start bit (from 0) of field `name` in message type `t`.
fn start_bit(t: u8, name: &str) -> u32 {
    all_fields(t)
        .take_while(|f| f.name != name)
        .map(|f| f.bits)
        .sum()
}

#[test]
fn fields_start_where_the_icd_figures_put_them() {
    // IS-GPS-705J Figures 20-1, 20-2, 20-3 and 20-6 (bit 1 there is bit 0 here).
    let cases = [
        (10, "WN", 38),
        (10, "top", 54),
        (10, "toe", 70),
        (10, "Delta A", 81),
        (10, "Adot", 107),
        (10, "Delta n0", 132),
        (10, "M0-n", 172),
        (10, "e-n", 205),
        (10, "omega-n", 238),
        (10, "Integrity status flag", 271),
        (11, "OMEGA0-n", 49),
        (11, "i0-n-DOT", 132),
        (11, "Crs-n", 179),
        (11, "Cuc-n", 248),
        (30, "toc", 60),
        (30, "af0-n", 71),
        (30, "af2-n", 117),
        (30, "TGD", 127),
        (30, "ISC_L5I5", 166),
        (30, "alpha0", 192),
        (30, "beta0", 224),
        (30, "WNop", 256),
        (33, "A0-n", 127),
        (33, "tot", 171),
        (33, "WNLSF", 200),
        (33, "Delta tLSF", 217),
    ];
    for (t, name, bit) in cases {
        assert_eq!(start_bit(t, name), bit, "{name} in type {t}");
    }
}

#[test]
fn the_header_carries_preamble_prn_type_tow_and_alert() {
    let enc = encoder(&realistic(5, epoch()));
    // Message 0 of the week: type 10, next message at TOW 6 s -> count 1.
    let bits = enc.message_bits(0);
    let expect: Vec<u8> = "10001011 000101 001010 00000000000000001 0"
        .chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| c as u8 - b'0')
        .collect();
    assert_eq!(bits[..38], expect[..]);
    // Type 10 continues with the week, 13 bits.
    assert_eq!(uint(&bits[38..51]), u64::from(WEEK));
    for n in 0..8 {
        assert_eq!(uint(&enc.message_bits(n)[..8]), 0b1000_1011, "message {n}");
    }
}

#[test]
fn the_crc_covers_the_first_276_bits() {
    let enc = encoder(&realistic(5, epoch()));
    for n in 0..4 {
        let bits = enc.message_bits(n);
        assert_eq!(crc24q_bits(&bits), 0, "message {n}");
        assert_eq!(u64::from(crc24q_bits(&bits[..276])), uint(&bits[276..]));
    }
}

#[test]
fn a_corrupted_message_fails_the_crc() {
    let enc = encoder(&realistic(5, epoch()));
    let n = 41;
    assert!(decode_message(&window(&enc, n)).is_ok());
    // Flip one data bit and re-encode the stream: the code is intact, the CRC is not.
    for flip in [40, 150, 275, 299] {
        let mut bits = enc.message_bits(n).to_vec();
        bits[flip] ^= 1;
        let previous = enc.message_bits(n - 1);
        let mut stream = previous.to_vec();
        stream.extend(&bits);
        stream.extend(enc.message_bits(n + 1));
        let symbols = ConvK7::GPS_L5.encode(&stream);
        let w = soft(&symbols[600 - 70..1200 + 70]);
        assert_eq!(decode_message(&w), Err(CnavDecodeError::Crc), "bit {flip}");
    }
}
