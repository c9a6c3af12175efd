//! P1-F2: paper 001 Fig. 2 (`BOOK_PAPER001_TARGETS.md` spec 2, TD-F2). A static receiver
//! near Changsha sees the three BDS-3 GEOs (bundled scenario [`SCENARIO`]); its 10 Hz
//! carrier phase, differenced in time (`navigation::tdcp`), shows the receiver oscillator's
//! frequency offset in every single difference (SD) and not in the time-satellite double
//! difference (DD). The paper prints no number: the SD's clock term is "very obvious", the
//! DD shows "no obvious drift".
//!
//! **Run.** Each seed synthesises the scenario's B1I samples and runs the bundled receiver
//! on them as they are rendered (`skyforge synth --receive`), in its default configuration
//! plus `[observables] rate_hz = 10` (the paper's rate; the observation level has whole
//! seconds only), assisted as `synth` assists it.
//!
//! **Estimator** (truth firewall: nothing of the run's truth): the receiver's observations,
//! the broadcast ephemerides it was given (`nav.rnx`) and the site's surveyed coordinates
//! (the scenario's `[platform.ground]`: a static site's survey is known to its user). Each
//! pair of consecutive epochs is differenced by [`time_differences`] with the antenna at
//! the surveyed point at both epochs, so each satellite's prefit residual is `z_i = c
//! ddt_r + (atmosphere's change) + noise`, and [`TdcpEpoch::double_differences`] (against
//! the highest satellite) cancels `c ddt_r`.
//!
//! **Statistics.** Consecutive pairs share an epoch (lag-1 correlation -1/2), so the mean
//! of all of them telescopes to `(e_N - e_0) / N` and no batch of them is independent of
//! the next. The pairs used are therefore disjoint: epochs `(2j, 2j + 1)` of the file, no
//! epoch in two pairs; white phase noise leaves them independent. Their values (per pair:
//! the SD averaged over the satellites; each DD series apart) are averaged over
//! [`BATCHES`] batches of consecutive pairs (non-overlapping batch means, for the loops'
//! and the atmosphere's slower correlation); the estimate is the mean of the batch means,
//! its standard error their standard deviation over `sqrt(BATCHES)`.
//!
//! **Verdicts** (registered before the first run): on every one of the seeds, the SD mean
//! more than [`SD_BAR_SE`] standard errors from zero and each DD mean within
//! [`DD_BAR_SE`] standard errors of zero. With 30 batches a DD mean of zero exceeds 3
//! standard errors with probability 0.0055 (Student t, 29 degrees of freedom): two DD
//! series on eight seeds make a false deviation about 8 % likely. SkyForge's own row: the
//! SD mean within [`THEORY_TOLERANCE`] (relative) of `c drift dt` on every seed (the
//! ionosphere's change in 0.1 s, below 0.1 mm, and the standard error are far inside it; a
//! wrong wavelength or time tag scale would not be).

use crate::draw::Draw;
use crate::observables::ErrorStats;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::tdcp::{TdcpConfig, TdcpEpoch, time_differences};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_orbits::time::TimeOrigin;
use skyforge_runner::{ObservationRun, signal_run_with};
use skyforge_scenarios::Scenario;
use std::collections::BTreeMap;
use std::ops::Range;

/// Table identifier.
pub const TABLE: &str = "P1-F2";
/// The bundled scenario of this table.
pub const SCENARIO: &str = "paper001-tdcp-static";
/// Registered runs: seeds `FIRST_SEED ..` (assumed: eight, chosen before any run).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 8;
/// Paper 001: BeiDou carrier phase at 10 Hz.
const RATE_HZ: f64 = 10.0;
/// What the receiver is told beside the `[assist]` table `synth` writes.
const RECEIVER_TOML: &str = "[observables]\nrate_hz = 10.0\n";
/// assumed: the first 10 s are left out (acquisition, pull-in, D2 bit sync and the PLL's
/// narrowing all happen in the first seconds of a track).
const SETTLE_S: f64 = 10.0;
/// assumed: 30 batches (10 s each over the 290 s used): each several hundred times the
/// loops' correlation time, enough of them that Student's t at 29 degrees of freedom is
/// near the normal.
pub const BATCHES: usize = 30;
/// TD-F2: the SD mean more than 10 standard errors from zero.
pub const SD_BAR_SE: f64 = 10.0;
/// TD-F2: the DD mean within 3 standard errors of zero.
pub const DD_BAR_SE: f64 = 3.0;
/// assumed: SkyForge's own bar, the SD mean within 0.1 % of `c drift dt` (3 mm of 3 m).
pub const THEORY_TOLERANCE: f64 = 1e-3;

/// The differences: the scenario's B1I; pairs more than one 10 Hz interval apart (a
/// missing epoch) are not used. The phase sigma only weights solutions, which this table
/// does not make; the mask is the scenario's.
fn tdcp_config() -> TdcpConfig {
    TdcpConfig {
        signal: Some(Signal::BdsB1I),
        max_gap_s: 1.5 / RATE_HZ,
        ..TdcpConfig::default()
    }
}

/// A mean and its standard error by non-overlapping batch means.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanSe {
    /// Mean of the batch means (m).
    pub mean_m: f64,
    /// Standard deviation of the batch means over `sqrt(batches)` (m).
    pub standard_error_m: f64,
}

impl MeanSe {
    /// `|mean| / standard error`.
    pub fn t(&self) -> f64 {
        self.mean_m.abs() / self.standard_error_m
    }
}

/// `values` (index of the disjoint pair, value) over `pairs` disjoint pairs, in
/// [`BATCHES`] batches of `pairs / BATCHES` consecutive pairs (the last few pairs left
/// out); `None` when a batch is empty.
pub fn batch_means(values: &[(usize, f64)], pairs: usize) -> Option<MeanSe> {
    let size = pairs / BATCHES;
    if size == 0 {
        return None;
    }
    let mut sums = [(0.0, 0usize); BATCHES];
    for &(j, v) in values.iter().filter(|(j, _)| *j < size * BATCHES) {
        let b = &mut sums[j / size];
        *b = (b.0 + v, b.1 + 1);
    }
    if sums.iter().any(|b| b.1 == 0) {
        return None;
    }
    let means: Vec<f64> = sums.iter().map(|&(s, n)| s / n as f64).collect();
    let stats = ErrorStats::of(&means);
    Some(MeanSe {
        mean_m: stats.mean?,
        standard_error_m: stats.std? / (BATCHES as f64).sqrt(),
    })
}

/// One seed's statistics.
#[derive(Debug, Clone, PartialEq)]
pub struct SeedStats {
    pub seed: u64,
    /// Disjoint pairs after [`SETTLE_S`], and how many of them had every satellite.
    pub pairs: usize,
    pub used: usize,
    /// The SD, averaged over the satellites of each pair.
    pub sd: MeanSe,
    /// Each DD series: (reference, satellite) and its statistics.
    pub dd: Vec<((SatId, SatId), MeanSe)>,
}

/// The antenna's surveyed position: the scenario's ground site (the antenna at the body
/// origin, its surveyed point).
fn surveyed_antenna(scenario: &Scenario) -> Result<Vec3, ValidateError> {
    let fail = |what: &str| ValidateError::Pipeline(format!("{TABLE}: {what}"));
    let ground = (scenario.platform.ground.as_ref()).ok_or_else(|| fail("not a ground site"))?;
    let antenna = scenario
        .antennas
        .first()
        .ok_or_else(|| fail("no antenna"))?;
    if antenna.position_body_m != [0.0; 3] {
        return Err(fail("the antenna is not on the site's surveyed point"));
    }
    match (ground.ecef_m, ground.latitude_deg, ground.longitude_deg) {
        (Some(r), _, _) => Ok(Vec3::from(r)),
        (None, Some(lat), Some(lon)) => Ok(geodetic_to_ecef(&Geodetic::from_degrees(
            lat,
            lon,
            ground.height_m.unwrap_or(0.0),
        ))),
        _ => Err(fail("the site has no coordinates")),
    }
}

/// One seed of `scenario`: synthesised, received at 10 Hz and differenced.
fn seed_stats(scenario: &Scenario, seed: u64) -> Result<SeedStats, ValidateError> {
    let mut scenario = scenario.clone();
    scenario.seed = seed;
    let site = surveyed_antenna(&scenario)?;
    let run = signal_run_with(&scenario, RECEIVER_TOML)
        .map_err(|e| ValidateError::Pipeline(format!("{TABLE} seed {seed}: {e}")))?;
    let satellites = scenario.gnss.beidou.prns.as_ref().map_or(0, Vec::len);
    differenced(&run, site, satellites, seed)
}

/// The statistics of `run`'s first antenna at `site`, pairs with all `satellites` only.
fn differenced(
    run: &ObservationRun,
    site: Vec3,
    satellites: usize,
    seed: u64,
) -> Result<SeedStats, ValidateError> {
    let fail = |what: String| ValidateError::Pipeline(format!("{TABLE} seed {seed}: {what}"));
    let obs = (run.measured.first()).ok_or_else(|| fail("no observations".into()))?;
    let origin = TimeOrigin::new(run.start);
    let store = EphemerisStore::new(run.ephemerides.clone(), &origin);
    let config = tdcp_config();
    let settled: Vec<_> = (obs.epochs.iter())
        .filter(|e| origin.seconds_since_start(e.time) >= SETTLE_S)
        .collect();
    let pairs = settled.len() / 2;
    let mut sd = Vec::new();
    let mut dd: BTreeMap<(SatId, SatId), Vec<(usize, f64)>> = BTreeMap::new();
    for (j, pair) in settled.chunks_exact(2).enumerate() {
        let Ok(epoch) = time_differences(pair[0], pair[1], site, site, &store, &origin, &config)
        else {
            continue;
        };
        if epoch.sats.len() < satellites.max(2) {
            continue;
        }
        sd.push((j, mean_sd(&epoch)));
        let Some(d) = epoch.double_differences() else {
            continue;
        };
        for (sat, z) in d.sats.iter().zip(d.z_m.iter()) {
            dd.entry((d.reference, *sat)).or_default().push((j, *z));
        }
    }
    let short = || {
        fail(format!(
            "{} of {pairs} pairs usable: too few for {BATCHES} batches",
            sd.len()
        ))
    };
    let sd_stats = batch_means(&sd, pairs).ok_or_else(short)?;
    let dd = (dd.into_iter())
        .map(|(key, v)| Ok((key, batch_means(&v, pairs).ok_or_else(short)?)))
        .collect::<Result<Vec<_>, ValidateError>>()?;
    Ok(SeedStats {
        seed,
        pairs,
        used: sd.len(),
        sd: sd_stats,
        dd,
    })
}

/// The pair's single differences averaged over its satellites (m).
fn mean_sd(epoch: &TdcpEpoch) -> f64 {
    epoch.sats.iter().map(|s| s.z_m).sum::<f64>() / epoch.sats.len() as f64
}

/// Every seed of `seeds` on `scenario`, one after the other: a signal-level run keeps the
/// cores busy itself (synthesis and reception side by side, each parallel inside, waiting
/// on each other), and runs side by side on the pool's workers would leave no worker for
/// the synthesis they wait on (as `attitude::seeds` runs signal-level seeds).
pub fn evaluate(scenario: &Scenario, seeds: Range<u64>) -> Result<Vec<SeedStats>, ValidateError> {
    seeds.map(|seed| seed_stats(scenario, seed)).collect()
}

/// `c drift dt`: the receiver clock's change over one 10 Hz interval (m) for the
/// scenario's oscillator (the tags are receiver time: a factor `1 / (1 + drift)`, 3e-7 m,
/// left out).
pub fn theory_m(scenario: &Scenario) -> f64 {
    let drift = scenario
        .errors
        .receiver_clock
        .as_ref()
        .map_or(0.0, |c| c.drift);
    C_MPS * drift / RATE_HZ
}

/// `mean +- se` in mm for each seed.
fn listed(stats: &[SeedStats], pick: impl Fn(&SeedStats) -> Option<MeanSe>) -> String {
    (stats.iter())
        .map(|s| match pick(s) {
            Some(m) => format!(
                "seed {}: {:.4} +- {:.4} mm ({:.1} SE)",
                s.seed,
                m.mean_m * 1e3,
                m.standard_error_m * 1e3,
                m.t()
            ),
            None => format!("seed {}: missing", s.seed),
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The rows of P1-F2 from the seeds' statistics; `theory_m` is `c drift dt`.
pub fn rows_of(stats: &[SeedStats], theory_m: f64) -> Vec<Row> {
    let usage = (stats.iter())
        .map(|s| format!("{}/{}", s.used, s.pairs))
        .collect::<Vec<_>>()
        .join(", ");
    let common = format!(
        "disjoint 0.1 s pairs after {SETTLE_S} s (used/total per seed: {usage}); standard \
         errors by {BATCHES} non-overlapping batch means; antenna at the surveyed site"
    );
    let mut rows = Vec::new();
    let sd_t = stats.iter().map(|s| s.sd.t()).fold(f64::INFINITY, f64::min);
    rows.push(
        Row::measured(
            TABLE,
            "SD TDCP mean (3 GEOs), static receiver",
            "smallest |mean| / standard error over seeds",
            "1",
            None,
            sd_t,
            (
                format!("> {SD_BAR_SE} on every seed"),
                Verdict::from_ok(!stats.is_empty() && sd_t > SD_BAR_SE),
            ),
        )
        .with_note(format!(
            "paper: the clock drift \"very obvious\"; {}; {common}",
            listed(stats, |s| Some(s.sd))
        )),
    );
    let series: Vec<(SatId, SatId)> = stats
        .first()
        .map_or_else(Vec::new, |s| s.dd.iter().map(|(k, _)| *k).collect());
    for key in series {
        let pick = |s: &SeedStats| s.dd.iter().find(|(k, _)| *k == key).map(|(_, m)| *m);
        let worst = (stats.iter())
            .map(|s| pick(s).map_or(f64::INFINITY, |m| m.t()))
            .fold(0.0, f64::max);
        rows.push(
            Row::measured(
                TABLE,
                format!("DD TDCP mean {} - {}, static receiver", key.1, key.0),
                "largest |mean| / standard error over seeds",
                "1",
                None,
                worst,
                (
                    format!("<= {DD_BAR_SE} on every seed"),
                    Verdict::from_ok(worst <= DD_BAR_SE),
                ),
            )
            .with_note(format!(
                "paper: \"no obvious drift\"; reference {} (the highest); {}; {common}",
                key.0,
                listed(stats, pick)
            )),
        );
    }
    let ratios: Vec<f64> = stats.iter().map(|s| s.sd.mean_m / theory_m).collect();
    let worst = ratios
        .iter()
        .copied()
        .max_by(|a, b| (a - 1.0).abs().total_cmp(&(b - 1.0).abs()))
        .unwrap_or(f64::NAN);
    rows.push(
        Row::measured(
            TABLE,
            "SD TDCP mean against c drift dt (SkyForge)",
            "SD mean / (c drift dt), the seed farthest from 1",
            "1",
            None,
            worst,
            (
                format!("within {THEORY_TOLERANCE} of 1 on every seed"),
                Verdict::from_ok((worst - 1.0).abs() <= THEORY_TOLERANCE),
            ),
        )
        .with_note(format!(
            "c drift dt = {theory_m:.6} m; ratios {}; {common}",
            ratios
                .iter()
                .map(|r| format!("{r:.6}"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    );
    rows
}

/// The rows of P1-F2 over `draw`'s seeds.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let scenario = skyforge_scenarios::named(SCENARIO)?;
    let stats = evaluate(&scenario, draw.seeds(FIRST_SEED, RUNS))?;
    Ok(rows_of(&stats, theory_m(&scenario)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batch_means_of_a_known_series() {
        // 60 pairs, 2 per batch: batch b holds b and b + 0.5, mean b + 0.25.
        let values: Vec<(usize, f64)> = (0..60)
            .map(|j| (j, (j / 2) as f64 + 0.5 * (j % 2) as f64))
            .collect();
        let m = batch_means(&values, 61).unwrap();
        assert!((m.mean_m - 14.75).abs() < 1e-12);
        let std = (30.0 * 31.0 / 12.0_f64).sqrt();
        assert!((m.standard_error_m - std / 30f64.sqrt()).abs() < 1e-12);
        assert!(batch_means(&values[..10], 61).is_none());
        assert!(batch_means(&values, 29).is_none());
    }

    /// The row on a short form of its run (two seeds, 60 s instead of eight and 300 s):
    /// every verdict as registered.
    #[test]
    fn a_short_run_shows_the_drift_in_the_sd_and_not_in_the_dd() {
        let mut scenario = skyforge_scenarios::named(SCENARIO).unwrap();
        scenario.time.duration_s = 60.0;
        let stats = evaluate(&scenario, 1..3).unwrap();
        let rows = rows_of(&stats, theory_m(&scenario));
        for r in &rows {
            println!("{} {:?} {:?} {}", r.row, r.ours, r.verdict, r.note);
        }
        assert_eq!(rows.len(), 4, "{rows:#?}");
        assert!((theory_m(&scenario) - 2.99792458).abs() < 1e-9);
        for r in &rows {
            assert_eq!(r.verdict, Verdict::Reproduced, "{r:#?}");
        }
    }
}
