//! The BeiDou B-CNAV1 navigation message of the B1C data component
//! (BDS-SIS-ICD-B1C-1.0 §6, §7), encoder and frame decoder.
//!
//! Timing (6.2.1, Table 7-2): 100 symbols/s, a frame of 1800 symbols lasts 18 s;
//! SkyForge starts frames at BDT whole 18 s of the week (33600 frames a week), so SOH =
//! (SOW mod 3600) / 18 and HOW = SOW / 3600 of the frame's first symbol. Frame: subframe
//! 1 (PRN and SOH as BCH words, 72 symbols, [`subframe1`]), then subframe 2 (600 bits:
//! time, issue of data, ephemeris, clock, group delays, CRC-24Q; LDPC(200, 100)) and
//! subframe 3 (264 bits, page type 1: health, integrity flags, accuracy indices,
//! ionosphere, BDT-UTC, CRC-24Q; LDPC(88, 44)) interleaved together ([`interleave`]).
//! Every frame sends page type 1; SkyForge sends no almanac, EOP or BGTO pages.

mod interleave;
mod subframe1;
#[cfg(test)]
mod tests;

use super::bds_cnav_eph::{self as e, BdsCnavError, BdsCnavParams, rev};
use super::crc24q::crc24q_bits;
use super::field::{Field, Fields, Lsb, field, push_bits, read_fields};
use super::ldpc_gf64::{B1C_SUBFRAME2, B1C_SUBFRAME3};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};
use subframe1::{PRN_SYMBOLS, SOH_SYMBOLS, decode_soh, prn_word, soh_word};

/// Channel symbol rate of the B1C data component (symbols/s).
pub const CNAV1_SYMBOL_RATE_HZ: f64 = 100.0;
/// Frame duration (s) and symbols.
pub const CNAV1_FRAME_S: u64 = 18;
pub const CNAV1_FRAME_SYMBOLS: usize = 1800;
/// Subframe 1 symbols.
const SF1_SYMBOLS: usize = PRN_SYMBOLS + SOH_SYMBOLS;
/// Frames in a week.
const FRAMES_PER_WEEK: u64 = 604_800 / CNAV1_FRAME_S;
/// Min-sum iterations before a subframe is given up.
const LDPC_ITERATIONS: usize = 30;

/// Table 7-2: hours of week.
const HOW: Field = field("HOW", 8, false, Lsb::Count);
/// Table 7-1: page type.
const PAGE_ID: Field = field("PageID", 6, false, Lsb::Count);

/// Figure 6-6: subframe 2 without its CRC (576 bits).
fn subframe2_fields() -> Vec<Field> {
    let mut v = vec![e::WN, HOW, e::IODC, e::IODE];
    v.extend(e::EPHEMERIS_1);
    v.extend(e::EPHEMERIS_2);
    v.extend(e::CLOCK);
    v.extend([e::TGD_B2AP, e::ISC_B1CD, e::TGD_B1CP, rev(7)]);
    v
}

/// Figure 6-8: subframe 3 page type 1 without its CRC (240 bits).
fn page1_fields() -> Vec<Field> {
    let mut v = vec![PAGE_ID, e::HS];
    v.extend(e::FLAGS_B1C);
    v.extend([e::SISMAI, e::SISAI_OE, e::SISAI_OC]);
    v.extend(e::IONO);
    v.extend(e::BDT_UTC);
    v.push(rev(27));
    v
}

/// `fields` of `f` packed and followed by their CRC-24Q.
fn pack(fields: &[Field], f: &Fields) -> Vec<u8> {
    let mut bits = Vec::new();
    for (field, v) in fields.iter().zip(f.values_for(fields)) {
        push_bits(&mut bits, v, field.bits);
    }
    let crc = crc24q_bits(&bits);
    push_bits(&mut bits, i64::from(crc), 24);
    bits
}

/// The channel symbols of one satellite's B-CNAV1 message, counted from the start of BDT
/// week [`Self::week`].
#[derive(Debug, Clone)]
pub struct BdsCnav1Encoder {
    sat: SatId,
    week: u32,
    fields: Fields,
    toe: Epoch,
    toc: Epoch,
}

impl BdsCnav1Encoder {
    /// An encoder for BeiDou MEO/IGSO ephemeris `eph` from the start of BDT week
    /// `bdt_week`. toe and toc must be on the 300 s grid; every value must fit its field.
    pub fn new(
        eph: &BroadcastEphemeris,
        params: &BdsCnavParams,
        bdt_week: u32,
    ) -> Result<Self, BdsCnavError> {
        Ok(Self {
            sat: eph.sat,
            week: bdt_week,
            fields: e::quantise(eph, params)?,
            toe: eph.toe,
            toc: eph.toc,
        })
    }

    /// BDT week of symbol 0.
    pub fn week(&self) -> u32 {
        self.week
    }

    /// Start of BDT week [`Self::week`], where symbol 0 (the first symbol of a frame)
    /// starts.
    pub fn week_start(&self) -> Epoch {
        skyforge_orbits::time::epoch_from_bdt(self.week, 0.0)
    }

    /// Channel symbol `k` (0/1), symbol 0 the first of the week's first frame.
    pub fn symbol(&self, k: u64) -> u8 {
        let n = CNAV1_FRAME_SYMBOLS as u64;
        self.frame_symbols(k / n)[(k % n) as usize]
    }

    /// The ephemeris the messages describe, in SI units (every field quantised and
    /// converted back; `tgd_s` = TGD_B1Cp, IODE, IODC, health = HS, 3 h fit).
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        e::to_ephemeris(&self.fields, self.sat, self.toe, self.toc, &e::TGD_B1CP)
    }

    /// BDT week and SOW (s) of the start of frame `n`.
    pub fn frame_time(&self, n: u64) -> (u32, u32) {
        let week = self.week + (n / FRAMES_PER_WEEK) as u32;
        (week, ((n % FRAMES_PER_WEEK) * CNAV1_FRAME_S) as u32)
    }

    /// Subframe 2 (600 bits) and subframe 3 (264 bits) of frame `n`.
    pub fn subframe_bits(&self, n: u64) -> (Vec<u8>, Vec<u8>) {
        let (week, sow) = self.frame_time(n);
        let mut f = self.fields.clone();
        f.set(&e::WN, i64::from(week % (1 << e::WN.bits)));
        f.set(&HOW, i64::from(sow / 3600));
        f.set(&PAGE_ID, 1);
        (pack(&subframe2_fields(), &f), pack(&page1_fields(), &f))
    }

    /// The 1800 channel symbols (0/1) of frame `n`.
    pub fn frame_symbols(&self, n: u64) -> Vec<u8> {
        let (_, sow) = self.frame_time(n);
        let (sf2, sf3) = self.subframe_bits(n);
        let mut out = prn_word(self.sat.prn);
        out.extend(soh_word(((sow % 3600) / 18) as u8));
        let mut coded = B1C_SUBFRAME2.encode_bits(&sf2);
        coded.extend(B1C_SUBFRAME3.encode_bits(&sf3));
        out.extend(interleave::interleave(&coded));
        out
    }

    /// `count` channel symbols from symbol `first` on.
    pub fn symbols(&self, first: u64, count: usize) -> Vec<u8> {
        e::symbols_of_frames(CNAV1_FRAME_SYMBOLS, first, count, |n| self.frame_symbols(n))
    }
}

/// One decoded frame: the SOH count, and subframe 2 and the subframe 3 page where they
/// passed LDPC decoding and CRC.
#[derive(Debug, Clone, PartialEq)]
pub struct Cnav1Frame {
    pub soh: u8,
    sf2: Option<Fields>,
    page: Option<Fields>,
}

/// Why soft symbols are not a B-CNAV1 frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Cnav1DecodeError {
    #[error("a B-CNAV1 frame is 1800 soft symbols, got {0}")]
    Length(usize),
    #[error("subframe 1 does not hold the PRN word")]
    Prn,
    #[error("neither subframe 2 nor subframe 3 decoded")]
    Subframes,
}

impl Cnav1Frame {
    /// BDT week and SOW (s) of the frame's first symbol, once subframe 2 gave WN and HOW.
    pub fn time(&self) -> Option<(u32, u32)> {
        let f = self.sf2.as_ref()?;
        let sow = f.get(&HOW) as u32 * 3600 + u32::from(self.soh) * 18;
        Some((f.get(&e::WN) as u32, sow))
    }

    /// The subframe 3 page type, if subframe 3 decoded.
    pub fn page_id(&self) -> Option<u8> {
        self.page.as_ref().map(|p| p.get(&PAGE_ID) as u8)
    }

    /// The ephemeris and clock of subframe 2 (which holds a complete set).
    pub fn ephemeris(&self, sat: SatId) -> Option<BroadcastEphemeris> {
        let f = self.sf2.as_ref()?;
        let (week, sow) = self.time()?;
        let sow = i64::from(sow);
        let toe = e::reference_epoch(week, sow, f.get(&e::TOE) * 300);
        let toc = e::reference_epoch(week, sow, f.get(&e::TOC) * 300);
        Some(e::to_ephemeris(f, sat, toe, toc, &e::TGD_B1CP))
    }
}

/// Decode one frame of 1800 polarity-corrected soft symbols (positive = logic 0) of
/// satellite `prn`: the PRN word must correlate above 0.5 (normalised), the SOH is the
/// most likely BCH(51, 8) word, and subframes 2 and 3 are de-interleaved, soft-decoded and
/// CRC-checked each on its own.
pub fn decode_frame(soft: &[f32], prn: u8) -> Result<Cnav1Frame, Cnav1DecodeError> {
    if soft.len() != CNAV1_FRAME_SYMBOLS {
        return Err(Cnav1DecodeError::Length(soft.len()));
    }
    if prn_correlation(&soft[..PRN_SYMBOLS], prn) < 0.5 {
        return Err(Cnav1DecodeError::Prn);
    }
    let (soh, _) = decode_soh(&soft[PRN_SYMBOLS..SF1_SYMBOLS]);
    let coded = interleave::deinterleave(&soft[SF1_SYMBOLS..]);
    let (c2, c3) = coded.split_at(interleave::SF2_SYMBOLS);
    let read = |bits: Option<Vec<u8>>, fields: Vec<Field>| {
        let bits = bits.filter(|b| crc24q_bits(b) == 0)?;
        let mut f = Fields::default();
        f.absorb(&fields, &read_fields(&bits, &fields));
        Some(f)
    };
    let sf2 = read(
        B1C_SUBFRAME2.decode_soft(c2, LDPC_ITERATIONS),
        subframe2_fields(),
    );
    let page = read(
        B1C_SUBFRAME3.decode_soft(c3, LDPC_ITERATIONS),
        page1_fields(),
    )
    .filter(|p| p.get(&PAGE_ID) == 1);
    if sf2.is_none() && page.is_none() {
        return Err(Cnav1DecodeError::Subframes);
    }
    Ok(Cnav1Frame { soh, sf2, page })
}

/// Normalised correlation of 21 soft symbols with the BCH(21, 6) word of `prn`: 1 for a
/// noiseless word, -1 for an inverted one.
pub fn prn_correlation(soft: &[f32], prn: u8) -> f32 {
    let norm: f32 = soft
        .iter()
        .map(|x| x.abs())
        .sum::<f32>()
        .max(f32::MIN_POSITIVE);
    let c: f32 = prn_word(prn)
        .iter()
        .zip(soft)
        .map(|(&b, &x)| if b == 0 { x } else { -x })
        .sum();
    c / norm
}
