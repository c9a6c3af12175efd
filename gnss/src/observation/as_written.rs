//! What a RINEX 3.04 observation file keeps of a receiver's observations: the time tags
//! and values [`ObsWriter`](super::rinex_write::ObsWriter) writes, as
//! [`read_obs_file`](super::read_obs_file) reads them back. A stage that takes the
//! receiver's observations in memory sees what a program reading its files sees, so
//! `skyforge receive --geometry` and `skyforge attitude` on the written files agree to
//! the byte, without text being written and parsed in between.

use super::record::{ObsEpoch, ObsRecord};
use super::rinex_write::{Stamp, calendar_gpst, f14_3, wrapped_phase};
use hifitime::Epoch;
use std::collections::BTreeMap;
use std::io;

/// The loss-of-lock indicators a reader knows (RINEX 3.04 section 5.7: bits 0-2); a digit
/// beyond them reads as blank.
const LLI_KNOWN_BITS: u8 = 0x07;

/// The time tag `at` as the file holds it: GPS time rounded to 100 ns (F11.7 seconds,
/// the rounding carried through the calendar).
pub fn time_as_written(at: Epoch) -> io::Result<Epoch> {
    Ok(Stamp::new(calendar_gpst(at))?.epoch())
}

/// A value as its F14.3 field holds it; `None` (blank) when it is not finite or does not
/// fit.
fn value_as_written(value: Option<f64>) -> Option<f64> {
    value
        .and_then(f14_3)
        .and_then(|text| text.trim().parse().ok())
}

/// One record as the file holds it: every value rounded to F14.3 (blank when it does not
/// fit or is not finite), the phase wrapped and flagged where it overflows, the
/// loss-of-lock indicator kept with a written phase (the writer's one digit, up to 9; a
/// digit beyond the known bits reads as blank). `None` when every field is blank: the
/// reader then has no record of the satellite.
pub fn record_as_written(r: &ObsRecord) -> Option<ObsRecord> {
    let (cycles, lli) = wrapped_phase(r.carrier_phase_cycles, r.phase_lli);
    let carrier_phase_cycles = value_as_written(cycles);
    let digit = lli.min(9);
    let phase_lli = match carrier_phase_cycles {
        Some(_) if digit <= LLI_KNOWN_BITS => digit,
        _ => 0,
    };
    let kept = ObsRecord {
        sat: r.sat,
        signal: r.signal,
        pseudorange_m: value_as_written(r.pseudorange_m),
        carrier_phase_cycles,
        doppler_hz: value_as_written(r.doppler_hz),
        cn0_dbhz: value_as_written(r.cn0_dbhz),
        phase_lli,
    };
    let blank = kept.pseudorange_m.is_none()
        && kept.carrier_phase_cycles.is_none()
        && kept.doppler_hz.is_none()
        && kept.cn0_dbhz.is_none();
    (!blank).then_some(kept)
}

/// One epoch as the file holds it: the time tag ([`time_as_written`]) and one record per
/// satellite and signal (the first given, as the writer takes it), in the reader's order
/// (by satellite, then signal).
pub fn epoch_as_written(at: Epoch, records: &[ObsRecord]) -> io::Result<ObsEpoch> {
    let mut kept = BTreeMap::new();
    for r in records {
        kept.entry((r.sat, r.signal)).or_insert(r);
    }
    Ok(ObsEpoch {
        time: time_as_written(at)?,
        sats: kept.into_values().filter_map(record_as_written).collect(),
    })
}
