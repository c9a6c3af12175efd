//! GST weeks and seconds of week (Galileo OS SIS ICD §5.1.2: WN counts weeks from the GST
//! start epoch, 1999-08-22 00:00:00 GST, which is the start of GPS week 1024; TOW counts
//! seconds from the start of the week, 0-604799).
//!
//! hifitime's `TimeScale::GST` starts at that epoch, so its GST duration divided into
//! weeks gives WN directly (checked against GPS week 1024 in the tests).

use hifitime::{Duration, Epoch};

/// Nanoseconds per week.
pub(super) const WEEK_NS: u64 = 604_800 * 1_000_000_000;
/// Seconds per week.
pub(crate) const WEEK_S: u64 = 604_800;

/// A GST instant as week number and nanoseconds of week.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct GstTime {
    pub week: u32,
    pub ns_of_week: u64,
}

impl GstTime {
    /// Seconds of week.
    pub(crate) fn sow_s(self) -> f64 {
        self.ns_of_week as f64 * 1e-9
    }
}

/// The GST week and time of week of `t` (before the GST epoch: week 0, clamped).
pub(crate) fn gst_time(t: Epoch) -> GstTime {
    let ns = t.to_gst_duration().total_nanoseconds().max(0) as u128;
    GstTime {
        week: (ns / u128::from(WEEK_NS)) as u32,
        ns_of_week: (ns % u128::from(WEEK_NS)) as u64,
    }
}

/// The epoch at GST week `week`, `sow_s` whole seconds of week (a later week where
/// `sow_s` exceeds a week).
pub(crate) fn gst_epoch(week: u32, sow_s: u64) -> Epoch {
    let s = u64::from(week) * WEEK_S + sow_s;
    Epoch::from_gst_duration(Duration::from_total_nanoseconds(
        i128::from(s) * 1_000_000_000,
    ))
}

/// Of the weeks next to `near`, the one in which `sow_s` is nearest to `near` (for
/// reference times that carry no week: t0e, t0c), among weeks congruent to `week_mod`
/// modulo `modulus` (1 for no constraint; 4 for WNa).
pub(crate) fn nearest_week(near: Epoch, sow_s: u64, week_mod: u32, modulus: u32) -> u32 {
    let w = gst_time(near).week;
    (w.saturating_sub(modulus)..=w + modulus)
        .filter(|c| c % modulus == week_mod % modulus)
        .min_by_key(|&c| (gst_epoch(c, sow_s) - near).abs().total_nanoseconds())
        .unwrap_or(w)
}
