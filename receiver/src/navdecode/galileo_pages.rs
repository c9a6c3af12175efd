//! What the Galileo decoders share (F/NAV of E5a-I, I/NAV of E1-B): a symbol stream cut
//! into pages by [`SymbolSync`], each page's GST time (its own TOW, or the last one of the
//! lock moved on by the pages since, Galileo OS SIS ICD §5.1.2), the week carried across
//! week ends, and the ephemeris the message's assembler completes. The message itself (its
//! page length, sync search, decoding and assembler) is a [`GalileoMessage`].

use super::symbol_sync::{SymbolFormat, SymbolSync, SyncedDecoder};
use super::{DecodedEphemeris, NavDecodeError, NavEvent, SubframeInfo};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};

/// Seconds per week.
pub(super) const WEEK_S: u32 = 604_800;

/// A Galileo navigation message as its decoder needs it.
pub(crate) trait GalileoMessage: SymbolFormat + Clone + std::fmt::Debug {
    /// What collects a satellite's pages into an ephemeris.
    type Assembler: Clone + std::fmt::Debug;
    /// Who broadcasts the message, for a decoder asked for another satellite.
    const BROADCAST_BY: &'static str;
    /// Page duration (s).
    const PAGE_S: u32;
    /// The framing for satellite `svid`.
    fn for_svid(svid: u8) -> Self;
    fn assembler() -> Self::Assembler;
    /// Add `page`; the ephemeris it completes, if any.
    fn push(assembler: &mut Self::Assembler, page: &Self::Message) -> Option<BroadcastEphemeris>;
    /// The page's type (F/NAV page type, I/NAV word type).
    fn id(page: &Self::Message) -> u8;
    /// The GST TOW and week the page carries, if any.
    fn tow(page: &Self::Message) -> Option<u32>;
    fn wn(page: &Self::Message) -> Option<u32>;
}

/// Decoder of one Galileo satellite's symbol stream of message `M`.
///
/// Each decoded page with a known time is a [`NavEvent::Subframe`]: `start_bit` is the
/// index of its first sync symbol, `id` the page (word) type, `tow_s` the GST TOW of that
/// symbol (for pages that carry none, the last TOW of the lock plus the page length per
/// page), `week` the GST week once a page gave it. A completed ephemeris is a
/// [`NavEvent::Ephemeris`] (`ura_index` 0: SISA is no URA).
#[derive(Debug, Clone)]
pub(crate) struct GalileoDecoder<M: GalileoMessage> {
    sat: SatId,
    format: M,
    sync: SymbolSync,
    assembler: M::Assembler,
    /// Start symbol and TOW of the last page that carried a TOW.
    anchor: Option<(u64, u32)>,
    /// GST week and TOW of the last page reported.
    time: Option<(Option<u32>, u32)>,
}

impl<M: GalileoMessage> GalileoDecoder<M> {
    /// A decoder for Galileo satellite `sat` (SVID 1-36).
    pub(crate) fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Galileo || !(1..=System::Galileo.max_prn()).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: M::BROADCAST_BY,
            });
        }
        Ok(Self {
            sat,
            format: M::for_svid(sat.prn),
            sync: SymbolSync::new(),
            assembler: M::assembler(),
            anchor: None,
            time: None,
        })
    }

    /// Whether page synchronisation is held.
    #[cfg(test)]
    pub(crate) fn is_synchronised(&self) -> bool {
        self.sync.locked_since().is_some()
    }

    /// The GST TOW of the page at `start`: its own, or the anchor's moved on by the pages
    /// since, if the anchor lies in the current lock.
    fn tow_of(&self, start: u64, page: &M::Message) -> Option<u32> {
        if let Some(tow) = M::tow(page) {
            return Some(tow);
        }
        let since = self.sync.locked_since()?;
        let (at, tow) = self.anchor.filter(|&(at, _)| at >= since)?;
        let pages = (start.checked_sub(at)? / M::PERIOD) as u32;
        Some((tow + pages * M::PAGE_S) % WEEK_S)
    }

    /// Report a decoded page starting at symbol `start`.
    fn take(&mut self, start: u64, inverted: bool, page: &M::Message, out: &mut Vec<NavEvent>) {
        let eph = M::push(&mut self.assembler, page);
        let tow = self.tow_of(start, page);
        if let Some(t) = M::tow(page) {
            self.anchor = Some((start, t));
        }
        if let Some(tow) = tow {
            let week = match (M::wn(page), self.time) {
                (Some(wn), _) => Some(wn),
                (None, Some((Some(week), last))) if tow < last => Some(week + 1),
                (None, last) => last.and_then(|(week, _)| week),
            };
            self.time = Some((week, tow));
            out.push(NavEvent::Subframe(SubframeInfo {
                start_bit: start,
                id: M::id(page),
                page: None,
                week,
                tow_s: f64::from(tow),
                inverted,
                corrected_bits: 0,
            }));
        }
        if let Some(eph) = eph.filter(|e| e.sat == self.sat) {
            out.push(NavEvent::Ephemeris(Box::new(DecodedEphemeris {
                eph,
                ura_index: 0,
                tgd2_s: None,
            })));
        }
    }
}

impl<M: GalileoMessage + Send> SyncedDecoder for GalileoDecoder<M>
where
    M::Assembler: Send,
{
    type Format = M;

    fn parts(&mut self) -> (&mut SymbolSync, &Self::Format) {
        (&mut self.sync, &self.format)
    }

    fn symbol_sync(&self) -> &SymbolSync {
        &self.sync
    }

    fn sat(&self) -> SatId {
        self.sat
    }

    fn message(&mut self, start: u64, inverted: bool, msg: &M::Message, out: &mut Vec<NavEvent>) {
        self.take(start, inverted, msg, out);
    }
}

/// Hard decisions of `symbols` that differ from `pattern` (logic bits).
pub(super) fn sync_errors(pattern: &[u8], symbols: &[f32]) -> usize {
    pattern
        .iter()
        .zip(symbols)
        .filter(|&(&s, &x)| (x < 0.0) != (s == 1))
        .count()
}
