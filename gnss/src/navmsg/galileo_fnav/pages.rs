//! F/NAV page layouts and the page's channel coding (Galileo OS SIS ICD §4.1.4, §4.2).
//!
//! A page (§4.2.2) is 12 synchronisation symbols followed by 488 encoded symbols: the
//! 6-bit page type and 208 bits of navigation data (214 bits, the CRC-24Q's input), the
//! 24 CRC bits and 6 zero tail bits (244 bits), convolutionally encoded (rate 1/2, K = 7,
//! G2 inverted, `conv_k7`) from the zero state and block-interleaved (§4.1.4.2: 61
//! columns where the data is written, 8 rows where it is read). Bits are sent most
//! significant first (§4.1, bit and byte ordering).
//!
//! Layouts (§4.2.4, Issue 1 Tables 31-36; widths and order agree with the layouts GNSSTk
//! documents, e.g. TOW starting at bits 167, 194, 186, 189 of page types 1-4):
//! 1: SVID, IODnav, clock, SISA, NeQuick, region flags, BGD(E1,E5a), E5aHS, WN, TOW,
//!    E5aDVS, 26 spare; 2: IODnav, M0, OMEGAdot, e, sqrtA, OMEGA0, idot, WN, TOW;
//! 3: IODnav, i0, omega, Delta n, Cuc, Cus, Crc, Crs, t0e, WN, TOW, 8 spare;
//! 4: IODnav, Cic, Cis, GST-UTC, GST-GPS, TOW, 5 spare;
//! 5: IODa, WNa, t0a, almanac of SVID1, SVID2 up to the 4 MSBs of its OMEGA0;
//! 6: IODa, the rest of SVID2's almanac, almanac of SVID3, 3 spare.

use super::quant::{self as q, Field};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;
use crate::navmsg::field::{push_bits, read_fields};

/// Page type and navigation data bits (the CRC's input).
pub const DATA_BITS: usize = 214;
/// Bits per page before encoding: data, CRC, tail.
pub const PAGE_BITS: usize = 244;
/// Encoded symbols per page.
pub const ENCODED_SYMBOLS: usize = 2 * PAGE_BITS;
/// Symbols per page, synchronisation pattern included.
pub const PAGE_SYMBOLS: usize = FNAV_SYNC.len() + ENCODED_SYMBOLS;
/// The F/NAV synchronisation pattern (§4.2.2), sent first and not encoded.
pub const FNAV_SYNC: [u8; 12] = [1, 0, 1, 1, 0, 1, 1, 1, 0, 0, 0, 0];
/// Block interleaver: columns written, rows read (§4.1.4.2).
const COLUMNS: usize = 61;
const ROWS: usize = 8;
/// Dummy page type.
pub const DUMMY_PAGE_TYPE: u8 = 63;

const PT1: [Field; 17] = [
    q::SVID,
    q::IODNAV,
    q::TOC,
    q::AF0,
    q::AF1,
    q::AF2,
    q::SISA,
    q::AI0,
    q::AI1,
    q::AI2,
    q::REGION_FLAGS,
    q::BGD_E1_E5A,
    q::E5A_HS,
    q::WN,
    q::TOW,
    q::E5A_DVS,
    q::spare(26),
];
const PT2: [Field; 9] = [
    q::IODNAV,
    q::M0,
    q::OMEGA_DOT,
    q::E,
    q::SQRT_A,
    q::OMEGA0,
    q::IDOT,
    q::WN,
    q::TOW,
];
const PT3: [Field; 12] = [
    q::IODNAV,
    q::I0,
    q::OMEGA,
    q::DELTA_N,
    q::CUC,
    q::CUS,
    q::CRC,
    q::CRS,
    q::TOE,
    q::WN,
    q::TOW,
    q::spare(8),
];
const PT4: [Field; 17] = [
    q::IODNAV,
    q::CIC,
    q::CIS,
    q::A0,
    q::A1,
    q::DT_LS,
    q::T0T,
    q::WN0T,
    q::WN_LSF,
    q::DN,
    q::DT_LSF,
    q::T0G,
    q::A0G,
    q::A1G,
    q::WN0G,
    q::TOW,
    q::spare(5),
];
/// One satellite's almanac but its SVID (§5.1.10), in transmission order.
pub(super) const ALMANAC_SAT: [Field; 11] = [
    q::SVID,
    q::ALM_DSQRT_A,
    q::ALM_E,
    q::ALM_OMEGA,
    q::ALM_DI,
    q::ALM_OMEGA0,
    q::ALM_OMEGA_DOT,
    q::ALM_M0,
    q::ALM_AF0,
    q::ALM_AF1,
    q::E5A_HS,
];
const PT5: [Field; 20] = [
    q::IODA,
    q::WNA,
    q::T0A,
    ALMANAC_SAT[0],
    ALMANAC_SAT[1],
    ALMANAC_SAT[2],
    ALMANAC_SAT[3],
    ALMANAC_SAT[4],
    ALMANAC_SAT[5],
    ALMANAC_SAT[6],
    ALMANAC_SAT[7],
    ALMANAC_SAT[8],
    ALMANAC_SAT[9],
    ALMANAC_SAT[10],
    ALMANAC_SAT[0],
    ALMANAC_SAT[1],
    ALMANAC_SAT[2],
    ALMANAC_SAT[3],
    ALMANAC_SAT[4],
    q::ALM_OMEGA0_MSB,
];
const PT6: [Field; 19] = [
    q::IODA,
    q::ALM_OMEGA0_LSB,
    ALMANAC_SAT[6],
    ALMANAC_SAT[7],
    ALMANAC_SAT[8],
    ALMANAC_SAT[9],
    ALMANAC_SAT[10],
    ALMANAC_SAT[0],
    ALMANAC_SAT[1],
    ALMANAC_SAT[2],
    ALMANAC_SAT[3],
    ALMANAC_SAT[4],
    ALMANAC_SAT[5],
    ALMANAC_SAT[6],
    ALMANAC_SAT[7],
    ALMANAC_SAT[8],
    ALMANAC_SAT[9],
    ALMANAC_SAT[10],
    q::spare(3),
];

/// The fields after the page type of page type `page_type` (1-6), in order.
pub fn layout(page_type: u8) -> Option<&'static [Field]> {
    match page_type {
        1 => Some(&PT1),
        2 => Some(&PT2),
        3 => Some(&PT3),
        4 => Some(&PT4),
        5 => Some(&PT5),
        6 => Some(&PT6),
        _ => None,
    }
}

/// The 214 data bits of a page: type, then `values` (raw, one per layout field; two's
/// complement for signed fields), zero padded.
pub(super) fn pack(page_type: u8, values: &[i64]) -> Vec<u8> {
    let mut bits = Vec::with_capacity(PAGE_BITS);
    push_bits(&mut bits, i64::from(page_type), q::PAGE_TYPE.bits);
    if let Some(fields) = layout(page_type) {
        for (f, &v) in fields.iter().zip(values) {
            push_bits(&mut bits, v, f.bits);
        }
    }
    bits.resize(DATA_BITS, 0);
    bits
}

/// Reads the raw values of `fields` from `bits` starting after the page type.
pub(super) fn unpack(bits: &[u8], fields: &[Field]) -> Vec<i64> {
    read_fields(&bits[q::PAGE_TYPE.bits as usize..], fields)
}

/// The 500 channel symbols of a page from its 214 data bits.
pub(super) fn encode_page(data: &[u8]) -> [u8; PAGE_SYMBOLS] {
    let mut bits = data.to_vec();
    let crc = crc24q_bits(data);
    push_bits(&mut bits, i64::from(crc), 24);
    bits.resize(PAGE_BITS, 0);
    let encoded = ConvK7::GALILEO.encode(&bits);
    let mut out = [0u8; PAGE_SYMBOLS];
    out[..FNAV_SYNC.len()].copy_from_slice(&FNAV_SYNC);
    for (j, &s) in encoded.iter().enumerate() {
        out[FNAV_SYNC.len() + interleaved_index(j)] = s;
    }
    out
}

/// Where encoded symbol `j` is sent: written column by column (8 per column), read row by
/// row (61 per row).
pub(super) fn interleaved_index(j: usize) -> usize {
    (j % ROWS) * COLUMNS + j / ROWS
}

/// The 244 decoded bits (data, CRC, tail) from the 488 received soft symbols after the
/// synchronisation pattern (positive = 0), and whether the CRC holds.
pub(super) fn decode_symbols(soft: &[f32]) -> (Vec<u8>, bool) {
    let deinterleaved: Vec<f32> = (0..ENCODED_SYMBOLS)
        .map(|j| soft[interleaved_index(j)])
        .collect();
    let bits = ConvK7::GALILEO.decode_soft(&deinterleaved, true);
    let ok = crc24q_bits(&bits[..DATA_BITS + 24]) == 0;
    (bits, ok)
}
