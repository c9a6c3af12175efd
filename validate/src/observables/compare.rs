//! A receiver's observations against SkyForge's RINEX truth of the same recording.
//!
//! Time. The truth is tagged with the sample clock (whole seconds from the recording's
//! first sample) and its pseudorange is `c (sample time - transmit time)`. A receiver tags
//! an epoch with its own time `t_e = T + d`, `T` the sample time of the measurement and
//! `d` its clock offset from the sample clock, and measures `PR_e = PR_truth(T) + c d`.
//! Comparing at the tag `t_e` instead of `T` would add `rho_dot * d` per satellite (up to
//! 0.8 m per ms of offset for a static receiver), so each epoch's `d` is estimated first:
//! `d = median over satellites of (PR_e - PR_truth(t_e - d)) / c`, iterated to a fixed
//! point (the iteration contracts by `|rho_dot| / c ~ 3e-6`). One epoch's estimate
//! carries the code noise over the root of the satellite count, a few ns for a
//! metre-level DLL; evaluating the truth a few ns off moves it by `rho_dot * dt`, a few
//! micrometres (800 m/s x 3 ns = 2.4 um), negligible even for the carrier phase, so each
//! epoch uses its own `d`. The truth at `T = t_e - d` comes from a cubic over its 4
//! neighbouring epochs (`interpolate`: below 1e-6 m for any GNSS geometry at 1 Hz
//! truth); there is no snapping to a truth epoch, whatever the tag.
//!
//! Errors, per system (GPS, BeiDou: their receiver clocks may differ by an inter-system
//! bias), fitted by exact two-way fixed-effects least squares (`fixed_effects`):
//! - pseudorange error `PR_e - PR_truth(T)` (m) = satellite bias + epoch clock term +
//!   noise. The per-satellite `mean` is the satellite's bias relative to the count-weighted
//!   mean of the system's satellites; `std` is the residual's, corrected for the degrees
//!   of freedom the clock terms and biases take.
//! - carrier-phase error `(phi_e - phi_truth(T)) lambda` (m) = arc offset + epoch term +
//!   noise, arcs split at a loss-of-lock indicator (bit 0) or a missing epoch. The arc
//!   offset (the receiver's ambiguity relative to the truth's zero ambiguity, plus its
//!   phase clock) is reported in cycles relative to the system's longest arc, with its
//!   distance to the nearest multiple of half a cycle.
//! - Doppler error (Hz): as the pseudorange (epoch term: clock-drift difference).
//! - C/N0 error (dB): no common term; `mean` is the bias.
//!
//! Signals. One comparison covers one signal: the truth's observations of others are left
//! out; an estimate of several signals is compared signal by signal ([`compare_signals`]).

use super::ObsError;
use super::error_stats::{ErrorStats, SatErrors, display};
use super::fixed_effects::{self, Fit, Sample};
use super::interpolate::Series;
use hifitime::{Duration, Epoch};
use serde::{Serialize, Serializer};
use skyforge_gnss::observation::{LLI_HALF_CYCLE, LLI_LOSS_OF_LOCK, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Fixed-point iterations of the time offset, and their convergence threshold (s).
const TIME_OFFSET_ITERATIONS: usize = 10;
const TIME_OFFSET_TOLERANCE_S: f64 = 1e-12;

/// Arc offsets within this many cycles of a multiple of half a cycle count as resolved
/// to (half-)integers.
pub const INTEGER_TOLERANCE_CYCLES: f64 = 0.05;

/// Settings of [`compare_with`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CompareOptions {
    /// Added to every estimate time tag before matching (s): corrects a file whose tags
    /// are in another time scale than its header says ([`ObsComparison::tag_error`]
    /// measures such an error).
    pub tag_offset_s: f64,
    /// Only estimate epochs whose measurements were taken within this sample-time span
    /// (inclusive; truth time scale): side by side with another receiver, the span of its
    /// matched epochs ([`ObsComparison::sample_span`]).
    pub window: Option<SampleSpan>,
}

/// First and last sample time of a set of matched epochs (the truth's time scale).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SampleSpan {
    #[serde(serialize_with = "display")]
    pub first: Epoch,
    #[serde(serialize_with = "display")]
    pub last: Epoch,
}

/// Error statistics of one observable.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObservableErrors {
    /// All satellites of all systems (`std` pooled over the systems' fits).
    pub overall: ErrorStats,
    pub per_system: Vec<SystemErrors>,
    pub per_satellite: Vec<SatErrors>,
}

/// One system's error statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SystemErrors {
    #[serde(serialize_with = "system_name")]
    pub system: System,
    #[serde(flatten)]
    pub stats: ErrorStats,
}

/// How far the estimate's time tags are from the times its pseudoranges belong to.
///
/// The offset `d` of each epoch is estimated from the pseudoranges, so a tag error common
/// to all satellites and consistent with the pseudoranges (a receiver clock offset) never
/// shows. A tag error `delta` the pseudoranges do not share (e.g. tags in another time
/// scale than the header states) evaluates the truth at the wrong time and leaves a
/// satellite bias `b_i = -rho_dot_i delta = lambda D_i delta` (`D_i` the truth Doppler).
/// `delta` is the least-squares slope of the pseudorange satellite biases on
/// `lambda D_i`, each system centred on its own mean. Correct it with
/// `CompareOptions::tag_offset_s = -delta`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TagError {
    /// `delta` (s): used sample time minus the measurement's sample time.
    pub delta_s: f64,
    /// Its standard error (s), from the regression's residuals.
    pub std_error_s: f64,
    /// Satellites in the regression.
    pub satellites: usize,
}

/// One continuous carrier-phase arc of the estimate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseArc {
    #[serde(serialize_with = "display")]
    pub sat: SatId,
    /// Time tag of the arc's first epoch.
    #[serde(serialize_with = "display")]
    pub start: Epoch,
    pub epochs: usize,
    /// The arc's phase offset from the truth (cycles), relative to the reference arc.
    pub offset_cycles: f64,
    /// This arc is the reference (longest) of its system.
    pub reference: bool,
    /// `offset_cycles` minus the nearest multiple of 0.5 cycle.
    pub off_half_cycle_grid: f64,
    /// `|off_half_cycle_grid| <= INTEGER_TOLERANCE_CYCLES`.
    pub integer_like: bool,
    /// A half-cycle indicator (LLI bit 1) was set in the arc.
    pub half_cycle_flag: bool,
}

/// The result of [`compare`]: estimate minus truth.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObsComparison {
    pub estimate: PathBuf,
    pub truth: PathBuf,
    /// Epochs in the estimate, and those matched with the truth.
    pub estimate_epochs: usize,
    pub matched_epochs: usize,
    /// Sample times of the first and last matched epoch.
    pub sample_span: SampleSpan,
    /// The estimate's time tag minus the sample-clock time of its measurement (s),
    /// per-epoch estimates.
    pub time_offset_s: ErrorStats,
    /// Error of the estimate's time tags as the pseudoranges see it, `None` with fewer
    /// than 3 satellites (see [`TagError`]).
    pub tag_error: Option<TagError>,
    pub pseudorange_m: ObservableErrors,
    pub carrier_phase_m: ObservableErrors,
    pub doppler_hz: ObservableErrors,
    pub cn0_dbhz: ObservableErrors,
    pub arcs: Vec<PhaseArc>,
    /// Satellites with estimate pseudoranges none of which could be matched with truth.
    #[serde(serialize_with = "display_all")]
    pub satellites_without_truth: Vec<SatId>,
}

fn system_name<S: Serializer>(s: &System, ser: S) -> Result<S::Ok, S::Error> {
    ser.serialize_str(s.name())
}

fn display_all<S: Serializer>(v: &[SatId], ser: S) -> Result<S::Ok, S::Error> {
    ser.collect_seq(v.iter().map(ToString::to_string))
}

/// The truth of one satellite: pseudorange (m), carrier phase (cycles), Doppler (Hz),
/// C/N0 (dB-Hz).
#[derive(Debug, Default)]
struct TruthSat {
    pseudorange: Series,
    phase: Series,
    doppler: Series,
    cn0: Series,
}

/// One matched observation: estimate epoch index, estimate, truth at the sample time.
#[derive(Debug, Clone, Copy)]
struct Matched {
    epoch: usize,
    est: ObsRecord,
    pseudorange_m: Option<f64>,
    phase_cycles: Option<f64>,
    doppler_hz: Option<f64>,
    cn0_dbhz: Option<f64>,
}

/// [`compare_with`] with the default options.
pub fn compare(estimate: &ObsFile, truth: &ObsFile) -> Result<ObsComparison, ObsError> {
    compare_with(estimate, truth, &CompareOptions::default())
}

/// Compare `estimate` (a receiver's observations) with `truth` (SkyForge's observation
/// truth of the same recording); see the module documentation for the method.
///
/// The estimate holds one signal per system (split a file of more with
/// [`compare_signals`]); the truth's observations of other signals are left out.
pub fn compare_with(
    estimate: &ObsFile,
    truth: &ObsFile,
    opts: &CompareOptions,
) -> Result<ObsComparison, ObsError> {
    let signals = estimate.signals();
    if let Some(system) = several_of_one_system(&signals) {
        return Err(ObsError::SeveralSignals(format!(
            "{} {}",
            system.name(),
            tags(signals.iter().filter(|s| s.system() == system))
        )));
    }
    let truth = if signals.is_empty() {
        truth.clone()
    } else {
        truth.of_signals(&signals)
    };
    let truth = &truth;
    let no_overlap = || ObsError::NoOverlap {
        estimate: span(estimate),
        truth: span(truth),
    };
    let t_ref = truth.epochs.first().ok_or_else(no_overlap)?.time;
    let secs = |t: Epoch| (t - t_ref).to_seconds();
    let mut truth_sats: BTreeMap<SatId, TruthSat> = BTreeMap::new();
    for e in &truth.epochs {
        let t = secs(e.time);
        for s in &e.sats {
            let ts = truth_sats.entry(s.sat).or_default();
            let pairs = [
                (&mut ts.pseudorange, s.pseudorange_m),
                (&mut ts.phase, s.carrier_phase_cycles),
                (&mut ts.doppler, s.doppler_hz),
                (&mut ts.cn0, s.cn0_dbhz),
            ];
            for (series, v) in pairs {
                if let Some(v) = v {
                    series.push(t, v);
                }
            }
        }
    }
    let max_span_s = 3.0 * nominal_interval_s(truth) * 1.01;

    // Per-epoch time offset d (estimate tag - sample time), warm-started.
    let t_est: Vec<f64> = estimate
        .epochs
        .iter()
        .map(|e| secs(e.time) + opts.tag_offset_s)
        .collect();
    let mut d_epoch: Vec<Option<f64>> = Vec::with_capacity(t_est.len());
    let mut warm = 0.0;
    for (e, &t) in estimate.epochs.iter().zip(&t_est) {
        let d = time_offset(&e.sats, &truth_sats, t, warm, max_span_s);
        if let Some(d) = d {
            warm = d;
        }
        d_epoch.push(d);
    }
    if let Some(w) = opts.window {
        // A microsecond of slack: spans come from another file's per-epoch offsets.
        let (from, to) = (secs(w.first) - 1e-6, secs(w.last) + 1e-6);
        for (d, &t) in d_epoch.iter_mut().zip(&t_est) {
            if d.is_some_and(|d| !(from..=to).contains(&(t - d))) {
                *d = None;
            }
        }
        if d_epoch.iter().all(Option::is_none) {
            return Err(ObsError::EmptyWindow {
                first: w.first.to_string(),
                last: w.last.to_string(),
            });
        }
    }
    // Sample times of the matched epochs (those with a time offset).
    let sample_times: Vec<f64> = d_epoch
        .iter()
        .zip(&t_est)
        .filter_map(|(d, &t)| Some(t - (*d)?))
        .collect();

    let mut matched: Vec<Matched> = Vec::new();
    let mut with_code: BTreeMap<SatId, bool> = BTreeMap::new();
    for (k, e) in estimate.epochs.iter().enumerate() {
        for s in &e.sats {
            let seen = with_code.entry(s.sat).or_insert(false);
            let (Some(d), Some(tr)) = (d_epoch[k], truth_sats.get(&s.sat)) else {
                continue;
            };
            let at = t_est[k] - d;
            let m = Matched {
                epoch: k,
                est: *s,
                pseudorange_m: tr.pseudorange.at(at, max_span_s),
                phase_cycles: tr.phase.at(at, max_span_s),
                doppler_hz: tr.doppler.at(at, max_span_s),
                cn0_dbhz: tr.cn0.at(at, max_span_s),
            };
            *seen |= m.pseudorange_m.is_some() && s.pseudorange_m.is_some();
            matched.push(m);
        }
    }
    let matched_epochs = sample_times.len();
    if matched_epochs == 0 {
        return Err(no_overlap());
    }
    let satellites_without_truth = with_code
        .iter()
        .filter(|&(sat, &ok)| {
            !ok && estimate.epochs.iter().any(|e| {
                e.sats
                    .iter()
                    .any(|s| s.sat == *sat && s.pseudorange_m.is_some())
            })
        })
        .map(|(sat, _)| *sat)
        .collect();

    let n_epochs = estimate.epochs.len();
    let (carrier_phase_m, arcs) = phase_errors(&matched, estimate);
    let pseudorange_m = satellite_fixed_effects(&matched, n_epochs, |m| {
        Some(m.est.pseudorange_m? - m.pseudorange_m?)
    });
    let tag_error = tag_error(&matched, &pseudorange_m);
    Ok(ObsComparison {
        estimate: estimate.source.clone(),
        truth: truth.source.clone(),
        estimate_epochs: estimate.epochs.len(),
        matched_epochs,
        sample_span: SampleSpan {
            first: t_ref + Duration::from_seconds(sample_times[0]),
            last: t_ref + Duration::from_seconds(sample_times[sample_times.len() - 1]),
        },
        time_offset_s: ErrorStats::of(&d_epoch.iter().flatten().copied().collect::<Vec<_>>()),
        tag_error,
        pseudorange_m,
        carrier_phase_m,
        doppler_hz: satellite_fixed_effects(&matched, n_epochs, |m| {
            Some(m.est.doppler_hz? - m.doppler_hz?)
        }),
        cn0_dbhz: plain_errors(&matched, |m| Some(m.est.cn0_dbhz? - m.cn0_dbhz?)),
        arcs,
        satellites_without_truth,
    })
}

/// One comparison of [`compare_signals`]: one signal per system.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SignalComparison {
    #[serde(serialize_with = "signal_tags")]
    pub signals: Vec<Signal>,
    #[serde(flatten)]
    pub comparison: ObsComparison,
}

impl SignalComparison {
    /// The compared signal of `system`, if it has one here.
    pub fn signal_of(&self, system: System) -> Option<Signal> {
        self.signals.iter().copied().find(|s| s.system() == system)
    }
}

fn signal_tags<S: Serializer>(s: &[Signal], ser: S) -> Result<S::Ok, S::Error> {
    ser.collect_seq(s.iter().map(|s| s.tag()))
}

/// `signals`' tags joined by `", "`.
fn tags<'a>(signals: impl Iterator<Item = &'a Signal>) -> String {
    signals.map(|s| s.tag()).collect::<Vec<_>>().join(", ")
}

/// A system with more than one of `signals`.
fn several_of_one_system(signals: &[Signal]) -> Option<System> {
    signals
        .iter()
        .map(|s| s.system())
        .find(|&sys| signals.iter().filter(|s| s.system() == sys).count() > 1)
}

/// `estimate` compared with [`compare_with`] in layers of one signal per system: the
/// first signal of each system (in [`Signal`] order) together, then the second, and so
/// on; one comparison when every system has one signal.
pub fn compare_signals(
    estimate: &ObsFile,
    truth: &ObsFile,
    opts: &CompareOptions,
) -> Result<Vec<SignalComparison>, ObsError> {
    let signals = estimate.signals();
    let mut layers: Vec<Vec<Signal>> = Vec::new();
    for signal in signals {
        match layers
            .iter_mut()
            .find(|l| l.iter().all(|s| s.system() != signal.system()))
        {
            Some(layer) => layer.push(signal),
            None => layers.push(vec![signal]),
        }
    }
    if layers.is_empty() {
        return compare_with(estimate, truth, opts).map(|_| Vec::new());
    }
    layers
        .into_iter()
        .map(|signals| {
            let comparison = compare_with(&estimate.of_signals(&signals), truth, opts)?;
            Ok(SignalComparison {
                signals,
                comparison,
            })
        })
        .collect()
}

/// `first .. last` time tags of `f`, for messages.
fn span(f: &ObsFile) -> String {
    match (f.epochs.first(), f.epochs.last()) {
        (Some(a), Some(b)) => format!("{} .. {}", a.time, b.time),
        _ => "no epochs".to_string(),
    }
}

/// Median spacing of `f`'s epochs (s); 1 s for fewer than two epochs.
fn nominal_interval_s(f: &ObsFile) -> f64 {
    let mut dt: Vec<f64> = f
        .epochs
        .windows(2)
        .map(|w| (w[1].time - w[0].time).to_seconds())
        .filter(|&d| d > 0.0)
        .collect();
    if dt.is_empty() {
        return 1.0;
    }
    dt.sort_by(f64::total_cmp);
    dt[dt.len() / 2]
}

fn median(v: &mut [f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// The time offset `d` of one estimate epoch tagged `t_s` (see the module documentation),
/// starting from `d0`; `None` without a pseudorange that the truth covers.
fn time_offset(
    sats: &[ObsRecord],
    truth: &BTreeMap<SatId, TruthSat>,
    t_s: f64,
    d0: f64,
    max_span_s: f64,
) -> Option<f64> {
    let try_from = |start: f64| {
        let mut d = start;
        for _ in 0..TIME_OFFSET_ITERATIONS {
            let mut diffs: Vec<f64> = sats
                .iter()
                .filter_map(|s| {
                    let pr = truth.get(&s.sat)?.pseudorange.at(t_s - d, max_span_s)?;
                    Some(s.pseudorange_m? - pr)
                })
                .collect();
            let next = median(&mut diffs)? / C_MPS;
            let done = (next - d).abs() < TIME_OFFSET_TOLERANCE_S;
            d = next;
            if done {
                return Some(d);
            }
        }
        Some(d)
    };
    // From the previous epoch's offset, else from the tag itself.
    try_from(d0).or_else(|| try_from(0.0))
}

/// The [`TagError`] regression.
fn tag_error(matched: &[Matched], code: &ObservableErrors) -> Option<TagError> {
    // (system, lambda * mean truth Doppler, bias) per satellite.
    let mut points: Vec<(System, f64, f64)> = Vec::new();
    for s in &code.per_satellite {
        let Some(bias) = s.stats.mean else { continue };
        let dop: Vec<f64> = matched
            .iter()
            .filter(|m| m.est.sat == s.sat)
            .filter_map(|m| Some(m.doppler_hz? * m.est.signal.wavelength_m()))
            .collect();
        if !dop.is_empty() {
            points.push((
                s.sat.system,
                dop.iter().sum::<f64>() / dop.len() as f64,
                bias,
            ));
        }
    }
    let systems: Vec<System> = points.iter().map(|p| p.0).collect();
    let mut centred: Vec<(f64, f64)> = Vec::new();
    for sys in [System::Gps, System::Beidou, System::Galileo] {
        let of: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.0 == sys)
            .map(|p| (p.1, p.2))
            .collect();
        let n = of.len() as f64;
        let (mx, my) = of
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
        centred.extend(of.iter().map(|p| (p.0 - mx, p.1 - my)));
    }
    let n_systems = [System::Gps, System::Beidou, System::Galileo]
        .iter()
        .filter(|s| systems.contains(s))
        .count();
    let dof = centred
        .len()
        .checked_sub(n_systems + 1)
        .filter(|&d| d > 0)?;
    let sxx: f64 = centred.iter().map(|p| p.0 * p.0).sum();
    if sxx <= 0.0 {
        return None;
    }
    let delta = centred.iter().map(|p| p.0 * p.1).sum::<f64>() / sxx;
    let ssr: f64 = centred.iter().map(|p| (p.1 - delta * p.0).powi(2)).sum();
    Some(TagError {
        delta_s: delta,
        std_error_s: (ssr / dof as f64 / sxx).sqrt(),
        satellites: centred.len(),
    })
}

/// Satellite index of every satellite in `matched`, per system.
fn systems_of(matched: &[Matched]) -> BTreeMap<System, Vec<SatId>> {
    let mut out: BTreeMap<System, Vec<SatId>> = BTreeMap::new();
    for m in matched {
        let v = out.entry(m.est.sat.system).or_default();
        if !v.contains(&m.est.sat) {
            v.push(m.est.sat);
        }
    }
    for v in out.values_mut() {
        v.sort();
    }
    out
}

/// Pooled overall statistics of per-system fits: `sqrt(sum SSR / sum dof)`.
fn pooled_fits(fits: &[(usize, Option<f64>, usize)]) -> ErrorStats {
    let count = fits.iter().map(|f| f.0).sum();
    let (ss, dof) = fits.iter().fold((0.0, 0usize), |(ss, d), &(_, std, dof)| {
        (ss + std.map_or(0.0, |s| s * s * dof as f64), d + dof)
    });
    ErrorStats {
        count,
        mean: None,
        std: (dof > 0).then(|| (ss / dof as f64).sqrt()),
    }
}

/// Errors with a satellite bias and an epoch term, per system (pseudorange, Doppler).
fn satellite_fixed_effects(
    matched: &[Matched],
    n_epochs: usize,
    error: impl Fn(&Matched) -> Option<f64>,
) -> ObservableErrors {
    let mut per_system = Vec::new();
    let mut per_satellite = Vec::new();
    let mut fits = Vec::new();
    for (system, sats) in systems_of(matched) {
        let samples: Vec<Sample> = matched
            .iter()
            .filter(|m| m.est.sat.system == system)
            .filter_map(|m| {
                Some(Sample {
                    group: sats.binary_search(&m.est.sat).ok()?,
                    epoch: m.epoch,
                    value: error(m)?,
                })
            })
            .collect();
        if samples.is_empty() {
            continue;
        }
        let Some(fit) = fixed_effects::fit(&samples, sats.len(), n_epochs) else {
            continue;
        };
        let means = centred_offsets(&fit, &samples, sats.len());
        for (g, sat) in sats.iter().enumerate() {
            let count = samples.iter().filter(|s| s.group == g).count();
            if count > 0 {
                per_satellite.push(SatErrors {
                    sat: *sat,
                    stats: ErrorStats {
                        count,
                        mean: Some(means[g]),
                        std: fit.std_of(&samples, |x| x == g),
                    },
                });
            }
        }
        let stats = ErrorStats {
            count: samples.len(),
            mean: None,
            std: fit.std(),
        };
        fits.push((samples.len(), fit.std(), fit.dof));
        per_system.push(SystemErrors { system, stats });
    }
    ObservableErrors {
        overall: pooled_fits(&fits),
        per_system,
        per_satellite,
    }
}

/// Group offsets with the count-weighted mean of each connected set removed.
fn centred_offsets(fit: &Fit, samples: &[Sample], n_groups: usize) -> Vec<f64> {
    let mut count = vec![0usize; n_groups];
    for s in samples {
        count[s.group] += 1;
    }
    let n_sets = fit.set_reference.len();
    let (mut sum, mut n) = (vec![0.0; n_sets], vec![0usize; n_sets]);
    for g in (0..n_groups).filter(|&g| count[g] > 0) {
        let s = fit.group_set[g];
        sum[s] += count[g] as f64 * fit.group_offset[g];
        n[s] += count[g];
    }
    (0..n_groups)
        .map(|g| match fit.group_set[g] {
            usize::MAX => f64::NAN,
            s => fit.group_offset[g] - sum[s] / n[s] as f64,
        })
        .collect()
}

/// Errors with neither a satellite nor an epoch term removed (C/N0).
fn plain_errors(matched: &[Matched], error: impl Fn(&Matched) -> Option<f64>) -> ObservableErrors {
    let mut per_system = Vec::new();
    let mut per_satellite = Vec::new();
    let mut all = Vec::new();
    for (system, sats) in systems_of(matched) {
        let mut in_system = Vec::new();
        for sat in sats {
            let v: Vec<f64> = matched
                .iter()
                .filter(|m| m.est.sat == sat)
                .filter_map(&error)
                .collect();
            if !v.is_empty() {
                per_satellite.push(SatErrors {
                    sat,
                    stats: ErrorStats::of(&v),
                });
            }
            in_system.extend(v);
        }
        per_system.push(SystemErrors {
            system,
            stats: ErrorStats::of(&in_system),
        });
        all.extend(in_system);
    }
    ObservableErrors {
        overall: ErrorStats::of(&all),
        per_system,
        per_satellite,
    }
}

/// Carrier-phase errors (m) with arc offsets and epoch terms removed, per system, and the
/// arcs.
fn phase_errors(matched: &[Matched], estimate: &ObsFile) -> (ObservableErrors, Vec<PhaseArc>) {
    let mut per_system = Vec::new();
    let mut per_satellite = Vec::new();
    let mut arcs_out = Vec::new();
    let mut fits = Vec::new();
    let n_epochs = estimate.epochs.len();
    for (system, sats) in systems_of(matched) {
        // Arcs: (sat, first epoch, last epoch, half-cycle flag); samples in metres.
        let mut arcs: Vec<(SatId, usize, usize, bool)> = Vec::new();
        let mut open: BTreeMap<SatId, usize> = BTreeMap::new();
        let mut samples = Vec::new();
        let mut lambda = 0.0;
        for m in matched.iter().filter(|m| m.est.sat.system == system) {
            let (Some(est), Some(tru)) = (m.est.carrier_phase_cycles, m.phase_cycles) else {
                continue;
            };
            lambda = m.est.signal.wavelength_m();
            let continues = open
                .get(&m.est.sat)
                .copied()
                .filter(|&a| arcs[a].2 + 1 == m.epoch && m.est.phase_lli & LLI_LOSS_OF_LOCK == 0);
            let arc = match continues {
                Some(a) => a,
                None => {
                    arcs.push((m.est.sat, m.epoch, m.epoch, false));
                    open.insert(m.est.sat, arcs.len() - 1);
                    arcs.len() - 1
                }
            };
            arcs[arc].2 = m.epoch;
            arcs[arc].3 |= m.est.phase_lli & LLI_HALF_CYCLE != 0;
            samples.push(Sample {
                group: arc,
                epoch: m.epoch,
                value: (est - tru) * lambda,
            });
        }
        if samples.is_empty() {
            continue;
        }
        let Some(fit) = fixed_effects::fit(&samples, arcs.len(), n_epochs) else {
            continue;
        };
        for (a, &(sat, first, _, half)) in arcs.iter().enumerate() {
            let offset_cycles = fit.group_offset[a] / lambda;
            let off = offset_cycles - (2.0 * offset_cycles).round() / 2.0;
            arcs_out.push(PhaseArc {
                sat,
                start: estimate.epochs[first].time,
                epochs: samples.iter().filter(|s| s.group == a).count(),
                offset_cycles,
                reference: fit.set_reference.contains(&a),
                off_half_cycle_grid: off,
                integer_like: off.abs() <= INTEGER_TOLERANCE_CYCLES,
                half_cycle_flag: half,
            });
        }
        for sat in sats {
            let of_sat = |g: usize| arcs[g].0 == sat;
            let count = samples.iter().filter(|s| of_sat(s.group)).count();
            if count > 0 {
                per_satellite.push(SatErrors {
                    sat,
                    stats: ErrorStats {
                        count,
                        mean: None,
                        std: fit.std_of(&samples, of_sat),
                    },
                });
            }
        }
        fits.push((samples.len(), fit.std(), fit.dof));
        per_system.push(SystemErrors {
            system,
            stats: ErrorStats {
                count: samples.len(),
                mean: None,
                std: fit.std(),
            },
        });
    }
    let errors = ObservableErrors {
        overall: pooled_fits(&fits),
        per_system,
        per_satellite,
    };
    (errors, arcs_out)
}
