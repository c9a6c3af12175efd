//! Receiving I/NAV: a page part from its 250 soft symbols (synchronisation pattern,
//! de-interleaving, Viterbi decoding), a page from its even and odd parts (even/odd flags,
//! nominal page type, CRC-24Q, word), and the assembly of word types 1-5 into an
//! ephemeris and of 7-10 into the almanac.
//!
//! Soft symbols: positive = logic 0, negative = logic 1 (BPSK +1 for 0), magnitude the
//! confidence; hard symbols map as 0 -> +1.0, 1 -> -1.0.

use super::almanac;
use super::eph;
use super::pages::{self, INAV_SYNC, PAGE_SYMBOLS, PART_SYMBOLS};
use super::quant as q;
use super::words::{self, layout};
use crate::navmsg::field::Fields;
use crate::navmsg::galileo_fnav::eph::T_REF_GRID_S;
use crate::navmsg::galileo_fnav::time::{gst_epoch, nearest_week};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};
use std::collections::BTreeMap;

/// Sync symbols that may disagree with the pattern before a page part is refused.
const SYNC_MAX_MISMATCHES: usize = 2;

/// Why symbols are not a page part or two parts not a page.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum InavDecodeError {
    #[error("an I/NAV page part is {PART_SYMBOLS} symbols and a page {PAGE_SYMBOLS}, got {0}")]
    Length(usize),
    #[error("{0} of the 10 symbols differ from the I/NAV synchronisation pattern")]
    Sync(usize),
    #[error("the page parts are not an even part followed by an odd one")]
    EvenOdd,
    #[error("an alert page (page type 1), which SkyForge does not decode")]
    Alert,
    #[error("CRC-24Q mismatch")]
    Crc,
}

/// One decoded page part: its 114 bits before the tail, the even/odd flag first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InavPagePart {
    bits: Vec<u8>,
}

impl InavPagePart {
    /// Whether this is an odd part (even/odd flag 1).
    pub fn is_odd(&self) -> bool {
        self.bits[0] == 1
    }

    /// The 114 bits: even/odd, page type, then the part's data.
    pub fn bits(&self) -> &[u8] {
        &self.bits
    }
}

/// Decode one page part from 250 soft symbols starting at its first sync symbol.
pub fn decode_page_part(soft: &[f32]) -> Result<InavPagePart, InavDecodeError> {
    if soft.len() != PART_SYMBOLS {
        return Err(InavDecodeError::Length(soft.len()));
    }
    let mismatches = INAV_SYNC
        .iter()
        .zip(soft)
        .filter(|&(&s, &x)| (x < 0.0) != (s == 1))
        .count();
    if mismatches > SYNC_MAX_MISMATCHES {
        return Err(InavDecodeError::Sync(mismatches));
    }
    Ok(InavPagePart {
        bits: pages::decode_symbols(&soft[INAV_SYNC.len()..]),
    })
}

/// Decode one page from 500 soft symbols: its even part, then its odd part.
pub fn decode_page(soft: &[f32]) -> Result<InavPage, InavDecodeError> {
    if soft.len() != PAGE_SYMBOLS {
        return Err(InavDecodeError::Length(soft.len()));
    }
    let even = decode_page_part(&soft[..PART_SYMBOLS])?;
    let odd = decode_page_part(&soft[PART_SYMBOLS..])?;
    InavPage::from_parts(&even, &odd)
}

/// One decoded nominal page: its word type and the word's fields' raw values (in LSB units,
/// two's complement fields sign-extended) in the layout order of §4.3.5. Word types
/// SkyForge does not send (dummy 63, 16-22 and the others of Issue 2.1) have no fields.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InavPage {
    pub word_type: u8,
    values: Vec<i64>,
}

impl InavPage {
    /// The page of an even and an odd part: both nominal (page type 0), in that order, and
    /// the odd part's CRC matching both.
    pub fn from_parts(even: &InavPagePart, odd: &InavPagePart) -> Result<Self, InavDecodeError> {
        if even.is_odd() || !odd.is_odd() {
            return Err(InavDecodeError::EvenOdd);
        }
        if even.bits[1] == 1 || odd.bits[1] == 1 {
            return Err(InavDecodeError::Alert);
        }
        if !pages::crc_holds(&even.bits, &odd.bits) {
            return Err(InavDecodeError::Crc);
        }
        let word = pages::word(&even.bits, &odd.bits);
        let word_type = words::word_type(&word);
        let values = layout(word_type).map_or_else(Vec::new, |l| words::unpack(&word, l));
        Ok(Self { word_type, values })
    }

    /// The fields after the word type: ICD name and raw value (almanac names repeat for
    /// each satellite; spare and reserved fields are named "Spare").
    pub fn fields(&self) -> impl Iterator<Item = (&'static str, i64)> + '_ {
        layout(self.word_type)
            .unwrap_or(&[])
            .iter()
            .map(|f| f.name)
            .zip(self.values.iter().copied())
    }

    /// The raw value of the first field named `name` (e.g. "IODnav", "af0", "TOW").
    pub fn field(&self, name: &str) -> Option<i64> {
        self.fields().find(|(n, _)| *n == name).map(|(_, v)| v)
    }

    /// Whether the page's WN and TOW are valid: word types 5 and 6, and 0 with its time
    /// field '10' (§4.3.5).
    fn timed(&self) -> bool {
        self.word_type != 0 || self.field(q::TIME.name) == Some(q::TIME_VALID)
    }

    /// GST week number (word types 0 and 5).
    pub fn wn(&self) -> Option<u32> {
        self.field(q::WN.name)
            .filter(|_| self.timed())
            .map(|v| v as u32)
    }

    /// GST time of week (s) of the first symbol of the page's even part (word types 0, 5
    /// and 6; §5.1.2).
    pub fn tow(&self) -> Option<u32> {
        self.field(q::TOW.name)
            .filter(|_| self.timed())
            .map(|v| v as u32)
    }

    fn values(&self) -> &[i64] {
        &self.values
    }
}

/// A decoded ephemeris with the GST of the start of the page that completed it.
#[derive(Debug, Clone, PartialEq)]
pub struct InavEphemeris {
    pub eph: BroadcastEphemeris,
    pub wn: u32,
    pub tow: u32,
}

/// Collects decoded pages of one satellite: word types 1-4 of one IODnav and the last word
/// type 5 make an ephemeris, words 7, 8, 9 and 10 received in that order with one IODa
/// the almanac of three satellites.
#[derive(Debug, Clone, Default)]
pub struct InavAssembler {
    eph_words: [Option<InavPage>; 5],
    gst: Option<(u32, u32)>,
    last: Option<BroadcastEphemeris>,
    almanac_words: Vec<InavPage>,
    almanac: BTreeMap<u8, BroadcastEphemeris>,
}

impl InavAssembler {
    pub fn new() -> Self {
        Self::default()
    }

    /// Week and TOW of the start of the last page that carried time (WN from word types
    /// 0 and 5; a word type 6 moves the TOW, and the week at the week's end).
    pub fn gst(&self) -> Option<(u32, u32)> {
        self.gst
    }

    /// The almanac sets received so far, one per SVID (the latest), as ephemerides
    /// without harmonic terms or Delta n, toe = toc = t0a.
    pub fn almanac(&self) -> Vec<BroadcastEphemeris> {
        self.almanac.values().cloned().collect()
    }

    /// Take one page; returns the ephemeris when word types 1-4 of one IODnav and a word
    /// type 5 are in and it differs from the last one returned.
    pub fn push(&mut self, page: &InavPage) -> Option<InavEphemeris> {
        self.update_time(page);
        match page.word_type {
            1..=5 => self.eph_words[usize::from(page.word_type - 1)] = Some(page.clone()),
            7..=10 => self.take_almanac(page),
            _ => {}
        }
        let out = self.ephemeris()?;
        if self.last.as_ref() == Some(&out.eph) {
            return None;
        }
        self.last = Some(out.eph.clone());
        Some(out)
    }

    fn update_time(&mut self, page: &InavPage) {
        self.gst = match (page.wn(), page.tow(), self.gst) {
            (Some(wn), Some(tow), _) => Some((wn, tow)),
            (None, Some(tow), Some((wn, last))) => {
                Some((if tow < last { wn + 1 } else { wn }, tow))
            }
            (_, _, g) => g,
        };
    }

    fn ephemeris(&self) -> Option<InavEphemeris> {
        let words: Vec<&InavPage> = self.eph_words.iter().flatten().collect();
        if words.len() < 5 {
            return None;
        }
        let iod = words[0].field(q::IODNAV.name)?;
        if words[..4]
            .iter()
            .any(|w| w.field(q::IODNAV.name) != Some(iod))
        {
            return None;
        }
        let (wn, tow) = self.gst?;
        let mut fields = Fields::default();
        for w in &words {
            fields.absorb(layout(w.word_type)?, w.values());
        }
        let svid = u8::try_from(fields.get(&q::SVID)).ok()?;
        if svid == 0 || svid > System::Galileo.max_prn() {
            return None;
        }
        let now = gst_epoch(wn, u64::from(tow));
        let at = |f: &q::Field| {
            let sow = fields.get(f) as u64 * T_REF_GRID_S;
            gst_epoch(nearest_week(now, sow, 0, 1), sow)
        };
        let eph = eph::to_ephemeris(&fields, SatId::galileo(svid), at(&q::TOE), at(&q::TOC));
        Some(InavEphemeris { eph, wn, tow })
    }

    /// Words 7 to 10 in sequence: anything else restarts the sequence (a word 7) or
    /// drops it, so that no satellite is made of words of two triples.
    fn take_almanac(&mut self, page: &InavPage) {
        let expected = 7 + self.almanac_words.len() as u8;
        if page.word_type != expected {
            self.almanac_words.clear();
            if page.word_type != 7 {
                return;
            }
        }
        self.almanac_words.push(page.clone());
        if self.almanac_words.len() < 4 {
            return;
        }
        let w = std::mem::take(&mut self.almanac_words);
        let Some((wn, tow)) = self.gst else {
            return;
        };
        let now = gst_epoch(wn, u64::from(tow));
        let values = [w[0].values(), w[1].values(), w[2].values(), w[3].values()];
        for e in almanac::decode(values, now) {
            self.almanac.insert(e.sat.prn, e);
        }
    }
}
