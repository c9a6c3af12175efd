//! BeiDou D1/D2 decoder state machine (BDS-SIS-ICD-B1I-3.0 §5.2, §5.3).

use super::bds_bch::decode_subframe;
use super::bds_fields::{self, Clock, Header};
use super::decoder::{Common, Decoder, MessageFormat};
use super::framer::FrameSpec;
use super::{NavDecodeError, NavEvent, SUBFRAME_BITS, SubframeInfo, WEEK_S, time_consistent};
use skyforge_gnss::navmsg::BdsNavFormat;
use skyforge_gnss::navmsg::Klobuchar;
use skyforge_orbits::ephemeris::{OrbitClass, SatId, System};

/// Preamble 11100010010 (BDS-SIS-ICD-B1I-3.0 §5.2.3).
const PREAMBLE: u32 = 0b111_0001_0010;
/// Preamble length (bits).
const PREAMBLE_LEN: u32 = 11;
/// Bits of the next subframe the confirmation looks at: its words 1 and 2 (header).
const NEXT_HEADER_BITS: usize = 60;
/// Preamble bits allowed wrong where a subframe is expected (the preamble is not
/// BCH-protected).
const PREAMBLE_TOLERANCE: u32 = 1;

/// Framing: a candidate preamble is confirmed by the next subframe's header 300 bits later
/// (preamble within one bit, FraID and SOW continuing the candidate's), after BCH
/// correction of both headers.
const SPEC: FrameSpec = FrameSpec {
    preamble: PREAMBLE,
    preamble_len: PREAMBLE_LEN,
    confirm_len: SUBFRAME_BITS + NEXT_HEADER_BITS,
    locked_tolerance: PREAMBLE_TOLERANCE,
};

/// Subframe duration of a format (s).
fn subframe_s(format: BdsNavFormat) -> f64 {
    format.subframe_period_s()
}

/// Time of week (s) of the start of a subframe with header `h`: D1 SOW counts at each
/// subframe; D2 SOW counts at the frame start, same in its five subframes
/// (§5.3.2, as SkyForge's encoder and the C01 broadcast vectors show).
fn start_tow_s(format: BdsNavFormat, h: &Header) -> f64 {
    match format {
        BdsNavFormat::D1 => f64::from(h.sow),
        BdsNavFormat::D2 => {
            f64::from(h.sow) + subframe_s(format) * f64::from(h.fra_id.saturating_sub(1))
        }
    }
}

/// Whether `b` follows `a` by exactly one subframe (mod one week).
fn follows(format: BdsNavFormat, a: &Header, b: &Header) -> bool {
    let dt = (start_tow_s(format, b) - start_tow_s(format, a)).rem_euclid(WEEK_S);
    valid(a) && valid(b) && b.fra_id == a.fra_id % 5 + 1 && (dt - subframe_s(format)).abs() < 1e-6
}

/// FraID 1-5 and SOW within the week.
fn valid(h: &Header) -> bool {
    (1..=5).contains(&h.fra_id) && f64::from(h.sow) < WEEK_S
}

/// Number of differing bits between the first `PREAMBLE_LEN` of `bits` and the preamble.
fn preamble_errors(bits: &[u8]) -> u32 {
    (0..PREAMBLE_LEN)
        .filter(|&k| {
            let want = ((PREAMBLE >> (PREAMBLE_LEN - 1 - k)) & 1) as u8;
            bits.get(k as usize) != Some(&want)
        })
        .count() as u32
}

/// Confirmation of a candidate (polarity-corrected window: two unused bits, the candidate
/// subframe, then the next subframe's first 60 bits).
fn confirm(format: BdsNavFormat, window: &[u8]) -> bool {
    let (Some(this), Some(next)) = (
        window.get(2..2 + SUBFRAME_BITS),
        window.get(2 + SUBFRAME_BITS..),
    ) else {
        return false;
    };
    let mut next_padded = next.to_vec();
    next_padded.resize(SUBFRAME_BITS, 0);
    let a = Header::new(&decode_subframe(this).0);
    let b = Header::new(&decode_subframe(&next_padded).0);
    preamble_errors(next) <= PREAMBLE_TOLERANCE && follows(format, &a, &b)
}

/// Decoder of one BeiDou satellite's B1I message (D1 or D2 by PRN).
///
/// Subframe sync: preamble 11100010010 in either polarity, confirmed by the next
/// subframe's header; each subframe is then BCH-corrected word by word (one error per
/// codeword) and accepted when its FraID and SOW agree with the stream time of the
/// previous accepted subframe. D1: clock from subframe 1, orbit from subframes 2-3 of
/// the same frame. D2: subframe 1 pages 1-10 of one 30-s cycle assembled.
pub type BdsDecoder = Decoder<D1D2>;

/// D1/D2's own decoding state: the format, the subframes and pages of the ephemeris, the
/// Klobuchar coefficients.
#[derive(Debug, Clone)]
pub struct D1D2 {
    format: BdsNavFormat,
    /// D1: frame number (SOW / 30) and information bits of subframes 1-3.
    d1: [Option<(u32, Vec<u8>)>; 3],
    /// D2: 30-s cycle number (SOW / 30) and information bits of subframe 1 pages 1-10.
    d2: Vec<Option<(u32, Vec<u8>)>>,
    iono: Option<Klobuchar>,
}

/// Seconds of a D1 frame and of a D2 subframe-1 page cycle.
const CYCLE_S: u32 = 30;
/// Pages of D2 subframe 1.
const D2_PAGES: usize = 10;

impl Decoder<D1D2> {
    /// A decoder for BeiDou satellite `sat` (PRN 1-63); D2 for the GEO PRNs 1-5 and
    /// 59-63, D1 otherwise.
    pub fn new(sat: SatId) -> Result<Self, NavDecodeError> {
        if sat.system != System::Beidou || !(1..=63).contains(&sat.prn) {
            return Err(NavDecodeError::WrongSatellite {
                sat: sat.to_string(),
                what: "D1/D2 are broadcast by BeiDou PRN 1-63",
            });
        }
        let message = D1D2 {
            format: BdsNavFormat::for_prn(sat.prn),
            d1: [None, None, None],
            d2: vec![None; D2_PAGES],
            iono: None,
        };
        Ok(Decoder::with(sat, SPEC, message))
    }

    /// The message format being decoded.
    pub fn format(&self) -> BdsNavFormat {
        self.message.format
    }

    /// The last Klobuchar coefficients.
    pub fn iono(&self) -> Option<Klobuchar> {
        self.message.iono
    }
}

impl MessageFormat for D1D2 {
    fn confirm(&self, window: &[u8]) -> bool {
        confirm(self.format, window)
    }

    /// Decode one subframe; a changed ionosphere is announced after it.
    fn subframe(
        &mut self,
        c: &mut Common,
        start_bit: u64,
        inverted: bool,
        bits: &[u8],
        out: &mut Vec<NavEvent>,
    ) {
        let iono_before = self.iono;
        let body = bits.get(2..).unwrap_or(&[]);
        let (info, corrected) = decode_subframe(body);
        let h = Header::new(&info);
        let tow_s = start_tow_s(self.format, &h);
        let bit_s = self.format.bit_period_s();
        if !(valid(&h) && time_consistent(c.stream.anchor, start_bit, tow_s, bit_s)) {
            c.stream.drop_subframe(start_bit, 1, out);
            return;
        }
        c.stream.accept(start_bit, tow_s, &mut c.week, out);
        c.stream.stats.corrected_bits += u64::from(corrected);
        let page = self.store(c, &h, info);
        out.push(NavEvent::Subframe(SubframeInfo {
            start_bit,
            id: h.fra_id,
            page,
            week: c.week,
            tow_s,
            inverted,
            corrected_bits: corrected,
        }));
        match self.format {
            BdsNavFormat::D1 => self.try_d1(c, tow_s, out),
            BdsNavFormat::D2 => self.try_d2(c, tow_s, out),
        }
        if let Some(iono) = self.iono
            && iono_before != Some(iono)
        {
            out.push(NavEvent::BdsIono(iono));
        }
    }
}

impl D1D2 {
    /// Keep what the ephemeris needs; returns the page number of paged subframes.
    fn store(&mut self, c: &mut Common, h: &Header, info: Vec<u8>) -> Option<u8> {
        let cycle = h.sow / CYCLE_S;
        match (self.format, h.fra_id) {
            (BdsNavFormat::D1, 1..=3) => {
                if h.fra_id == 1 {
                    let (clock, iono) = bds_fields::d1_subframe1(&info);
                    c.week = Some(clock.wn);
                    self.iono = Some(iono);
                }
                self.d1[usize::from(h.fra_id - 1)] = Some((cycle, info));
                None
            }
            (BdsNavFormat::D1, _) | (BdsNavFormat::D2, 5) => {
                Some(bds_fields::page_number(&info, 1, 7))
            }
            (BdsNavFormat::D2, 1) => {
                let pnum = bds_fields::page_number(&info, 0, 4);
                match pnum {
                    1 => c.week = Some(bds_fields::d2_page1(&info).wn),
                    2 => self.iono = Some(bds_fields::d2_page2(&info)),
                    _ => {}
                }
                if let Some(slot) = self.d2.get_mut(usize::from(pnum).wrapping_sub(1)) {
                    *slot = Some((cycle, info));
                }
                Some(pnum)
            }
            (BdsNavFormat::D2, 2) => Some(bds_fields::page_number(&info, 1, 4)),
            (BdsNavFormat::D2, _) => None,
        }
    }

    fn try_d1(&self, c: &mut Common, tx_sow: f64, out: &mut Vec<NavEvent>) {
        let [Some((k1, s1)), Some((k2, s2)), Some((k3, s3))] = &self.d1 else {
            return;
        };
        if !(k1 == k2 && k2 == k3) {
            return;
        }
        let (clock, _) = bds_fields::d1_subframe1(s1);
        let orbit = bds_fields::d1_orbit(s2, s3);
        self.emit(c, &clock, &orbit, tx_sow, out);
    }

    fn try_d2(&self, c: &mut Common, tx_sow: f64, out: &mut Vec<NavEvent>) {
        let Some(Some((cycle, _))) = self.d2.first() else {
            return;
        };
        let cycle = *cycle;
        let pages: Option<Vec<&[u8]>> = self
            .d2
            .iter()
            .map(|p| match p {
                Some((c, info)) if *c == cycle => Some(info.as_slice()),
                _ => None,
            })
            .collect();
        let Some(pages) = pages.and_then(|p| <[&[u8]; D2_PAGES]>::try_from(p).ok()) else {
            return;
        };
        let (clock, orbit) = bds_fields::d2_pages(&pages);
        self.emit(c, &clock, &orbit, tx_sow, out);
    }

    fn emit(
        &self,
        c: &mut Common,
        clock: &Clock,
        orbit: &bds_fields::Orbit,
        tx_sow: f64,
        out: &mut Vec<NavEvent>,
    ) {
        let class = match self.format {
            BdsNavFormat::D1 => OrbitClass::Standard,
            BdsNavFormat::D2 => OrbitClass::BeidouGeo,
        };
        c.offer_ephemeris(
            bds_fields::ephemeris(c.sat, class, tx_sow, clock, orbit),
            out,
        );
    }
}
