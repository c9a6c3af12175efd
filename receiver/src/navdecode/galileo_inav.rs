//! Galileo E1-B I/NAV decoder (Galileo OS SIS ICD Issue 2.1 §4.3.2-§4.3.5, §5.1.2) fed
//! with E1-B channel symbols, 250 per second (one per 4 ms code period).
//!
//! A page is 500 symbols (2 s): an even and an odd part, each the 10-symbol
//! synchronisation pattern and 240 interleaved symbols of a code that restarts every part;
//! the CRC-24Q spans both parts. The search takes each place where the pattern (or its
//! complement, an inverted stream) appears with at most two wrong hard decisions both
//! there and 250 symbols later as a candidate page start, which [`decode_page`] confirms
//! (even part first, CRC). Locked, a page follows every 500 symbols.

use super::symbol_sync::{SymbolFormat, SymbolSync, with_polarity};
use super::{DecodeStats, DecodedEphemeris, NavDecodeError, NavDecoder, NavEvent, SubframeInfo};
use skyforge_gnss::navmsg::galileo_inav::{
    INAV_PAGE_S, INAV_PAGE_SYMBOLS, INAV_PART_SYMBOLS, INAV_SYNC, InavAssembler, InavPage,
    decode_page,
};
use skyforge_orbits::ephemeris::{SatId, System};
use std::cmp::Ordering;

/// Seconds per week.
const WEEK_S: u32 = 604_800;
/// Wrong hard decisions allowed in each of a search candidate's two sync patterns (as
/// many as [`decode_page`] allows).
const SEARCH_SYNC_ERRORS: usize = 2;

/// Decoder of one Galileo satellite's E1-B I/NAV symbol stream.
///
/// Each decoded page with a known time is a [`NavEvent::Subframe`]: `start_bit` is the
/// index of the first sync symbol of its even part, `id` the word type, `tow_s` the GST
/// TOW of that symbol (§5.1.2; for words without one, all but 0, 5 and 6, the last TOW of
/// the lock plus 2 s a page), `week` the GST week once a word type 0 or 5 gave it. Word
/// types 1-4 of one IODnav and a word type 5 make a [`NavEvent::Ephemeris`] (`ura_index`
/// 0: SISA is no URA).
#[derive(Debug, Clone)]
pub struct InavDecoder {
    sat: SatId,
    format: Inav,
    sync: SymbolSync,
    assembler: InavAssembler,
    /// Start symbol and TOW of the last page that carried a TOW.
    anchor: Option<(u64, u32)>,
    /// GST week and TOW of the last page reported.
    time: Option<(Option<u32>, u32)>,
}

impl InavDecoder {
    /// A decoder for Galileo satellite `sat` (SVID 1-36).
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Galileo || !(1..=System::Galileo.max_prn()).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "I/NAV is broadcast by Galileo SVID 1-36",
            });
        }
        Ok(Self {
            sat,
            format: Inav { svid: sat.prn },
            sync: SymbolSync::new(),
            assembler: InavAssembler::new(),
            anchor: None,
            time: None,
        })
    }

    /// Whether page synchronisation is held.
    pub fn is_synchronised(&self) -> bool {
        self.sync.locked_since().is_some()
    }

    /// The GST TOW of the page at `start`: its own, or the anchor's moved on by the pages
    /// since, if the anchor lies in the current lock.
    fn tow_of(&self, start: u64, page: &InavPage) -> Option<u32> {
        if let Some(tow) = page.tow() {
            return Some(tow);
        }
        let since = self.sync.locked_since()?;
        let (at, tow) = self.anchor.filter(|&(at, _)| at >= since)?;
        let pages = (start.checked_sub(at)? / INAV_PAGE_SYMBOLS as u64) as u32;
        Some((tow + pages * INAV_PAGE_S as u32) % WEEK_S)
    }

    /// Report a decoded page starting at symbol `start`.
    fn take(&mut self, start: u64, inverted: bool, page: &InavPage, out: &mut Vec<NavEvent>) {
        let eph = self.assembler.push(page);
        let tow = self.tow_of(start, page);
        if let Some(t) = page.tow() {
            self.anchor = Some((start, t));
        }
        if let Some(tow) = tow {
            let week = match (page.wn(), self.time) {
                (Some(wn), _) => Some(wn),
                (None, Some((Some(week), last))) if tow < last => Some(week + 1),
                (None, last) => last.and_then(|(week, _)| week),
            };
            self.time = Some((week, tow));
            out.push(NavEvent::Subframe(SubframeInfo {
                start_bit: start,
                id: page.word_type,
                page: None,
                week,
                tow_s: f64::from(tow),
                inverted,
                corrected_bits: 0,
            }));
        }
        if let Some(e) = eph.filter(|e| e.eph.sat == self.sat) {
            out.push(NavEvent::Ephemeris(Box::new(DecodedEphemeris {
                eph: e.eph,
                ura_index: 0,
                tgd2_s: None,
            })));
        }
    }
}

impl NavDecoder for InavDecoder {
    fn feed(&mut self, soft_bits: &[f32]) -> Vec<NavEvent> {
        self.sync.push(soft_bits);
        let mut out = Vec::new();
        while let Some((start, inverted, page)) = self.sync.next(&self.format, &mut out) {
            self.take(start, inverted, &page, &mut out);
        }
        out
    }

    fn restart(&mut self) {
        self.sync.restart();
    }

    fn stats(&self) -> DecodeStats {
        self.sync.stats
    }

    fn satellite(&self) -> SatId {
        self.sat
    }
}

/// I/NAV framing: a page whose SVID (word type 4) is the expected one and whose TOW is
/// below one week.
#[derive(Debug, Clone, Copy)]
struct Inav {
    svid: u8,
}

impl SymbolFormat for Inav {
    type Message = InavPage;
    const PERIOD: u64 = INAV_PAGE_SYMBOLS as u64;
    const LEAD_IN: u64 = 0;
    const SPAN: u64 = INAV_PAGE_SYMBOLS as u64;

    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)> {
        let n = INAV_SYNC.len();
        (0..Self::PERIOD as usize)
            .filter_map(|offset| {
                let at = |k: usize| window.get(k..k + n).map(sync_errors);
                let errors = [at(offset)?, at(offset + INAV_PART_SYMBOLS)?];
                let inverted = if errors.iter().all(|&e| e <= SEARCH_SYNC_ERRORS) {
                    false
                } else if errors.iter().all(|&e| n - e <= SEARCH_SYNC_ERRORS) {
                    true
                } else {
                    return None;
                };
                Some((offset as u64, inverted))
            })
            .collect()
    }

    /// The polarity is the one the majority of the 20 sync symbols agree with (`inverted`
    /// on a tie); the sync symbols, which carry no data, are then replaced by the pattern
    /// so that a noisy pattern at a known place does not refuse a page the CRC accepts.
    fn decode(&self, window: &[f32], inverted: bool) -> Option<(InavPage, bool)> {
        let n = INAV_SYNC.len();
        let parts = [0, INAV_PART_SYMBOLS];
        let errors: usize = parts
            .iter()
            .map(|&at| window.get(at..at + n).map(sync_errors))
            .sum::<Option<usize>>()?;
        let inv = match errors.cmp(&(2 * n - errors)) {
            Ordering::Less => false,
            Ordering::Greater => true,
            Ordering::Equal => inverted,
        };
        let mut symbols = with_polarity(window, inv);
        for at in parts {
            for (x, &s) in symbols[at..].iter_mut().zip(&INAV_SYNC) {
                *x = if s == 0 { 1.0 } else { -1.0 };
            }
        }
        let page = decode_page(&symbols).ok()?;
        let svid_ok = page.word_type != 4 || page.field("SVID") == Some(i64::from(self.svid));
        let tow_ok = page.tow().is_none_or(|t| t < WEEK_S);
        (svid_ok && tow_ok).then_some((page, inv))
    }
}

/// Hard decisions of `symbols` that differ from the sync pattern.
fn sync_errors(symbols: &[f32]) -> usize {
    INAV_SYNC
        .iter()
        .zip(symbols)
        .filter(|&(&s, &x)| (x < 0.0) != (s == 1))
        .count()
}

#[cfg(test)]
mod tests;
