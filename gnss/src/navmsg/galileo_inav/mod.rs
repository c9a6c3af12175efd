//! The Galileo I/NAV navigation message of E1-B (Galileo OS SIS ICD Issue 2.1, §4.1, §4.3,
//! §5.1), encoder and decoder.
//!
//! Timing (§4.3, §5.1.2): E1-B carries 250 symbols/s, one per 4 ms code period. A page is
//! an even and an odd part of 1 s each (10 sync + 240 encoded symbols, `pages`); it
//! carries one 128-bit word (§4.3.5, `words`). A subframe is 15 pages (30 s), a frame 24
//! subframes (720 s). In the nominal sub-frame table (§4.3.3, T0 synchronised with GST
//! modulo 30 s) E1-B's even parts start at T0 + 1, 3, ..., 29 s (E5b-I's at the even
//! seconds), so E1-B pages start at odd GST seconds.
//!
//! Page schedule (§4.3.3, E1-B column of Issue 2.1): word types 2, 4, 6, 7 or 9, 8 or 10,
//! 17 or 18, 19 or 20, 16, 0, 22, 1, 3, 5, 0, 16. SkyForge sends word type 0 (spare, with
//! WN and TOW) in the slots of the reduced clock and ephemeris (16), its Reed-Solomon
//! words (17-20) and the ARAIM message (22), which it does not generate: the E1-B layout
//! of Issue 1, and within what Issue 2.1 allows (it calls the table indicative, and word
//! type 0 spare capacity). Words 7 and 8 go in the 1st, 3rd, ... subframes of a frame, 9
//! and 10 in the 2nd, 4th, ..., so a frame carries 12 almanac triples, 36 satellites
//! (§4.3.4). The odd part at GST second s carries SSP1, SSP2 or SSP3 for
//! s = 2, 4, 0 modulo 6 (§4.3.3, §5.1.9.5).
//!
//! Time: the TOW of word types 0, 5 and 6 is the GST of "the leading edge of the first
//! chip of the first code sequence of the first page symbol" (§5.1.2), the first sync
//! symbol of its page's even part, an odd second. SkyForge starts subframes at GST 1 s
//! modulo 30 s and frames at GST 1 s modulo 720 s (604800 s is 840 frames, so the layout
//! repeats each week): the ICD fixes the subframe phase, the frame's is a choice here.
//!
//! [`InavEncoder`] turns one ephemeris (plus [`InavParams`] and a constellation for the
//! almanac) into channel symbols; [`decode_page`] (or [`decode_page_part`] and
//! [`InavPage::from_parts`]) and [`InavAssembler`] turn received soft symbols back into
//! words and an ephemeris. [`InavEncoder::broadcast_ephemeris`] is the quantised ephemeris,
//! the one the signal must follow and a decoder recovers.

mod almanac;
mod decode;
mod eph;
mod pages;
mod quant;
#[cfg(test)]
mod tests;
mod words;

pub use decode::{
    InavAssembler, InavDecodeError, InavEphemeris, InavPage, InavPagePart, decode_page,
    decode_page_part,
};
pub use pages::{INAV_SYNC, PAGE_SYMBOLS as INAV_PAGE_SYMBOLS, PART_SYMBOLS as INAV_PART_SYMBOLS};

use crate::navmsg::field::{Fields, OutOfRange};
use crate::navmsg::galileo_fnav::time::{WEEK_S, gst_epoch};
use hifitime::Epoch;
use quant as q;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};

/// Channel symbol rate of E1-B (symbols/s).
pub const INAV_SYMBOL_RATE_HZ: f64 = 250.0;
/// Page duration (s): an even and an odd part.
pub const INAV_PAGE_S: u64 = 2;
/// Pages per subframe, subframes per frame.
const PAGES_PER_SUBFRAME: u64 = 15;
const SUBFRAMES_PER_FRAME: u64 = 24;
/// Frame duration (s).
const FRAME_S: u64 = INAV_PAGE_S * PAGES_PER_SUBFRAME * SUBFRAMES_PER_FRAME;
/// The word type of each page of a subframe: in the 1st, 3rd, ... subframes of a frame, in
/// the 2nd, 4th, ....
const SUBFRAME_WORDS: [[u8; 2]; PAGES_PER_SUBFRAME as usize] = [
    [2, 2],
    [4, 4],
    [6, 6],
    [7, 9],
    [8, 10],
    [0, 0],
    [0, 0],
    [0, 0],
    [0, 0],
    [0, 0],
    [1, 1],
    [3, 3],
    [5, 5],
    [0, 0],
    [0, 0],
];

/// I/NAV's parameters (word types 3, 5, 6 and 10 besides the clock, ephemeris and
/// almanac): the Galileo messages' one set, SISA being SISA(E1,E5b) here.
pub use crate::navmsg::galileo_fnav::GalileoParams as InavParams;

/// Why an I/NAV message cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InavError {
    /// The ephemeris is not a Galileo one.
    #[error("{sat}: not a Galileo satellite; I/NAV is a Galileo message")]
    NotGalileo { sat: String },
    /// A value does not fit its field.
    #[error("{sat}: {field} = {value:e} is outside the range I/NAV carries [{min:e}, {max:e}]")]
    FieldOutOfRange {
        sat: String,
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    /// toe or toc is not on its field's grid.
    #[error("{sat}: {field} (GST seconds of week {sow_s}) is not a multiple of {grid_s} s")]
    OffGrid {
        sat: String,
        field: &'static str,
        sow_s: f64,
        grid_s: f64,
    },
}

impl InavError {
    /// `sat`'s value that did not fit its field.
    fn out_of_range(sat: &str, e: OutOfRange) -> Self {
        Self::FieldOutOfRange {
            sat: sat.to_string(),
            field: e.field,
            value: e.value,
            min: e.min,
            max: e.max,
        }
    }
}

/// The E1-B channel symbols of one satellite's I/NAV message, counted from the start of
/// GST week [`Self::week`]: symbol 0 is the first sync symbol of an odd page part. Page
/// `n` starts (its even part) 2n - 1 s into the week, so page 0 starts in the week before
/// and its odd part is symbols 0-249.
#[derive(Debug, Clone, PartialEq)]
pub struct InavEncoder {
    sat: SatId,
    week: u32,
    fields: Fields,
    toe: Epoch,
    toc: Epoch,
    almanac: Vec<[Vec<i64>; 4]>,
}

impl InavEncoder {
    /// An encoder for Galileo ephemeris `eph`, from the start of GST week `week` (WN = GPS
    /// week - 1024). `almanac_set`: the constellation whose almanac words 7-10 carry (the
    /// Galileo sets among it; see the `almanac` notes). toe and toc must be whole minutes
    /// of GST; every value must fit its field.
    pub fn new(
        eph: &BroadcastEphemeris,
        almanac_set: &[BroadcastEphemeris],
        params: &InavParams,
        week: u32,
    ) -> Result<Self, InavError> {
        let sat = eph.sat.to_string();
        if eph.sat.system != System::Galileo {
            return Err(InavError::NotGalileo { sat });
        }
        let fields = eph::quantise(eph, params, &sat)?;
        let gst_gps = fields.values_for(&words::GST_GPS);
        Ok(Self {
            sat: eph.sat,
            week,
            fields,
            toe: eph.toe,
            toc: eph.toc,
            almanac: almanac::words(almanac_set, eph.toe, &gst_gps),
        })
    }

    /// GST week of symbol 0.
    pub fn week(&self) -> u32 {
        self.week
    }

    /// Start of GST week [`Self::week`], where symbol 0 starts.
    pub fn week_start(&self) -> Epoch {
        gst_epoch(self.week, 0)
    }

    /// The ephemeris the message describes, in SI units: every field quantised and
    /// converted back (message I/NAV, tgd_s = BGD(E1,E5b), tgd2_s = BGD(E1,E5a), iode =
    /// iodc = IODnav, health = the E1-B and E5b bits of the RINEX layout, 4 h fit). The
    /// orbit and clock the signal must follow.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        eph::to_ephemeris(&self.fields, self.sat, self.toe, self.toc)
    }

    /// GST seconds (since the GST epoch) at the start of page `page` (0 for the page
    /// before the epoch).
    fn page_start_s(&self, page: u64) -> u64 {
        (u64::from(self.week) * WEEK_S + INAV_PAGE_S * page).saturating_sub(1)
    }

    /// GST week and TOW (s) at the start of page `page`.
    pub fn page_time(&self, page: u64) -> (u32, u32) {
        let s = self.page_start_s(page);
        ((s / WEEK_S) as u32, (s % WEEK_S) as u32)
    }

    /// Frame number (since the GST epoch), subframe in the frame and page in the subframe
    /// of page `page`.
    fn position(&self, page: u64) -> (u64, u64, usize) {
        // Frames and subframes start at GST 1 s (modulo 720 s and 30 s).
        let s = self.page_start_s(page).saturating_sub(1);
        let subframe = s % FRAME_S / (FRAME_S / SUBFRAMES_PER_FRAME);
        let slot = s % (FRAME_S / SUBFRAMES_PER_FRAME) / INAV_PAGE_S;
        (s / FRAME_S, subframe, slot as usize)
    }

    /// Word type of page `page`.
    pub fn word_type(&self, page: u64) -> u8 {
        let (_, subframe, slot) = self.position(page);
        SUBFRAME_WORDS[slot][(subframe % 2) as usize]
    }

    /// The raw field values of page `page`'s word, in its layout's order.
    fn word_values(&self, page: u64) -> Vec<i64> {
        let word_type = self.word_type(page);
        if (7..=10).contains(&word_type) {
            let (frame, subframe, _) = self.position(page);
            let triple =
                (frame * SUBFRAMES_PER_FRAME / 2 + subframe / 2) % self.almanac.len() as u64;
            return self.almanac[triple as usize][usize::from(word_type - 7)].clone();
        }
        let (wn, tow) = self.page_time(page);
        let mut f = self.fields.clone();
        f.set(&q::WN, i64::from(wn % (1 << q::WN.bits)));
        f.set(&q::TOW, i64::from(tow));
        f.values_for(words::layout(word_type).unwrap_or(&[]))
    }

    /// The 128 bits of page `page`'s word (word type first).
    pub fn word_bits(&self, page: u64) -> Vec<u8> {
        words::pack(self.word_type(page), &self.word_values(page))
    }

    /// The even and odd parts of page `page`, 114 bits each before the tail.
    pub fn part_bits(&self, page: u64) -> [Vec<u8>; 2] {
        let odd_start = self.page_start_s(page) + 1;
        let ssp = match odd_start % 6 {
            2 => pages::SSP[0],
            4 => pages::SSP[1],
            _ => pages::SSP[2],
        };
        pages::parts(&self.word_bits(page), ssp)
    }

    /// The 500 channel symbols (0/1) of page `page`: the even part, then the odd part,
    /// each its sync pattern and its encoded, interleaved bits.
    pub fn page_symbols(&self, page: u64) -> [u8; INAV_PAGE_SYMBOLS] {
        let [even, odd] = self.part_bits(page);
        let mut out = [0u8; INAV_PAGE_SYMBOLS];
        out[..INAV_PART_SYMBOLS].copy_from_slice(&pages::encode_part(&even));
        out[INAV_PART_SYMBOLS..].copy_from_slice(&pages::encode_part(&odd));
        out
    }

    /// Page and index in it of channel symbol `k`.
    fn locate(k: u64) -> (u64, usize) {
        let n = INAV_PAGE_SYMBOLS as u64;
        let shifted = k + INAV_PART_SYMBOLS as u64;
        (shifted / n, (shifted % n) as usize)
    }

    /// Channel symbol `k` (0/1) counted from [`Self::week_start`] (builds its page).
    pub fn symbol(&self, k: u64) -> u8 {
        let (page, i) = Self::locate(k);
        self.page_symbols(page)[i]
    }

    /// `count` channel symbols from symbol `first` on (each page built once).
    pub fn symbols(&self, first: u64, count: usize) -> Vec<u8> {
        let mut out = Vec::with_capacity(count);
        let mut k = first;
        while out.len() < count {
            let (page, from) = Self::locate(k);
            let symbols = self.page_symbols(page);
            let take = (INAV_PAGE_SYMBOLS - from).min(count - out.len());
            out.extend_from_slice(&symbols[from..from + take]);
            k += take as u64;
        }
        out
    }
}
