//! The per-run statistics a study can keep: each one number per run, computed from the
//! run's observables and the attitude chain's comparison with the run's own truth
//! ([`crate::attitude`]). A run without the quantity (no fixed epoch, say) gives NaN,
//! which the summaries leave out and count.

use crate::attitude::{ChainComparison, ObservationRun, compare, nominal_geometry};
use crate::stats::rms;
use skyforge_orbits::ephemeris::SatId;
use skyforge_receiver::relative::RelativeConfig;
use skyforge_scenarios::Scenario;
use skyforge_signals::obs_model::Level;
use skyforge_signals::observation::ObsRecord;
use skyforge_signals::signal::Signal;
use std::collections::{BTreeMap, HashMap};

/// One per-run statistic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// Measured minus true pseudorange, RMS over every antenna, satellite and epoch (m).
    PseudorangeRms,
    /// Measured minus true carrier phase (m) with each arc's mean removed (its integer
    /// ambiguity and any constant), RMS over every antenna, satellite and epoch.
    PhaseRms,
    /// Epochs with every ambiguity fixed over the epochs from the first fix on.
    FixRate,
    /// Fixed epochs with a wrong integer over the fixed epochs.
    WrongFixRate,
    /// Seconds from the start to the first fixed epoch.
    FirstFix,
    /// Baseline error norm (ECEF), RMS over fixed epochs and baselines (m).
    BaselineRms,
    /// Attitude error RMS over fixed epochs (deg), per axis.
    YawRms,
    PitchRms,
    RollRms,
}

/// Every metric, in the order of [`Metric::names`].
const ALL: [Metric; 9] = [
    Metric::PseudorangeRms,
    Metric::PhaseRms,
    Metric::FixRate,
    Metric::WrongFixRate,
    Metric::FirstFix,
    Metric::BaselineRms,
    Metric::YawRms,
    Metric::PitchRms,
    Metric::RollRms,
];

impl Metric {
    /// The name in study files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            Metric::PseudorangeRms => "pseudorange_rms_m",
            Metric::PhaseRms => "phase_rms_m",
            Metric::FixRate => "fix_rate",
            Metric::WrongFixRate => "wrong_fix_rate",
            Metric::FirstFix => "first_fix_s",
            Metric::BaselineRms => "baseline_rms_m",
            Metric::YawRms => "yaw_rms_deg",
            Metric::PitchRms => "pitch_rms_deg",
            Metric::RollRms => "roll_rms_deg",
        }
    }

    /// Unit of the values.
    pub fn unit(self) -> &'static str {
        match self {
            Metric::PseudorangeRms | Metric::PhaseRms | Metric::BaselineRms => "m",
            Metric::FixRate | Metric::WrongFixRate => "1",
            Metric::FirstFix => "s",
            Metric::YawRms | Metric::PitchRms | Metric::RollRms => "deg",
        }
    }

    /// Every name, for messages.
    pub fn names() -> Vec<&'static str> {
        ALL.iter().map(|m| m.name()).collect()
    }

    /// The metric named `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether it needs the attitude chain (two antennas or more).
    fn needs_chain(self) -> bool {
        !matches!(self, Metric::PseudorangeRms | Metric::PhaseRms)
    }

    /// Whether `scenario` can give this metric; what it needs otherwise.
    pub fn check(self, scenario: &Scenario) -> Result<(), String> {
        if scenario.observation.level != Level::Observation {
            return Err(
                "the runs of a study are at the observation level: the base scenario needs [observation] level = \"observation\"".into(),
            );
        }
        if self.needs_chain() && scenario.antennas.len() < 2 {
            return Err(format!(
                "{} comes from the attitude chain, which needs two antennas or more (the scenario has {})",
                self.name(),
                scenario.antennas.len()
            ));
        }
        Ok(())
    }
}

/// The values of `metrics` for one run (NaN where the run has none).
pub fn measure(run: &ObservationRun, metrics: &[Metric]) -> Result<Vec<f64>, String> {
    let chain = if metrics.iter().any(|m| m.needs_chain()) {
        Some(
            compare(run, &nominal_geometry(run), RelativeConfig::default())
                .map_err(|e| format!("attitude chain: {e}"))?,
        )
    } else {
        None
    };
    Ok(metrics
        .iter()
        .map(|&m| match (m, &chain) {
            (Metric::PseudorangeRms, _) => pseudorange_rms(run),
            (Metric::PhaseRms, _) => phase_rms(run),
            (m, Some(c)) => chain_metric(m, c),
            (_, None) => f64::NAN,
        })
        .collect())
}

/// A chain metric of `c`.
fn chain_metric(m: Metric, c: &ChainComparison) -> f64 {
    let fixed = !c.fixed.is_empty();
    let or_nan = |v: f64| if fixed { v } else { f64::NAN };
    match m {
        Metric::FixRate => c.fix_rate(),
        Metric::WrongFixRate if c.fixed_epochs == 0 => f64::NAN,
        Metric::WrongFixRate => c.fixed_epochs_wrong as f64 / c.fixed_epochs as f64,
        Metric::FirstFix => c.first_fix_s.unwrap_or(f64::NAN),
        Metric::BaselineRms => {
            let norms: Vec<f64> = c
                .fixed
                .iter()
                .flat_map(|e| e.baseline_ecef_m.iter())
                .map(|b| (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt())
                .collect();
            or_nan(rms(&norms))
        }
        Metric::YawRms => or_nan(rms(&c.attitude_axis(0))),
        Metric::PitchRms => or_nan(rms(&c.attitude_axis(1))),
        Metric::RollRms => or_nan(rms(&c.attitude_axis(2))),
        Metric::PseudorangeRms | Metric::PhaseRms => f64::NAN,
    }
}

/// One measured-minus-true difference: its antenna (index), satellite and signal, and the
/// difference in the observable's unit.
type Difference = (usize, SatId, Signal, f64);

/// Measured minus true `pick` (an observable of a record) wherever both exist, antenna by
/// antenna in epoch order.
fn differences(run: &ObservationRun, pick: fn(&ObsRecord) -> Option<f64>) -> Vec<Difference> {
    let mut out = Vec::new();
    for (a, (measured, truth)) in run.measured.iter().zip(&run.truth).enumerate() {
        let true_at: HashMap<_, f64> = truth
            .epochs
            .iter()
            .flat_map(|e| {
                e.sats
                    .iter()
                    .filter_map(move |r| Some(((e.time, r.sat, r.signal), pick(r)?)))
            })
            .collect();
        for e in &measured.epochs {
            for r in &e.sats {
                if let (Some(m), Some(t)) = (pick(r), true_at.get(&(e.time, r.sat, r.signal))) {
                    out.push((a, r.sat, r.signal, m - t));
                }
            }
        }
    }
    out
}

/// RMS of `errors`, NaN when there are none.
fn rms_or_nan(errors: &[f64]) -> f64 {
    if errors.is_empty() {
        f64::NAN
    } else {
        rms(errors)
    }
}

/// RMS of measured minus true pseudorange over every antenna, satellite and epoch.
fn pseudorange_rms(run: &ObservationRun) -> f64 {
    let errors: Vec<f64> = differences(run, |r| r.pseudorange_m)
        .into_iter()
        .map(|d| d.3)
        .collect();
    rms_or_nan(&errors)
}

/// RMS of measured minus true carrier phase (m) over every antenna, satellite and epoch,
/// each arc (antenna, satellite, signal) less its own mean: the integer ambiguity and the
/// constant part go, the noise and anything that changes along the arc (a slip) stay.
fn phase_rms(run: &ObservationRun) -> f64 {
    // Ordered: the sum of squares must not depend on a hash seed (runs are compared bit
    // for bit across shard layouts).
    let mut arcs: BTreeMap<(usize, SatId, Signal), Vec<f64>> = BTreeMap::new();
    for (a, sat, signal, cycles) in differences(run, |r| r.carrier_phase_cycles) {
        arcs.entry((a, sat, signal))
            .or_default()
            .push(cycles * signal.wavelength_m());
    }
    let errors: Vec<f64> = arcs
        .values()
        .flat_map(|arc| {
            let mean = arc.iter().sum::<f64>() / arc.len() as f64;
            arc.iter().map(move |e| e - mean)
        })
        .collect();
    rms_or_nan(&errors)
}
