//! Receiving CNAV: one message from its soft symbols (Viterbi decoding of the continuous
//! code, preamble, CRC-24Q, fields), and the assembly of message types 10, 11 and 30 into
//! an ephemeris.
//!
//! Soft symbols: positive = logic 0, negative = logic 1 (BPSK +1 for 0), magnitude the
//! confidence, 0 an erasure; hard symbols map as 0 -> +1.0, 1 -> -1.0.

use super::eph::{self, Fields, T_REF_GRID_S};
use super::layout::{self, CNAV_PREAMBLE, HEADER, MESSAGE_BITS, MESSAGE_SYMBOLS};
use super::quant::{self as q, Field};
use crate::navmsg::conv_k7::ConvK7;
use crate::navmsg::crc24q::crc24q_bits;
use crate::navmsg::field::read_fields;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};
use skyforge_orbits::time::epoch_from_gpst;

/// Symbols before a message's first symbol that [`decode_message`] takes: the end of the
/// previous message, 35 bits (five constraint lengths) over which the decoder's unknown
/// start state settles. Where they are not at hand (the start of a recording), zeros
/// (erasures) stand in and the first bits are less protected.
pub const CNAV_LEAD_IN_SYMBOLS: usize = 70;
/// Messages in a week (the TOW count runs 0..100799).
const MESSAGES_PER_WEEK: u32 = 100_800;

/// One decoded message: header and, for the types SkyForge knows (10, 11, 30, 33), the
/// raw payload values (in LSB units, two's complement fields sign-extended) in the layout
/// order of IS-GPS-705J Figures 20-1, 20-2, 20-3, 20-6.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CnavMessage {
    pub prn: u8,
    pub msg_type: u8,
    /// Message TOW count: the TOW of the start of the next message in 6 s units.
    pub tow_count: u32,
    pub alert: bool,
    pub(super) values: Vec<i64>,
}

/// Why soft symbols are not a CNAV message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum CnavDecodeError {
    #[error("a CNAV message needs {need} soft symbols (lead-in and message), got {got}")]
    Length { need: usize, got: usize },
    #[error("the decoded bits do not start with the CNAV preamble 10001011")]
    Preamble,
    #[error("the symbols are inverted (preamble and CRC hold for the complemented bits)")]
    InvertedPolarity,
    #[error("CRC-24Q mismatch")]
    Crc,
}

impl CnavMessage {
    /// The payload fields: ICD name and raw value (reserved fields named "Reserved");
    /// none for a type SkyForge does not build.
    pub fn fields(&self) -> impl Iterator<Item = (&'static str, i64)> + '_ {
        let layout = layout::layout(self.msg_type).unwrap_or(&[]);
        layout
            .iter()
            .map(|f| f.name)
            .zip(self.values.iter().copied())
    }

    /// The raw value of the payload field named `name` (e.g. "toe", "af0-n", "WN").
    pub fn field(&self, name: &str) -> Option<i64> {
        self.fields().find(|(n, _)| *n == name).map(|(_, v)| v)
    }

    /// GPS TOW (s) of the start of the next message (0 for the first of a week).
    pub fn next_tow_s(&self) -> u32 {
        self.tow_count * 6
    }

    fn get(&self, f: &Field) -> Option<i64> {
        self.field(f.name)
    }
}

/// Decode one message from soft symbols: [`CNAV_LEAD_IN_SYMBOLS`] symbols before it, its
/// 600 symbols, and optionally symbols of the next message (which protect its last bits
/// as the lead-in protects its first). Symbols are G1, G2 pairs aligned on a bit.
pub fn decode_message(soft: &[f32]) -> Result<CnavMessage, CnavDecodeError> {
    let need = CNAV_LEAD_IN_SYMBOLS + MESSAGE_SYMBOLS;
    if soft.len() < need {
        return Err(CnavDecodeError::Length {
            need,
            got: soft.len(),
        });
    }
    let decoded = ConvK7::GPS_L5.decode_soft_window(soft);
    let start = CNAV_LEAD_IN_SYMBOLS / 2;
    let bits = &decoded[start..start + MESSAGE_BITS];
    check(bits)?;
    let header = read_fields(bits, &HEADER);
    let msg_type = header[2] as u8;
    let payload = layout::layout(msg_type).unwrap_or(&[]);
    let values = read_fields(&bits[38..], payload);
    Ok(CnavMessage {
        prn: header[1] as u8,
        msg_type,
        tow_count: header[3] as u32,
        alert: header[4] == 1,
        values,
    })
}

fn check(bits: &[u8]) -> Result<(), CnavDecodeError> {
    let preamble = bits[..8].iter().fold(0u8, |a, &b| (a << 1) | b);
    let crc_ok = |b: &[u8]| crc24q_bits(b) == 0;
    if preamble == CNAV_PREAMBLE {
        return if crc_ok(bits) {
            Ok(())
        } else {
            Err(CnavDecodeError::Crc)
        };
    }
    let flipped: Vec<u8> = bits.iter().map(|b| b ^ 1).collect();
    if preamble == !CNAV_PREAMBLE && crc_ok(&flipped) {
        Err(CnavDecodeError::InvertedPolarity)
    } else {
        Err(CnavDecodeError::Preamble)
    }
}

/// A decoded ephemeris with the GPS week and TOW of the start of the message after the
/// one that completed it.
#[derive(Debug, Clone, PartialEq)]
pub struct CnavEphemeris {
    pub eph: BroadcastEphemeris,
    pub week: u32,
    pub tow: u32,
}

/// Collects decoded messages of one satellite: types 10 and 11 of one toe and a type 30
/// (clock and TGD) of the same top make an ephemeris. A set with a non-zero Adot or
/// Delta n0 dot is not returned: [`BroadcastEphemeris`] cannot hold those terms.
#[derive(Debug, Clone, Default)]
pub struct CnavAssembler {
    prn: Option<u8>,
    parts: [Option<CnavMessage>; 3],
    time: Option<(u32, u32)>,
    last: Option<BroadcastEphemeris>,
}

impl CnavAssembler {
    pub fn new() -> Self {
        Self::default()
    }

    /// GPS week and TOW (s) of the start of the message after the last one taken, once a
    /// type 10 has given the week (WN, 13 bits, taken as the full week); later messages
    /// move it on, into the next week where their TOW count wraps.
    pub fn time(&self) -> Option<(u32, u32)> {
        self.time
    }

    /// Take one message; returns the ephemeris when types 10, 11 and 30 agree and it
    /// differs from the last one returned. A message of another PRN starts afresh.
    pub fn push(&mut self, msg: &CnavMessage) -> Option<CnavEphemeris> {
        if self.prn != Some(msg.prn) {
            *self = Self {
                prn: Some(msg.prn),
                ..Self::default()
            };
        }
        self.update_time(msg);
        let slot = match msg.msg_type {
            10 => 0,
            11 => 1,
            30 => 2,
            _ => return None,
        };
        self.parts[slot] = Some(msg.clone());
        let out = self.ephemeris()?;
        if self.last.as_ref() == Some(&out.eph) {
            return None;
        }
        self.last = Some(out.eph.clone());
        Some(out)
    }

    fn update_time(&mut self, msg: &CnavMessage) {
        if msg.tow_count >= MESSAGES_PER_WEEK {
            return;
        }
        let next = msg.next_tow_s();
        let wrapped = u32::from(msg.tow_count == 0);
        self.time = match (msg.get(&q::WN), self.time) {
            (Some(wn), _) => Some((wn as u32 + wrapped, next)),
            (None, Some((week, last))) => Some((week + u32::from(next < last), next)),
            (None, None) => None,
        };
    }

    fn ephemeris(&self) -> Option<CnavEphemeris> {
        let [Some(m10), Some(m11), Some(m30)] = &self.parts else {
            return None;
        };
        let agree = m10.get(&q::TOE) == m11.get(&q::TOE) && m10.get(&q::TOP) == m30.get(&q::TOP);
        let lnav_like = m10.get(&q::A_DOT) == Some(0) && m10.get(&q::DELTA_N0_DOT) == Some(0);
        let prn = self.prn.filter(|&p| p > 0 && p <= System::Gps.max_prn())?;
        let (week, tow) = self.time?;
        if !agree || !lnav_like {
            return None;
        }
        let mut fields = Fields::default();
        for m in [m10, m11, m30] {
            fields.absorb(layout::layout(m.msg_type)?, &m.values);
        }
        let now = epoch_from_gpst(week, f64::from(tow));
        let at = |f: &Field| nearest(now, fields.get(f) as u64 * T_REF_GRID_S);
        let eph = eph::to_ephemeris(&fields, SatId::gps(prn), at(&q::TOE), at(&q::TOC));
        Some(CnavEphemeris { eph, week, tow })
    }
}

/// The epoch `sow_s` seconds into the GPS week (of the weeks around `near`) nearest to
/// `near`: toe and toc carry no week.
fn nearest(near: Epoch, sow_s: u64) -> Epoch {
    let week = skyforge_orbits::time::gpst_week_sow(near).0;
    (week.saturating_sub(1)..=week + 1)
        .map(|w| epoch_from_gpst(w, sow_s as f64))
        .min_by_key(|&t| (t - near).abs().total_nanoseconds())
        .unwrap_or(near)
}
