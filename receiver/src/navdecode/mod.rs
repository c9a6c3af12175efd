//! Navigation-message decoding: GPS LNAV, BeiDou D1/D2, GPS L5 CNAV, Galileo E5a F/NAV
//! and Galileo E1-B I/NAV to ephemeris, clock, ionosphere and time.
//!
//! Input, LNAV and D1/D2: the data-bit stream a tracking channel produces after bit
//! synchronisation (and, for BeiDou D1, after the NH code is wiped), one soft value per
//! bit. CNAV, F/NAV and I/NAV: the channel symbols (before FEC decoding), one soft value
//! per symbol. The sign carries the bit or symbol with the BPSK mapping of the encoders (`+`
//! is logic 0, `-` is logic 1); the magnitude (confidence) is used by the Viterbi decoding
//! of CNAV, F/NAV and I/NAV only. The polarity of the whole stream is unknown (the 180 deg
//! ambiguity of a Costas loop) and may flip after a half-cycle slip: each subframe's,
//! message's or page's polarity is taken from its preamble or sync pattern.
//!
//! Decoders are state machines fed bits one by one or in slices ([`NavDecoder::feed`]);
//! they return [`NavEvent`]s: synchronisation gained or lost, each decoded subframe with
//! the time of week of its first bit, parity failures, and, when complete, the ephemeris
//! as the orbits crate's [`BroadcastEphemeris`], the Klobuchar coefficients and (GPS) the
//! UTC parameters. [`decoder_for`] picks the decoder of a satellite and signal.
//!
//! - [`GpsLnavDecoder`]: IS-GPS-200 20.3.2-20.3.5 (preamble 10001011, word parity of table
//!   20-XIV, subframes 1-3, subframe 4 page 18).
//! - [`BdsDecoder`]: BDS-SIS-ICD-B1I-3.0 §5.2 (D1) and §5.3 (D2): preamble 11100010010,
//!   BCH(15,11) single-error correction, de-interleaving of words 2-10, D1 subframes 1-3,
//!   D2 subframe 1 pages 1-10.
//! - [`CnavDecoder`]: IS-GPS-705J §3.3.3.1.1, §20.3 (continuous rate 1/2 K = 7 code,
//!   preamble 10001011, CRC-24Q, message types 10, 11, 30).
//! - [`FnavDecoder`]: Galileo OS SIS ICD §4.2 (sync pattern, de-interleaving, Viterbi,
//!   CRC-24Q, page types 1-4).
//! - [`InavDecoder`]: Galileo OS SIS ICD §4.3 (even and odd page parts, sync pattern,
//!   de-interleaving, Viterbi, CRC-24Q over both parts, word types 1-5).

mod bds;
mod bds_bch;
mod bds_cnav1;
mod bds_cnav2;
mod bds_fields;
mod decoder;
mod framer;
mod galileo_fnav;
mod galileo_inav;
mod galileo_pages;
mod gps;
mod gps_cnav;
mod gps_fields;
mod gps_parity;
mod symbol_sync;
#[cfg(test)]
mod symbol_test_support;

pub use bds::{BdsDecoder, D1D2};
pub use bds_cnav1::BdsCnav1Decoder;
pub use bds_cnav2::BdsCnav2Decoder;
pub use decoder::{Decoder, MessageFormat};
pub(crate) use galileo_fnav::FnavDecoder;
pub(crate) use galileo_inav::InavDecoder;
pub use gps::{DEFAULT_GPS_REFERENCE_WEEK, GpsLnavDecoder, Lnav};
pub use gps_cnav::CnavDecoder;

use skyforge_gnss::navmsg::Klobuchar;
use skyforge_gnss::navmsg::gps_lnav::IonoParams;
use skyforge_gnss::navmsg::gps_lnav::UtcParams;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, OrbitClass, SatId, System};

/// Bits per subframe, GPS LNAV and BeiDou D1/D2 alike.
pub const SUBFRAME_BITS: usize = 300;

/// An ephemeris decoded from the message, with the message fields that
/// [`BroadcastEphemeris`] does not hold.
#[derive(Debug, Clone, PartialEq)]
pub struct DecodedEphemeris {
    /// Orbit and clock in SI units (angles in rad); toe and toc in the system time scale.
    /// GPS: `health` is the 6-bit SV health, `tgd_s` is TGD, `iode`/`iodc` are IODE/IODC.
    /// BeiDou: `health` is SatH1, `tgd_s` is TGD1 (B1I), `iode`/`iodc` are AODE/AODC.
    /// GPS CNAV and Galileo F/NAV and I/NAV: as the gnss crate's encoders'
    /// `broadcast_ephemeris` (CNAV: the three health bits, TGD, no IODE/IODC; F/NAV: E5aHS
    /// and E5aDVS, BGD(E1,E5a), IODnav; I/NAV: the E1-B and E5b health and validity bits,
    /// BGD(E1,E5b) and BGD(E1,E5a), IODnav).
    pub eph: BroadcastEphemeris,
    /// URA index (GPS LNAV, IS-GPS-200 20.3.3.3.1.3), URA_ED index clamped to 0-15 (GPS
    /// CNAV, message type 10, IS-GPS-705J 20.3.3.1) or URAI (BeiDou), 0-15; 0 for Galileo.
    pub ura_index: u8,
    /// BeiDou TGD2 (B2I group delay, s); `None` for GPS and Galileo.
    pub tgd2_s: Option<f64>,
}

impl DecodedEphemeris {
    /// Push a BDS-3 ephemeris of B-CNAV1 or B-CNAV2 (`eph` when the frames completed one)
    /// as an event when it is of the standard orbit class and differs from `last`.
    pub(crate) fn push_bds3(
        last: &mut Option<DecodedEphemeris>,
        eph: Option<BroadcastEphemeris>,
        out: &mut Vec<NavEvent>,
    ) {
        let Some(eph) = eph.filter(|e| e.class == OrbitClass::Standard) else {
            return;
        };
        let decoded = DecodedEphemeris {
            eph,
            ura_index: 0,
            tgd2_s: None,
        };
        if last.as_ref() != Some(&decoded) {
            *last = Some(decoded.clone());
            out.push(NavEvent::Ephemeris(Box::new(decoded)));
        }
    }
}

/// One decoded subframe (CNAV: message; F/NAV, I/NAV: page): where it starts in the stream
/// and what time it carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubframeInfo {
    /// Index (counted from the first bit or symbol fed, from 0, on across restarts) of the
    /// subframe's first bit (CNAV: the message's first symbol; F/NAV: the first sync
    /// symbol; I/NAV: the first sync symbol of the even part).
    pub start_bit: u64,
    /// Subframe ID (GPS, from the HOW), FraID (BeiDou), 1-5; message type (CNAV); page
    /// type (F/NAV); word type (I/NAV).
    pub id: u8,
    /// Page number when the subframe is paged: GPS subframes 4/5 SV ID (data ID
    /// stripped, e.g. 56 for page 18), BeiDou D1 subframes 4/5 and D2 subframes 1, 2, 5
    /// Pnum; `None` otherwise.
    pub page: Option<u8>,
    /// Full week number if known (GPS: from subframe 1, resolved with the reference week;
    /// BeiDou: BDT week from D1 subframe 1 or D2 subframe 1 page 1; CNAV: GPS week from
    /// a type 10; F/NAV: GST week from a page type 1-3, I/NAV: from a word type 0 or 5,
    /// moved on where TOW wraps).
    pub week: Option<u32>,
    /// Time of week (s, system time) of the leading edge of the subframe's first bit.
    /// GPS: HOW TOW count x 6 s - 6 s (the count refers to the next subframe,
    /// IS-GPS-200 20.3.3.2). BeiDou D1: SOW; D2: SOW of the frame + 0.6 s x (FraID - 1).
    /// CNAV: message TOW count x 6 s - 6 s (IS-GPS-705J 20.3.3). F/NAV: the page's TOW
    /// (Galileo OS SIS ICD §5.1.2), or for pages without one the last TOW plus 10 s a page;
    /// I/NAV likewise, 2 s a page.
    pub tow_s: f64,
    /// Whether the stream was inverted in this subframe (preamble or sync pattern
    /// received complemented).
    pub inverted: bool,
    /// Bits corrected by the BCH decoder (BeiDou; 0 for GPS).
    pub corrected_bits: u32,
}

/// What a decoder reports while it is fed bits.
#[derive(Debug, Clone, PartialEq)]
pub enum NavEvent {
    /// Subframe synchronisation gained: a subframe starts at bit `start_bit`.
    SyncAcquired {
        /// Index of the first bit of the subframe.
        start_bit: u64,
        /// Whether the stream is inverted.
        inverted: bool,
    },
    /// Subframe synchronisation lost (preambles missing or repeated failures); the
    /// decoder searches again.
    SyncLost {
        /// Index of the expected subframe start where it gave up.
        at_bit: u64,
    },
    /// A subframe passed its checks and was decoded.
    Subframe(SubframeInfo),
    /// A subframe failed its checks and was dropped: GPS word parity (bit k of
    /// `words` set for word k + 1), BeiDou header inconsistent with the stream time,
    /// or a missing preamble at an expected subframe start (`words` = 0).
    SubframeDropped {
        /// Index of the subframe's first bit.
        start_bit: u64,
        /// Failed words (bit k = word k + 1).
        words: u16,
    },
    /// A complete, consistent ephemeris and clock set that differs from the previous one.
    Ephemeris(Box<DecodedEphemeris>),
    /// GPS subframe 4 page 18: Klobuchar coefficients and UTC parameters (emitted when they
    /// change; needs the week from subframe 1 to resolve the 8-bit weeks).
    GpsIonoUtc {
        /// Klobuchar alpha/beta.
        iono: IonoParams,
        /// UTC parameters with full week numbers.
        utc: UtcParams,
    },
    /// BeiDou Klobuchar coefficients (D1 subframe 1, D2 subframe 1 page 2), when they change.
    BdsIono(Klobuchar),
}

/// Running counters of a decoder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DecodeStats {
    /// Bits (CNAV, F/NAV, I/NAV: symbols) fed so far.
    pub bits: u64,
    /// Subframes (CNAV messages, F/NAV and I/NAV pages) decoded.
    pub subframes: u64,
    /// Subframes dropped (parity, header, missing preamble; CNAV, F/NAV, I/NAV: CRC).
    pub dropped_subframes: u64,
    /// GPS words that failed parity.
    pub parity_failed_words: u64,
    /// Bits corrected by BCH (BeiDou).
    pub corrected_bits: u64,
    /// Times synchronisation was lost.
    pub sync_losses: u64,
}

/// Why a decoder cannot be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NavDecodeError {
    /// The satellite does not broadcast the message this decoder reads.
    #[error("{sat}: {what}")]
    WrongSatellite {
        /// The satellite.
        sat: String,
        /// What was expected.
        what: &'static str,
    },
}

/// A navigation-message decoder fed with soft bits.
pub trait NavDecoder: Send {
    /// Feed the next bits or symbols (soft values, sign = bit, see the module notes);
    /// returns what was decoded on the way, in stream order.
    fn feed(&mut self, soft_bits: &[f32]) -> Vec<NavEvent>;
    /// The bit stream was interrupted (e.g. the tracking loop lost lock): forget the
    /// buffered bits and the synchronisation, keep what was decoded. Bit indices keep
    /// counting from the bits fed so far.
    fn restart(&mut self);
    /// Counters so far.
    fn stats(&self) -> DecodeStats;
    /// The satellite whose message this is.
    fn satellite(&self) -> SatId;
}

/// The decoder for `sat`'s message on `signal`: GPS L5 CNAV for GPS L5, GPS LNAV for the
/// other GPS signals, Galileo F/NAV for E5a and I/NAV for E1, BeiDou B-CNAV2 for B2a,
/// B-CNAV1 for B1C (locked on the stream's first symbol, a frame start) and
/// D1/D2 for the other BeiDou signals (by PRN: D2 for the GEO PRNs 1-5 and 59-63). GPS LNAV weeks are resolved near
/// [`DEFAULT_GPS_REFERENCE_WEEK`].
pub fn decoder_for(sat: SatId, signal: Signal) -> Result<Box<dyn NavDecoder>, NavDecodeError> {
    let wrong = |what| {
        Err(NavDecodeError::WrongSatellite {
            sat: sat.to_string(),
            what,
        })
    };
    if signal.system() != sat.system {
        return wrong("a satellite of the system that transmits the signal");
    }
    Ok(match (sat.system, signal) {
        (System::Gps, Signal::GpsL5) => Box::new(CnavDecoder::new(sat)?),
        (System::Gps, _) => Box::new(GpsLnavDecoder::new(sat)?),
        (System::Beidou, Signal::BdsB2a) => Box::new(BdsCnav2Decoder::new(sat)?),
        // The channel hands on B1C symbols from a frame start (the pilot's secondary code).
        (System::Beidou, Signal::BdsB1C) => Box::new(BdsCnav1Decoder::aligned(sat)?),
        (System::Beidou, _) => Box::new(BdsDecoder::new(sat)?),
        (System::Galileo, Signal::GalE5a) => Box::new(FnavDecoder::new(sat)?),
        (System::Galileo, Signal::GalE1) => Box::new(InavDecoder::new(sat)?),
        (System::Galileo, _) => {
            return wrong("Galileo E5a (F/NAV) or E1 (I/NAV); no other Galileo message is decoded");
        }
    })
}

/// Hard decision: negative soft value is logic 1.
fn hard_bit(soft: f32) -> u8 {
    u8::from(soft < 0.0)
}

/// Seconds per week.
const WEEK_S: f64 = skyforge_orbits::time::SECONDS_PER_WEEK as f64;

/// The week of a reference time given as seconds of week `ref_sow` relative to the week
/// `week` in which another time (at `tx_sow`) lies: the reference is at most half a week
/// away from the transmission (IS-GPS-200 20.3.3.4.3 note on toe/toc near week ends;
/// the same rule for BDT).
fn week_of_reference(week: u32, tx_sow: f64, ref_sow: f64) -> u32 {
    let d = ref_sow - tx_sow;
    if d > WEEK_S / 2.0 {
        week.saturating_sub(1)
    } else if d < -WEEK_S / 2.0 {
        week + 1
    } else {
        week
    }
}

/// Whether a subframe starting at stream bit `start_bit` with time of week `tow_s` fits
/// the last accepted one (`anchor`: its start bit and time of week) given the bit period:
/// the stream time between them must equal the difference of the broadcast times
/// (modulo one week). Without an anchor anything fits.
fn time_consistent(anchor: Option<(u64, f64)>, start_bit: u64, tow_s: f64, bit_s: f64) -> bool {
    anchor.is_none_or(|(bit, tow)| {
        let t = tow + start_bit.saturating_sub(bit) as f64 * bit_s;
        ((t - tow_s + WEEK_S / 2.0).rem_euclid(WEEK_S) - WEEK_S / 2.0).abs() < 1e-6
    })
}

/// Two's-complement value of the `len` low bits of `v`.
fn sign_extend(v: u64, len: u32) -> i64 {
    let shift = 64 - len;
    ((v << shift) as i64) >> shift
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_week_follows_the_nearest_crossing() {
        assert_eq!(week_of_reference(2000, 604_000.0, 3600.0), 2001);
        assert_eq!(week_of_reference(2000, 100.0, 603_000.0), 1999);
        assert_eq!(week_of_reference(2000, 300_000.0, 307_200.0), 2000);
    }

    #[test]
    fn decoder_for_picks_the_message_of_the_system_and_signal() {
        let cases = [
            (SatId::gps(5), Signal::GpsL1Ca),
            (SatId::gps(5), Signal::GpsL5),
            (SatId::beidou(1), Signal::BdsB1I),
            (SatId::beidou(19), Signal::BdsB1I),
            (SatId::galileo(11), Signal::GalE5a),
            (SatId::galileo(11), Signal::GalE1),
            (SatId::beidou(19), Signal::BdsB2a),
            (SatId::beidou(30), Signal::BdsB1C),
        ];
        for (sat, signal) in cases {
            let dec = decoder_for(sat, signal).map(|d| d.satellite());
            assert_eq!(dec, Ok(sat), "{signal:?}");
        }
        assert!(decoder_for(SatId::gps(40), Signal::GpsL1Ca).is_err());
        assert!(decoder_for(SatId::gps(40), Signal::GpsL5).is_err());
        assert!(decoder_for(SatId::galileo(37), Signal::GalE1).is_err());
        assert!(decoder_for(SatId::galileo(11), Signal::GpsL5).is_err());
        assert!(decoder_for(SatId::gps(5), Signal::GalE5a).is_err());
    }

    #[test]
    fn stream_time_must_match_broadcast_time() {
        let anchor = Some((1000, 604_794.0));
        assert!(time_consistent(None, 5, 12.0, 0.02));
        assert!(time_consistent(anchor, 1300, 0.0, 0.02));
        assert!(time_consistent(anchor, 1600, 6.0, 0.02));
        assert!(!time_consistent(anchor, 1600, 0.0, 0.02));
        assert!(!time_consistent(anchor, 1301, 0.0, 0.02));
    }

    #[test]
    fn sign_extension_and_hard_bits() {
        assert_eq!(sign_extend(0xFF, 8), -1);
        assert_eq!(sign_extend(0x7F, 8), 127);
        assert_eq!(sign_extend(0x80, 8), -128);
        assert_eq!(sign_extend(0x3F_FFFF, 22), -1);
        assert_eq!((hard_bit(0.3), hard_bit(-0.3)), (0, 1));
    }
}
