//! `skyforge calibrate`: the observation-level noise factors, measured on a signal-level
//! run. The scenario is synthesised and received as a user would; each antenna's
//! observations are compared with the observation truth; per signal, the measured code
//! and phase noise variances are divided by the loop formulas' (at each satellite's true
//! C/N0 and the receiver's loop settings after pull-in), summed over satellites weighted
//! by their epoch counts.
//!
//! Multipath and fault events in the calibration scenario would count as noise: calibrate
//! on a scenario without them.

use hifitime::Duration;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use skyforge_receiver::tracking::TrackingConfig;
use skyforge_runner::{ChainError, synth_and_receive};
use skyforge_scenarios::Scenario;
use skyforge_signals::obs_model::{Calibration, LoopNoise, SignalCalibration};
use skyforge_validate::observables::compare::{
    CompareOptions, ObservableErrors, SampleSpan, SignalComparison, compare_signals,
};
use skyforge_validate::observables::{ObsError, ObsFile};
use std::path::Path;

/// Seconds at the start of the run left out: acquisition, pull-in and loop narrowing.
pub const SETTLING_S: f64 = 10.0;
/// The shortest run calibrated on: the settling and 10 s of observations.
pub const MIN_DURATION_S: f64 = SETTLING_S + 10.0;

/// Why a calibration could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CalibrateError {
    #[error(transparent)]
    Chain(#[from] ChainError),
    #[error("comparing antenna {antenna} with its truth: {error}")]
    Compare { antenna: String, error: ObsError },
    #[error(
        "the run is {0} s long: at least {MIN_DURATION_S} s ({SETTLING_S} s of settling, then observations) are needed"
    )]
    TooShort(f64),
}

/// The loops of `tracking` after pull-in, for `signal`.
pub fn settled_loops(tracking: &TrackingConfig, signal: Signal) -> LoopNoise {
    LoopNoise {
        pll_bandwidth_hz: tracking
            .pll_narrow_bandwidth_hz
            .unwrap_or(tracking.pll_bandwidth_hz),
        dll_bandwidth_hz: tracking
            .dll_narrow_bandwidth_hz
            .unwrap_or(tracking.dll_bandwidth_hz),
        spacing_chips: tracking
            .narrow_early_late_spacing_chips
            .unwrap_or(tracking.early_late_spacing_chips),
        coherent_s: f64::from(tracking.coherent_ms) * signal.code_period_s(),
    }
}

/// Sums of one signal: measured and formula variances weighted by epoch counts.
#[derive(Debug, Default, Clone, Copy)]
struct Sums {
    code_measured: f64,
    code_formula: f64,
    phase_measured: f64,
    phase_formula: f64,
    doppler_measured: f64,
    doppler_formula: f64,
    samples: usize,
    cn0_min: f64,
    cn0_max: f64,
}

/// Mean formula variances of one satellite over the truth epochs, and its C/N0 range.
struct FormulaVariances {
    code: f64,
    phase: f64,
    doppler: f64,
    cn0_min: f64,
    cn0_max: f64,
}

/// [`FormulaVariances`] of `sat` on `signal`.
fn formula_variances(
    truth: &ObsFile,
    sat: SatId,
    signal: Signal,
    loops: &LoopNoise,
) -> Option<FormulaVariances> {
    let cn0: Vec<f64> = truth
        .epochs
        .iter()
        .flat_map(|e| e.sats.iter())
        .filter(|r| r.sat == sat && r.signal == signal)
        .filter_map(|r| r.cn0_dbhz)
        .collect();
    if cn0.is_empty() {
        return None;
    }
    let n = cn0.len() as f64;
    let code = cn0
        .iter()
        .map(|c| loops.code_sigma_m(signal, *c).powi(2))
        .sum::<f64>()
        / n;
    let phase = cn0
        .iter()
        .map(|c| loops.phase_sigma_m(signal, *c).powi(2))
        .sum::<f64>()
        / n;
    let doppler = cn0
        .iter()
        .map(|c| loops.doppler_sigma_hz(*c).powi(2))
        .sum::<f64>()
        / n;
    let (lo, hi) = cn0
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
            (a.min(*c), b.max(*c))
        });
    Some(FormulaVariances {
        code,
        phase,
        doppler,
        cn0_min: lo,
        cn0_max: hi,
    })
}

/// Add the satellites of one antenna's comparison `layer` (against `truth`) to `sums`.
fn add_layer(
    sums: &mut Vec<(Signal, Sums)>,
    layer: &SignalComparison,
    truth: &ObsFile,
    tracking: &TrackingConfig,
) {
    let cmp = &layer.comparison;
    // A satellite's count and std of one observable's errors.
    let of = |errors: &ObservableErrors, sat: SatId| {
        errors
            .per_satellite
            .iter()
            .find(|s| s.sat == sat)
            .and_then(|s| Some((s.stats.count, s.stats.std?)))
    };
    let phase_of = |sat| of(&cmp.carrier_phase_m, sat);
    let doppler_of = |sat| of(&cmp.doppler_hz, sat);
    for code in &cmp.pseudorange_m.per_satellite {
        let (Some(code_std), Some((phase_n, phase_std))) = (code.stats.std, phase_of(code.sat))
        else {
            continue;
        };
        let Some(signal) = layer.signal_of(code.sat.system) else {
            continue;
        };
        let loops = settled_loops(tracking, signal);
        let Some(formula) = formula_variances(truth, code.sat, signal, &loops) else {
            continue;
        };
        let at = match sums.iter().position(|(s, _)| *s == signal) {
            Some(i) => i,
            None => {
                sums.push((
                    signal,
                    Sums {
                        cn0_min: f64::INFINITY,
                        cn0_max: f64::NEG_INFINITY,
                        ..Sums::default()
                    },
                ));
                sums.len() - 1
            }
        };
        let s = &mut sums[at].1;
        let n = code.stats.count as f64;
        let m = phase_n as f64;
        s.code_measured += n * code_std * code_std;
        s.code_formula += n * formula.code;
        s.phase_measured += m * phase_std * phase_std;
        s.phase_formula += m * formula.phase;
        if let Some((count, std)) = doppler_of(code.sat) {
            let k = count as f64;
            s.doppler_measured += k * std * std;
            s.doppler_formula += k * formula.doppler;
        }
        s.samples += code.stats.count;
        s.cn0_min = s.cn0_min.min(formula.cn0_min);
        s.cn0_max = s.cn0_max.max(formula.cn0_max);
    }
}

/// Calibrate on `scenario`, synthesising into `work` (an existing directory; recordings
/// can take gigabytes).
pub fn calibrate(scenario: &Scenario, work: &Path) -> Result<Calibration, CalibrateError> {
    let duration_s = scenario.time.duration_s;
    if duration_s < MIN_DURATION_S {
        return Err(CalibrateError::TooShort(duration_s));
    }
    let chain = synth_and_receive(scenario, work, None)?;
    let start = scenario.time.start;
    let window = SampleSpan {
        first: start + Duration::from_seconds(SETTLING_S),
        last: start + Duration::from_seconds(duration_s),
    };
    let options = CompareOptions {
        window: Some(window),
        ..CompareOptions::default()
    };
    let mut sums: Vec<(Signal, Sums)> = Vec::new();
    for ((name, estimate), truth) in chain
        .antennas
        .iter()
        .zip(&chain.observations)
        .zip(&chain.truth)
    {
        let comparisons = compare_signals(estimate, truth, &options).map_err(|error| {
            CalibrateError::Compare {
                antenna: name.clone(),
                error,
            }
        })?;
        for c in &comparisons {
            add_layer(&mut sums, c, truth, &chain.config.tracking);
        }
    }
    sums.sort_by_key(|(s, _)| *s);
    let signals = sums
        .into_iter()
        .filter(|(_, s)| s.samples > 0)
        .map(|(signal, s)| SignalCalibration {
            signal: signal.tag().to_string(),
            loops: settled_loops(&chain.config.tracking, signal),
            code_factor: (s.code_measured / s.code_formula).sqrt(),
            phase_factor: (s.phase_measured / s.phase_formula).sqrt(),
            doppler_factor: (s.doppler_formula > 0.0)
                .then(|| (s.doppler_measured / s.doppler_formula).sqrt()),
            cn0_dbhz: [s.cn0_min, s.cn0_max],
            samples: s.samples,
        })
        .collect();
    Ok(Calibration {
        scenario: scenario.name.clone(),
        seed: scenario.seed,
        duration_s: duration_s - SETTLING_S,
        signals,
    })
}
