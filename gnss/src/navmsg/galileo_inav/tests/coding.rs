//! Word layouts, page parts and channel coding.

use super::super::pages::{self, INAV_SYNC, PART_BITS, PART_SYMBOLS, SSP, interleaved_index};
use super::super::quant as q;
use super::super::words::{self, WORD_BITS};
use super::{encoder, epoch, realistic};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;
use skyforge_orbits::ephemeris::nominal;

/// The encoded symbols of a page part in the order they left the encoder.
fn deinterleave(part: &[u8]) -> Vec<u8> {
    (0..PART_SYMBOLS - INAV_SYNC.len())
        .map(|j| part[INAV_SYNC.len() + interleaved_index(j)])
        .collect()
}

#[test]
fn every_layout_fills_the_128_bit_word() {
    for wt in 0..=10 {
        let bits: u32 = words::layout(wt).unwrap().iter().map(|f| f.bits).sum();
        assert_eq!(bits + q::WORD_TYPE.bits, WORD_BITS as u32, "word type {wt}");
    }
    assert!(
        [11, 16, 22, 63]
            .iter()
            .all(|&wt| words::layout(wt).is_none())
    );
}

#[test]
fn wn_and_tow_sit_where_the_icd_puts_them() {
    // Bit offsets from the start of the word (§4.3.5 tables): word 0 WN at 96 and TOW at
    // 108, word 5 at 73 and 85, word 6's TOW at 105.
    let offset = |wt: u8, name: &str| {
        let before: u32 = words::layout(wt)
            .unwrap()
            .iter()
            .take_while(|f| f.name != name)
            .map(|f| f.bits)
            .sum();
        before + q::WORD_TYPE.bits
    };
    assert_eq!((offset(0, "WN"), offset(0, "TOW")), (96, 108));
    assert_eq!((offset(5, "WN"), offset(5, "TOW")), (73, 85));
    assert_eq!(offset(6, "TOW"), 105);
}

#[test]
fn interleaver_writes_30_columns_of_8_and_reads_8_rows_of_30() {
    // The definition (§4.1.4.2): the 240 encoded symbols fill an 8 x 30 matrix column
    // after column, and are sent row after row.
    let mut matrix = [[0usize; 30]; 8];
    for (j, cell) in (0..240).zip((0..30).flat_map(|c| (0..8).map(move |r| (r, c)))) {
        matrix[cell.0][cell.1] = j;
    }
    let sent: Vec<usize> = matrix.iter().flatten().copied().collect();
    for (position, &j) in sent.iter().enumerate() {
        assert_eq!(interleaved_index(j), position);
    }
}

#[test]
fn a_page_is_two_parts_of_sync_and_the_interleaved_code_of_bits_and_tail() {
    let enc = encoder(&realistic(11, epoch()));
    for n in 100..115 {
        let word = enc.word_bits(n);
        let [even, odd] = enc.part_bits(n);
        assert_eq!((even.len(), odd.len()), (PART_BITS, PART_BITS));
        // Even/odd flags, nominal page type, the word split 112 + 16.
        assert_eq!((even[0], even[1], odd[0], odd[1]), (0, 0, 1, 0));
        assert_eq!([&even[2..], &odd[2..18]].concat(), word);
        // OSNMA, SAR and spare sent as zeros; CRC over the 196 bits before it.
        assert!(odd[18..82].iter().all(|&b| b == 0));
        assert_eq!(crc24q_bits(&[&even[..], &odd[..106]].concat()), 0);
        let symbols = enc.page_symbols(n);
        for (part, bits) in symbols.chunks(PART_SYMBOLS).zip([&even, &odd]) {
            assert_eq!(part[..10], INAV_SYNC);
            let coded = deinterleave(part);
            let decoded = ConvK7::GALILEO.decode_hard(&coded, true);
            assert_eq!(ConvK7::GALILEO.encode(&decoded), coded);
            assert_eq!(decoded[..PART_BITS], bits[..]);
            assert_eq!(decoded[PART_BITS..], [0; 6]);
        }
        let wt = word[..6].iter().fold(0u8, |a, &b| (a << 1) | b);
        assert_eq!(wt, enc.word_type(n));
    }
}

#[test]
fn encoded_ssp_symbols_are_the_icds() {
    // §5.1.9.5: the last 16 symbols of an E1 page after encoding the 8 SSP bits and the 6
    // tail bits. This checks the code's generators, their order and G2's inversion too.
    let table = [
        (SSP[0], "1110100100100101"),
        (SSP[1], "0110110001001110"),
        (SSP[2], "1101000000111110"),
    ];
    let enc = encoder(&realistic(11, epoch()));
    let mut seen = Vec::new();
    for n in 1..4 {
        let odd = &enc.page_symbols(n)[PART_SYMBOLS..];
        let coded = deinterleave(odd);
        let tail: String = coded[240 - 16..].iter().map(|s| s.to_string()).collect();
        let ssp = enc.part_bits(n)[1][106..]
            .iter()
            .fold(0u8, |a, &b| (a << 1) | b);
        let (_, expected) = table.iter().find(|(s, _)| *s == ssp).expect("an SSP");
        assert_eq!(&tail, expected, "page {n}");
        seen.push(ssp);
    }
    seen.sort_unstable();
    assert_eq!(seen, SSP);
}

#[test]
fn the_crc_catches_any_flipped_bit_it_covers() {
    let enc = encoder(&realistic(11, epoch()));
    let [even, odd] = enc.part_bits(40);
    assert!(pages::crc_holds(&even, &odd));
    for k in 0..2 * PART_BITS {
        let (mut e, mut o) = (even.clone(), odd.clone());
        let (part, at) = if k < PART_BITS {
            (&mut e, k)
        } else {
            (&mut o, k - PART_BITS)
        };
        part[at] ^= 1;
        // The SSP (the odd part's last 8 bits) is outside the CRC.
        assert_eq!(pages::crc_holds(&e, &o), k >= 2 * PART_BITS - 8, "bit {k}");
    }
}

#[test]
fn packing_and_unpacking_are_inverse_with_sign_extension() {
    let set = nominal::galileo(epoch());
    let enc = super::InavEncoder::new(&set[0], &set, &super::InavParams::default(), 1229).unwrap();
    for n in 1..31 {
        let wt = enc.word_type(n);
        let layout = words::layout(wt).unwrap();
        let values = words::unpack(&enc.word_bits(n), layout);
        assert_eq!(values.len(), layout.len());
        assert_eq!(words::pack(wt, &values), enc.word_bits(n));
        for (f, v) in layout.iter().zip(&values) {
            if f.name == "Spare" {
                // Spare and reserved bits are zeros (word 0's 88 are no i64 range).
                assert_eq!(*v, 0);
                continue;
            }
            let (min, max) = f.raw_range();
            assert!((min..=max).contains(v), "{} = {v}", f.name);
        }
    }
}
