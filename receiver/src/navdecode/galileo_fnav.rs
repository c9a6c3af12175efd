//! Galileo E5a F/NAV decoder (Galileo OS SIS ICD Issue 2.1 §4.2.2-§4.2.4, §5.1.2) fed
//! with E5a-I channel symbols, 50 per second.
//!
//! A page is 500 symbols (10 s): the 12-symbol synchronisation pattern, then 488
//! interleaved symbols of a code that restarts every page. The search takes each place
//! where the pattern (or its complement, an inverted stream) appears with at most two
//! wrong hard decisions as a candidate, which [`decode_page`] confirms by CRC-24Q. Locked,
//! a page follows every 500 symbols.

use super::symbol_sync::{SymbolFormat, SymbolSync, with_polarity};
use super::{DecodeStats, DecodedEphemeris, NavDecodeError, NavDecoder, NavEvent, SubframeInfo};
use skyforge_gnss::navmsg::galileo_fnav::{
    FNAV_PAGE_S, FNAV_PAGE_SYMBOLS, FNAV_SYNC, FnavAssembler, FnavPage, decode_page,
};
use skyforge_orbits::ephemeris::{SatId, System};
use std::cmp::Ordering;

/// Seconds per week.
const WEEK_S: u32 = 604_800;
/// Wrong hard decisions allowed in a search candidate's sync pattern (as many as
/// [`decode_page`] allows).
const SEARCH_SYNC_ERRORS: usize = 2;

/// Decoder of one Galileo satellite's E5a F/NAV symbol stream.
///
/// Each decoded page with a known time is a [`NavEvent::Subframe`]: `start_bit` is the
/// index of its first sync symbol, `id` the page type, `tow_s` the GST TOW of that
/// symbol (§5.1.2; for page types 5, 6 and 63, which carry none, the last TOW of the
/// lock plus 10 s a page), `week` the GST week once a page type 1-3 gave it. Page types
/// 1-4 of one IODnav make a [`NavEvent::Ephemeris`] (`ura_index` 0: SISA is no URA).
#[derive(Debug, Clone)]
pub struct FnavDecoder {
    sat: SatId,
    format: Fnav,
    sync: SymbolSync,
    assembler: FnavAssembler,
    /// Start symbol and TOW of the last page that carried a TOW.
    anchor: Option<(u64, u32)>,
    /// GST week and TOW of the last page reported.
    time: Option<(Option<u32>, u32)>,
}

impl FnavDecoder {
    /// A decoder for Galileo satellite `sat` (SVID 1-36).
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Galileo || !(1..=System::Galileo.max_prn()).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "F/NAV is broadcast by Galileo SVID 1-36",
            });
        }
        Ok(Self {
            sat,
            format: Fnav { svid: sat.prn },
            sync: SymbolSync::new(),
            assembler: FnavAssembler::new(),
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
    fn tow_of(&self, start: u64, page: &FnavPage) -> Option<u32> {
        if let Some(tow) = page.tow() {
            return Some(tow);
        }
        let since = self.sync.locked_since()?;
        let (at, tow) = self.anchor.filter(|&(at, _)| at >= since)?;
        let pages = (start.checked_sub(at)? / FNAV_PAGE_SYMBOLS as u64) as u32;
        Some((tow + pages * FNAV_PAGE_S as u32) % WEEK_S)
    }

    /// Report a decoded page starting at symbol `start`.
    fn take(&mut self, start: u64, inverted: bool, page: &FnavPage, out: &mut Vec<NavEvent>) {
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
                id: page.page_type,
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

impl NavDecoder for FnavDecoder {
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

/// F/NAV framing: a page whose SVID (page type 1) is the expected one and whose TOW is
/// below one week.
#[derive(Debug, Clone, Copy)]
struct Fnav {
    svid: u8,
}

impl SymbolFormat for Fnav {
    type Message = FnavPage;
    const PERIOD: u64 = FNAV_PAGE_SYMBOLS as u64;
    const LEAD_IN: u64 = 0;
    const SPAN: u64 = FNAV_PAGE_SYMBOLS as u64;

    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)> {
        let n = FNAV_SYNC.len();
        (0..Self::PERIOD as usize)
            .filter_map(|offset| {
                let errors = sync_errors(window.get(offset..offset + n)?);
                let inverted = if errors <= SEARCH_SYNC_ERRORS {
                    false
                } else if n - errors <= SEARCH_SYNC_ERRORS {
                    true
                } else {
                    return None;
                };
                Some((offset as u64, inverted))
            })
            .collect()
    }

    /// The polarity is the one the majority of the sync symbols agree with (`inverted`
    /// on a tie); the sync symbols, which carry no data, are then replaced by the pattern
    /// so that a noisy pattern at a known place does not refuse a page the CRC accepts.
    fn decode(&self, window: &[f32], inverted: bool) -> Option<(FnavPage, bool)> {
        let n = FNAV_SYNC.len();
        let errors = sync_errors(window.get(..n)?);
        let inv = match errors.cmp(&(n - errors)) {
            Ordering::Less => false,
            Ordering::Greater => true,
            Ordering::Equal => inverted,
        };
        let mut symbols = with_polarity(window, inv);
        for (x, &s) in symbols.iter_mut().zip(&FNAV_SYNC) {
            *x = if s == 0 { 1.0 } else { -1.0 };
        }
        let page = decode_page(&symbols).ok()?;
        // Page type 1's SVID is the transmitter's (5 and 6 name almanac satellites).
        let svid_ok = page.page_type != 1 || page.field("SVID") == Some(i64::from(self.svid));
        let tow_ok = page.tow().is_none_or(|t| t < WEEK_S);
        (svid_ok && tow_ok).then_some((page, inv))
    }
}

/// Hard decisions of `symbols` that differ from the sync pattern.
fn sync_errors(symbols: &[f32]) -> usize {
    FNAV_SYNC
        .iter()
        .zip(symbols)
        .filter(|&(&s, &x)| (x < 0.0) != (s == 1))
        .count()
}

#[cfg(test)]
mod tests;
