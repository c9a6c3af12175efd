//! The BeiDou B-CNAV2 navigation message of the B2a data component
//! (BDS-SIS-ICD-B2a-1.0 §6, §7), encoder and decoder.
//!
//! Timing (6.2.1, Table 7-2): 200 symbols/s, a frame of 600 symbols lasts 3 s and its
//! SOW is the BDT of its first preamble symbol; SkyForge starts frames at BDT whole 3 s
//! of the week (201600 frames a week). Frame: preamble 0xE24DE8 (24 symbols), then the
//! 288 bits PRN, MesType, SOW, 234 data bits and CRC-24Q (6.1.2), LDPC(96, 48) encoded
//! ([`crate::navmsg::ldpc_gf64::B2A_FRAME`]) to 576 symbols.
//!
//! Schedule: types 10, 11, 30, 34 repeating from each week's start (a 12 s cycle, 201600
//! frames a week being a multiple of 4); 10 and 11 follow each other as 6.2.3 requires,
//! types 30 and 34 both carry the clock. SkyForge sends no almanac (31, 33, 40), EOP
//! (32) or BGTO messages. Field order within the 234 data bits is [`layout`]'s.
//!
//! [`BdsCnav2Encoder`] turns one ephemeris into channel symbols; [`decode_frame`] and
//! [`Cnav2Assembler`] turn received soft symbols back into messages and an ephemeris.

mod decode;
mod layout;
#[cfg(test)]
mod tests;

pub use decode::{Cnav2Assembler, Cnav2DecodeError, Cnav2Message, decode_frame};
pub use layout::{CNAV2_FRAME_SYMBOLS, CNAV2_PREAMBLE};

use super::bds_cnav_eph::{self as e, BdsCnavError, BdsCnavParams};
use super::crc24q::crc24q_bits;
use super::field::{Fields, push_bits};
use super::ldpc_gf64::B2A_FRAME;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Channel symbol rate of the B2a data component (symbols/s).
pub const CNAV2_SYMBOL_RATE_HZ: f64 = 200.0;
/// Frame duration (s).
pub const CNAV2_FRAME_S: u64 = 3;
/// The repeating message schedule, from each week's start.
pub const CNAV2_SCHEDULE: [u8; 4] = [10, 11, 30, 34];
/// Frames in a week.
const FRAMES_PER_WEEK: u64 = 604_800 / CNAV2_FRAME_S;

/// The channel symbols of one satellite's B-CNAV2 message, counted from the start of BDT
/// week [`Self::week`] (symbol 0 is the first preamble symbol of a type 10 frame).
#[derive(Debug, Clone)]
pub struct BdsCnav2Encoder {
    sat: SatId,
    week: u32,
    fields: Fields,
    toe: Epoch,
    toc: Epoch,
}

impl BdsCnav2Encoder {
    /// An encoder for BeiDou MEO/IGSO ephemeris `eph` from the start of BDT week
    /// `bdt_week`. toe and toc must be on the 300 s grid; every value must fit its field.
    pub fn new(
        eph: &BroadcastEphemeris,
        params: &BdsCnavParams,
        bdt_week: u32,
    ) -> Result<Self, BdsCnavError> {
        Ok(Self {
            sat: eph.sat,
            week: bdt_week,
            fields: e::quantise(eph, params)?,
            toe: eph.toe,
            toc: eph.toc,
        })
    }

    /// BDT week of symbol 0.
    pub fn week(&self) -> u32 {
        self.week
    }

    /// Start of BDT week [`Self::week`], where symbol 0 starts.
    pub fn week_start(&self) -> Epoch {
        skyforge_orbits::time::epoch_from_bdt(self.week, 0.0)
    }

    /// The ephemeris the messages describe, in SI units (every field quantised and
    /// converted back; `tgd_s` = TGD_B2ap, IODE, IODC, health = HS, 3 h fit).
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        e::to_ephemeris(&self.fields, self.sat, self.toe, self.toc, &e::TGD_B2AP)
    }

    /// Message type of frame `n` (frame 0 starts at the week start).
    pub fn message_type(&self, n: u64) -> u8 {
        CNAV2_SCHEDULE[(n % CNAV2_SCHEDULE.len() as u64) as usize]
    }

    /// BDT week and SOW (s) of the start of frame `n`.
    pub fn frame_time(&self, n: u64) -> (u32, u32) {
        let week = self.week + (n / FRAMES_PER_WEEK) as u32;
        (week, ((n % FRAMES_PER_WEEK) * CNAV2_FRAME_S) as u32)
    }

    /// The 288 bits of frame `n`, CRC included.
    pub fn frame_bits(&self, n: u64) -> Vec<u8> {
        let t = self.message_type(n);
        let (week, sow) = self.frame_time(n);
        let mut f = self.fields.clone();
        f.set(&layout::PRN, i64::from(self.sat.prn));
        f.set(&layout::MES_TYPE, i64::from(t));
        f.set(&layout::SOW, i64::from(sow) / CNAV2_FRAME_S as i64);
        f.set(&e::WN, i64::from(week % (1 << e::WN.bits)));
        let fields: Vec<_> = layout::HEADER
            .into_iter()
            .chain(layout::data_fields(t).unwrap_or_default())
            .collect();
        let mut bits = Vec::with_capacity(layout::FRAME_BITS);
        for (field, v) in fields.iter().zip(f.values_for(&fields)) {
            push_bits(&mut bits, v, field.bits);
        }
        let crc = crc24q_bits(&bits);
        push_bits(&mut bits, i64::from(crc), 24);
        bits
    }

    /// The 600 channel symbols (0/1) of frame `n`: preamble and LDPC codeword.
    pub fn frame_symbols(&self, n: u64) -> Vec<u8> {
        let mut out = Vec::with_capacity(CNAV2_FRAME_SYMBOLS);
        push_bits(&mut out, i64::from(CNAV2_PREAMBLE), 24);
        out.extend(B2A_FRAME.encode_bits(&self.frame_bits(n)));
        out
    }

    /// Channel symbol `k` (0/1), symbol 0 the first of the week's first frame.
    pub fn symbol(&self, k: u64) -> u8 {
        let n = CNAV2_FRAME_SYMBOLS as u64;
        self.frame_symbols(k / n)[(k % n) as usize]
    }

    /// `count` channel symbols from symbol `first` on.
    pub fn symbols(&self, first: u64, count: usize) -> Vec<u8> {
        e::symbols_of_frames(CNAV2_FRAME_SYMBOLS, first, count, |n| self.frame_symbols(n))
    }
}
