//! BeiDou D1 (MEO/IGSO) and D2 (GEO) navigation messages on B1I, as a real receiver
//! decodes them (BDS-SIS-ICD-B1I-3.0, February 2019, §5).
//!
//! [`BdsNavEncoder`] turns one broadcast ephemeris (plus the Klobuchar parameters and the
//! constellation, for the almanac) into the data bits of the satellite's message:
//! - D1 (PRNs 6-58): 50 bit/s, 5 subframes of 300 bits per 30 s frame, subframes 4/5 in
//!   24 pages (12 min superframe). The synthesiser applies the 20-bit NH secondary code.
//! - D2 (PRNs 1-5, 59-63): 500 bit/s, 5 subframes of 300 bits per 3 s frame, the
//!   ephemeris in 10 pages of subframe 1, subframe 5 in 120 pages (6 min superframe).
//!   No secondary code.
//!
//! Every word is BCH(15,11)-encoded and words 2-10 are interleaved (`bch` module notes).
//! Subframe contents, page schedules and what each placeholder holds are described in
//! the `d1` and `d2` module notes, almanac generation in the `almanac` notes.
//!
//! The orbit the signal follows must be the one the message describes:
//! [`BdsNavEncoder::broadcast_ephemeris`] returns the quantised parameters in SI units;
//! the synthesiser should propagate that, not the input. An input whose toe or toc is not
//! a multiple of 8 s is first re-expressed on the grid (exact, see the `reexpress` notes).
//!
//! Verification: the layouts are checked bit for bit against subframes broadcast by C06
//! (D1) and C01 (D2) in BDT week 810 (GNSSTk test vectors, with their decoded values),
//! through an independent decoder that lives in the tests.

mod almanac;
mod bch;
mod d1;
mod d2;
mod info;
mod pages;
mod quant;
#[cfg(test)]
mod real_words;
mod reexpress;
#[cfg(test)]
mod test_decoder;
#[cfg(test)]
mod tests;

use almanac::{ALMANAC_PRNS, Almanac, is_geo_prn};
use hifitime::Epoch;
use pages::{Content, UtcFields};
use quant::{EphFields, IonoFields, Quantiser};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, OrbitClass, System};
use skyforge_orbits::time::{bdt_week_sow, epoch_from_bdt};

/// Seconds per week.
const WEEK_S: u64 = skyforge_orbits::time::SECONDS_PER_WEEK as u64;
/// Bits per subframe.
const SUBFRAME_BITS: u64 = 300;
/// TAI - BDT (s): BDT was UTC on 2006-01-01, when TAI - UTC was 33 s (§3.3).
const TAI_MINUS_BDT_S: f64 = 33.0;

/// Which of the two B1I navigation messages a satellite broadcasts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BdsNavFormat {
    /// MEO/IGSO satellites: 50 bit/s, NH secondary code.
    D1,
    /// GEO satellites: 500 bit/s.
    D2,
}

impl BdsNavFormat {
    /// The message a PRN broadcasts: D2 for the GEO PRNs 1-5 and 59-63, D1 otherwise
    /// (the rule receivers use to pick the decoder).
    pub fn for_prn(prn: u8) -> Self {
        if is_geo_prn(prn) { Self::D2 } else { Self::D1 }
    }

    /// Data bit duration (s): 20 ms (D1), 2 ms (D2).
    pub fn bit_period_s(self) -> f64 {
        self.subframe_ms() as f64 * 1e-3 / SUBFRAME_BITS as f64
    }

    /// Subframe duration (s): 6 s (D1), 0.6 s (D2).
    pub fn subframe_period_s(self) -> f64 {
        self.subframe_ms() as f64 * 1e-3
    }

    fn subframe_ms(self) -> u64 {
        match self {
            Self::D1 => d1::SUBFRAME_MS,
            Self::D2 => d2::SUBFRAME_MS,
        }
    }
}

/// Klobuchar ionosphere parameters as broadcast (BDS-SIS-ICD-B1I-3.0 §5.2.4):
/// alpha_n in s/semicircle^n, beta_n in s/semicircle^n.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Klobuchar {
    pub alpha: [f64; 4],
    pub beta: [f64; 4],
}

/// Message fields that [`BroadcastEphemeris`] does not carry. Default: URAI 0, TGD2 0.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BdsExtraFields {
    /// URA index (4 bits).
    pub urai: u8,
    /// TGD2, the B2I group delay (s).
    pub tgd2_s: f64,
}

/// Why a message cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BdsNavError {
    /// The ephemeris is not a BeiDou one.
    #[error("{sat}: not a BeiDou satellite; D1/D2 messages are BeiDou only")]
    NotBeidou { sat: String },
    /// The orbit class does not match the message the PRN broadcasts.
    #[error(
        "{sat}: orbit class {class:?} does not match the {format:?} message this PRN \
         broadcasts (GEO algorithm and D2 for PRNs 1-5 and 59-63, standard and D1 otherwise)"
    )]
    ClassMismatch {
        sat: String,
        class: OrbitClass,
        format: BdsNavFormat,
    },
    /// A parameter does not fit its field.
    #[error(
        "{sat}: {field} = {value:e} is outside the range the message carries [{min:e}, {max:e}]"
    )]
    FieldOutOfRange {
        sat: String,
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    /// A GEO ephemeris whose toe is off the 8 s grid and cannot be re-expressed exactly.
    #[error(
        "{sat}: toe (BDT seconds of week {toe_sow}) is not a multiple of 8 s and this GEO set \
         has non-zero harmonic corrections, IDOT or Omega dot, so it cannot be moved onto the \
         grid exactly; give a toe that is a multiple of 8 s"
    )]
    ToeOffGrid { sat: String, toe_sow: f64 },
}

/// The data bits of one satellite's D1 or D2 message.
///
/// Subframes are numbered from the start of BDT week [`Self::week`]: subframe `k` starts
/// `k` subframe periods after it (it may lie in a later week; WN and SOW follow).
#[derive(Debug, Clone, PartialEq)]
pub struct BdsNavEncoder {
    format: BdsNavFormat,
    week: u32,
    /// The input with toe/toc on the 8 s grid.
    grid: BroadcastEphemeris,
    eph: EphFields,
    iono: IonoFields,
    almanac: Almanac,
    utc: UtcFields,
}

impl BdsNavEncoder {
    /// An encoder for `eph`'s satellite, with subframe 0 at the start of BDT week `week`.
    /// `almanac_set` is the constellation whose almanac the message carries (any systems
    /// and epochs; the BeiDou PRNs 1-30 with toe nearest to toa are used). URAI and TGD2
    /// are zero ([`Self::with_extra_fields`] sets them).
    pub fn new(
        eph: &BroadcastEphemeris,
        iono: &Klobuchar,
        almanac_set: &[BroadcastEphemeris],
        week: u32,
    ) -> Result<Self, BdsNavError> {
        Self::with_extra_fields(eph, iono, almanac_set, week, &BdsExtraFields::default())
    }

    /// As [`Self::new`], with URAI and TGD2.
    pub fn with_extra_fields(
        eph: &BroadcastEphemeris,
        iono: &Klobuchar,
        almanac_set: &[BroadcastEphemeris],
        week: u32,
        extra: &BdsExtraFields,
    ) -> Result<Self, BdsNavError> {
        let sat = eph.sat.to_string();
        if eph.sat.system != System::Beidou {
            return Err(BdsNavError::NotBeidou { sat });
        }
        let format = BdsNavFormat::for_prn(eph.sat.prn);
        let geo_class = eph.class == OrbitClass::BeidouGeo;
        if geo_class != (format == BdsNavFormat::D2) {
            return Err(BdsNavError::ClassMismatch {
                sat,
                class: eph.class,
                format,
            });
        }
        let grid = reexpress::onto_grid(eph)?;
        let q = Quantiser { sat: &sat };
        Ok(Self {
            format,
            week,
            eph: EphFields::quantise(&grid, extra, q)?,
            iono: IonoFields::quantise(iono, q)?,
            almanac: Almanac::build(almanac_set, grid.toe),
            utc: utc_fields(grid.toe),
            grid,
        })
    }

    /// The message this satellite broadcasts.
    pub fn format(&self) -> BdsNavFormat {
        self.format
    }

    /// BDT week of subframe 0.
    pub fn week(&self) -> u32 {
        self.week
    }

    /// Start of BDT week [`Self::week`], where subframe 0 and bit 0 start.
    pub fn week_start(&self) -> Epoch {
        epoch_from_bdt(self.week, 0.0)
    }

    /// The ephemeris the message describes, in SI units: the quantised fields converted
    /// back (toe and toc on the 8 s grid; health = SatH1; TGD = TGD1; iode = AODE, where
    /// an input AODE of 0 is broadcast as 1, see the `quant` notes). This is the orbit and
    /// clock the signal must follow.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        self.eph.to_ephemeris(&self.grid)
    }

    /// PRNs (1-30) whose almanac the message carries.
    pub fn almanac_prns(&self) -> Vec<u8> {
        (1..=ALMANAC_PRNS)
            .filter(|&p| self.almanac.sats[usize::from(p - 1)].is_some())
            .collect()
    }

    /// The ten 30-bit words of subframe `index` (BCH-encoded and interleaved, bit 29 sent
    /// first).
    pub fn subframe(&self, index: u64) -> [u32; 10] {
        let start_ms = index * self.format.subframe_ms();
        let week_ms = WEEK_S * 1000;
        // WN is carried on 13 bits.
        let wn = ((u64::from(self.week) + start_ms / week_ms) % 8192) as u32;
        let sow_s = (start_ms % week_ms) / 1000;
        let content = Content {
            eph: &self.eph,
            iono: &self.iono,
            almanac: &self.almanac,
            utc: &self.utc,
        };
        let info = match self.format {
            BdsNavFormat::D1 => d1::subframe(&content, index, wn, sow_s as u32),
            BdsNavFormat::D2 => {
                let frame_sow = sow_s / d2::FRAME_S * d2::FRAME_S;
                d2::subframe(&content, index, wn, frame_sow as u32)
            }
        };
        info.encode()
    }

    /// Index of the data bit being sent at `t` (bit 0 starts at [`Self::week_start`]);
    /// `None` before it.
    pub fn bit_index_at(&self, t: Epoch) -> Option<u64> {
        let ns = (t - self.week_start()).total_nanoseconds();
        let bit_ns = i128::from(self.format.subframe_ms() * 1_000_000 / SUBFRAME_BITS);
        u64::try_from(ns.div_euclid(bit_ns)).ok()
    }

    /// `count` data bits (0 or 1) from bit `first_bit` on, in transmission order.
    pub fn bits(&self, first_bit: u64, count: usize) -> Vec<u8> {
        let mut out = Vec::with_capacity(count);
        let mut n = first_bit;
        while out.len() < count {
            let index = n / SUBFRAME_BITS;
            let words = self.subframe(index);
            let first = (n % SUBFRAME_BITS) as usize;
            let take = (SUBFRAME_BITS as usize - first).min(count - out.len());
            out.extend((first..first + take).map(|b| ((words[b / 30] >> (29 - b % 30)) & 1) as u8));
            n = (index + 1) * SUBFRAME_BITS;
        }
        out
    }
}

/// UTC parameters at `t`: BDT - UTC from the leap-second table (TAI - UTC - 33 s), no
/// leap second pending (Delta t_LSF = Delta t_LS, WN_LSF = the week of `t`, DN = 0),
/// A0UTC = A1UTC = 0.
fn utc_fields(t: Epoch) -> UtcFields {
    let dt_ls = t
        .leap_seconds(true)
        .map_or(0, |tai_utc| (tai_utc - TAI_MINUS_BDT_S).round() as i64);
    UtcFields {
        dt_ls,
        dt_lsf: dt_ls,
        wn_lsf: i64::from(bdt_week_sow(t).0 % 256),
        dn: 0,
    }
}
