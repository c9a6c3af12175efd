//! CNAV message layouts and the message's channel coding (IS-GPS-705J §20.3.3, §20.3.5,
//! §3.3.3.1.1).
//!
//! A message (§20.3.3) is 300 bits: a 38-bit header (preamble 10001011, PRN, message
//! type ID, message TOW count, alert flag), 238 bits of payload and 24 CRC-24Q parity bits
//! over the first 276 (§20.3.5). Bits are sent most significant first. The 50 bps stream is
//! encoded by the rate 1/2, K = 7 code (G1 = 171o first, G2 = 133o, `conv_k7::GPS_L5`)
//! without reset at message boundaries (§3.3.3.1.1): a message's 600 symbols depend on
//! the last six bits of the message before it.
//!
//! Payload layouts (Figures 20-1, 20-2, 20-3, 20-6; start bits agree with GNSSTk's
//! GPSCBits.hpp, e.g. toe at bit 70 of type 10, af0 at bit 71 and TGD at bit 127 of the
//! clock messages, counting from 0):
//! 10: WN, L1/L2/L5 health, top, URA_ED, toe, Delta A, Adot, Delta n0, Delta n0 dot, M0,
//!     e, omega, integrity flag, L2C phasing, 3 reserved;
//! 11: toe, OMEGA0, i0, Delta OMEGAdot, IDOT, Cis, Cic, Crs, Crc, Cus, Cuc, 7 reserved;
//! 30: clock block, TGD, four ISCs, alpha0-3, beta0-3, WNop, 12 reserved;
//! 33: clock block, A0, A1, A2, Delta tLS, tot, WNot, WNLSF, DN, Delta tLSF, 51 reserved.
//! The clock block (types 30-37): top, URA_NED0, URA_NED1, URA_NED2, toc, af0, af1, af2.

use super::quant::{self as q, Field, reserved};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;
use crate::navmsg::field::push_bits;

/// Bits per message.
pub const MESSAGE_BITS: usize = 300;
/// Bits the CRC covers: header and payload.
pub const DATA_BITS: usize = 276;
/// Channel symbols per message (rate 1/2).
pub const MESSAGE_SYMBOLS: usize = 2 * MESSAGE_BITS;
/// The preamble, 10001011 (IS-GPS-705J §20.3.3).
pub const CNAV_PREAMBLE: u8 = 0b1000_1011;

/// The header fields, in order.
pub const HEADER: [Field; 5] = [q::PREAMBLE, q::PRN, q::MSG_TYPE, q::TOW, q::ALERT];

const MT10: [Field; 17] = [
    q::WN,
    q::HEALTH_L1,
    q::HEALTH_L2,
    q::HEALTH_L5,
    q::TOP,
    q::URA_ED,
    q::TOE,
    q::DELTA_A,
    q::A_DOT,
    q::DELTA_N0,
    q::DELTA_N0_DOT,
    q::M0,
    q::E,
    q::OMEGA,
    q::INTEGRITY,
    q::L2C_PHASING,
    reserved(3),
];
const MT11: [Field; 12] = [
    q::TOE,
    q::OMEGA0,
    q::I0,
    q::DELTA_OMEGA_DOT,
    q::IDOT,
    q::CIS,
    q::CIC,
    q::CRS,
    q::CRC,
    q::CUS,
    q::CUC,
    reserved(7),
];
const MT30: [Field; 23] = [
    q::TOP,
    q::URA_NED0,
    q::URA_NED1,
    q::URA_NED2,
    q::TOC,
    q::AF0,
    q::AF1,
    q::AF2,
    q::TGD,
    q::ISC_L1CA,
    q::ISC_L2C,
    q::ISC_L5I5,
    q::ISC_L5Q5,
    q::ALPHA[0],
    q::ALPHA[1],
    q::ALPHA[2],
    q::ALPHA[3],
    q::BETA[0],
    q::BETA[1],
    q::BETA[2],
    q::BETA[3],
    q::WN_OP,
    reserved(12),
];
const MT33: [Field; 18] = [
    q::TOP,
    q::URA_NED0,
    q::URA_NED1,
    q::URA_NED2,
    q::TOC,
    q::AF0,
    q::AF1,
    q::AF2,
    q::A0,
    q::A1,
    q::A2,
    q::DT_LS,
    q::TOT,
    q::WN_OT,
    q::WN_LSF,
    q::DN,
    q::DT_LSF,
    reserved(51),
];

/// The payload fields (after the header) of message type `msg_type`, for the types
/// SkyForge builds (10, 11, 30, 33).
pub fn layout(msg_type: u8) -> Option<&'static [Field]> {
    match msg_type {
        10 => Some(&MT10),
        11 => Some(&MT11),
        30 => Some(&MT30),
        33 => Some(&MT33),
        _ => None,
    }
}

/// Header then payload fields of `msg_type`, in order (an unknown type: the header).
pub(super) fn all_fields(msg_type: u8) -> impl Iterator<Item = &'static Field> {
    HEADER.iter().chain(layout(msg_type).unwrap_or(&[]))
}

/// The 300 bits of a message: `values` (raw, one per field of [`all_fields`], two's
/// complement for signed fields), then the CRC over the first 276.
pub(super) fn pack(msg_type: u8, values: &[i64]) -> [u8; MESSAGE_BITS] {
    let mut bits = Vec::with_capacity(MESSAGE_BITS);
    for (f, &v) in all_fields(msg_type).zip(values) {
        push_bits(&mut bits, v, f.bits);
    }
    bits.resize(DATA_BITS, 0);
    let crc = crc24q_bits(&bits);
    push_bits(&mut bits, i64::from(crc), 24);
    let mut out = [0u8; MESSAGE_BITS];
    out.copy_from_slice(&bits);
    out
}

/// The 600 channel symbols of `message`, sent after `previous` (the encoder continues
/// from the state the previous message's last six bits left).
pub(super) fn encode(previous: &[u8], message: &[u8]) -> Vec<u8> {
    ConvK7::GPS_L5.encode_after(previous, message)
}
