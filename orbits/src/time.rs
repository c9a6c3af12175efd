//! Time scales (GPST, BDT, UTC with leap seconds through `hifitime`) and the scenario time
//! origin. Inside hot loops time is `f64` seconds since [`TimeOrigin::start`].
//!
//! Week numbers follow the GNSS interface documents: GPS week 0 starts at
//! 1980-01-06 00:00:00 GPST (= UTC then), IS-GPS-200 section 3.3.4 and 20.3.3.3.1.1;
//! BeiDou week 0 starts at 2006-01-01 00:00:00 BDT (= UTC then), BDS-SIS-ICD section 4.2.
//! Since GPST - UTC was 0 s in 1980 and BDT - UTC was 0 s in 2006 (TAI - UTC = 19 s and
//! 33 s), BDT = GPST - 14 s for all time. Weeks are continuous (no 1024/8192 roll-over).

use hifitime::{Duration, Epoch, TimeScale};
use std::str::FromStr;

/// Nanoseconds in one second.
const NS_PER_S: i128 = 1_000_000_000;
/// Seconds in one week.
/// Seconds in a GPS or BeiDou week.
pub const SECONDS_PER_WEEK: u32 = 604_800;
const S_PER_WEEK: i128 = SECONDS_PER_WEEK as i128;

/// The times SkyForge handles, as users are told: scenario starts and recording start
/// times (SigMF `core:datetime`) must lie in it ([`in_supported_range`]).
pub const SUPPORTED_RANGE: &str = "from the GPS epoch (1980-01-06T00:00:00 GPST) to before 2100-01-01T00:00:00 (in the time's own scale)";

/// Whether `epoch` lies in [`SUPPORTED_RANGE`]: not before GPS week 0 (weeks count from it
/// continuously, so earlier times have no GPS week), and before 2100-01-01T00:00:00 read
/// in the epoch's own time scale (the date as written: `2100-01-01T00:00:01 GPST` is out
/// although it is 2099-12-31 in UTC).
pub fn in_supported_range(epoch: Epoch) -> bool {
    let end = Epoch::from_gregorian_at_midnight(2100, 1, 1, epoch.time_scale);
    epoch >= Epoch::from_gpst_seconds(0.0) && epoch < end
}

/// Error parsing or converting a time.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TimeError {
    /// The text is not an epoch hifitime understands.
    #[error("cannot read epoch {text:?}: {reason}")]
    Parse { text: String, reason: String },
}

/// The instant `t = 0` of a scenario; converts between epochs and `f64` seconds.
///
/// Differences are taken exactly (integer nanoseconds in GPST, a uniform scale without
/// leap seconds) and only then converted to `f64`, so `t` is exact to rounding of the
/// `f64` itself (about 0.1 ns after a day).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeOrigin {
    start: Epoch,
}

impl TimeOrigin {
    /// An origin at `start`.
    pub fn new(start: Epoch) -> Self {
        Self { start }
    }
    /// The scenario start epoch.
    pub fn start(&self) -> Epoch {
        self.start
    }
    /// Seconds from the start to `epoch` (exact difference, then to `f64`).
    pub fn seconds_since_start(&self, epoch: Epoch) -> f64 {
        let dt = epoch.to_time_scale(TimeScale::GPST) - self.start.to_time_scale(TimeScale::GPST);
        nanoseconds_to_seconds(dt.total_nanoseconds())
    }
    /// The epoch `t_s` seconds after the start, in GPST, rounded to the nanosecond.
    pub fn epoch_at(&self, t_s: f64) -> Epoch {
        self.start.to_time_scale(TimeScale::GPST) + seconds_to_duration(t_s)
    }
}

/// `ns` nanoseconds as `f64` seconds, splitting whole and fractional seconds (both with
/// the sign of `ns`) so that no precision is lost before the final rounding.
fn nanoseconds_to_seconds(ns: i128) -> f64 {
    let whole_s = ns / NS_PER_S;
    let frac_ns = ns % NS_PER_S;
    whole_s as f64 + frac_ns as f64 * 1e-9
}

/// `t_s` seconds as a duration, rounded to the nanosecond.
fn seconds_to_duration(t_s: f64) -> Duration {
    let whole_s = t_s.floor();
    let frac_ns = ((t_s - whole_s) * 1e9).round();
    Duration::from_total_nanoseconds(whole_s as i128 * NS_PER_S + frac_ns as i128)
}

/// Parse an epoch such as `2023-03-12T00:00:00 GPST`, `... UTC`, `... BDT`.
///
/// The time scale is mandatory (a trailing `Z` counts as UTC): a bare date is rejected
/// rather than silently read as UTC, 18 s away from GPST. Any scale hifitime knows is
/// accepted (`GPST`/`GPS`, `BDT`/`BDS`, `UTC`, `GST`, `TAI`, `TT`, ...).
pub fn parse_epoch(text: &str) -> Result<Epoch, TimeError> {
    let error = |reason: &str| TimeError::Parse {
        text: text.to_string(),
        reason: reason.to_string(),
    };
    let trimmed = text.trim();
    let last_token = trimmed.split_whitespace().last().unwrap_or("");
    let has_scale =
        TimeScale::from_str(last_token).is_ok() && trimmed.contains(char::is_whitespace);
    if !has_scale && !trimmed.ends_with('Z') {
        return Err(error(
            "add the time scale, e.g. `2023-03-12T00:00:00 GPST` (GPST, BDT, UTC, GST, TAI)",
        ));
    }
    Epoch::from_str(trimmed).map_err(|e| {
        error(&format!(
            "{e}; expected e.g. `2023-03-12T00:00:00 GPST`, `2023-03-12T00:00:00.5 UTC`"
        ))
    })
}

/// Continuous week and seconds of week of a duration since a week-0 start.
/// Before week 0 the week saturates at 0 and the seconds of week are negative.
fn week_sow(since_week0: Duration) -> (u32, f64) {
    let ns = since_week0.total_nanoseconds();
    let ns_per_week = S_PER_WEEK * NS_PER_S;
    let week = ns.div_euclid(ns_per_week).clamp(0, i128::from(u32::MAX));
    let sow_ns = ns - week * ns_per_week;
    (week as u32, nanoseconds_to_seconds(sow_ns))
}

/// Duration since a week-0 start of week `week`, `sow` seconds, rounded to the nanosecond.
fn duration_from_week_sow(week: u32, sow: f64) -> Duration {
    Duration::from_total_nanoseconds(i128::from(week) * S_PER_WEEK * NS_PER_S)
        + seconds_to_duration(sow)
}

/// GST week 0 (1999-08-22 00:00:00 GST, GST = GPST) in GPS weeks (Galileo OS SIS ICD
/// §5.1.2): Galileo's WN is the GPS week less this.
pub const GST_WEEK0_IN_GPS_WEEKS: u32 = 1024;

/// GPS week number (continuous, no roll-over) and seconds of week.
pub fn gpst_week_sow(epoch: Epoch) -> (u32, f64) {
    week_sow(epoch.to_gpst_duration())
}

/// BeiDou week number and seconds of week (BDT).
pub fn bdt_week_sow(epoch: Epoch) -> (u32, f64) {
    week_sow(epoch.to_bdt_duration())
}

/// The epoch at GPS week `week` and seconds of week `sow`.
pub fn epoch_from_gpst(week: u32, sow: f64) -> Epoch {
    Epoch::from_gpst_duration(duration_from_week_sow(week, sow))
}

/// The epoch at BDT week `week` and seconds of week `sow`.
pub fn epoch_from_bdt(week: u32, sow: f64) -> Epoch {
    Epoch::from_bdt_duration(duration_from_week_sow(week, sow))
}

/// GST - GPST, as Galileo's satellites keep it and broadcast it (Galileo OS SIS ICD Issue
/// 2.1 §5.1.8, the GST-GPS conversion: `dt = A0G + A1G (TOW - t0G + 604800 (WN - WN0G))`):
/// an offset at a reference time and its rate. Zero by default: GST is GPST.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct GstGpsOffset {
    /// A0G (s).
    pub a0_s: f64,
    /// A1G (s/s).
    pub a1: f64,
    /// t0G (s since the time origin, GPST): the whole GST hour at or before the origin,
    /// as the broadcast's 3600 s LSB can carry it.
    pub t0_s: f64,
}

impl GstGpsOffset {
    /// `a0_s` and `a1` referred to the whole hour at or before `origin`'s start.
    pub fn at_origin(a0_s: f64, a1: f64, origin: &TimeOrigin) -> Self {
        let (_, sow) = gpst_week_sow(origin.start());
        Self {
            a0_s,
            a1,
            t0_s: -(sow % 3600.0),
        }
    }

    /// GST - GPST (s) at `t_s` (s since the origin).
    pub fn at(&self, t_s: f64) -> f64 {
        self.a0_s + self.a1 * (t_s - self.t0_s)
    }

    /// The reference time t0G for the origin `origin`: (seconds of week, continuous GPS
    /// week; GST's week is aligned with it, `GST_WEEK0_IN_GPS_WEEKS` apart).
    pub fn reference(&self, origin: &TimeOrigin) -> (u32, u32) {
        let (week, sow) = gpst_week_sow(origin.start());
        ((sow + self.t0_s).round().max(0.0) as u32, week)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn the_gst_gps_offset_refers_to_the_hour_before_the_origin() {
        // 2023-03-12T00:40:00 GPST: Sunday, GPS week 2253, 2400 s into it.
        let origin = TimeOrigin::new(parse_epoch("2023-03-12T00:40:00 GPST").unwrap());
        let g = GstGpsOffset::at_origin(20e-9, 1e-14, &origin);
        assert_eq!(g.t0_s, -2400.0);
        assert_eq!(g.reference(&origin), (0, 2253));
        assert!((g.at(0.0) - (20e-9 + 2400.0 * 1e-14)).abs() < 1e-20);
        assert_eq!(GstGpsOffset::default().at(1234.5), 0.0);
    }

    #[test]
    fn the_supported_range_is_read_in_the_epochs_own_scale() {
        let at = |text: &str| in_supported_range(parse_epoch(text).unwrap());
        assert!(at("1980-01-06T00:00:00 GPST"));
        assert!(!at("1980-01-05T23:59:59 GPST"));
        assert!(at("2099-12-31T23:59:59 GPST"));
        assert!(!at("2100-01-01T00:00:00 UTC"));
        // 2099-12-31T23:59:4x UTC, but written as 2100 in GPST: out.
        assert!(!at("2100-01-01T00:00:01 GPST"));
        assert!(!at("1900-01-01T00:00:00 UTC"));
        assert!(!at("9999-12-31T00:00:00 UTC"));
    }

    fn parse(text: &str) -> Epoch {
        match parse_epoch(text) {
            Ok(e) => e,
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn published_gps_week_of_2020_06_25() {
        // 2020-06-25 is a Thursday of GPS week 2111 (IGS file names of day 177: week 2111,
        // day 4), so 4 days into the week: 345600 s.
        let (week, sow) = gpst_week_sow(parse("2020-06-25T00:00:00 GPST"));
        assert_eq!(week, 2111);
        assert_eq!(sow, 345_600.0);
        assert_eq!(
            epoch_from_gpst(2111, 345_600.0),
            parse("2020-06-25T00:00:00 GPST")
        );
    }

    #[test]
    fn gps_week_zero_starts_1980_01_06() {
        assert_eq!(gpst_week_sow(parse("1980-01-06T00:00:00 UTC")), (0, 0.0));
        // GPS week 1024 (first roll-over) began 1999-08-22 00:00:00 GPST.
        assert_eq!(
            gpst_week_sow(parse("1999-08-22T00:00:00 GPST")),
            (1024, 0.0)
        );
    }

    #[test]
    fn bdt_week_zero_is_gps_week_1356_plus_14_s() {
        // BDS-SIS-ICD: BDT starts 2006-01-01 00:00:00 UTC, which is GPS week 1356 sow 14
        // (GPST - UTC = 14 s at that time).
        let bdt0 = parse("2006-01-01T00:00:00 UTC");
        assert_eq!(bdt_week_sow(bdt0), (0, 0.0));
        assert_eq!(gpst_week_sow(bdt0), (1356, 14.0));
        assert_eq!(epoch_from_bdt(0, 0.0), bdt0);
    }

    #[test]
    fn bdt_is_gpst_minus_14_s() {
        // Mid-week (a week start in GPST is still the previous week in BDT).
        let e = parse("2023-03-15T00:00:00 GPST");
        let (gw, gs) = gpst_week_sow(e);
        let (bw, bs) = bdt_week_sow(e);
        assert_eq!(gw - bw, 1356);
        assert_eq!(gs - bs, 14.0);
        // The same clock reading in BDT is 14 s later than in GPST.
        let b = parse("2023-03-15T00:00:00 BDT");
        assert_eq!(TimeOrigin::new(e).seconds_since_start(b), 14.0);
    }

    #[test]
    fn gpst_minus_utc_is_18_s_in_2020() {
        // IERS Bulletin C: TAI - UTC = 37 s since 2017-01-01, so GPST - UTC = 18 s.
        let gpst = parse("2020-06-25T00:00:00 GPST");
        let utc = parse("2020-06-25T00:00:00 UTC");
        assert_eq!(TimeOrigin::new(gpst).seconds_since_start(utc), 18.0);
        // ... and 16 s in the first half of 2015 (TAI - UTC = 35 s until the 2015-06-30 leap
        // second).
        let gpst = parse("2015-03-01T00:00:00 GPST");
        let utc = parse("2015-03-01T00:00:00 UTC");
        assert_eq!(TimeOrigin::new(gpst).seconds_since_start(utc), 16.0);
    }

    #[test]
    fn origin_counts_leap_second_across_2016_12_31() {
        // A leap second was inserted at the end of 2016: 2 UTC seconds span 3 SI seconds.
        let o = TimeOrigin::new(parse("2016-12-31T23:59:59 UTC"));
        assert_eq!(o.seconds_since_start(parse("2017-01-01T00:00:00 UTC")), 2.0);
    }

    #[test]
    fn origin_sub_nanosecond_precision() {
        let o = TimeOrigin::new(parse("2023-03-12T00:00:00 GPST"));
        let e = o.epoch_at(-1e-9);
        assert_eq!(o.seconds_since_start(e), -1e-9);
        assert_eq!(
            o.seconds_since_start(o.epoch_at(86_400.123_456_789)),
            86_400.123_456_789
        );
    }

    #[test]
    fn parse_rejects_missing_scale_and_garbage() {
        for bad in [
            "2023-03-12T00:00:00",
            "",
            "GPST",
            "yesterday GPST",
            "2023-13-40T00:00:00 UTC",
        ] {
            match parse_epoch(bad) {
                Err(TimeError::Parse { text, reason }) => {
                    assert_eq!(text, bad);
                    assert!(!reason.is_empty());
                }
                Ok(e) => panic!("{bad:?} parsed as {e}"),
            }
        }
    }

    #[test]
    fn parse_survives_odd_numbers() {
        for odd in [
            "2023-03-12T00:00:00.99999999999 GPST",
            "99999-01-01T00:00:00 UTC",
            "-5-01-01T00:00:00 UTC",
            "2023-03-12T25:61:61 UTC",
            "2023-02-29T00:00:00 GPST",
            "2023-03-12T00:00:00+99:99 UTC",
            "4294967296-01-01T00:00:00 UTC",
            "JD 2452312.5 GPST",
            "MJD 1e300 UTC",
            "SEC nan GPST",
        ] {
            let _ = parse_epoch(odd);
        }
    }

    #[test]
    fn parse_accepts_scales_and_fractions() {
        let z = parse("2023-03-12T00:00:00Z");
        assert_eq!(z, parse("2023-03-12T00:00:00 UTC"));
        let half = parse("2023-03-12T00:00:00.5 GPST");
        let o = TimeOrigin::new(parse("2023-03-12T00:00:00 GPST"));
        assert_eq!(o.seconds_since_start(half), 0.5);
        assert_eq!(
            o.seconds_since_start(parse("2023-03-12T00:00:00 BDS")),
            14.0
        );
    }

    proptest! {
        #[test]
        fn gpst_week_sow_round_trip(week in 0u32..5000, sow_ns in 0i64..604_800_000_000_000) {
            let sow = sow_ns as f64 * 1e-9;
            let e = epoch_from_gpst(week, sow);
            let (w, s) = gpst_week_sow(e);
            prop_assert_eq!(w, week);
            prop_assert!((s - sow).abs() < 1e-9);
        }

        #[test]
        fn bdt_week_sow_round_trip(week in 0u32..3000, sow_ns in 0i64..604_800_000_000_000) {
            let sow = sow_ns as f64 * 1e-9;
            let (w, s) = bdt_week_sow(epoch_from_bdt(week, sow));
            prop_assert_eq!(w, week);
            prop_assert!((s - sow).abs() < 1e-9);
        }

        #[test]
        fn origin_round_trip(t_ns in -1_000_000_000_000_000i64..1_000_000_000_000_000) {
            let o = TimeOrigin::new(epoch_from_gpst(2111, 345_600.0));
            let t_s = t_ns as f64 * 1e-9;
            let back = o.seconds_since_start(o.epoch_at(t_s));
            prop_assert!((back - t_s).abs() <= 1e-9);
        }

        #[test]
        fn parse_display_round_trip(week in 200u32..3000, sow_s in 0u32..604_800) {
            let e = epoch_from_gpst(week, f64::from(sow_s));
            for ts in [TimeScale::GPST, TimeScale::UTC, TimeScale::BDT] {
                let text = e.to_time_scale(ts).to_string();
                let back = parse_epoch(&text);
                prop_assert!(back.is_ok(), "{text}");
                if let Ok(b) = back {
                    prop_assert_eq!(TimeOrigin::new(e).seconds_since_start(b), 0.0, "{}", text);
                }
            }
        }

        #[test]
        fn parse_never_panics(text in "\\PC{0,40}") {
            let _ = parse_epoch(&text);
        }
    }
}
