//! The B-CNAV2 frame layout (BDS-SIS-ICD-B2a-1.0 6.2.1, 6.2.3, Figures 6-3 to 6-9):
//! 24-symbol preamble, then 288 bits (PRN 6, MesType 6, SOW 18, 234 data bits, CRC-24Q)
//! LDPC(96, 48) encoded to 576 symbols.

use crate::navmsg::bds_cnav_eph::{self as e, rev};
use crate::navmsg::field::{Field, Lsb, field};

/// 6.2.1: the preamble 0xE24DE8, MSB first.
pub const CNAV2_PREAMBLE: u32 = 0x00E2_4DE8;
/// Preamble symbols.
pub(super) const PREAMBLE_SYMBOLS: usize = 24;
/// Bits before encoding, CRC included.
pub(super) const FRAME_BITS: usize = 288;
/// Symbols per frame: preamble and the LDPC codeword.
pub const CNAV2_FRAME_SYMBOLS: usize = 600;

pub(super) const PRN: Field = field("PRN", 6, false, Lsb::Count);
pub(super) const MES_TYPE: Field = field("MesType", 6, false, Lsb::Count);
/// Table 7-2: SOW of the frame's first preamble chip, scale 3 s.
pub(super) const SOW: Field = field("SOW", 18, false, Lsb::Value(3.0));
pub(super) const HEADER: [Field; 3] = [PRN, MES_TYPE, SOW];

/// The B2a integrity flags, SISMAI and the B1C integrity flags, in every message type.
const FLAGS: [Field; 7] = [
    e::FLAGS_B2A[0],
    e::FLAGS_B2A[1],
    e::FLAGS_B2A[2],
    e::SISMAI,
    e::FLAGS_B1C[0],
    e::FLAGS_B1C[1],
    e::FLAGS_B1C[2],
];

/// The 234 data bits of message type `t` (10, 11, 30 or 34), in broadcast order.
pub(super) fn data_fields(t: u8) -> Option<Vec<Field>> {
    let flags = FLAGS;
    let mut v = Vec::new();
    match t {
        // Figure 6-3: WN, flags, IODE, ephemeris I.
        10 => {
            v.push(e::WN);
            v.extend(flags);
            v.push(e::IODE);
            v.extend(e::EPHEMERIS_1);
        }
        // Figure 6-4: HS, flags, ephemeris II.
        11 => {
            v.push(e::HS);
            v.extend(flags);
            v.extend(e::EPHEMERIS_2);
        }
        // Figure 6-5: HS, flags, clock, IODC, TGD_B2ap, ISC_B2ad, ionosphere, TGD_B1Cp.
        30 => {
            v.push(e::HS);
            v.extend(flags);
            v.extend(e::CLOCK);
            v.extend([e::IODC, e::TGD_B2AP, e::ISC_B2AD]);
            v.extend(e::IONO);
            v.extend([e::TGD_B1CP, rev(33)]);
        }
        // Figure 6-9: HS, flags, SISAIoc, clock, IODC, BDT-UTC.
        34 => {
            v.push(e::HS);
            v.extend(flags);
            v.extend([e::SISAI_OC]);
            v.extend(e::CLOCK);
            v.push(e::IODC);
            v.extend(e::BDT_UTC);
            v.push(rev(24));
        }
        _ => return None,
    }
    Some(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_message_fills_234_data_bits() {
        for t in [10, 11, 30, 34] {
            let bits: u32 = data_fields(t).unwrap().iter().map(|f| f.bits).sum();
            assert_eq!(bits, 234, "type {t}");
        }
        let header: u32 = HEADER.iter().map(|f| f.bits).sum();
        assert_eq!(header as usize + 234 + 24, FRAME_BITS);
        assert!(data_fields(31).is_none());
    }

    /// Offset (bits, 0-based from the PRN's first bit) of field `name` in message type `t`.
    fn offset(t: u8, name: &str) -> u32 {
        let fields: Vec<Field> = HEADER.into_iter().chain(data_fields(t).unwrap()).collect();
        let at = fields.iter().position(|f| f.name == name).unwrap();
        fields[..at].iter().map(|f| f.bits).sum()
    }

    /// Absolute positions, which round trips through the shared layout cannot check: an
    /// independent reading of Figures 6-3/6-4 (the bit positions GNSS-SDR's B2a decoder
    /// reads real frames with, and cssrlib's unpacking: WN, the ten flag bits, IODE, then
    /// ephemeris I; HS, the flags, then ephemeris II).
    #[test]
    fn ephemeris_messages_put_their_fields_where_receivers_read_them() {
        assert_eq!(offset(10, "WN"), 30);
        assert_eq!(offset(10, "DIF(B2a)"), 43);
        assert_eq!(offset(10, "IODE"), 53);
        assert_eq!(offset(10, "toe"), 61);
        assert_eq!(offset(11, "HS"), 30);
        assert_eq!(offset(11, "Omega0"), 42);
        assert_eq!(offset(30, "HS"), 30);
        assert_eq!(offset(30, "toc"), 42);
    }
}
