//! What the RINEX observation readers (versions 2 and 3) share: their error, the quantity
//! an observation code names, the check of an epoch line's time tag and the physical
//! ranges of the values.

use super::record::ObsRecord;
use hifitime::{Epoch, TimeScale};
use std::path::PathBuf;

/// Which quantity an observation code holds (RINEX 3 and 2 alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    Code,
    Phase,
    Doppler,
    Strength,
}

/// Why an observation file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ObsReadError {
    /// The file could not be read or parsed as RINEX.
    #[error("{path}: {message}")]
    Read { path: PathBuf, message: String },
    /// The file is not well formed at `line` (1-based; 0 when the whole file is at fault).
    #[error("{path}:{line}: {message}")]
    Syntax {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// The file is RINEX but not an observation file.
    #[error("{0}: not a RINEX observation file")]
    NotObservation(PathBuf),
}

/// The time tag of an epoch line as its fields say it, in the file's time scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EpochFields {
    pub year: i32,
    pub month: u8,
    pub day: u8,
    pub hour: u8,
    pub minute: u8,
    pub seconds: f64,
}

/// Years an epoch may lie in: SkyForge's time runs from the GPS epoch (1980-01-06) and
/// its scenarios end before 2100 (docs/limits.md).
const YEARS: std::ops::Range<i32> = 1980..2100;

impl EpochFields {
    /// Why the fields are no time tag: each within its calendar range (seconds below 61,
    /// which leaves room for a leap second in UTC files), the year in 1980-2099, the day
    /// one of its month's.
    pub fn check(&self) -> Result<(), String> {
        let s = self;
        let bad = |what: &str, value: String, allowed: &str| {
            Err(format!("epoch {what} {value}: allowed {allowed}"))
        };
        if !YEARS.contains(&s.year) {
            return bad("year", s.year.to_string(), "1980 to 2099");
        }
        if !(1..=12).contains(&s.month) {
            return bad("month", s.month.to_string(), "1 to 12");
        }
        if !(1..=31).contains(&s.day) {
            return bad("day", s.day.to_string(), "1 to 31");
        }
        if s.hour > 23 {
            return bad("hour", s.hour.to_string(), "0 to 23");
        }
        if s.minute > 59 {
            return bad("minute", s.minute.to_string(), "0 to 59");
        }
        if !(0.0..61.0).contains(&s.seconds) {
            let shown = match s.seconds.abs() < 1e9 {
                true => s.seconds.to_string(),
                false => format!("{:e}", s.seconds),
            };
            return bad("seconds", shown, "0 to below 61");
        }
        Epoch::maybe_from_gregorian(s.year, s.month, s.day, 0, 0, 0, 0, TimeScale::GPST)
            .map(|_| ())
            .map_err(|e| format!("epoch date {}-{}-{}: {e}", s.year, s.month, s.day))
    }

    /// The whole seconds and the nanoseconds of the F11.7 seconds (100 ns resolution).
    pub fn whole_and_ns(&self) -> (u8, u32) {
        let ns = (self.seconds.fract() * 1e7).round() as u32 * 100;
        (self.seconds.trunc() as u8, ns)
    }

    /// The epoch in `scale` (the fields must have passed [`Self::check`]).
    pub fn epoch(&self, scale: TimeScale) -> Result<Epoch, String> {
        let s = self;
        let (whole, ns) = s.whole_and_ns();
        let start =
            Epoch::maybe_from_gregorian(s.year, s.month, s.day, s.hour, s.minute, 0, 0, scale)
                .map_err(|e| format!("epoch date: {e}"))?;
        Ok(start
            + hifitime::Duration::from_seconds(f64::from(whole))
            + hifitime::Duration::from_total_nanoseconds(i128::from(ns)))
    }
}

/// The physical range of a pseudorange (m): from the Earth's surface or an orbit within
/// SkyForge's limits (apogee radius up to 100 000 km, docs/limits.md) to a GNSS satellite
/// (MEO 19 100-23 200 km up, GEO/IGSO 35 800 km) the range lies between about 1.9e7 and
/// 1.3e8 m, but a receiver that does not steer its clock adds c times its offset, which
/// can be a good part of a second (GNSS-SDR 0.0.17 writes BeiDou pseudoranges 3.5e7 m
/// below the range, seen in the interoperability tier). A magnitude of 1e9 m (3.3
/// light-seconds) bounds both; beyond it no satellite is measured.
pub const PSEUDORANGE_RANGE_M: std::ops::RangeInclusive<f64> = -1e9..=1e9;
/// Largest carrier phase magnitude (cycles): what the RINEX F14.3 field can hold
/// (9 999 999 999.999; RINEX 3.04 table A3). Phase has an arbitrary start, so the field's
/// width is its only bound.
pub const PHASE_MAX_CYCLES: f64 = 1e10;
/// Largest Doppler magnitude (Hz): the receiver drops a channel whose carrier Doppler runs
/// past 100 kHz as diverged; a LEO sees at most about 45 kHz at L1 (8.5 km/s of range
/// rate).
pub const DOPPLER_MAX_HZ: f64 = 1e5;

/// Why `rec` holds no physical observation: a pseudorange outside
/// [`PSEUDORANGE_RANGE_M`], a phase beyond [`PHASE_MAX_CYCLES`], a Doppler beyond
/// [`DOPPLER_MAX_HZ`], or a signal strength that is not a finite number.
pub(crate) fn check_physical(rec: &ObsRecord) -> Result<(), String> {
    let what = |quantity: &str, v: f64, allowed: String| {
        Err(format!(
            "{} {} {quantity} {v:e}: allowed {allowed}",
            rec.sat, rec.signal
        ))
    };
    if let Some(p) = rec
        .pseudorange_m
        .filter(|p| !PSEUDORANGE_RANGE_M.contains(p))
    {
        let (lo, hi) = PSEUDORANGE_RANGE_M.into_inner();
        return what("pseudorange (m)", p, format!("{lo:e} to {hi:e} m"));
    }
    if let Some(l) = rec
        .carrier_phase_cycles
        .filter(|l| l.is_nan() || l.abs() >= PHASE_MAX_CYCLES)
    {
        return what(
            "carrier phase (cycles)",
            l,
            format!("magnitude below {PHASE_MAX_CYCLES:e} cycles"),
        );
    }
    if let Some(d) = rec
        .doppler_hz
        .filter(|d| d.is_nan() || d.abs() > DOPPLER_MAX_HZ)
    {
        return what(
            "Doppler (Hz)",
            d,
            format!("magnitude up to {DOPPLER_MAX_HZ:e} Hz"),
        );
    }
    if let Some(s) = rec.cn0_dbhz.filter(|s| !s.is_finite()) {
        return what("signal strength", s, "a finite number".into());
    }
    Ok(())
}

/// The name a `MARKER NAME` header line gives (columns 1-60), `None` when blank.
pub(crate) fn marker_name(line: &str) -> Option<String> {
    let name = line.get(..60).unwrap_or("").trim();
    (!name.is_empty()).then(|| name.to_string())
}
