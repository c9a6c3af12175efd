//! Galileo E1-B I/NAV decoder (Galileo OS SIS ICD Issue 2.1 §4.3.2-§4.3.5, §5.1.2) fed
//! with E1-B channel symbols, 250 per second (one per 4 ms code period).
//!
//! A page is 500 symbols (2 s): an even and an odd part, each the 10-symbol
//! synchronisation pattern and 240 interleaved symbols of a code that restarts every part;
//! the CRC-24Q spans both parts. The search takes each place where the pattern (or its
//! complement, an inverted stream) appears with at most two wrong hard decisions both
//! there and 250 symbols later as a candidate page start, which [`decode_page`] confirms
//! (even part first, CRC). Locked, a page follows every 500 symbols.

use super::galileo_pages::{GalileoDecoder, GalileoMessage, WEEK_S, sync_errors};
use super::symbol_sync::{SymbolFormat, with_polarity};
use skyforge_gnss::navmsg::galileo_inav::{
    INAV_PAGE_S, INAV_PAGE_SYMBOLS, INAV_PART_SYMBOLS, INAV_SYNC, InavAssembler, InavPage,
    decode_page,
};
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use std::cmp::Ordering;

/// Wrong hard decisions allowed in each of a search candidate's two sync patterns (as
/// many as [`decode_page`] allows).
const SEARCH_SYNC_ERRORS: usize = 2;

/// Decoder of one Galileo satellite's I/NAV symbol stream ([`GalileoDecoder`]).
pub(crate) type InavDecoder = GalileoDecoder<Inav>;

impl GalileoMessage for Inav {
    type Assembler = InavAssembler;
    const BROADCAST_BY: &'static str = "I/NAV is broadcast by Galileo SVID 1-36";
    const PAGE_S: u32 = INAV_PAGE_S as u32;

    fn for_svid(svid: u8) -> Self {
        Self { svid }
    }

    fn assembler() -> InavAssembler {
        InavAssembler::new()
    }

    fn push(assembler: &mut InavAssembler, page: &InavPage) -> Option<BroadcastEphemeris> {
        assembler.push(page).map(|e| e.eph)
    }

    fn id(page: &InavPage) -> u8 {
        page.word_type
    }

    fn tow(page: &InavPage) -> Option<u32> {
        page.tow()
    }

    fn wn(page: &InavPage) -> Option<u32> {
        page.wn()
    }
}

/// I/NAV framing: a page whose SVID (word type 4) is the expected one and whose TOW is
/// below one week.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Inav {
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
                let at = |k: usize| window.get(k..k + n).map(|w| sync_errors(&INAV_SYNC, w));
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
            .map(|&at| window.get(at..at + n).map(|w| sync_errors(&INAV_SYNC, w)))
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

#[cfg(test)]
mod tests;
