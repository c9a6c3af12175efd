//! BeiDou B-CNAV2 decoder (BDS-SIS-ICD-B2a-1.0 §6.2) fed with B2a data-component channel
//! symbols, 200 per second.
//!
//! Frame synchronisation: a search correlates the 24-symbol preamble 0xE24DE8 (6.2.1) at
//! every offset of a 600-symbol window; each offset whose normalised correlation exceeds
//! [`PREAMBLE_THRESHOLD`] (its sign giving the polarity) is a candidate, confirmed by
//! [`decode_frame`]: soft LDPC(96, 48) decoding over GF(64) (min-sum, see
//! `skyforge_gnss::navmsg::ldpc_gf64`) and CRC-24Q (6.1.2). Locked, a frame follows every
//! 600 symbols. Types 10, 11 and 30 of one issue make a [`NavEvent::Ephemeris`].
//! [`decoder_for`] returns it for `Signal::BdsB2a`.
//!
//! [`decoder_for`]: super::decoder_for

use super::symbol_sync::{SymbolFormat, SymbolSync, SyncedDecoder, with_polarity};
use super::{DecodedEphemeris, NavDecodeError, NavEvent, SubframeInfo};
use skyforge_gnss::navmsg::bds_cnav2::{
    CNAV2_FRAME_SYMBOLS, CNAV2_PREAMBLE, Cnav2Assembler, Cnav2DecodeError, Cnav2Message,
    decode_frame,
};
use skyforge_orbits::ephemeris::{SatId, System};

/// Normalised preamble correlation (sum of s_k p_k over sum of |s_k|) that makes a
/// candidate frame start: a noiseless preamble gives 1.
const PREAMBLE_THRESHOLD: f32 = 0.6;
/// Seconds per week.
const WEEK_S: u32 = 604_800;

/// Decoder of one BeiDou MEO/IGSO satellite's B-CNAV2 symbol stream.
///
/// Each decoded frame is a [`NavEvent::Subframe`]: `start_bit` is the index of its first
/// preamble symbol, `id` the message type, `tow_s` its SOW, `week` the BDT week once a
/// type 10 gave it.
#[derive(Debug, Clone)]
pub struct BdsCnav2Decoder {
    sat: SatId,
    format: Cnav2,
    sync: SymbolSync,
    assembler: Cnav2Assembler,
    last: Option<DecodedEphemeris>,
}

impl BdsCnav2Decoder {
    /// A decoder for BeiDou satellite `sat` (PRN 1-63; B2a is broadcast by the BDS-3 MEO
    /// and IGSO satellites).
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Beidou || !(1..=63).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "B-CNAV2 is broadcast by BeiDou PRN 1-63",
            });
        }
        Ok(Self {
            sat,
            format: Cnav2 { prn: sat.prn },
            sync: SymbolSync::new(),
            assembler: Cnav2Assembler::new(sat),
            last: None,
        })
    }

    /// Whether frame synchronisation is held.
    pub fn is_synchronised(&self) -> bool {
        self.sync.locked_since().is_some()
    }

    fn take(&mut self, start: u64, inverted: bool, msg: &Cnav2Message, out: &mut Vec<NavEvent>) {
        let eph = self.assembler.push(msg);
        out.push(NavEvent::Subframe(SubframeInfo {
            start_bit: start,
            id: msg.mes_type,
            page: None,
            week: self.assembler.week(),
            tow_s: f64::from(msg.sow_s),
            inverted,
            corrected_bits: 0,
        }));
        DecodedEphemeris::push_bds3(&mut self.last, eph, out);
    }
}

impl SyncedDecoder for BdsCnav2Decoder {
    type Format = Cnav2;

    fn parts(&mut self) -> (&mut SymbolSync, &Self::Format) {
        (&mut self.sync, &self.format)
    }

    fn symbol_sync(&self) -> &SymbolSync {
        &self.sync
    }

    fn sat(&self) -> SatId {
        self.sat
    }

    fn message(&mut self, start: u64, inverted: bool, msg: &Cnav2Message, out: &mut Vec<NavEvent>) {
        self.take(start, inverted, msg, out);
    }
}

/// B-CNAV2 framing: a frame of the expected PRN with a SOW below one week.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cnav2 {
    prn: u8,
}

impl SymbolFormat for Cnav2 {
    type Message = Cnav2Message;
    const PERIOD: u64 = CNAV2_FRAME_SYMBOLS as u64;
    const LEAD_IN: u64 = 0;
    const SPAN: u64 = CNAV2_FRAME_SYMBOLS as u64;

    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)> {
        let sign = |k: usize| {
            if (CNAV2_PREAMBLE >> (23 - k)) & 1 == 1 {
                -1.0
            } else {
                1.0
            }
        };
        (0..Self::PERIOD as usize)
            .filter_map(|offset| {
                let w = window.get(offset..offset + 24)?;
                let norm: f32 = w.iter().map(|x| x.abs()).sum();
                let corr: f32 = w.iter().enumerate().map(|(k, x)| sign(k) * x).sum();
                let c = corr / norm.max(f32::MIN_POSITIVE);
                (c.abs() > PREAMBLE_THRESHOLD).then_some((offset as u64, c < 0.0))
            })
            .collect()
    }

    fn decode(&self, window: &[f32], inverted: bool) -> Option<(Cnav2Message, bool)> {
        let (msg, inv) = match decode_frame(&with_polarity(window, inverted)) {
            Ok(msg) => (msg, inverted),
            Err(Cnav2DecodeError::Preamble { inverted: true }) => (
                decode_frame(&with_polarity(window, !inverted)).ok()?,
                !inverted,
            ),
            Err(_) => return None,
        };
        (msg.prn == self.prn && msg.sow_s < WEEK_S).then_some((msg, inv))
    }
}

#[cfg(test)]
mod tests;
