//! I/NAV word layouts (Galileo OS SIS ICD Issue 2.1 §4.3.5, "I/NAV word types").
//!
//! A word is 128 bits: the 6-bit word type, then its fields, most significant bit first
//! (§4.1, bit and byte ordering). The layouts SkyForge sends:
//! 0: Time ('10'), 88 spare, WN, TOW; 1: IODnav, t0e, M0, e, sqrtA, 2 reserved;
//! 2: IODnav, OMEGA0, i0, omega, idot, 2 reserved;
//! 3: IODnav, OMEGAdot, Delta n, Cuc, Cus, Crc, Crs, SISA(E1,E5b);
//! 4: IODnav, SVID, Cic, Cis, t0c, af0, af1, af2, 2 spare;
//! 5: ai0, ai1, ai2, region flags 1-5, BGD(E1,E5a), BGD(E1,E5b), E5bHS, E1BHS, E5bDVS,
//!    E1BDVS, WN, TOW, 23 spare;
//! 6: A0, A1, Delta tLS, t0t, WN0t, WNLSF, DN, Delta tLSF, TOW, 3 spare;
//! 7: IODa, WNa, t0a, SVID1's almanac up to its M0, 6 reserved;
//! 8: IODa, the rest of SVID1's (af0, af1, E5bHS, E1BHS), SVID2's up to its OMEGAdot, 1
//!    spare; 9: IODa, WNa, t0a, the rest of SVID2's, SVID3's up to its delta i;
//! 10: IODa, the rest of SVID3's, A0G, A1G, t0G, WN0G.
//! Reserved bits are sent as zeros, as spare ones are.

use super::quant::{self as q, Field};
use crate::navmsg::field::{push_bits, read_fields};

/// Bits per word, type included.
pub const WORD_BITS: usize = 128;

const W0: [Field; 4] = [q::TIME, q::spare(88), q::WN, q::TOW];
const W1: [Field; 6] = [q::IODNAV, q::TOE, q::M0, q::E, q::SQRT_A, q::spare(2)];
const W2: [Field; 6] = [q::IODNAV, q::OMEGA0, q::I0, q::OMEGA, q::IDOT, q::spare(2)];
const W3: [Field; 8] = [
    q::IODNAV,
    q::OMEGA_DOT,
    q::DELTA_N,
    q::CUC,
    q::CUS,
    q::CRC,
    q::CRS,
    q::SISA,
];
const W4: [Field; 9] = [
    q::IODNAV,
    q::SVID,
    q::CIC,
    q::CIS,
    q::TOC,
    q::AF0,
    q::AF1,
    q::AF2,
    q::spare(2),
];
const W5: [Field; 13] = [
    q::AI0,
    q::AI1,
    q::AI2,
    q::REGION_FLAGS,
    q::BGD_E1_E5A,
    q::BGD_E1_E5B,
    q::E5B_HS,
    q::E1B_HS,
    q::E5B_DVS,
    q::E1B_DVS,
    q::WN,
    q::TOW,
    q::spare(23),
];
const W6: [Field; 10] = [
    q::A0,
    q::A1,
    q::DT_LS,
    q::T0T,
    q::WN0T,
    q::WN_LSF,
    q::DN,
    q::DT_LSF,
    q::TOW,
    q::spare(3),
];
/// One satellite's I/NAV almanac (§5.1.10), in transmission order: SVID, the orbit and
/// clock as in F/NAV, then E5bHS and E1BHS.
pub(super) const ALMANAC_SAT: [Field; 12] = [
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
    q::E5B_HS,
    q::E1B_HS,
];
const A: [Field; 12] = ALMANAC_SAT;
const W7: [Field; 12] = [
    q::IODA,
    q::WNA,
    q::T0A,
    A[0],
    A[1],
    A[2],
    A[3],
    A[4],
    A[5],
    A[6],
    A[7],
    q::spare(6),
];
const W8: [Field; 13] = [
    q::IODA,
    A[8],
    A[9],
    A[10],
    A[11],
    A[0],
    A[1],
    A[2],
    A[3],
    A[4],
    A[5],
    A[6],
    q::spare(1),
];
const W9: [Field; 13] = [
    q::IODA,
    q::WNA,
    q::T0A,
    A[7],
    A[8],
    A[9],
    A[10],
    A[11],
    A[0],
    A[1],
    A[2],
    A[3],
    A[4],
];
/// The GST-GPS conversion parameters (§5.1.8) closing word type 10.
pub(super) const GST_GPS: [Field; 4] = [q::A0G, q::A1G, q::T0G, q::WN0G];
const W10: [Field; 12] = [
    q::IODA,
    A[5],
    A[6],
    A[7],
    A[8],
    A[9],
    A[10],
    A[11],
    GST_GPS[0],
    GST_GPS[1],
    GST_GPS[2],
    GST_GPS[3],
];

/// The fields after the word type of word type `word_type` (0-10), in order.
pub fn layout(word_type: u8) -> Option<&'static [Field]> {
    Some(match word_type {
        0 => &W0,
        1 => &W1,
        2 => &W2,
        3 => &W3,
        4 => &W4,
        5 => &W5,
        6 => &W6,
        7 => &W7,
        8 => &W8,
        9 => &W9,
        10 => &W10,
        _ => return None,
    })
}

/// The 128 bits of a word: type, then `values` (raw, one per layout field; two's
/// complement for signed fields), zero padded.
pub(super) fn pack(word_type: u8, values: &[i64]) -> Vec<u8> {
    let mut bits = Vec::with_capacity(WORD_BITS);
    push_bits(&mut bits, i64::from(word_type), q::WORD_TYPE.bits);
    for (f, &v) in layout(word_type).unwrap_or(&[]).iter().zip(values) {
        push_bits(&mut bits, v, f.bits);
    }
    bits.resize(WORD_BITS, 0);
    bits
}

/// The word type of a word's bits.
pub(super) fn word_type(word: &[u8]) -> u8 {
    word[..q::WORD_TYPE.bits as usize]
        .iter()
        .fold(0, |acc, &b| (acc << 1) | b)
}

/// Reads the raw values of `fields` from `word` starting after the word type.
pub(super) fn unpack(word: &[u8], fields: &[Field]) -> Vec<i64> {
    read_fields(&word[q::WORD_TYPE.bits as usize..], fields)
}
