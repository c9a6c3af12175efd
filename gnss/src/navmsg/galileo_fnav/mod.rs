//! The Galileo F/NAV navigation message of E5a-I (Galileo OS SIS ICD Issue 2.1, §4.1, §4.2,
//! §5.1), encoder and decoder.
//!
//! Timing (§4.2.2, §4.2.3, §5.1.2): 50 symbols/s; a page lasts 10 s (12 sync + 488 encoded
//! symbols), a subframe 5 pages (50 s), a frame 12 subframes (600 s). Every subframe
//! sends page types 1, 2, 3, 4 and then an almanac page, 5 in odd subframes (1st, 3rd,
//! ...) and 6 in even ones; a 5/6 pair carries the almanacs of three satellites, so a
//! frame carries 18 (§4.2.3, F/NAV nominal sub-frame layout). The TOW of a page is the GST of the
//! leading edge of its first symbol (§5.1.2). SkyForge starts pages at GST whole 10 s and
//! frames at whole 600 s of the week (604800 s is 1008 frames, so the layout repeats each
//! week): the ICD fixes TOW's meaning, not a phase for the frame, which is a choice here.
//!
//! [`FnavEncoder`] turns one ephemeris (plus [`FnavParams`] and a constellation for the
//! almanac) into channel symbols; [`decode_page`] and [`FnavAssembler`] turn received
//! soft symbols back into pages and an ephemeris. [`FnavEncoder::broadcast_ephemeris`] is
//! the quantised ephemeris, the one the signal must follow and a decoder recovers.

// The fields, GST time helpers, almanac propagation and ephemeris conversion I/NAV shares.
pub(crate) mod almanac;
mod decode;
pub(crate) mod eph;
mod pages;
pub(crate) mod quant;
#[cfg(test)]
mod tests;
pub(crate) mod time;

pub use decode::{FnavAssembler, FnavDecodeError, FnavEphemeris, FnavPage, decode_page};
pub use pages::{DUMMY_PAGE_TYPE, FNAV_SYNC, PAGE_SYMBOLS as FNAV_PAGE_SYMBOLS};

use eph::Fields;
use hifitime::Epoch;
use quant::{self as q, Field};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};
use time::{WEEK_S, gst_epoch};

/// Channel symbol rate of E5a-I (symbols/s).
pub const FNAV_SYMBOL_RATE_HZ: f64 = 50.0;
/// Page duration (s).
pub const FNAV_PAGE_S: u64 = 10;
/// Pages per subframe and subframes per frame.
const PAGES_PER_SUBFRAME: u64 = 5;
const SUBFRAMES_PER_FRAME: u64 = 12;
/// Frame duration (s).
const FRAME_S: u64 = FNAV_PAGE_S * PAGES_PER_SUBFRAME * SUBFRAMES_PER_FRAME;

/// What the Galileo messages carry besides the clock, ephemeris and almanac (F/NAV page
/// types 1 and 4, I/NAV word types 3, 5, 6 and 10), in SI units and the integers the ICD
/// defines once for both. Default: all zero, leap seconds 18 s (GST - UTC since 2017).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GalileoParams {
    /// SISA index (0-255) of the message's signal pair (F/NAV: E1,E5a; I/NAV: E1,E5b),
    /// sent as given.
    pub sisa_index: u8,
    /// NeQuick effective ionisation level coefficients (§5.1.6): ai0 (sfu), ai1
    /// (sfu/deg), ai2 (sfu/deg^2).
    pub ai0: f64,
    pub ai1: f64,
    pub ai2: f64,
    /// GST-UTC (§5.1.7): A0 (s), A1 (s/s), Delta tLS (s), t0t (s of week), WN0t (week,
    /// 8 bits), WNLSF (week, 8 bits), DN (day of week, 3 bits), Delta tLSF (s).
    pub a0_s: f64,
    pub a1_s_s: f64,
    pub dt_ls_s: i32,
    pub t0t_s: u32,
    pub wn0t: u32,
    pub wn_lsf: u32,
    pub dn: u32,
    pub dt_lsf_s: i32,
    /// GST-GPS (§5.1.8): A0G (s), A1G (s/s), t0G (s of week), WN0G (week, 6 bits).
    pub a0g_s: f64,
    pub a1g_s_s: f64,
    pub t0g_s: u32,
    pub wn0g: u32,
}

impl Default for GalileoParams {
    fn default() -> Self {
        Self {
            sisa_index: 0,
            ai0: 0.0,
            ai1: 0.0,
            ai2: 0.0,
            a0_s: 0.0,
            a1_s_s: 0.0,
            dt_ls_s: 18,
            t0t_s: 0,
            wn0t: 0,
            wn_lsf: 0,
            dn: 0,
            dt_lsf_s: 18,
            a0g_s: 0.0,
            a1g_s_s: 0.0,
            t0g_s: 0,
            wn0g: 0,
        }
    }
}

/// F/NAV's parameters ([`GalileoParams`]).
pub type FnavParams = GalileoParams;

impl GalileoParams {
    /// Each field with its value in the field's SI unit, the SISA index in the message's
    /// field `sisa`.
    pub(crate) fn values(&self, sisa: &'static Field) -> [(&'static Field, f64); 16] {
        [
            (sisa, f64::from(self.sisa_index)),
            (&q::AI0, self.ai0),
            (&q::AI1, self.ai1),
            (&q::AI2, self.ai2),
            (&q::A0, self.a0_s),
            (&q::A1, self.a1_s_s),
            (&q::DT_LS, f64::from(self.dt_ls_s)),
            (&q::T0T, f64::from(self.t0t_s)),
            (&q::WN0T, f64::from(self.wn0t)),
            (&q::WN_LSF, f64::from(self.wn_lsf)),
            (&q::DN, f64::from(self.dn)),
            (&q::DT_LSF, f64::from(self.dt_lsf_s)),
            (&q::A0G, self.a0g_s),
            (&q::A1G, self.a1g_s_s),
            (&q::T0G, f64::from(self.t0g_s)),
            (&q::WN0G, f64::from(self.wn0g)),
        ]
    }
}

/// Why an F/NAV message cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FnavError {
    /// The ephemeris is not a Galileo one.
    #[error("{sat}: not a Galileo satellite; F/NAV is a Galileo message")]
    NotGalileo { sat: String },
    /// A value does not fit its field.
    #[error("{sat}: {field} = {value:e} is outside the range F/NAV carries [{min:e}, {max:e}]")]
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

impl FnavError {
    /// `sat`'s value that did not fit its field.
    fn out_of_range(sat: &str, e: crate::navmsg::field::OutOfRange) -> Self {
        Self::FieldOutOfRange {
            sat: sat.to_string(),
            field: e.field,
            value: e.value,
            min: e.min,
            max: e.max,
        }
    }
}

/// The channel symbols of one satellite's F/NAV message, counted from the start of GST
/// week [`Self::week`] (symbol 0 is the first sync symbol of a frame's first page).
#[derive(Debug, Clone, PartialEq)]
pub struct FnavEncoder {
    sat: SatId,
    week: u32,
    fields: Fields,
    toe: Epoch,
    toc: Epoch,
    almanac: Vec<[Vec<i64>; 2]>,
}

impl FnavEncoder {
    /// An encoder for Galileo ephemeris `eph`, from the start of GST week `week` (WN = GPS
    /// week - 1024). `almanac_set`: the constellation whose almanac pages 5 and 6 carry
    /// (the Galileo sets among it; see the `almanac` notes). toe and toc must be whole
    /// minutes of GST; every value must fit its field.
    pub fn new(
        eph: &BroadcastEphemeris,
        almanac_set: &[BroadcastEphemeris],
        params: &FnavParams,
        week: u32,
    ) -> Result<Self, FnavError> {
        let sat = eph.sat.to_string();
        if eph.sat.system != System::Galileo {
            return Err(FnavError::NotGalileo { sat });
        }
        let fields = eph::quantise(eph, params, &sat)?;
        Ok(Self {
            sat: eph.sat,
            week,
            fields,
            toe: eph.toe,
            toc: eph.toc,
            almanac: almanac::pages(almanac_set, eph.toe),
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
    /// converted back (message F/NAV, tgd_s = BGD(E1,E5a), tgd2_s = 0, iode = iodc =
    /// IODnav, health = E5aHS << 4 | E5aDVS << 3, 4 h fit). The orbit and clock the signal
    /// must follow.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        eph::to_ephemeris(&self.fields, self.sat, self.toe, self.toc)
    }

    /// Page type of page `page` (page 0 starts at [`Self::week_start`]).
    pub fn page_type(&self, page: u64) -> u8 {
        let in_frame = page % (PAGES_PER_SUBFRAME * SUBFRAMES_PER_FRAME);
        let (subframe, slot) = (in_frame / PAGES_PER_SUBFRAME, in_frame % PAGES_PER_SUBFRAME);
        match slot {
            0..=3 => slot as u8 + 1,
            _ if subframe % 2 == 0 => 5,
            _ => 6,
        }
    }

    /// GST week and TOW (s) at the start of page `page`.
    pub fn page_time(&self, page: u64) -> (u32, u32) {
        let s = page * FNAV_PAGE_S;
        (
            (u64::from(self.week) + s / WEEK_S) as u32,
            (s % WEEK_S) as u32,
        )
    }

    /// The raw field values of page `page`, in its layout's order.
    fn page_values(&self, page: u64) -> Vec<i64> {
        let page_type = self.page_type(page);
        let (wn, tow) = self.page_time(page);
        if page_type >= 5 {
            let frame = (u64::from(wn) * WEEK_S + u64::from(tow)) / FRAME_S;
            let subframe = page % (PAGES_PER_SUBFRAME * SUBFRAMES_PER_FRAME) / PAGES_PER_SUBFRAME;
            let pair = (frame * SUBFRAMES_PER_FRAME / 2 + subframe / 2) % self.almanac.len() as u64;
            return self.almanac[pair as usize][usize::from(page_type - 5)].clone();
        }
        let mut f = self.fields.clone();
        f.set(&q::WN, i64::from(wn % (1 << q::WN.bits)));
        f.set(&q::TOW, i64::from(tow));
        f.values_for(pages::layout(page_type).unwrap_or(&[]))
    }

    /// The 214 data bits (page type and navigation data) of page `page`.
    pub fn page_bits(&self, page: u64) -> Vec<u8> {
        pages::pack(self.page_type(page), &self.page_values(page))
    }

    /// The 500 channel symbols (0/1) of page `page`: sync pattern, then the encoded and
    /// interleaved page.
    pub fn page_symbols(&self, page: u64) -> [u8; FNAV_PAGE_SYMBOLS] {
        pages::encode_page(&self.page_bits(page))
    }

    /// Channel symbol `k` (0/1) counted from [`Self::week_start`] (builds its page).
    pub fn symbol(&self, k: u64) -> u8 {
        let n = FNAV_PAGE_SYMBOLS as u64;
        self.page_symbols(k / n)[(k % n) as usize]
    }

    /// `count` channel symbols from symbol `first` on (each page built once).
    pub fn symbols(&self, first: u64, count: usize) -> Vec<u8> {
        let n = FNAV_PAGE_SYMBOLS as u64;
        let mut out = Vec::with_capacity(count);
        let mut k = first;
        while out.len() < count {
            let page = self.page_symbols(k / n);
            let from = (k % n) as usize;
            let take = (FNAV_PAGE_SYMBOLS - from).min(count - out.len());
            out.extend_from_slice(&page[from..from + take]);
            k += take as u64;
        }
        out
    }
}
