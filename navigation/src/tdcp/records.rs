//! Which records of a satellite are differenced, and why a satellite has no difference.

use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use std::collections::BTreeSet;

/// Why a satellite of the second epoch has no time difference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Exclusion {
    /// Loss of lock flagged at the second epoch (LLI bit 0, RINEX 3.04 section 5.7):
    /// a cycle slip may lie between the epochs.
    LossOfLock,
    /// Not observed at the first epoch (on the configured signal, or on any).
    NotInPrevious,
    /// No finite carrier phase at one of the epochs.
    MissingPhase,
    /// No finite pseudorange at one of the epochs (it gives the transmit time).
    MissingPseudorange,
    /// Observed at both epochs, but on no common signal.
    DifferentSignal,
    /// No broadcast ephemeris usable at the second epoch.
    NoEphemeris,
    /// Below the elevation mask at the second epoch.
    BelowMask,
}

/// The satellites of `records` with a record on `signal` (any signal when `None`).
pub(crate) fn satellites(records: &[ObsRecord], signal: Option<Signal>) -> BTreeSet<SatId> {
    (records.iter())
        .filter(|r| signal.is_none_or(|s| r.signal == s))
        .map(|r| r.sat)
        .collect()
}

/// A value that was measured and is finite.
fn measured(value: Option<f64>) -> bool {
    value.is_some_and(f64::is_finite)
}

/// Whether the records `(first, second)` of one signal can be differenced.
fn status(first: &ObsRecord, second: &ObsRecord) -> Result<(), Exclusion> {
    if second.loss_of_lock() {
        Err(Exclusion::LossOfLock)
    } else if !(measured(first.carrier_phase_cycles) && measured(second.carrier_phase_cycles)) {
        Err(Exclusion::MissingPhase)
    } else if !(measured(first.pseudorange_m) && measured(second.pseudorange_m)) {
        Err(Exclusion::MissingPseudorange)
    } else {
        Ok(())
    }
}

/// The records of `sat` to difference, first and second epoch, on `signal` or (`None`)
/// the first signal in [`Signal`] order whose records at both epochs can be differenced;
/// otherwise why none can (the first signal's reason).
pub(crate) fn pick<'a>(
    (first, second): (&'a [ObsRecord], &'a [ObsRecord]),
    sat: SatId,
    signal: Option<Signal>,
) -> Result<(&'a ObsRecord, &'a ObsRecord), Exclusion> {
    let mut candidates: Vec<&ObsRecord> = (second.iter())
        .filter(|r| r.sat == sat && signal.is_none_or(|s| r.signal == s))
        .collect();
    candidates.sort_by_key(|r| r.signal);
    let pairs: Vec<(&ObsRecord, &ObsRecord)> = (candidates.into_iter())
        .filter_map(|b| {
            let a = first
                .iter()
                .find(|a| a.sat == sat && a.signal == b.signal)?;
            Some((a, b))
        })
        .collect();
    let Some(&(a, b)) = pairs.first() else {
        return Err(if first.iter().any(|a| a.sat == sat) {
            Exclusion::DifferentSignal
        } else {
            Exclusion::NotInPrevious
        });
    };
    (pairs.iter())
        .find(|(a, b)| status(a, b).is_ok())
        .copied()
        .ok_or_else(|| status(a, b).err().unwrap_or(Exclusion::MissingPhase))
}
