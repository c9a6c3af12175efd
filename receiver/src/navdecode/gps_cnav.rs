//! GPS L5 CNAV decoder (IS-GPS-705J §3.3.3.1.1, §20.3.3-20.3.5) fed with I5 channel
//! symbols, 100 per second.
//!
//! The rate 1/2, K = 7 code runs on across messages, so neither the symbol pair (G1, G2)
//! nor the message start is known at first: the search Viterbi-decodes a window in both
//! pair alignments and takes each preamble 10001011 (or its complement, an inverted
//! stream) as a candidate, which [`decode_message`] confirms by CRC-24Q (§20.3.5) over
//! the lead-in, the 600 message symbols and as many after them. Locked, a message follows
//! every 600 symbols.

use super::symbol_sync::{SymbolFormat, SymbolSync, SyncedDecoder, with_polarity};
use super::{DecodedEphemeris, NavDecodeError, NavEvent, SubframeInfo};
use skyforge_gnss::navmsg::conv_k7::ConvK7;
use skyforge_gnss::navmsg::gps_cnav::{
    CNAV_LEAD_IN_SYMBOLS, CNAV_MESSAGE_S, CNAV_MESSAGE_SYMBOLS, CNAV_PREAMBLE, CnavAssembler,
    CnavDecodeError, CnavMessage, decode_message,
};
use skyforge_orbits::ephemeris::{SatId, System};

/// Messages in a GPS week: the TOW count runs 0..100799 (§20.3.3).
const MESSAGES_PER_WEEK: u32 = 100_800;
/// Seconds per week.
const WEEK_S: u32 = 604_800;

/// Decoder of one GPS satellite's L5 CNAV symbol stream.
///
/// Each decoded message is a [`NavEvent::Subframe`]: `start_bit` is the index of its
/// first symbol, `id` the message type, `tow_s` the GPS TOW of that symbol (the message
/// TOW count x 6 s - 6 s), `week` the GPS week once a type 10 gave it. Types 10, 11 and
/// 30 of one toe/top make a [`NavEvent::Ephemeris`].
#[derive(Debug, Clone)]
pub struct CnavDecoder {
    sat: SatId,
    format: Cnav,
    sync: SymbolSync,
    assembler: CnavAssembler,
    /// URA_ED index of the last type 10, clamped to 0-15.
    ura_index: u8,
}

impl CnavDecoder {
    /// A decoder for GPS satellite `sat` (PRN 1-32).
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Gps || !(1..=System::Gps.max_prn()).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "L5 CNAV is broadcast by GPS PRN 1-32",
            });
        }
        Ok(Self {
            sat,
            format: Cnav { prn: sat.prn },
            sync: SymbolSync::new(),
            assembler: CnavAssembler::new(),
            ura_index: 0,
        })
    }

    /// Whether message synchronisation is held.
    pub fn is_synchronised(&self) -> bool {
        self.sync.locked_since().is_some()
    }

    /// Report a decoded message starting at symbol `start`.
    fn take(&mut self, start: u64, inverted: bool, msg: &CnavMessage, out: &mut Vec<NavEvent>) {
        let eph = self.assembler.push(msg);
        if msg.msg_type == 10
            && let Some(ura) = msg.field("URA_ED index")
        {
            self.ura_index = ura.clamp(0, 15) as u8;
        }
        let message_s = CNAV_MESSAGE_S as u32;
        // The TOW count gives the start of the next message (§20.3.3).
        let week = self.assembler.time().and_then(|(week, next_tow)| {
            if next_tow < message_s {
                week.checked_sub(1)
            } else {
                Some(week)
            }
        });
        let tow = (msg.next_tow_s() + WEEK_S - message_s) % WEEK_S;
        out.push(NavEvent::Subframe(SubframeInfo {
            start_bit: start,
            id: msg.msg_type,
            page: None,
            week,
            tow_s: f64::from(tow),
            inverted,
            corrected_bits: 0,
        }));
        if let Some(e) = eph {
            out.push(NavEvent::Ephemeris(Box::new(DecodedEphemeris {
                eph: e.eph,
                ura_index: self.ura_index,
                tgd2_s: None,
            })));
        }
    }
}

impl SyncedDecoder for CnavDecoder {
    type Format = Cnav;

    fn parts(&mut self) -> (&mut SymbolSync, &Self::Format) {
        (&mut self.sync, &self.format)
    }

    fn symbol_sync(&self) -> &SymbolSync {
        &self.sync
    }

    fn sat(&self) -> SatId {
        self.sat
    }

    fn message(&mut self, start: u64, inverted: bool, msg: &CnavMessage, out: &mut Vec<NavEvent>) {
        self.take(start, inverted, msg, out);
    }
}

/// CNAV framing: a message of the expected PRN with a TOW count below one week.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cnav {
    prn: u8,
}

impl SymbolFormat for Cnav {
    type Message = CnavMessage;
    const PERIOD: u64 = CNAV_MESSAGE_SYMBOLS as u64;
    const LEAD_IN: u64 = CNAV_LEAD_IN_SYMBOLS as u64;
    /// The message and a lead-out as long as the lead-in, which protects its last bits.
    const SPAN: u64 = (CNAV_MESSAGE_SYMBOLS + CNAV_LEAD_IN_SYMBOLS) as u64;

    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)> {
        let lead = CNAV_LEAD_IN_SYMBOLS;
        let mut out = Vec::new();
        for align in 0..2 {
            let Some(symbols) = window.get(align..) else {
                continue;
            };
            let bits = ConvK7::GPS_L5.decode_soft_window(symbols);
            for (i, w) in bits.windows(8).enumerate() {
                let byte = w.iter().fold(0u8, |a, &b| (a << 1) | b);
                let inverted = match byte {
                    CNAV_PREAMBLE => false,
                    b if b == !CNAV_PREAMBLE => true,
                    _ => continue,
                };
                let offset = (align + 2 * i).checked_sub(lead).map(|o| o as u64);
                if let Some(offset) = offset.filter(|&o| o < Self::PERIOD) {
                    out.push((offset, inverted));
                }
            }
        }
        out.sort_unstable_by_key(|&(offset, _)| offset);
        out
    }

    fn decode(&self, window: &[f32], inverted: bool) -> Option<(CnavMessage, bool)> {
        let (msg, inv) = match decode_message(&with_polarity(window, inverted)) {
            Ok(msg) => (msg, inverted),
            Err(CnavDecodeError::InvertedPolarity) => (
                decode_message(&with_polarity(window, !inverted)).ok()?,
                !inverted,
            ),
            Err(_) => return None,
        };
        (msg.prn == self.prn && msg.tow_count < MESSAGES_PER_WEEK).then_some((msg, inv))
    }
}

#[cfg(test)]
mod tests;
