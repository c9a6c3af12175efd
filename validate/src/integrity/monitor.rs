//! Thresholds from fault-free runs, and the paper's fault cases as patterns (table group
//! P2-4.2).

use super::lab::{Case, MonitoredRun, monitored, scenario};
use rayon::prelude::*;
use skyforge_gnss::observation::ObsFile;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::integrity::run_files;
use skyforge_navigation::integrity::{
    MonitorConfig, MonitorEpoch, SatelliteEpoch, SigmaCalibrator, SigmaTable, Station, Statistic,
    ThresholdConfig, Unmonitored,
};
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_scenarios::Scenario;
use std::collections::BTreeMap;

/// Lower edges of the threshold table's elevation bins (deg). # assumed: finer where the
/// noise changes fastest, chosen before any run.
pub const ELEVATION_BINS_DEG: [f64; 6] = [10.0, 15.0, 20.0, 30.0, 45.0, 60.0];
/// Probability that one fault-free B value exceeds its threshold. # assumed: 1e-7 per
/// test, the order of the per-monitor false-alarm budgets of GBAS ground facilities;
/// about 4e5 tests per 1800 s run make 0.04 expected false alarms per run for normal
/// B values. Chosen before any run.
pub const FALSE_ALARM: f64 = 1e-7;
/// Paper 002 section 4.2.3: the smoothed-pseudorange B-value threshold (m).
pub const SMOOTHED_THRESHOLD_M: f64 = 0.5;
/// Seeds of the fault-free calibration runs. # assumed: eight 1800 s runs, seeds
/// 1..=8, apart from every evaluation seed; chosen before any run.
pub const CALIBRATION_SEEDS: std::ops::RangeInclusive<u64> = 1..=8;

/// A monitor configuration with `sigma` (the defaults of docs/integrity.md otherwise).
pub fn config(sigma: Sigmas) -> MonitorConfig {
    MonitorConfig::new(ThresholdConfig {
        false_alarm: FALSE_ALARM,
        smoothed_code_m: SMOOTHED_THRESHOLD_M,
        sigma,
        sigma_geo: Sigmas::new(),
    })
}

/// Sigma tables by signal tag.
pub type Sigmas = BTreeMap<String, SigmaTable>;

/// Placeholder sigma tables for runs whose alarms are not used (calibration).
fn unit_sigma() -> Sigmas {
    let ones = vec![1.0; ELEVATION_BINS_DEG.len()];
    let table = SigmaTable {
        elevation_deg: ELEVATION_BINS_DEG.to_vec(),
        code_m: ones.clone(),
        smoothed_code_m: ones.clone(),
        carrier_cycles: ones.clone(),
        divergence_mps: ones,
    };
    Signal::DEFAULT_FIX
        .iter()
        .map(|s| (s.tag().to_string(), table.clone()))
        .collect()
}

/// Feed the armed B values of `epochs` to `cal`.
pub fn accumulate(cal: &mut SigmaCalibrator, epochs: &[MonitorEpoch]) {
    for s in epochs.iter().flat_map(|e| &e.sats) {
        accumulate_satellite(cal, s);
    }
}

/// Feed the armed B values of one satellite's epoch to `cal`.
fn accumulate_satellite(cal: &mut SigmaCalibrator, s: &SatelliteEpoch) {
    for v in s.stations.iter().flatten() {
        for stat in Statistic::ALL {
            if s.armed[stat.index()] {
                cal.add(s.signal, stat, s.elevation_deg, v.b[stat.index()]);
            }
        }
    }
}

/// A configuration calibrated on files, and how many B values each of its sigma bins
/// rests on (per table name, `sigma.<tag>` or `sigma_geo.<tag>`; the fewest over the
/// statistics).
#[derive(Debug, Clone)]
pub struct FilesCalibration {
    pub config: MonitorConfig,
    pub values_per_bin: BTreeMap<String, Vec<u64>>,
}

/// The fault-free sigma tables of one run recorded in `files` (one per station of
/// `stations`): what a ground facility measures on its own fault-free data, and what the
/// signal-level reference uses, where the receivers' observables carry errors the
/// observation level does not model (docs/integrity.md). The result is `base` (stations,
/// common point, time constants, false-alarm probability, the smoothed code's floor) with
/// the measured sigma tables; with `geo_apart` the BeiDou GEOs get tables of their own
/// (`sigma_geo`) and the others' leave them out. A signal whose tracks never last long
/// enough to test every statistic is an error: its satellites would go unmonitored.
pub fn calibrate_files(
    files: &[ObsFile],
    stations: Vec<Station>,
    ephemerides: Vec<BroadcastEphemeris>,
    base: &MonitorConfig,
    geo_apart: bool,
) -> Result<FilesCalibration, String> {
    let mut measuring = base.clone();
    measuring.thresholds.sigma = unit_sigma();
    measuring.thresholds.sigma_geo = Sigmas::new();
    let mut common = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
    let mut geo = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
    run_files(files, stations, ephemerides, measuring, |e| {
        for s in &e.sats {
            let cal = if geo_apart && s.geo {
                &mut geo
            } else {
                &mut common
            };
            accumulate_satellite(cal, s);
        }
    })
    .map_err(|e| e.to_string())?;
    let (sigma, mut values_per_bin) = complete_tables(&common, "sigma", "any satellite", base)?;
    let mut config = base.clone();
    config.thresholds.sigma = sigma;
    config.thresholds.sigma_geo = Sigmas::new();
    if geo_apart {
        let (sigma_geo, counts) =
            complete_tables(&geo, "sigma_geo", "a BeiDou GEO (--geo-apart)", base)?;
        config.thresholds.sigma_geo = sigma_geo;
        values_per_bin.extend(counts);
    }
    Ok(FilesCalibration {
        config,
        values_per_bin,
    })
}

/// The tables of `cal` (named `key`, calibrated on `what`), and the values per bin of
/// each; an error when a signal lacks a statistic or no signal has any values.
fn complete_tables(
    cal: &SigmaCalibrator,
    key: &str,
    what: &str,
    base: &MonitorConfig,
) -> Result<(Sigmas, BTreeMap<String, Vec<u64>>), String> {
    let incomplete: Vec<&str> = cal.incomplete().iter().map(|s| s.tag()).collect();
    let sigma = cal.tables();
    if !incomplete.is_empty() || sigma.is_empty() {
        let short = format!(
            "every statistic needs fault-free values, and the divergence is tested only once \
             a track is smoothing_s + divergence_s = {} s old; give files whose tracks last \
             longer",
            base.smoothing_s + base.divergence_s
        );
        return Err(if incomplete.is_empty() {
            format!("cannot calibrate {key}: the files hold no B values of {what}; {short}")
        } else {
            format!(
                "cannot calibrate {key} of {}: {short}",
                incomplete.join(", ")
            )
        });
    }
    let counts = Signal::ALL
        .iter()
        .filter(|s| sigma.contains_key(s.tag()))
        .map(|&s| (format!("{key}.{}", s.tag()), cal.counts(s)))
        .collect();
    Ok((sigma, counts))
}

/// The fault-free sigma tables of `scenario` (observation level, without fault events)
/// over `seeds` (runs in parallel).
pub fn calibrate(
    scenario: &Scenario,
    seeds: impl IntoParallelIterator<Item = u64>,
) -> Result<Sigmas, String> {
    if !scenario.errors.events.is_empty() {
        return Err(format!(
            "{}: has fault events ([[errors.events]]); calibrate on the fault-free set-up",
            scenario.name
        ));
    }
    let cal = seeds
        .into_par_iter()
        .map(|seed| {
            let mut s = scenario.clone();
            s.seed = seed;
            let run = monitored(&s, &config(unit_sigma()))?;
            let mut cal = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
            accumulate(&mut cal, &run.epochs);
            Ok((cal, run.epochs.len(), run.unmonitored))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let mut all = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
    let (mut epochs, mut unmonitored) = (0, Unmonitored::default());
    for (c, n, u) in &cal {
        all.merge(c);
        epochs += n;
        unmonitored.add(u);
    }
    let tables = all.tables();
    if tables.is_empty() {
        let why = unmonitored.describe(
            "the scenario's constellation",
            config(unit_sigma()).elevation_mask_deg,
        );
        return Err(format!(
            "the calibration runs ({} seeds, {epochs} epochs) gave no B value: {why}",
            cal.len()
        ));
    }
    Ok(tables)
}

/// The lab set-up's fault-free sigma tables on [`CALIBRATION_SEEDS`] shifted by
/// `offset` (`validate thesis --seed-base`).
pub fn calibrate_lab(offset: u64) -> Result<Sigmas, String> {
    let (first, last) = CALIBRATION_SEEDS.into_inner();
    calibrate(
        &scenario(&[], 0, None)?,
        first.wrapping_add(offset)..=last.wrapping_add(offset),
    )
}

/// The lab run of `case` on `seed` with thresholds from `sigma`.
pub fn case_run(case: Case, seed: u64, sigma: &Sigmas) -> Result<MonitoredRun, String> {
    monitored(
        &scenario(&case.events(), seed, None)?,
        &config(sigma.clone()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_calibration_without_values_or_with_a_statistic_missing_says_which() {
        let base = config(unit_sigma());
        let empty = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
        let e =
            complete_tables(&empty, "sigma_geo", "a BeiDou GEO (--geo-apart)", &base).unwrap_err();
        assert!(
            e.starts_with("cannot calibrate sigma_geo: the files hold no B values of a BeiDou GEO"),
            "{e}"
        );
        assert!(e.contains("300 s old"), "{e}");
        // Code values only: the divergence (and the rest) missing for B1I.
        let mut code_only = SigmaCalibrator::new(ELEVATION_BINS_DEG.to_vec());
        code_only.add(Signal::BdsB1I, Statistic::Code, 40.0, 0.3);
        let e = complete_tables(&code_only, "sigma", "any satellite", &base).unwrap_err();
        assert!(e.starts_with("cannot calibrate sigma of bds-b1i: "), "{e}");
    }
}
