//! Galileo E5a F/NAV decoder (Galileo OS SIS ICD Issue 2.1 §4.2.2-§4.2.4, §5.1.2) fed
//! with E5a-I channel symbols, 50 per second.
//!
//! A page is 500 symbols (10 s): the 12-symbol synchronisation pattern, then 488
//! interleaved symbols of a code that restarts every page. The search takes each place
//! where the pattern (or its complement, an inverted stream) appears with at most two
//! wrong hard decisions as a candidate, which [`decode_page`] confirms by CRC-24Q. Locked,
//! a page follows every 500 symbols.

use super::galileo_pages::{GalileoDecoder, GalileoMessage, WEEK_S, sync_errors};
use super::symbol_sync::{SymbolFormat, with_polarity};
use skyforge_gnss::navmsg::galileo_fnav::{
    FNAV_PAGE_S, FNAV_PAGE_SYMBOLS, FNAV_SYNC, FnavAssembler, FnavPage, decode_page,
};
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use std::cmp::Ordering;

/// Wrong hard decisions allowed in a search candidate's sync pattern (as many as
/// [`decode_page`] allows).
const SEARCH_SYNC_ERRORS: usize = 2;

/// Decoder of one Galileo satellite's F/NAV symbol stream ([`GalileoDecoder`]).
pub(crate) type FnavDecoder = GalileoDecoder<Fnav>;

impl GalileoMessage for Fnav {
    type Assembler = FnavAssembler;
    const BROADCAST_BY: &'static str = "F/NAV is broadcast by Galileo SVID 1-36";
    const PAGE_S: u32 = FNAV_PAGE_S as u32;

    fn for_svid(svid: u8) -> Self {
        Self { svid }
    }

    fn assembler() -> FnavAssembler {
        FnavAssembler::new()
    }

    fn push(assembler: &mut FnavAssembler, page: &FnavPage) -> Option<BroadcastEphemeris> {
        assembler.push(page).map(|e| e.eph)
    }

    fn id(page: &FnavPage) -> u8 {
        page.page_type
    }

    fn tow(page: &FnavPage) -> Option<u32> {
        page.tow()
    }

    fn wn(page: &FnavPage) -> Option<u32> {
        page.wn()
    }
}

/// F/NAV framing: a page whose SVID (page type 1) is the expected one and whose TOW is
/// below one week.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Fnav {
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
                let errors = sync_errors(&FNAV_SYNC, window.get(offset..offset + n)?);
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
        let errors = sync_errors(&FNAV_SYNC, window.get(..n)?);
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

#[cfg(test)]
mod tests;
