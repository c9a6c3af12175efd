//! Zero-baseline double differences (thesis section 5.4, table 5.4-2): two receivers (or
//! two channels) fed the same antenna signal, on one oscillator. The between-receiver
//! single difference `SD_i = obs_A,i - obs_B,i` removes everything of the signal (range,
//! satellite clock, atmosphere) and leaves the receivers' clock difference, their
//! inter-channel biases and their independent noise; the double difference
//! `DD_i = SD_i - SD_ref` against a reference satellite of the same system removes the
//! clock difference. For independent noise of std `sigma` in each of the four terms,
//! `std(DD) = 2 sigma`.
//!
//! - Epochs of A and B are paired when their tags differ by at most
//!   [`DdOptions::max_tag_difference_s`]; B's observations are moved to A's tag with B's
//!   Doppler (`dPR/dt = -lambda D`, `dphi/dt = -D`, RINEX signs), so a tag difference does
//!   not leave `(rho_dot_i - rho_dot_ref) dt` in the double differences.
//! - Reference satellite per system: the satellite with code and phase single differences
//!   in the most common epochs (ties: the lowest PRN). An observation file carries no
//!   elevation; over a short run the satellite seen longest is usually a high one, and
//!   choosing it keeps the most double differences. Epochs without the reference give no
//!   double differences.
//! - Pseudorange DD (m): mean and std (n - 1) per satellite pair.
//! - Carrier-phase DD: per arc (split at a loss-of-lock indicator of any of the four
//!   phases or a missing epoch) the integer nearest the arc's mean (cycles) is removed and
//!   the rest converted to metres; per pair `mean` is the count-weighted mean of what the
//!   integers leave (a fractional or half-cycle bias shows here) and `std` the pooled
//!   within-arc std (each arc's own mean removed, so a receiver whose ambiguities are not
//!   integers still gets its noise measured).
//! - Per system: the pairs pooled ([`ErrorStats::pooled`]), and the standard error of
//!   each pooled mean from batch means ([`mean_standard_error`]): the pairs share the reference
//!   satellite and the loop noise is correlated over seconds, so the double differences are
//!   not independent samples and `std / sqrt(count)` would be far too small.

use super::ObsError;
use super::error_stats::{ErrorStats, display};
use crate::stats::batch_means_standard_error;
use hifitime::Epoch;
use serde::{Serialize, Serializer};
use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsFile, ObsRecord};
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Settings of [`zero_baseline_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DdOptions {
    /// Largest time-tag difference (s) for which an epoch of A and one of B are the same.
    pub max_tag_difference_s: f64,
}

impl Default for DdOptions {
    /// 1 us: receivers on one oscillator tag the same samples identically; anything above
    /// a microsecond is a different epoch.
    fn default() -> Self {
        Self {
            max_tag_difference_s: 1e-6,
        }
    }
}

/// One continuous carrier-phase double-difference arc.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DdArc {
    /// Time tag (receiver A) of the arc's first epoch.
    #[serde(serialize_with = "display")]
    pub start: Epoch,
    pub epochs: usize,
    /// The integer removed (cycles).
    pub integer_cycles: f64,
    /// The arc's mean minus that integer (cycles).
    pub fraction_cycles: f64,
}

/// The double differences of one satellite against the reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairDd {
    #[serde(serialize_with = "display")]
    pub sat: SatId,
    #[serde(serialize_with = "display")]
    pub reference: SatId,
    pub pseudorange_m: ErrorStats,
    pub carrier_phase_m: ErrorStats,
    pub arcs: Vec<DdArc>,
    /// Per common epoch (index): the code DD (m), and the phase DD less its arc's integer
    /// (m), for the system's batch means.
    #[serde(skip)]
    by_epoch: [Vec<(usize, f64)>; 2],
}

/// The double differences of one system.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SystemDd {
    #[serde(serialize_with = "system_name")]
    pub system: System,
    #[serde(serialize_with = "display")]
    pub reference: SatId,
    /// The pairs pooled.
    pub pseudorange_m: ErrorStats,
    pub carrier_phase_m: ErrorStats,
    /// The standard errors of the two pooled means (m) by batch means.
    pub pseudorange_mean_se_m: Option<f64>,
    pub carrier_phase_mean_se_m: Option<f64>,
    pub pairs: Vec<PairDd>,
}

/// Epochs per batch of [`mean_standard_error`].
// assumed: 10 epochs (10 s at 1 Hz), fixed before any run over seeds: ten times the
// correlation time of the default code loop (about 1 / (4 x 0.25 Hz) = 1 s), so batch
// means are nearly independent, while a 60 s run still gives five batches.
pub const BATCH_EPOCHS: usize = 10;

/// The standard error of a mean of double differences that are correlated across pairs
/// (one reference) and over time (loop noise): average the pairs at each epoch, average
/// those over consecutive batches of [`BATCH_EPOCHS`] epochs, and take the spread of the
/// batch means, `std(batch means) / sqrt(batches)`; `None` with fewer than two batches.
/// `values`: (common-epoch index, value) of every pair.
pub fn mean_standard_error(values: impl IntoIterator<Item = (usize, f64)>) -> Option<f64> {
    let mut per_epoch: BTreeMap<usize, (f64, usize)> = BTreeMap::new();
    for (k, v) in values {
        let e = per_epoch.entry(k).or_default();
        *e = (e.0 + v, e.1 + 1);
    }
    batch_means_standard_error(
        per_epoch
            .into_iter()
            .map(|(k, (sum, n))| (k, sum / n as f64)),
        BATCH_EPOCHS,
    )
}

/// The result of [`zero_baseline`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZeroBaseline {
    pub receiver_a: PathBuf,
    pub receiver_b: PathBuf,
    /// Epochs of A paired with an epoch of B.
    pub common_epochs: usize,
    /// Largest |tag A - tag B| among them (s).
    pub max_tag_difference_s: f64,
    pub systems: Vec<SystemDd>,
}

impl ZeroBaseline {
    /// The double differences of `system`, if it has any.
    pub fn system(&self, system: System) -> Option<&SystemDd> {
        self.systems.iter().find(|s| s.system == system)
    }
}

fn system_name<S: Serializer>(s: &System, ser: S) -> Result<S::Ok, S::Error> {
    ser.serialize_str(s.name())
}

/// Between-receiver single differences of one satellite at one common epoch.
#[derive(Debug, Clone, Copy)]
struct Sd {
    code_m: Option<f64>,
    phase_cycles: Option<f64>,
    /// A loss of lock in either receiver's phase.
    slip: bool,
}

/// [`zero_baseline_with`] with the default options.
pub fn zero_baseline(a: &ObsFile, b: &ObsFile) -> Result<ZeroBaseline, ObsError> {
    zero_baseline_with(a, b, &DdOptions::default())
}

/// Double differences of receivers `a` and `b` (see the module documentation).
pub fn zero_baseline_with(
    a: &ObsFile,
    b: &ObsFile,
    opts: &DdOptions,
) -> Result<ZeroBaseline, ObsError> {
    // Pair epochs (both lists are in time order).
    let mut common: Vec<(usize, usize, f64)> = Vec::new();
    let mut j = 0;
    for (i, ea) in a.epochs.iter().enumerate() {
        while j < b.epochs.len()
            && (ea.time - b.epochs[j].time).to_seconds() > opts.max_tag_difference_s
        {
            j += 1;
        }
        if let Some(eb) = b.epochs.get(j) {
            let dt = (ea.time - eb.time).to_seconds();
            if dt.abs() <= opts.max_tag_difference_s {
                common.push((i, j, dt));
                j += 1;
            }
        }
    }
    if common.is_empty() {
        return Err(ObsError::NoCommonEpoch {
            tolerance_s: opts.max_tag_difference_s,
        });
    }
    // Single differences per common epoch.
    let sds: Vec<BTreeMap<SatId, Sd>> = common
        .iter()
        .map(|&(i, j, dt)| {
            a.epochs[i]
                .sats
                .iter()
                .filter_map(|sa| {
                    let sb = b.epochs[j].sats.iter().find(|s| s.sat == sa.sat)?;
                    (sb.signal == sa.signal).then(|| (sa.sat, single_difference(sa, sb, dt)))
                })
                .collect()
        })
        .collect();
    let mut by_system: BTreeMap<System, BTreeMap<SatId, usize>> = BTreeMap::new();
    for epoch in &sds {
        for (sat, sd) in epoch {
            let n = by_system
                .entry(sat.system)
                .or_default()
                .entry(*sat)
                .or_default();
            *n += usize::from(sd.code_m.is_some() && sd.phase_cycles.is_some());
        }
    }
    let mut systems = Vec::new();
    for (system, counts) in by_system {
        // Most epochs first, then the lowest PRN (BTreeMap order).
        let Some((&reference, _)) = counts
            .iter()
            .rev()
            .max_by_key(|&(_, &n)| n)
            .filter(|&(_, &n)| n > 0)
        else {
            continue;
        };
        let lambda = wavelength(a, reference);
        let pairs: Vec<PairDd> = counts
            .keys()
            .filter(|&&s| s != reference)
            .map(|&sat| pair(&sds, &common, a, sat, reference, lambda))
            .filter(|p| p.pseudorange_m.count > 0 || p.carrier_phase_m.count > 0)
            .collect();
        if pairs.is_empty() {
            continue;
        }
        let code: Vec<ErrorStats> = pairs.iter().map(|p| p.pseudorange_m).collect();
        let phase: Vec<ErrorStats> = pairs.iter().map(|p| p.carrier_phase_m).collect();
        let all = |i: usize| {
            pairs
                .iter()
                .flat_map(move |p| p.by_epoch[i].iter().copied())
        };
        systems.push(SystemDd {
            system,
            reference,
            pseudorange_m: ErrorStats::pooled(&code),
            carrier_phase_m: ErrorStats::pooled(&phase),
            pseudorange_mean_se_m: mean_standard_error(all(0)),
            carrier_phase_mean_se_m: mean_standard_error(all(1)),
            pairs,
        });
    }
    Ok(ZeroBaseline {
        receiver_a: a.source.clone(),
        receiver_b: b.source.clone(),
        common_epochs: common.len(),
        max_tag_difference_s: common.iter().fold(0.0, |m, c| f64::max(m, c.2.abs())),
        systems,
    })
}

/// Carrier wavelength (m) of `sat`'s signal in `f`.
fn wavelength(f: &ObsFile, sat: SatId) -> f64 {
    let signal = f
        .epochs
        .iter()
        .flat_map(|e| &e.sats)
        .find(|s| s.sat == sat)
        .map(|s| s.signal);
    signal.map_or(f64::NAN, |s| s.wavelength_m())
}

/// `a - b`, with `b` moved from its tag to `a`'s (`dt = tag_a - tag_b`) by its Doppler.
fn single_difference(a: &ObsRecord, b: &ObsRecord, dt: f64) -> Sd {
    let lambda = a.signal.wavelength_m();
    let phase_rate = b.doppler_hz.map_or(0.0, |d| -d);
    Sd {
        code_m: a
            .pseudorange_m
            .zip(b.pseudorange_m)
            .map(|(pa, pb)| pa - (pb + lambda * phase_rate * dt)),
        phase_cycles: a
            .carrier_phase_cycles
            .zip(b.carrier_phase_cycles)
            .map(|(pa, pb)| pa - (pb + phase_rate * dt)),
        slip: (a.phase_lli | b.phase_lli) & LLI_LOSS_OF_LOCK != 0,
    }
}

/// The double differences of `sat` against `reference` over all common epochs.
fn pair(
    sds: &[BTreeMap<SatId, Sd>],
    common: &[(usize, usize, f64)],
    a: &ObsFile,
    sat: SatId,
    reference: SatId,
    lambda: f64,
) -> PairDd {
    let mut code = Vec::new();
    let mut code_by_epoch = Vec::new();
    // Phase arcs: (first common epoch, (epoch, value in cycles)).
    let mut arcs: Vec<(usize, Vec<(usize, f64)>)> = Vec::new();
    let mut last_phase: Option<usize> = None;
    for (k, epoch) in sds.iter().enumerate() {
        let (Some(s), Some(r)) = (epoch.get(&sat), epoch.get(&reference)) else {
            continue;
        };
        if let (Some(cs), Some(cr)) = (s.code_m, r.code_m) {
            code.push(cs - cr);
            code_by_epoch.push((k, cs - cr));
        }
        if let (Some(ps), Some(pr)) = (s.phase_cycles, r.phase_cycles) {
            let continues = last_phase == Some(k.wrapping_sub(1)) && !s.slip && !r.slip;
            if !continues || arcs.is_empty() {
                arcs.push((k, Vec::new()));
            }
            if let Some(arc) = arcs.last_mut() {
                arc.1.push((k, ps - pr));
            }
            last_phase = Some(k);
        }
    }
    let mut arc_out = Vec::new();
    let mut arc_stats = Vec::new();
    let mut phase_by_epoch = Vec::new();
    for (first, cycles) in &arcs {
        let mean = cycles.iter().map(|c| c.1).sum::<f64>() / cycles.len() as f64;
        let n = mean.round();
        let metres: Vec<f64> = cycles.iter().map(|c| (c.1 - n) * lambda).collect();
        phase_by_epoch.extend(cycles.iter().zip(&metres).map(|(c, &m)| (c.0, m)));
        arc_stats.push(ErrorStats::of(&metres));
        arc_out.push(DdArc {
            start: a.epochs[common[*first].0].time,
            epochs: cycles.len(),
            integer_cycles: n,
            fraction_cycles: mean - n,
        });
    }
    PairDd {
        sat,
        reference,
        pseudorange_m: ErrorStats::of(&code),
        carrier_phase_m: ErrorStats::pooled(&arc_stats),
        arcs: arc_out,
        by_epoch: [code_by_epoch, phase_by_epoch],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};

    fn noise(seed: u64, n: usize) -> Vec<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
    }

    #[test]
    fn independent_epochs_give_about_the_naive_standard_error() {
        let v = noise(1, 4000);
        let se = mean_standard_error(v.iter().copied().enumerate()).unwrap();
        let naive = 1.0 / 4000f64.sqrt();
        assert!((se / naive - 1.0).abs() < 0.3, "{se} vs {naive}");
    }

    #[test]
    fn pairs_sharing_the_reference_do_not_count_as_independent() {
        // Eight pairs whose double differences are all the reference's noise: the pooled
        // mean is no better than one pair's, whatever the number of pairs.
        let reference = noise(2, 400);
        let one: Vec<(usize, f64)> = reference.iter().copied().enumerate().collect();
        let eight: Vec<(usize, f64)> = (0..8).flat_map(|_| one.clone()).collect();
        assert_eq!(mean_standard_error(one.clone()), mean_standard_error(eight));
    }

    #[test]
    fn noise_correlated_over_epochs_widens_the_standard_error() {
        // AR(1) with a 5-epoch correlation time: the mean's standard error is about
        // sqrt((1 + a) / (1 - a)) = 3.2 times the naive one.
        let a: f64 = (-1.0f64 / 5.0).exp();
        let w = noise(3, 20_000);
        let mut x = 0.0;
        let series: Vec<(usize, f64)> = w
            .iter()
            .enumerate()
            .map(|(k, e)| {
                x = a * x + (1.0 - a * a).sqrt() * e;
                (k, x)
            })
            .collect();
        let se = mean_standard_error(series.clone()).unwrap();
        let naive = 1.0 / 20_000f64.sqrt();
        assert!(se / naive > 2.0, "{}", se / naive);
        // Too few epochs for two batches: no standard error.
        assert_eq!(
            mean_standard_error(series[..BATCH_EPOCHS].iter().copied()),
            None
        );
    }
}
