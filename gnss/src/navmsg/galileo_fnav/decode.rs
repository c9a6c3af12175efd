//! Receiving F/NAV: one page from its 500 soft symbols (the ICD's page processing
//! sequence at reception: synchronisation pattern, de-interleaving, Viterbi decoding, CRC,
//! fields), and the assembly of page types 1-4 into an ephemeris.
//!
//! Soft symbols: positive = logic 0, negative = logic 1 (BPSK +1 for 0), magnitude the
//! confidence; hard symbols map as 0 -> +1.0, 1 -> -1.0.

use super::almanac;
use super::eph::{self, Fields};
use super::pages::{self, DATA_BITS, FNAV_SYNC, PAGE_SYMBOLS};
use super::quant as q;
use super::time::{gst_epoch, nearest_week};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};
use std::collections::BTreeMap;

/// Sync symbols that may disagree with the pattern before a page is refused.
const SYNC_MAX_MISMATCHES: usize = 2;

/// One decoded page: its type and its fields' raw values (in LSB units, two's complement
/// fields sign-extended), in the layout order of §4.2.4.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FnavPage {
    pub page_type: u8,
    values: Vec<i64>,
}

/// Why 500 symbols are not a page.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum FnavDecodeError {
    #[error("an F/NAV page is {PAGE_SYMBOLS} symbols, got {0}")]
    Length(usize),
    #[error("{0} of the 12 symbols differ from the F/NAV synchronisation pattern")]
    Sync(usize),
    #[error("CRC-24Q mismatch")]
    Crc,
    #[error("page type {0} is not an F/NAV page type SkyForge knows (1-6, 63 dummy)")]
    PageType(u8),
}

impl FnavPage {
    /// The fields after the page type: ICD name and raw value (almanac names repeat for
    /// each satellite; spare fields are named "Spare").
    pub fn fields(&self) -> impl Iterator<Item = (&'static str, i64)> + '_ {
        let layout = pages::layout(self.page_type).unwrap_or(&[]);
        layout
            .iter()
            .map(|f| f.name)
            .zip(self.values.iter().copied())
    }

    /// The raw value of the first field named `name` (e.g. "IODnav", "af0", "TOW").
    pub fn field(&self, name: &str) -> Option<i64> {
        self.fields().find(|(n, _)| *n == name).map(|(_, v)| v)
    }

    /// GST week number (page types 1-3).
    pub fn wn(&self) -> Option<u32> {
        self.field(q::WN.name).map(|v| v as u32)
    }

    /// GST time of week (s) at the start of the page (page types 1-4).
    pub fn tow(&self) -> Option<u32> {
        self.field(q::TOW.name).map(|v| v as u32)
    }

    pub(super) fn values(&self) -> &[i64] {
        &self.values
    }
}

/// Decode one page from 500 soft symbols starting at its first sync symbol.
pub fn decode_page(soft: &[f32]) -> Result<FnavPage, FnavDecodeError> {
    if soft.len() != PAGE_SYMBOLS {
        return Err(FnavDecodeError::Length(soft.len()));
    }
    let mismatches = FNAV_SYNC
        .iter()
        .zip(soft)
        .filter(|&(&s, &x)| (x < 0.0) != (s == 1))
        .count();
    if mismatches > SYNC_MAX_MISMATCHES {
        return Err(FnavDecodeError::Sync(mismatches));
    }
    let (bits, crc_ok) = pages::decode_symbols(&soft[FNAV_SYNC.len()..]);
    if !crc_ok {
        return Err(FnavDecodeError::Crc);
    }
    let data = &bits[..DATA_BITS];
    let page_type = data[..q::PAGE_TYPE.bits as usize]
        .iter()
        .fold(0u8, |acc, &b| (acc << 1) | b);
    match pages::layout(page_type) {
        Some(layout) => Ok(FnavPage {
            page_type,
            values: pages::unpack(data, layout),
        }),
        None if page_type == pages::DUMMY_PAGE_TYPE => Ok(FnavPage {
            page_type,
            values: Vec::new(),
        }),
        None => Err(FnavDecodeError::PageType(page_type)),
    }
}

/// A decoded ephemeris with the GST of the start of the page that completed it.
#[derive(Debug, Clone, PartialEq)]
pub struct FnavEphemeris {
    pub eph: BroadcastEphemeris,
    pub wn: u32,
    pub tow: u32,
}

/// Collects decoded pages of one satellite: page types 1-4 of one IODnav make an
/// ephemeris, page 5/6 pairs of one IODa the almanac.
#[derive(Debug, Clone, Default)]
pub struct FnavAssembler {
    eph_pages: [Option<FnavPage>; 4],
    gst: Option<(u32, u32)>,
    last: Option<BroadcastEphemeris>,
    pt5: Option<FnavPage>,
    almanac: BTreeMap<u8, BroadcastEphemeris>,
}

impl FnavAssembler {
    pub fn new() -> Self {
        Self::default()
    }

    /// Week and TOW of the start of the last page that carried time (WN from page types
    /// 1-3; a page 4 after them moves the TOW, and the week at the week's end).
    pub fn gst(&self) -> Option<(u32, u32)> {
        self.gst
    }

    /// The almanac sets received so far, one per SVID (the latest), as ephemerides
    /// without harmonic terms or Delta n, toe = toc = t0a.
    pub fn almanac(&self) -> Vec<BroadcastEphemeris> {
        self.almanac.values().cloned().collect()
    }

    /// Take one page; returns the ephemeris when page types 1-4 of one IODnav are all in
    /// and it differs from the last one returned.
    pub fn push(&mut self, page: &FnavPage) -> Option<FnavEphemeris> {
        self.update_time(page);
        match page.page_type {
            1..=4 => self.eph_pages[usize::from(page.page_type - 1)] = Some(page.clone()),
            5 => self.pt5 = Some(page.clone()),
            6 => self.take_almanac(page),
            _ => {}
        }
        let out = self.ephemeris()?;
        if self.last.as_ref() == Some(&out.eph) {
            return None;
        }
        self.last = Some(out.eph.clone());
        Some(out)
    }

    fn update_time(&mut self, page: &FnavPage) {
        self.gst = match (page.wn(), page.tow(), self.gst) {
            (Some(wn), Some(tow), _) => Some((wn, tow)),
            (None, Some(tow), Some((wn, last))) => {
                Some((if tow < last { wn + 1 } else { wn }, tow))
            }
            (_, _, g) => g,
        };
    }

    fn ephemeris(&self) -> Option<FnavEphemeris> {
        let pages: Vec<&FnavPage> = self.eph_pages.iter().flatten().collect();
        let iod = pages.first()?.field(q::IODNAV.name)?;
        if pages.len() < 4 || pages.iter().any(|p| p.field(q::IODNAV.name) != Some(iod)) {
            return None;
        }
        let (wn, tow) = self.gst?;
        let mut fields = Fields::default();
        for p in &pages {
            fields.absorb(pages::layout(p.page_type)?, p.values());
        }
        let svid = u8::try_from(fields.get(&q::SVID)).ok()?;
        if svid == 0 || svid > System::Galileo.max_prn() {
            return None;
        }
        let now = gst_epoch(wn, u64::from(tow));
        let at = |f: &q::Field| {
            let sow = fields.get(f) as u64 * eph::T_REF_GRID_S;
            gst_epoch(nearest_week(now, sow, 0, 1), sow)
        };
        let eph = eph::to_ephemeris(&fields, SatId::galileo(svid), at(&q::TOE), at(&q::TOC));
        Some(FnavEphemeris { eph, wn, tow })
    }

    fn take_almanac(&mut self, pt6: &FnavPage) {
        let (Some(pt5), Some((wn, tow))) = (self.pt5.take(), self.gst) else {
            return;
        };
        let now = gst_epoch(wn, u64::from(tow));
        for e in almanac::decode(pt5.values(), pt6.values(), now) {
            self.almanac.insert(e.sat.prn, e);
        }
    }
}
