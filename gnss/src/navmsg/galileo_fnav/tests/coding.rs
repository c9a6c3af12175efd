//! Page layouts and channel coding.

use super::super::pages::{self, DATA_BITS, ENCODED_SYMBOLS, FNAV_SYNC, interleaved_index};
use super::super::quant as q;
use super::{encoder, epoch, realistic};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;

#[test]
fn every_layout_fills_the_208_navigation_data_bits() {
    for pt in 1..=6 {
        let bits: u32 = pages::layout(pt).unwrap().iter().map(|f| f.bits).sum();
        assert_eq!(bits + q::PAGE_TYPE.bits, DATA_BITS as u32, "page type {pt}");
    }
    assert!(pages::layout(0).is_none() && pages::layout(63).is_none());
}

#[test]
fn tow_sits_where_the_icd_puts_it() {
    // Bit offsets of TOW from the start of page types 1-4 (§4.2.3 tables).
    for (pt, offset) in [(1, 167), (2, 194), (3, 186), (4, 189)] {
        let layout = pages::layout(pt).unwrap();
        let before: u32 = layout
            .iter()
            .take_while(|f| f.name != "TOW")
            .map(|f| f.bits)
            .sum();
        assert_eq!(before + q::PAGE_TYPE.bits, offset, "page type {pt}");
    }
}

#[test]
fn interleaver_writes_columns_of_8_and_reads_rows_of_61() {
    // Symbol j goes to column j / 8, row j % 8; rows are read out one after the other.
    assert_eq!(interleaved_index(0), 0);
    assert_eq!(interleaved_index(1), 61);
    assert_eq!(interleaved_index(7), 7 * 61);
    assert_eq!(interleaved_index(8), 1);
    assert_eq!(interleaved_index(ENCODED_SYMBOLS - 1), ENCODED_SYMBOLS - 1);
    let mut seen = vec![false; ENCODED_SYMBOLS];
    for j in 0..ENCODED_SYMBOLS {
        assert!(!std::mem::replace(&mut seen[interleaved_index(j)], true));
    }
}

#[test]
fn a_page_is_sync_then_the_interleaved_code_of_data_crc_and_tail() {
    let enc = encoder(&realistic(11, epoch()));
    for n in 0..6 {
        let data = enc.page_bits(n);
        assert_eq!(data.len(), DATA_BITS);
        let symbols = enc.page_symbols(n);
        assert_eq!(symbols[..12], FNAV_SYNC);
        // Undo the interleaver by the definition, then check code, CRC and tail.
        let coded: Vec<u8> = (0..ENCODED_SYMBOLS)
            .map(|j| symbols[12 + interleaved_index(j)])
            .collect();
        let bits = ConvK7::GALILEO.decode_hard(&coded, true);
        assert_eq!(ConvK7::GALILEO.encode(&bits), coded);
        assert_eq!(bits[..DATA_BITS], data[..]);
        assert_eq!(crc24q_bits(&bits[..DATA_BITS + 24]), 0);
        assert_eq!(bits[DATA_BITS + 24..], [0; 6]);
        // The page type leads the data.
        let pt = data[..6].iter().fold(0u8, |a, &b| (a << 1) | b);
        assert_eq!(pt, enc.page_type(n));
    }
}

#[test]
fn packing_and_unpacking_are_inverse_with_sign_extension() {
    let enc = encoder(&realistic(11, epoch()));
    for n in 0..10 {
        let pt = enc.page_type(n);
        let layout = pages::layout(pt).unwrap();
        let values = pages::unpack(&enc.page_bits(n), layout);
        assert_eq!(pages::pack(pt, &values), enc.page_bits(n));
        for (f, v) in layout.iter().zip(&values) {
            let (min, max) = f.raw_range();
            assert!((min..=max).contains(v), "{} = {v}", f.name);
        }
    }
}
