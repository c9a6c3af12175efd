//! GPS LNAV navigation message (L1 C/A, 50 bps), IS-GPS-200 appendix II, sections
//! 20.3.2-20.3.5.
//!
//! What a real receiver decodes: 1500-bit frames of five 300-bit subframes, each of ten
//! 30-bit words (24 data bits, 6 parity bits, table 20-XIV). Subframe 1 carries the week
//! number, health, URA, TGD and clock (table 20-I); subframes 2 and 3 the ephemeris
//! (table 20-II, scales table 20-III); subframes 4 and 5 cycle through 25 pages each
//! (table 20-V): almanac (table 20-VI), health, ionosphere and UTC (table 20-X), A-S flags
//! and SV configurations, NMCT, special message, reserved pages.
//!
//! The flow is:
//! 1. [`Almanac::from_ephemerides`] once per scenario (derived from the same ephemerides
//!    the satellites broadcast, at a reference time toa on the 4096 s grid);
//! 2. [`LnavEncoder::new`] per satellite, which quantises the ephemeris as the ICD says;
//! 3. [`LnavEncoder::broadcast_ephemeris`] is the orbit and clock the signal must follow
//!    (the quantised values, back in SI units), so that what the receiver decodes is
//!    exactly the truth;
//! 4. [`LnavEncoder::subframe`], [`LnavEncoder::bits`] or [`LnavEncoder::bit`] for the
//!    synthesiser.
//!
//! Time is counted in subframes and bits since the GPS epoch (1980-01-06 00:00:00 GPST):
//! subframe `k` is transmitted (satellite time) from `6 k` s to `6 (k + 1)` s and data bit
//! `b` from `0.02 b` s to `0.02 (b + 1)` s, so bit edges fall on every 20th C/A code
//! period boundary counted from the week start (IS-GPS-200 20.3.2: 50 bps data
//! synchronous with the C/A code epochs, subframes starting on multiples of 6 s of GPS
//! time as the HOW TOW count implies). A bit value `1` is a logic one of the data
//! stream; with the usual BPSK mapping it multiplies the code by -1.
//!
//! Quantisation residuals (measured by the tests in this module and in
//! `tests/real_data_lnav.rs`): see [`LnavEncoder::broadcast_ephemeris`].

mod almanac;
mod encoder;
mod ephemeris;
#[cfg(any(test, feature = "test-support"))]
pub mod fixtures;
mod iono_utc;
mod pages;
pub mod parity;
mod scale;
mod words;

#[cfg(test)]
mod tests;

pub use almanac::Almanac;
pub use encoder::LnavEncoder;
pub use iono_utc::{IonoParams, UtcParams};

use hifitime::{Duration, Epoch};

/// The value of pi the ICD uses to convert semicircles to radians (IS-GPS-200 table
/// 20-IV notes: "pi = 3.1415926535898"); receivers decode with this value, so it is used
/// on purpose instead of `std::f64::consts::PI` (they differ by 7e-15).
#[allow(clippy::approx_constant)]
pub const GPS_PI: f64 = 3.141_592_653_589_8;
/// Bits per 30-bit word.
pub const BITS_PER_WORD: usize = 30;
/// Words per subframe.
pub const WORDS_PER_SUBFRAME: usize = 10;
/// Bits per subframe (6 s at 50 bps).
pub const BITS_PER_SUBFRAME: usize = BITS_PER_WORD * WORDS_PER_SUBFRAME;
/// Duration of one data bit (s): 20 C/A code periods.
pub const BIT_PERIOD_S: f64 = 0.02;
/// Duration of one subframe (s).
pub const SUBFRAME_PERIOD_S: f64 = 6.0;
/// Subframes per GPS week (604800 s / 6 s).
pub const SUBFRAMES_PER_WEEK: u64 = 100_800;
/// The TLM word preamble 10001011 (IS-GPS-200 20.3.3.1).
pub const PREAMBLE: u32 = 0x8B;

/// Nanoseconds in one second.
const NS_PER_S: i128 = 1_000_000_000;
/// Seconds in one week.
const WEEK_S: i64 = skyforge_orbits::time::SECONDS_PER_WEEK as i64;

/// Error building the LNAV message.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LnavError {
    /// LNAV carries GPS satellites with PRN 1-32 only.
    #[error("{sat}: LNAV carries GPS PRN 1-32 only")]
    NotGps {
        /// The satellite (e.g. `C19`, `G40`).
        sat: String,
    },
    /// A parameter does not fit its ICD field.
    #[error(
        "{what} = {value:e} {unit} does not fit the LNAV field (allowed {min:e} to {max:e} {unit}, IS-GPS-200 {table})"
    )]
    OutOfRange {
        /// Satellite and parameter, e.g. `G05 af0`.
        what: String,
        /// The value in ICD units.
        value: f64,
        /// Smallest representable value.
        min: f64,
        /// Largest representable value.
        max: f64,
        /// ICD unit of the value.
        unit: &'static str,
        /// The ICD table that defines the field.
        table: &'static str,
    },
    /// An integer parameter is outside its allowed set.
    #[error("{what} = {value} is not allowed ({allowed})")]
    BadValue {
        /// Satellite and parameter.
        what: String,
        /// The value given.
        value: i64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// An epoch before the GPS epoch cannot be expressed in LNAV time.
    #[error("epoch {epoch} is before the GPS epoch 1980-01-06 00:00:00 GPST")]
    BeforeGpsEpoch {
        /// The epoch.
        epoch: String,
    },
}

/// Nanoseconds of GPS time since the GPS epoch.
fn gps_ns(epoch: Epoch) -> i128 {
    epoch.to_gpst_duration().total_nanoseconds()
}

/// The epoch `ns` nanoseconds of GPS time after the GPS epoch.
fn epoch_from_gps_ns(ns: i128) -> Epoch {
    Epoch::from_gpst_duration(Duration::from_total_nanoseconds(ns))
}

/// Full GPS week and seconds of week of a whole number of GPS seconds since the epoch.
fn week_and_sow(gps_s: i64) -> (i64, i64) {
    (gps_s.div_euclid(WEEK_S), gps_s.rem_euclid(WEEK_S))
}

/// Index of the subframe being transmitted at `epoch` (GPS time, satellite time scale),
/// counted from the GPS epoch: `floor(t / 6 s)`.
pub fn subframe_index_at(epoch: Epoch) -> Result<u64, LnavError> {
    let ns = gps_ns(epoch);
    if ns < 0 {
        return Err(LnavError::BeforeGpsEpoch {
            epoch: epoch.to_string(),
        });
    }
    Ok((ns / (6 * NS_PER_S)) as u64)
}

/// Start epoch (GPST) of subframe `index` (see [`subframe_index_at`]).
pub fn subframe_start(index: u64) -> Epoch {
    epoch_from_gps_ns(i128::from(index) * 6 * NS_PER_S)
}
