//! The 25 pages of subframes 4 and 5 (IS-GPS-200 20.3.3.5, table 20-V, figure 20-1
//! sheets 4-11). Words 1 and 2 (TLM, HOW) are written by the encoder.

use super::almanac::Almanac;
use super::iono_utc::{RawIono, RawUtc, page18};
use super::words::DataWords;

/// Pages per subframe 4 or 5 cycle.
pub(crate) const PAGES: usize = 25;

/// SV ID of subframe 4 pages 1-25 (IS-GPS-200 table 20-V): almanac of PRN 25-32 on
/// pages 2-5 and 7-10, 52 NMCT, 55 special message, 56 ionosphere/UTC, 63 A-S flags and
/// configurations with health of PRN 25-32, the others reserved.
pub(crate) const SF4_SV_ID: [u32; PAGES] = [
    57, 25, 26, 27, 28, 57, 29, 30, 31, 32, 57, 62, 52, 53, 54, 57, 55, 56, 58, 59, 57, 60, 61, 62,
    63,
];
/// SV ID of subframe 5 page 25 (health of PRN 1-24, toa, WNa).
pub(crate) const SF5_PAGE25_SV_ID: u32 = 51;
/// Data ID of the LNAV structure, binary 01 (IS-GPS-200 20.3.3.5.1.1).
const DATA_ID: u32 = 0b01;
/// The 22-character special message of page 17 (8-bit ASCII, table 20-IX characters).
const SPECIAL_MESSAGE: &[u8; 22] = b"SKYFORGE SIMULATED NAV";
/// NMCT availability indicator "no correction table available" (IS-GPS-200 20.3.3.5.1.9).
const NMCT_NOT_AVAILABLE: u32 = 0b10;
/// Estimated range deviation "no data" (six-bit 100000, IS-GPS-200 20.3.3.5.1.9).
const ERD_NO_DATA: u32 = 0b10_0000;
/// Four-bit A-S flag and configuration of an SV with an almanac: A-S on (MSB 1),
/// configuration 001 "A-S capability, plus flags for A-S and alert in HOW"
/// (IS-GPS-200 20.3.3.5.1.4); 0000 for the others.
const CONFIG_PRESENT: u32 = 0b1001;

/// A page with its data ID and SV ID written.
fn page(sv_id: u32) -> DataWords {
    let mut d = DataWords::default();
    d.put(3, 1, 2, DATA_ID);
    d.put(3, 3, 6, sv_id);
    d
}

/// Reserved page: every data bit after the SV ID alternates ones and zeros.
fn reserved(sv_id: u32) -> DataWords {
    let mut d = page(sv_id);
    d.put_alternating(3, 9, 16);
    for w in 4..=9 {
        d.put_alternating(w, 1, 24);
    }
    d.put_alternating(10, 1, 22);
    d
}

/// Almanac page of `prn` (SV ID = PRN, or 0 for a dummy SV).
fn almanac_page(almanac: &Almanac, prn: u8) -> DataWords {
    let mut d = DataWords::default();
    let sv_id = almanac.write_page(prn, &mut d);
    d.put(3, 1, 2, DATA_ID);
    d.put(3, 3, 6, sv_id);
    d
}

/// Subframe 4, pages 1-25.
pub(crate) fn subframe4(almanac: &Almanac, iono: &RawIono, utc: &RawUtc) -> [DataWords; PAGES] {
    std::array::from_fn(|k| {
        let sv_id = SF4_SV_ID[k];
        match sv_id {
            25..=32 => almanac_page(almanac, sv_id as u8),
            52 => {
                let mut d = page(sv_id);
                let mut c = d.cursor(3, 9);
                c.push(2, NMCT_NOT_AVAILABLE);
                for _ in 0..30 {
                    c.push(6, ERD_NO_DATA);
                }
                d
            }
            55 => {
                let mut d = page(sv_id);
                let mut c = d.cursor(3, 9);
                for &ch in SPECIAL_MESSAGE {
                    c.push(8, u32::from(ch));
                }
                d.put_alternating(10, 17, 6);
                d
            }
            56 => {
                let mut d = page(sv_id);
                page18(&mut d, iono, utc);
                d
            }
            63 => {
                let mut d = page(sv_id);
                let present = almanac.prns();
                let mut c = d.cursor(3, 9);
                for prn in 1u8..=32 {
                    let config = if present.contains(&prn) {
                        CONFIG_PRESENT
                    } else {
                        0
                    };
                    c.push(4, config);
                }
                c.push(2, 0b10);
                for prn in 25u8..=32 {
                    c.push(6, almanac.health6(prn));
                }
                c.push(4, 0b1010);
                d
            }
            _ => reserved(sv_id),
        }
    })
}

/// Subframe 5, pages 1-25.
pub(crate) fn subframe5(almanac: &Almanac) -> [DataWords; PAGES] {
    std::array::from_fn(|k| {
        if k < 24 {
            almanac_page(almanac, k as u8 + 1)
        } else {
            let mut d = page(SF5_PAGE25_SV_ID);
            almanac.write_health_1_24(&mut d);
            d
        }
    })
}
