//! GPS LNAV decoder state machine (IS-GPS-200 20.3.2-20.3.5).

use super::decoder::{Common, Decoder, MessageFormat};
use super::framer::FrameSpec;
use super::gps_fields::{
    self, Header, PAGE18_SV_ID, Page18, Subframe1, Subframe2, Subframe3, nearest_week,
};
use super::gps_parity::{check_subframe, check_word};
use super::{NavDecodeError, NavEvent, SubframeInfo, time_consistent};
use skyforge_gnss::navmsg::gps_lnav::BIT_PERIOD_S;
use skyforge_gnss::navmsg::gps_lnav::IonoParams;
use skyforge_gnss::navmsg::gps_lnav::PREAMBLE;
use skyforge_gnss::navmsg::gps_lnav::SUBFRAMES_PER_WEEK;
use skyforge_gnss::navmsg::gps_lnav::UtcParams;
use skyforge_orbits::ephemeris::{SatId, System};

/// Default reference for resolving the 10-bit week number: the middle of the third
/// 1024-week era (weeks 2048-3071, April 2019 to November 2038).
pub const DEFAULT_GPS_REFERENCE_WEEK: u32 = 2560;

/// Framing of LNAV: preamble 10001011 (IS-GPS-200 20.3.3.1); a candidate is confirmed by
/// the parity of TLM and HOW, so 60 bits are needed.
const SPEC: FrameSpec = FrameSpec {
    preamble: PREAMBLE,
    preamble_len: 8,
    confirm_len: 60,
    locked_tolerance: 0,
};

/// Whether a polarity-corrected window (D29, D30 of the previous word, then TLM and HOW)
/// starts a subframe: both words pass parity, the HOW ends with the t bits solved to
/// D29 = D30 = 0 (IS-GPS-200 20.3.5.2), the subframe ID is 1-5 and the TOW count is
/// below one week.
fn confirm(window: &[u8]) -> bool {
    // D29*, D30* of the TLM are the t-bit-solved zeros of the previous word 10.
    let bit = |k: usize| {
        if k < 2 {
            0
        } else {
            window.get(k).copied().unwrap_or(0)
        }
    };
    let word = |k: usize| (0..30).fold(0u32, |a, j| (a << 1) | u32::from(bit(2 + 30 * k + j)));
    let (tlm, how) = (word(0), word(1));
    let Some(tlm_src) = check_word(tlm, bit(0), bit(1)) else {
        return false;
    };
    let Some(how_src) = check_word(how, ((tlm >> 1) & 1) as u8, (tlm & 1) as u8) else {
        return false;
    };
    let id = (how_src >> 2) & 0b111;
    let tow_count = how_src >> 7;
    window.len() >= 62
        && tlm_src >> 16 == PREAMBLE
        && how & 0b11 == 0
        && (1..=5).contains(&id)
        && u64::from(tow_count) < SUBFRAMES_PER_WEEK
}

/// Decoder of one GPS satellite's LNAV stream.
///
/// Feed soft bits with [`super::NavDecoder::feed`]. Subframe sync: preamble 10001011 in either
/// polarity confirmed by TLM and HOW parity; then every 300 bits a subframe whose ten
/// words must all pass parity (table 20-XIV) or the whole subframe is dropped. The ten
/// bits of week number are resolved to the full week nearest the reference week.
pub type GpsLnavDecoder = Decoder<Lnav>;

/// LNAV's own decoding state: the reference week, subframes 1-3 and page 18.
#[derive(Debug, Clone)]
pub struct Lnav {
    reference_week: u32,
    sf1: Option<Subframe1>,
    sf2: Option<Subframe2>,
    sf3: Option<Subframe3>,
    page18: Option<Page18>,
    iono_utc: Option<(IonoParams, UtcParams)>,
}

impl Decoder<Lnav> {
    /// A decoder for GPS satellite `sat` (PRN 1-32), resolving weeks near
    /// [`DEFAULT_GPS_REFERENCE_WEEK`].
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        Self::with_reference_week(sat, DEFAULT_GPS_REFERENCE_WEEK)
    }

    /// As [`Self::new`], resolving the broadcast 10-bit week to the full week within
    /// 512 weeks of `reference_week` (e.g. from the recording's approximate date).
    pub fn with_reference_week(sat: SatId, reference_week: u32) -> Result<Self, NavDecodeError> {
        if sat.system != System::Gps || !(1..=32).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "LNAV is broadcast by GPS PRN 1-32",
            });
        }
        let lnav = Lnav {
            reference_week,
            sf1: None,
            sf2: None,
            sf3: None,
            page18: None,
            iono_utc: None,
        };
        Ok(Decoder::with(sat, SPEC, lnav))
    }

    /// The last Klobuchar and UTC parameters (page 18).
    pub fn iono_utc(&self) -> Option<(IonoParams, UtcParams)> {
        self.message.iono_utc
    }
}

impl MessageFormat for Lnav {
    fn confirm(&self, window: &[u8]) -> bool {
        confirm(window)
    }

    fn subframe(
        &mut self,
        c: &mut Common,
        start_bit: u64,
        inverted: bool,
        bits: &[u8],
        out: &mut Vec<NavEvent>,
    ) {
        // The previous word 10 ends with D29 = D30 = 0 in true polarity (IS-GPS-200
        // 20.3.5.2): using these instead of the received bits keeps an error there from
        // spoiling this subframe too.
        let mut bits = bits.to_vec();
        bits.iter_mut().take(2).for_each(|b| *b = 0);
        let src = match check_subframe(&bits) {
            Ok(src) => src,
            Err(words) => {
                c.stream.stats.parity_failed_words += u64::from(words.count_ones());
                c.stream.drop_subframe(start_bit, words, out);
                return;
            }
        };
        let header = Header::new(&src);
        let tow_s = header.start_tow_s();
        if header.preamble != PREAMBLE
            || !(1..=5).contains(&header.id)
            || !time_consistent(c.stream.anchor, start_bit, tow_s, BIT_PERIOD_S)
        {
            // Parity passed but TLM/HOW contradict the stream (undetected errors).
            c.stream.drop_subframe(start_bit, 0b11, out);
            return;
        }
        c.stream.accept(start_bit, tow_s, &mut c.week, out);
        let mut page = None;
        match header.id {
            1 => {
                let s1 = Subframe1::new(&src);
                c.week = Some(nearest_week(s1.wn10, 10, self.reference_week));
                self.sf1 = Some(s1);
            }
            2 => self.sf2 = Some(Subframe2::new(&src)),
            3 => self.sf3 = Some(Subframe3::new(&src)),
            4 | 5 => {
                let sv_id = gps_fields::page_sv_id(&src);
                page = Some(sv_id);
                if header.id == 4 && sv_id == PAGE18_SV_ID {
                    self.page18 = Some(Page18::new(&src));
                }
            }
            _ => {}
        }
        out.push(NavEvent::Subframe(SubframeInfo {
            start_bit,
            id: header.id,
            page,
            week: c.week,
            tow_s,
            inverted,
            corrected_bits: 0,
        }));
        self.try_ephemeris(c, tow_s, out);
        self.try_iono_utc(c.week, out);
    }
}

impl Lnav {
    /// Emit the ephemeris when subframes 1-3 share one issue of data (IODE of subframes 2
    /// and 3 equal to the 8 LSBs of IODC, IS-GPS-200 20.3.4.4) and it changed.
    fn try_ephemeris(&mut self, c: &mut Common, tx_sow: f64, out: &mut Vec<NavEvent>) {
        let (Some(s1), Some(s2), Some(s3), Some(week)) = (self.sf1, self.sf2, self.sf3, c.week)
        else {
            return;
        };
        if s2.iode != s3.iode || s1.iodc & 0xFF != s2.iode {
            return;
        }
        c.offer_ephemeris(
            gps_fields::ephemeris(c.sat, week, tx_sow, &s1, &s2, &s3),
            out,
        );
    }

    /// Emit page 18 once the week is known and when it changed.
    fn try_iono_utc(&mut self, week: Option<u32>, out: &mut Vec<NavEvent>) {
        let (Some(p), Some(week)) = (self.page18, week) else {
            return;
        };
        let now = (p.iono, p.utc(week));
        if self.iono_utc != Some(now) {
            self.iono_utc = Some(now);
            out.push(NavEvent::GpsIonoUtc {
                iono: now.0,
                utc: now.1,
            });
        }
    }
}
