//! Table group P2-PD: detection probability against fault size for each statistic, at
//! the observation level over many seeds (issue 15's curves; no paper value).
//!
//! Each run carries four faults at station C, one per statistic, each on its own BeiDou
//! GEO satellite (constant elevation, so one threshold per fault): a code step on C01
//! (code), a code step on C02 (smoothed code), a carrier phase jump on C03 (carrier) and
//! an ionospheric ramp on C04 (divergence: code and carrier part at twice the ramp). The
//! B values of different satellites do not share noise, so the four curves come from the
//! same runs. Sizes are multiples of each statistic's threshold at its satellite.

use super::lab::{Fault, MonitoredRun, monitored, scenario};
use super::monitor::{Sigmas, config};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use rayon::prelude::*;
use skyforge_navigation::integrity::{PerStatistic, Statistic};

/// The table group's identifier.
pub const TABLE: &str = "P2-PD";
/// Fault sizes in thresholds. # assumed: 0 to 2 in halves, chosen before any run.
pub const SIZES: [f64; 5] = [0.0, 0.5, 1.0, 1.5, 2.0];
/// Seeds per size (issue 15: at least 200).
pub const SEEDS: u64 = 200;
/// First seed of size index i: `FIRST_SEED + 1000 i`. # assumed: apart from the
/// calibration (1..=8) and pattern (2002..) seeds, chosen before any run.
pub const FIRST_SEED: u64 = 10_000;
/// Fault onset and the end of the run (s). # assumed: onset after the divergence is
/// armed (100 s smoothing + 200 s divergence), then 300 s to detect; chosen before any run.
pub const ONSET_S: f64 = 400.0;
pub const END_S: f64 = 700.0;

/// The satellite of each statistic's fault.
const SATELLITES: PerStatistic<&str> = ["C01", "C02", "C03", "C04"];

/// The fault of `stat` of size `size` thresholds, whose threshold is `threshold`.
fn fault(stat: Statistic, size: f64, threshold: f64) -> Fault {
    let value = size * threshold;
    let (kind, value) = match stat {
        Statistic::Code | Statistic::SmoothedCode => ("code-step", value),
        Statistic::Carrier => ("phase-jump", value),
        // Code delayed and carrier advanced by the ramp: the divergence is twice it.
        Statistic::Divergence => ("iono-ramp", value / 2.0),
    };
    Fault {
        kind,
        station: Some(super::lab::FAULT_STATION),
        satellite: SATELLITES[stat.index()],
        start_s: ONSET_S,
        end_s: END_S,
        value,
    }
}

/// Each statistic's threshold at its satellite, from a fault-free run on `seed`.
fn thresholds(sigma: &Sigmas, seed: u64) -> Result<PerStatistic<f64>, String> {
    let run = monitored(&scenario(&[], seed, Some(END_S))?, &config(sigma.clone()))?;
    let last = run.epochs.last().ok_or("no monitored epoch")?;
    let mut out = [f64::NAN; 4];
    for stat in Statistic::ALL {
        let sat = SATELLITES[stat.index()];
        let s = last
            .sats
            .iter()
            .find(|s| s.sat.to_string() == sat)
            .ok_or_else(|| format!("{sat} is not monitored"))?;
        out[stat.index()] = s.threshold[stat.index()];
    }
    Ok(out)
}

/// Whether each statistic alarmed at C on its satellite from the onset on.
fn detected(run: &MonitoredRun) -> PerStatistic<bool> {
    let c = run
        .run
        .antennas
        .iter()
        .position(|a| a == super::lab::FAULT_STATION)
        .unwrap_or(0);
    Statistic::ALL.map(|stat| {
        run.epochs.iter().filter(|e| e.t_s >= ONSET_S).any(|e| {
            e.sats.iter().any(|s| {
                s.sat.to_string() == SATELLITES[stat.index()]
                    && s.stations
                        .get(c)
                        .copied()
                        .flatten()
                        .is_some_and(|v| v.alarm[stat.index()])
            })
        })
    })
}

/// Detection probability per statistic at one size, with its binomial standard error.
fn curve_point(
    sigma: &Sigmas,
    threshold: &PerStatistic<f64>,
    size_index: usize,
    draw: Draw,
) -> Result<PerStatistic<(f64, f64)>, String> {
    let size = SIZES[size_index];
    let faults: Vec<Fault> = if size == 0.0 {
        Vec::new()
    } else {
        Statistic::ALL
            .iter()
            .map(|&s| fault(s, size, threshold[s.index()]))
            .collect()
    };
    let hits: Vec<PerStatistic<bool>> = draw
        .seeds(FIRST_SEED + 1000 * size_index as u64, SEEDS)
        .into_par_iter()
        .map(|seed| {
            let s = scenario(&faults, seed, Some(END_S))?;
            Ok(detected(&monitored(&s, &config(sigma.clone()))?))
        })
        .collect::<Result<_, String>>()?;
    let n = hits.len() as f64;
    Ok(Statistic::ALL.map(|stat| {
        let p = hits.iter().filter(|h| h[stat.index()]).count() as f64 / n;
        (p, (p * (1.0 - p) / n).sqrt())
    }))
}

/// The rows: for every statistic, detection probability at each size, on the seeds of
/// `draw` (registered: [`SEEDS`] per size).
pub fn rows(sigma: &Sigmas, draw: Draw) -> Result<Vec<Row>, String> {
    let threshold = thresholds(sigma, draw.seed(FIRST_SEED))?;
    let seeds = draw.seeds(0, SEEDS).count();
    let points: Vec<PerStatistic<(f64, f64)>> = (0..SIZES.len())
        .map(|i| curve_point(sigma, &threshold, i, draw))
        .collect::<Result<_, String>>()?;
    let mut rows = Vec::new();
    for stat in Statistic::ALL {
        let k = stat.index();
        for (i, &size) in SIZES.iter().enumerate() {
            let (p, se) = points[i][k];
            let (tolerance, ok) = if size == 0.0 {
                ("<= 0.01 (false alarms only)".to_string(), p <= 0.01)
            } else if size >= 2.0 {
                (
                    "monotone (within 2 SE), >= 0.9 at twice the threshold".to_string(),
                    p >= 0.9 && p + 2.0 * se >= points[i - 1][k].0,
                )
            } else {
                (
                    "monotone: not below the smaller size's by more than 2 SE".to_string(),
                    p + 2.0 * se >= points[i - 1][k].0,
                )
            };
            let f = fault(stat, size, threshold[k]);
            rows.push(
                Row::measured(
                    TABLE,
                    format!("{}: {size} x threshold", stat.name()),
                    "detection probability within 300 s of onset",
                    "",
                    None,
                    p,
                    (tolerance, Verdict::from_ok(ok)),
                )
                .with_note(format!(
                    "{} of {:.4} {} on {} at C from {ONSET_S} s (threshold {:.4} {}); {seeds} seeds, SE {se:.3}; no paper value",
                    f.kind,
                    f.value,
                    match stat {
                        Statistic::Divergence => "m/s",
                        Statistic::Carrier => "cycles",
                        _ => "m",
                    },
                    f.satellite,
                    threshold[k],
                    stat.unit(),
                )),
            );
        }
    }
    Ok(rows)
}
