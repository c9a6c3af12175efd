//! BeiDou B-CNAV1 decoder (BDS-SIS-ICD-B1C-1.0 §6.2) fed with B1C data-component channel
//! symbols, 100 per second.
//!
//! Frame synchronisation: the tracking channel starts the symbol stream at a start of the
//! pilot's 1800-chip secondary code, which lasts one 18 s frame and starts with it, so the
//! decoder built by [`decoder_for`] is locked on symbol 0 from the start
//! ([`BdsCnav1Decoder::aligned`]). Should frames fail three times in a row (or for a
//! stream of unknown alignment, [`BdsCnav1Decoder::new`]) it searches: every offset of an
//! 1800-symbol window whose normalised correlation with the PRN's BCH(21, 6) word
//! (subframe 1) exceeds [`PRN_THRESHOLD`] is a candidate, confirmed by
//! [`decode_frame`]: the SOH's BCH(51, 8) word, subframes 2 and 3 de-interleaved, soft
//! LDPC-decoded over GF(64) (`skyforge_gnss::navmsg::ldpc_gf64`) and CRC-24Q checked. A
//! frame whose subframe 2 decoded gives its time (HOW and SOH) and a complete ephemeris.
//!
//! [`decoder_for`]: super::decoder_for

use super::symbol_sync::{SymbolFormat, SymbolSync, SyncedDecoder, with_polarity};
use super::{DecodedEphemeris, NavDecodeError, NavEvent, SubframeInfo};
use skyforge_gnss::navmsg::bds_cnav1::{
    CNAV1_FRAME_SYMBOLS, Cnav1Frame, decode_frame, prn_correlation,
};
use skyforge_orbits::ephemeris::{SatId, System};

/// Normalised PRN-word correlation (sum of s_k p_k over sum of |s_k|) that makes a
/// candidate frame start: a noiseless word gives 1.
const PRN_THRESHOLD: f32 = 0.6;
/// Symbols of the PRN word that opens a frame (BCH(21, 6), §6.2.2.1).
const PRN_WORD_SYMBOLS: usize = 21;
/// Seconds per week.
const WEEK_S: u32 = 604_800;

/// Decoder of one BeiDou MEO/IGSO satellite's B-CNAV1 symbol stream.
///
/// Each frame whose subframe 2 decoded is a [`NavEvent::Subframe`]: `start_bit` is the
/// index of its first symbol, `id` its subframe 3 page type (0 when subframe 3 failed),
/// `tow_s` its SOW, `week` its BDT week.
#[derive(Debug, Clone)]
pub struct BdsCnav1Decoder {
    sat: SatId,
    format: Cnav1,
    sync: SymbolSync,
    last: Option<DecodedEphemeris>,
}

impl BdsCnav1Decoder {
    /// A decoder for BeiDou satellite `sat` (PRN 1-63; B1C is broadcast by the BDS-3 MEO
    /// and IGSO satellites) on a stream of unknown alignment: it searches for frames.
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Beidou || !(1..=63).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "B-CNAV1 is broadcast by BeiDou PRN 1-63",
            });
        }
        Ok(Self {
            sat,
            format: Cnav1 { prn: sat.prn },
            sync: SymbolSync::new(),
            last: None,
        })
    }

    /// [`Self::new`] on a stream whose symbol 0 starts a frame (the tracking channel's,
    /// aligned by the pilot's secondary code): locked from symbol 0 on.
    pub fn aligned(sat: SatId) -> Result<Self, NavDecodeError> {
        Ok(Self {
            sync: SymbolSync::locked_at(0),
            ..Self::new(sat)?
        })
    }

    /// Whether frame synchronisation is held.
    pub fn is_synchronised(&self) -> bool {
        self.sync.locked_since().is_some()
    }

    fn take(&mut self, start: u64, inverted: bool, frame: &Cnav1Frame, out: &mut Vec<NavEvent>) {
        let Some((week, sow)) = frame.time() else {
            return;
        };
        out.push(NavEvent::Subframe(SubframeInfo {
            start_bit: start,
            id: frame.page_id().unwrap_or(0),
            page: None,
            week: Some(week),
            tow_s: f64::from(sow),
            inverted,
            corrected_bits: 0,
        }));
        DecodedEphemeris::push_bds3(&mut self.last, frame.ephemeris(self.sat), out);
    }
}

impl SyncedDecoder for BdsCnav1Decoder {
    type Format = Cnav1;

    fn parts(&mut self) -> (&mut SymbolSync, &Self::Format) {
        (&mut self.sync, &self.format)
    }

    fn symbol_sync(&self) -> &SymbolSync {
        &self.sync
    }

    fn sat(&self) -> SatId {
        self.sat
    }

    fn message(&mut self, start: u64, inverted: bool, frame: &Cnav1Frame, out: &mut Vec<NavEvent>) {
        self.take(start, inverted, frame, out);
    }
}

/// B-CNAV1 framing: a frame of the expected PRN whose subframe 2 gives a SOW below one
/// week.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cnav1 {
    prn: u8,
}

impl SymbolFormat for Cnav1 {
    type Message = Cnav1Frame;
    const PERIOD: u64 = CNAV1_FRAME_SYMBOLS as u64;
    const LEAD_IN: u64 = 0;
    const SPAN: u64 = CNAV1_FRAME_SYMBOLS as u64;

    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)> {
        (0..Self::PERIOD as usize)
            .filter_map(|offset| {
                let w = window.get(offset..offset + PRN_WORD_SYMBOLS)?;
                let c = prn_correlation(w, self.prn);
                (c.abs() > PRN_THRESHOLD).then_some((offset as u64, c < 0.0))
            })
            .collect()
    }

    /// The PRN word's sign says the polarity (the hint is not needed).
    fn decode(&self, window: &[f32], _hint: bool) -> Option<(Cnav1Frame, bool)> {
        let word = window.get(..PRN_WORD_SYMBOLS)?;
        let inverted = prn_correlation(word, self.prn) < 0.0;
        let frame = decode_frame(&with_polarity(window, inverted), self.prn).ok()?;
        frame
            .time()
            .is_some_and(|(_, sow)| sow < WEEK_S)
            .then_some((frame, inverted))
    }
}

#[cfg(test)]
mod tests;
