//! The LNAV data stream of one satellite: subframes 1-5 with TLM, HOW and parity.

use super::almanac::Almanac;
use super::ephemeris::RawEphemeris;
use super::iono_utc::{IonoParams, RawIono, RawUtc, UtcParams};
use super::pages::{self, PAGES};
use super::words::DataWords;
use super::{
    BITS_PER_SUBFRAME, BITS_PER_WORD, LnavError, PREAMBLE, SUBFRAMES_PER_WEEK, WORDS_PER_SUBFRAME,
};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Anti-spoof flag of the HOW: A-S on, as on the real constellation (IS-GPS-200 20.3.3.2).
const ANTI_SPOOF_ON: u32 = 1;

/// The LNAV message of one GPS satellite (IS-GPS-200 20.3.2-20.3.5).
///
/// Subframe `k` (counted from the GPS epoch, see [`super::subframe_index_at`]) has
/// subframe ID `k mod 5 + 1` and, for IDs 4 and 5, page `(k' / 5) mod 25 + 1` where `k'`
/// counts subframes from the start of the week (the page cycle restarts with page 1 at
/// each week start, IS-GPS-200 20.3.4.1); a 25-page cycle lasts 12.5 min. Within a word,
/// bit 29 of the `u32` is D1 (transmitted first) and bit 0 is D30.
#[derive(Debug, Clone, PartialEq)]
pub struct LnavEncoder {
    broadcast: BroadcastEphemeris,
    sf123: [DataWords; 3],
    sf4: [DataWords; PAGES],
    sf5: [DataWords; PAGES],
    iono: IonoParams,
    utc: UtcParams,
}

impl LnavEncoder {
    /// The message of the satellite of `eph`, with the almanac, ionosphere and UTC pages
    /// of `almanac`, `iono`, `utc` and URA index `ura_index` (0-15, IS-GPS-200
    /// 20.3.3.3.1.3).
    ///
    /// toe and toc are moved to the nearest multiple of 16 s if needed (the message can
    /// only carry such times): the elements and the clock polynomial are re-expressed at
    /// the new epochs, which leaves the user-algorithm orbit and clock unchanged (exactly,
    /// up to f64 rounding); then every parameter is rounded to its field (table 20-III).
    /// Errors: not a GPS PRN 1-32, a parameter outside its field, IODE not the 8 LSBs of
    /// IODC, URA index > 15.
    pub fn new(
        eph: &BroadcastEphemeris,
        almanac: &Almanac,
        iono: &IonoParams,
        utc: &UtcParams,
        ura_index: u8,
    ) -> Result<Self, LnavError> {
        let raw = RawEphemeris::new(eph)?;
        if ura_index > 15 {
            return Err(LnavError::BadValue {
                what: format!("{} URA index", eph.sat),
                value: i64::from(ura_index),
                allowed: "0-15",
            });
        }
        let raw_iono = RawIono::new(iono)?;
        let raw_utc = RawUtc::new(utc)?;
        Ok(Self {
            broadcast: raw.si_ephemeris(eph),
            sf123: [
                raw.subframe1(u32::from(ura_index)),
                raw.subframe2(),
                raw.subframe3(),
            ],
            sf4: pages::subframe4(almanac, &raw_iono, &raw_utc),
            sf5: pages::subframe5(almanac),
            iono: raw_iono.to_params(),
            utc: raw_utc.to_params(),
        })
    }

    /// The transmitting satellite.
    pub fn satellite(&self) -> SatId {
        self.broadcast.sat
    }

    /// The ephemeris and clock exactly as broadcast (quantised, back in SI units): the
    /// orbit the signal must follow so that the decoded message describes the truth.
    ///
    /// Quantisation residuals, position of this ephemeris minus the input one (both
    /// through the orbits crate's user algorithm), measured by the tests:
    /// - nominal 31-satellite constellation with toe off the 16-s grid (re-expressed),
    ///   every 60 s over 4 h from toe: max 3D 5.0 cm (`residuals_nominal_constellation`,
    ///   asserted < 8 cm); its clock is zero and stays exactly zero;
    /// - real broadcast ephemerides (ESBC00DNK 2020-06-25, all 257 GPS sets), every 5 min
    ///   over toe +-2 h: max 3D 0.033 mm, clock 5e-17 s (`tests/real_data_lnav.rs`,
    ///   asserted < 1 mm and < 1e-14 s). They were decoded from LNAV, so they already lie
    ///   on the ICD grid (within 3.4e-4 LSB, the 13 digits RINEX prints).
    ///
    /// For a general ephemeris each field is off by at most half an LSB: M0, OMEGA0, i0,
    /// omega by 2^-32 semicircles (1.9 cm at GPS radius), sqrt A by 2^-20 m^1/2 (1 cm
    /// radial, then along-track through the mean motion, 1.5 cm after 2 h), delta n,
    /// OMEGADOT and IDOT by 2^-44 semicircles/s (up to 1.7 cm per hour each), af0 by 2^-32 s
    /// (7 cm of range), af1 by 2^-44 s/s (12 cm of range after 2 h), TGD by 2^-32 s.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        self.broadcast.clone()
    }

    /// The Klobuchar coefficients as broadcast on page 18 (quantised).
    pub fn iono(&self) -> IonoParams {
        self.iono
    }

    /// The UTC parameters as broadcast on page 18 (quantised).
    pub fn utc(&self) -> UtcParams {
        self.utc
    }

    /// The ten transmitted words of subframe `index` (counted from the GPS epoch): TLM
    /// (preamble 10001011, TLM message and integrity flag 0), HOW (TOW count of the next
    /// subframe's start in 6-s units, 17 bits, alert 0, A-S on, subframe ID, t bits),
    /// words 3-10 of the subframe or page, parity per table 20-XIV. Words 2 and 10 end
    /// with D29 = D30 = 0, so the parity chain restarts at every subframe.
    pub fn subframe(&self, index: u64) -> [u32; WORDS_PER_SUBFRAME] {
        let week = index / SUBFRAMES_PER_WEEK;
        let in_week = index % SUBFRAMES_PER_WEEK;
        let id = (in_week % 5) as usize + 1;
        let page = ((in_week / 5) % PAGES as u64) as usize;
        let mut d = match id {
            1 => {
                let mut d = self.sf123[0];
                d.put(3, 1, 10, (week % 1024) as u32);
                d
            }
            2 | 3 => self.sf123[id - 1],
            4 => self.sf4[page],
            _ => self.sf5[page],
        };
        d.put(1, 1, 8, PREAMBLE);
        d.put(1, 9, 16, 0);
        let tow_next = ((in_week + 1) % SUBFRAMES_PER_WEEK) as u32;
        d.put(2, 1, 17, tow_next);
        d.put(2, 18, 1, 0);
        d.put(2, 19, 1, ANTI_SPOOF_ON);
        d.put(2, 20, 3, id as u32);
        d.encode()
    }

    /// The transmitted bits (0 or 1, in transmission order) of `n_subframes` subframes
    /// from subframe `first_subframe` on: 300 per subframe.
    pub fn bits(&self, first_subframe: u64, n_subframes: usize) -> Vec<u8> {
        let mut out = Vec::with_capacity(n_subframes * BITS_PER_SUBFRAME);
        for k in 0..n_subframes as u64 {
            for word in self.subframe(first_subframe + k) {
                out.extend((0..BITS_PER_WORD).rev().map(|b| ((word >> b) & 1) as u8));
            }
        }
        out
    }

    /// Data bit number `bit_index` counted from the GPS epoch (transmitted from
    /// `0.02 bit_index` s to `0.02 (bit_index + 1)` s of GPS time, satellite time scale).
    pub fn bit(&self, bit_index: u64) -> u8 {
        let per_subframe = BITS_PER_SUBFRAME as u64;
        let words = self.subframe(bit_index / per_subframe);
        let in_subframe = (bit_index % per_subframe) as usize;
        let word = words[in_subframe / BITS_PER_WORD];
        ((word >> (BITS_PER_WORD - 1 - in_subframe % BITS_PER_WORD)) & 1) as u8
    }
}
