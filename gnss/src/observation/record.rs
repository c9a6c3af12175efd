//! One satellite's observations of one signal at one epoch: what a receiver reports, what
//! the synthesiser's truth says and what a RINEX observation file holds.

use crate::signal::Signal;
use hifitime::Epoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use std::path::PathBuf;

/// RINEX 3.04 section 5.7: LLI bit 0, loss of lock between the previous and this epoch.
pub const LLI_LOSS_OF_LOCK: u8 = 0x01;
/// RINEX 3.04 section 5.7: LLI bit 1, half-cycle ambiguity or slip possible.
pub const LLI_HALF_CYCLE: u8 = 0x02;

/// One satellite's observations of one signal at one epoch; a value is `None` when it was
/// not measured (a RINEX file leaves it blank or does not list its observation code).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObsRecord {
    pub sat: SatId,
    pub signal: Signal,
    pub pseudorange_m: Option<f64>,
    /// Carrier phase (cycles), RINEX sign (grows with the range).
    pub carrier_phase_cycles: Option<f64>,
    /// Doppler (Hz), positive for an approaching satellite.
    pub doppler_hz: Option<f64>,
    /// Signal strength (`S` code), dB-Hz.
    pub cn0_dbhz: Option<f64>,
    /// Loss-of-lock indicator of the carrier phase ([`LLI_LOSS_OF_LOCK`],
    /// [`LLI_HALF_CYCLE`]; 0 when blank).
    pub phase_lli: u8,
}

impl ObsRecord {
    /// No value measured yet.
    pub fn empty(sat: SatId, signal: Signal) -> Self {
        Self {
            sat,
            signal,
            pseudorange_m: None,
            carrier_phase_cycles: None,
            doppler_hz: None,
            cn0_dbhz: None,
            phase_lli: 0,
        }
    }

    /// Every value measured, lock kept.
    pub fn complete(
        sat: SatId,
        signal: Signal,
        pseudorange_m: f64,
        carrier_phase_cycles: f64,
        doppler_hz: f64,
        cn0_dbhz: f64,
    ) -> Self {
        Self {
            sat,
            signal,
            pseudorange_m: Some(pseudorange_m),
            carrier_phase_cycles: Some(carrier_phase_cycles),
            doppler_hz: Some(doppler_hz),
            cn0_dbhz: Some(cn0_dbhz),
            phase_lli: 0,
        }
    }

    /// Lock lost between the previous epoch and this one (cycle slip possible).
    pub fn loss_of_lock(&self) -> bool {
        self.phase_lli & LLI_LOSS_OF_LOCK != 0
    }
}

/// One epoch of observations.
#[derive(Debug, Clone, PartialEq)]
pub struct ObsEpoch {
    /// The epoch's time tag (the receiver's clock), in GPS time.
    pub time: Epoch,
    /// Observations, ordered by satellite.
    pub sats: Vec<ObsRecord>,
}

/// The observations of one antenna (one RINEX observation file), epochs in time order.
#[derive(Debug, Clone, PartialEq)]
pub struct ObsFile {
    /// Where the observations came from (file path, or a label for text).
    pub source: PathBuf,
    /// The header's `APPROX POSITION XYZ` (ECEF, m), when it has one.
    pub approx_ecef_m: Option<Vec3>,
    /// The RINEX 3 code (band and attribute, e.g. `2W`) each signal's observations were
    /// read from ([`super::rinex_codes`]); empty where the file does not say (RINEX 2,
    /// observations made in memory).
    pub codes: std::collections::BTreeMap<Signal, &'static str>,
    pub epochs: Vec<ObsEpoch>,
    /// The header's `MARKER NAME` (SkyForge writes the antenna's name), when it has one.
    pub marker: Option<String>,
    /// Epochs and lines the reader could not use and left out, in file order.
    pub dropped: Vec<Dropped>,
}

/// An epoch (or a line between epochs) the reader left out, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Dropped {
    /// 1-based line of the file.
    pub line: usize,
    pub reason: String,
}

/// At most this many dropped lines are named in a message; the rest are counted.
const NAMED: usize = 5;

/// `dropped` as one line: each named with its reason, the first [`NAMED`] of them.
pub(crate) fn list_dropped(dropped: &[Dropped]) -> String {
    let mut text = dropped
        .iter()
        .take(NAMED)
        .map(|d| format!("line {}: {}", d.line, d.reason))
        .collect::<Vec<_>>()
        .join("; ");
    if dropped.len() > NAMED {
        text += &format!("; and {} more", dropped.len() - NAMED);
    }
    text
}

impl ObsFile {
    /// A file of `epochs` under this one's header (source, position, codes, marker),
    /// nothing dropped: what a stage makes of a file's epochs.
    pub fn with_epochs(&self, epochs: Vec<ObsEpoch>) -> ObsFile {
        ObsFile {
            source: self.source.clone(),
            approx_ecef_m: self.approx_ecef_m,
            codes: self.codes.clone(),
            epochs,
            marker: self.marker.clone(),
            dropped: Vec::new(),
        }
    }

    /// The signals observed in the file, in [`Signal`] order.
    pub fn signals(&self) -> Vec<Signal> {
        let set: std::collections::BTreeSet<Signal> = self
            .epochs
            .iter()
            .flat_map(|e| e.sats.iter().map(|r| r.signal))
            .collect();
        set.into_iter().collect()
    }

    /// The observations of `signals` alone (epochs left without any dropped).
    pub fn of_signals(&self, signals: &[Signal]) -> ObsFile {
        let epochs = self
            .epochs
            .iter()
            .map(|e| ObsEpoch {
                time: e.time,
                sats: e
                    .sats
                    .iter()
                    .filter(|r| signals.contains(&r.signal))
                    .copied()
                    .collect(),
            })
            .filter(|e| !e.sats.is_empty())
            .collect();
        ObsFile {
            source: self.source.clone(),
            approx_ecef_m: self.approx_ecef_m,
            codes: self
                .codes
                .iter()
                .filter(|(s, _)| signals.contains(s))
                .map(|(s, c)| (*s, *c))
                .collect(),
            epochs,
            marker: self.marker.clone(),
            dropped: self.dropped.clone(),
        }
    }

    /// What the reader left out, as a warning naming the file and the lines; `None` when
    /// it left nothing out.
    pub fn dropped_warning(&self) -> Option<String> {
        (!self.dropped.is_empty()).then(|| {
            format!(
                "{}: {} malformed epochs or lines left out ({} epochs read): {}",
                self.source.display(),
                self.dropped.len(),
                self.epochs.len(),
                list_dropped(&self.dropped)
            )
        })
    }
}
