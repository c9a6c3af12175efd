//! Table group P2-4.2: paper 002's fault cases (section 4.2) as patterns of the B values,
//! each measured on independent seeds.

use super::lab::{Case, FAULT_SATELLITE, FAULT_STATION, MonitoredRun};
use super::monitor::Sigmas;
use super::monitor::case_run;
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::AcrossRuns;
use rayon::prelude::*;
use skyforge_navigation::integrity::{SatelliteEpoch, Statistic};

/// The table group's identifier.
pub const TABLE: &str = "P2-4.2";
/// Evaluation seeds: 2002 and the next ones. # assumed: twenty runs per case, chosen
/// before any run, apart from the calibration seeds.
pub const FIRST_SEED: u64 = 2002;
pub const SEEDS: u64 = 20;

const SMOOTHED: usize = Statistic::SmoothedCode.index();
const CARRIER: usize = Statistic::Carrier.index();
const DIVERGENCE: usize = Statistic::Divergence.index();

/// The faulted satellite's epochs of a run, with their times.
fn faulted(run: &MonitoredRun) -> Vec<(f64, &SatelliteEpoch)> {
    run.epochs
        .iter()
        .filter_map(|e| {
            let s = e
                .sats
                .iter()
                .find(|s| s.sat.to_string() == FAULT_SATELLITE)?;
            Some((e.t_s, s))
        })
        .collect()
}

/// Index of the faulted station and of the others.
fn stations(run: &MonitoredRun) -> (usize, Vec<usize>) {
    let c = run
        .run
        .antennas
        .iter()
        .position(|a| a == FAULT_STATION)
        .unwrap_or(0);
    let others = (0..run.run.antennas.len()).filter(|&m| m != c).collect();
    (c, others)
}

/// B value of statistic `k` at station `m` (NaN when absent).
fn b(s: &SatelliteEpoch, m: usize, k: usize) -> f64 {
    s.stations
        .get(m)
        .copied()
        .flatten()
        .map_or(f64::NAN, |v| v.b[k])
}

/// Whether station `m` alarms on statistic `k`.
fn alarm(s: &SatelliteEpoch, m: usize, k: usize) -> bool {
    s.stations
        .get(m)
        .copied()
        .flatten()
        .is_some_and(|v| v.alarm[k])
}

/// Mean of `|B|` of statistic `k` over stations `ms`.
fn mean_abs(s: &SatelliteEpoch, ms: &[usize], k: usize) -> f64 {
    ms.iter().map(|&m| b(s, m, k).abs()).sum::<f64>() / ms.len() as f64
}

/// The mean of `f` over `series` epochs with `t` in `[from, to)`.
fn mean_over(
    series: &[(f64, &SatelliteEpoch)],
    from: f64,
    to: f64,
    f: impl Fn(&SatelliteEpoch) -> f64,
) -> f64 {
    let v: Vec<f64> = series
        .iter()
        .filter(|(t, _)| (from..to).contains(t))
        .map(|(_, s)| f(s))
        .collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// The first time in `[from, to)` where `f` holds, minus `from` (NaN when never).
fn first_after(
    series: &[(f64, &SatelliteEpoch)],
    from: f64,
    to: f64,
    f: impl Fn(&SatelliteEpoch) -> bool,
) -> f64 {
    series
        .iter()
        .find(|(t, s)| (from..to).contains(t) && f(s))
        .map_or(f64::NAN, |(t, _)| t - from)
}

/// The epoch in `[from, to)` where `f` is largest.
fn argmax<'a>(
    series: &[(f64, &'a SatelliteEpoch)],
    from: f64,
    to: f64,
    f: impl Fn(&SatelliteEpoch) -> f64,
) -> Option<(f64, &'a SatelliteEpoch)> {
    series
        .iter()
        .filter(|(t, _)| (from..to).contains(t))
        .max_by(|a, b| f(a.1).total_cmp(&f(b.1)))
        .copied()
}

/// Time from `from` to the first alarm of statistic `k` at the faulted station in
/// `[from, to)` (NaN when none).
fn first_alarm(r: &MonitoredRun, from: f64, to: f64, k: usize) -> f64 {
    let (c, _) = stations(r);
    first_after(&faulted(r), from, to, |s| alarm(s, c, k))
}

/// Mean |B| of statistic `k` at the other stations over |B| at the faulted one, at the
/// epoch after the slip where `key` of the faulted station's B is largest.
fn ratio_at_peak(r: &MonitoredRun, k: usize, key: fn(f64) -> f64) -> f64 {
    let (c, o) = stations(r);
    argmax(&faulted(r), SLIP_S, END_S, |s| key(b(s, c, k)))
        .map_or(f64::NAN, |(_, s)| mean_abs(s, &o, k) / b(s, c, k).abs())
}

/// One measured quantity of the table: row label, quantity, unit, the paper's value, the
/// check, and how a run gives it.
struct Measure {
    row: &'static str,
    quantity: &'static str,
    unit: &'static str,
    paper: Option<f64>,
    tolerance: &'static str,
    ok: fn(f64) -> bool,
    of: fn(&MonitoredRun) -> f64,
    note: &'static str,
}

impl Measure {
    /// A count or fraction of alarms where the paper has none: dimensionless, and must
    /// be 0.
    fn no_alarm(
        row: &'static str,
        quantity: &'static str,
        tolerance: &'static str,
        of: fn(&MonitoredRun) -> f64,
        note: &'static str,
    ) -> Self {
        Self {
            row,
            quantity,
            unit: "",
            paper: Some(0.0),
            tolerance,
            ok: |v| v == 0.0,
            of,
            note,
        }
    }
}

/// Slip at 500 s: epochs from 510 s are past the transition.
const SLIP_S: f64 = 500.0;
const AFTER_SLIP_S: f64 = 510.0;
const END_S: f64 = 1800.0;

fn slip_measures() -> Vec<Measure> {
    vec![
        Measure {
            row: "cycle slip: carrier B at C",
            quantity: "mean B after the slip",
            unit: "cycles",
            paper: Some(100.0),
            tolerance: "+-1 cycle",
            ok: |v| (v - 100.0).abs() <= 1.0,
            of: |r| {
                let (c, _) = stations(r);
                mean_over(&faulted(r), AFTER_SLIP_S, END_S, |s| b(s, c, CARRIER))
            },
            note: "paper: stays at 100 cycles",
        },
        Measure {
            row: "cycle slip: carrier B at A, B, D",
            quantity: "mean |B| after the slip",
            unit: "cycles",
            paper: Some(33.0),
            tolerance: "+-1 cycle",
            ok: |v| (v - 33.0).abs() <= 1.0,
            of: |r| {
                let (_, o) = stations(r);
                mean_over(&faulted(r), AFTER_SLIP_S, END_S, |s| {
                    mean_abs(s, &o, CARRIER)
                })
            },
            note: "paper: about 33 cycles (sign not stated; ours is negative)",
        },
        Measure {
            row: "cycle slip: smoothed-code B at C",
            quantity: "peak B after the slip",
            unit: "m",
            paper: Some(19.0),
            tolerance: "+-1 m (printed as 19 m)",
            ok: |v| (v - 19.0).abs() <= 1.0,
            of: |r| {
                let (c, _) = stations(r);
                argmax(&faulted(r), SLIP_S, END_S, |s| b(s, c, SMOOTHED))
                    .map_or(f64::NAN, |(_, s)| b(s, c, SMOOTHED))
            },
            note: "B1I: 100 lambda (N_s - 1) / N_s = 19.01 m (digest 2.4)",
        },
        Measure {
            row: "cycle slip: smoothed-code B, A, B, D over C",
            quantity: "ratio of |B| at C's peak",
            unit: "",
            paper: Some(1.0 / 3.0),
            tolerance: "+-0.05",
            ok: |v| (v - 1.0 / 3.0).abs() <= 0.05,
            of: |r| ratio_at_peak(r, SMOOTHED, |v| v),
            note: "paper: about a third",
        },
        Measure {
            row: "cycle slip: smoothed-code B convergence",
            quantity: "time from the slip to |B at C| < 1 % of its peak",
            unit: "s",
            paper: Some(500.0),
            tolerance: "+-100 s",
            ok: |v| (v - 500.0).abs() <= 100.0,
            of: |r| {
                let (c, _) = stations(r);
                let series = faulted(r);
                let Some((t_peak, peak)) = argmax(&series, SLIP_S, END_S, |s| b(s, c, SMOOTHED))
                else {
                    return f64::NAN;
                };
                let level = 0.01 * b(peak, c, SMOOTHED);
                first_after(&series, t_peak, END_S, |s| b(s, c, SMOOTHED).abs() < level) + t_peak
                    - SLIP_S
            },
            note: "paper: converges in about 500 s; 1 % of the peak is the plot's zero at 19 m full scale",
        },
        Measure {
            row: "cycle slip: divergence B at C",
            quantity: "time of the largest |B|",
            unit: "s",
            paper: Some(600.0),
            tolerance: "+-100 s",
            ok: |v| (v - 600.0).abs() <= 100.0,
            of: |r| {
                let (c, _) = stations(r);
                argmax(&faulted(r), SLIP_S, END_S, |s| b(s, c, DIVERGENCE).abs())
                    .map_or(f64::NAN, |(t, _)| t)
            },
            note: "paper: grows from 500 s, largest around 600 s, then decays",
        },
        Measure {
            row: "cycle slip: divergence B, A, B, D over C",
            quantity: "ratio of |B| at C's largest",
            unit: "",
            paper: Some(1.0 / 3.0),
            tolerance: "+-0.05",
            ok: |v| (v - 1.0 / 3.0).abs() <= 0.05,
            of: |r| ratio_at_peak(r, DIVERGENCE, f64::abs),
            note: "paper: about a third",
        },
        Measure {
            row: "cycle slip: detection by the carrier B",
            quantity: "time from the slip to the first carrier alarm at C",
            unit: "s",
            paper: Some(1.0),
            tolerance: "<= 1 epoch (1 s)",
            ok: |v| v <= 1.0,
            of: |r| first_alarm(r, SLIP_S, END_S, CARRIER),
            note: "paper: detection within a single epoch; the slip enters the first epoch after 500 s",
        },
    ]
}

const MULTIPATH_S: f64 = 600.0;

fn multipath_measures() -> Vec<Measure> {
    vec![
        Measure {
            row: "multipath: smoothed-code B at C crosses 0.5 m",
            quantity: "fraction of seeds with a smoothed-code alarm at C in 600-700 s",
            unit: "",
            paper: Some(1.0),
            tolerance: "1",
            ok: |v| v == 1.0,
            of: |r| {
                f64::from(u8::from(
                    first_alarm(r, MULTIPATH_S, 700.0, SMOOTHED).is_finite(),
                ))
            },
            note: "paper: accumulates and gradually exceeds the 0.5 m threshold",
        },
        Measure {
            row: "multipath: smoothed-code detection lags",
            quantity: "time from onset to the smoothed-code alarm at C",
            unit: "s",
            paper: None,
            tolerance: "lags, during the event: 1 s <= t < 5 s",
            ok: |v| (1.0..5.0).contains(&v),
            of: |r| first_alarm(r, MULTIPATH_S, 700.0, SMOOTHED),
            note: "paper: each epoch enters at 1/N_s, so detection lags (digest 2.4: 2nd epoch)",
        },
        Measure {
            row: "multipath: carrier B at C unchanged",
            quantity: "largest |B| / threshold in 600-700 s",
            unit: "",
            paper: None,
            tolerance: "< 1 (no alarm)",
            ok: |v| v < 1.0,
            of: |r| {
                let (c, _) = stations(r);
                faulted(r)
                    .iter()
                    .filter(|(t, _)| (MULTIPATH_S..700.0).contains(t))
                    .map(|(_, s)| b(s, c, CARRIER).abs() / s.threshold[CARRIER])
                    .fold(0.0, f64::max)
            },
            note: "paper: pseudorange multipath does not affect the carrier",
        },
    ]
}

/// Whether any statistic of the faulted satellite alarms at any station in `[from, to)`.
fn any_alarm(r: &MonitoredRun, from: f64, to: f64) -> f64 {
    let hit = faulted(r).iter().any(|(t, s)| {
        (from..to).contains(t)
            && s.stations
                .iter()
                .flatten()
                .any(|v| v.alarm.iter().any(|&a| a))
    });
    f64::from(u8::from(hit))
}

fn ramp_common_measures() -> Vec<Measure> {
    vec![Measure::no_alarm(
        "common iono ramp: not detected",
        "fraction of seeds with an alarm on C03 in 500-1000 s",
        "0",
        |r| any_alarm(r, 500.0, 1000.0),
        "paper: the gradient is common to the stations and cancels in every B value",
    )]
}

/// The ramp at C's rows: the paper's "not detected", and the premise that explains a
/// detection (the ramp's own B values at C beyond their thresholds), measured on the same
/// runs ([`explain_ramp_at_c`]).
fn ramp_at_c_measures() -> Vec<Measure> {
    vec![
        Measure::no_alarm(
            "iono ramp at C only: detected",
            "fraction of seeds with an alarm on C03 in 500-700 s",
            "0 (as printed)",
            |r| any_alarm(r, 500.0, 700.0),
            "a ramp at C alone reaches 17.3 m of code and -17.3 m of carrier at C by 673 s, beyond its thresholds; the paper's results fit only a common ramp (digest 2.3). Explained only where the next row, on the same runs, shows it",
        ),
        Measure {
            row: RAMP_PREMISE_ROW,
            quantity: "largest |B| / threshold at C (smoothed code, carrier) in 500-700 s",
            unit: "",
            paper: None,
            tolerance: "> 1 at every seed (beyond the thresholds)",
            ok: |v| v > 1.0,
            of: |r| {
                let (c, _) = stations(r);
                faulted(r)
                    .iter()
                    .filter(|(t, _)| (500.0..700.0).contains(t))
                    .flat_map(|(_, s)| {
                        [SMOOTHED, CARRIER].map(|k| b(s, c, k).abs() / s.threshold[k])
                    })
                    .fold(0.0, f64::max)
            },
            note: "the premise of the explanation above: the ramp at C is what the B values at C see",
        },
    ]
}

/// The row of the ramp at C's premise.
const RAMP_PREMISE_ROW: &str = "iono ramp at C only: B at C beyond its thresholds";

/// The detection row of the ramp at C deviates from the paper's "not detected" for a
/// reason the same runs check: where the premise row passes at every seed, the deviation
/// is explained; otherwise it stays a deviation.
fn explain_ramp_at_c(rows: &mut [Row], premise_at_every_seed: bool) {
    for r in rows.iter_mut() {
        if r.row != RAMP_PREMISE_ROW && r.verdict == Verdict::Deviates && premise_at_every_seed {
            r.verdict = Verdict::Explained;
        }
    }
}

fn fault_free_measures() -> Vec<Measure> {
    vec![
        Measure::no_alarm(
            "fault-free: no alarm",
            "alarms per 1800 s run (all satellites, stations, statistics)",
            "0",
            |r| {
                r.epochs
                    .iter()
                    .flat_map(|e| &e.sats)
                    .flat_map(|s| s.stations.iter().flatten())
                    .map(|v| v.alarm.iter().filter(|&&a| a).count() as f64)
                    .sum()
            },
            "paper 4.2.1: code and carrier B values stable; thresholds at 1e-7 per test",
        ),
        Measure {
            row: "fault-free: divergence B at mm level",
            quantity: "RMS of the armed divergence B values",
            unit: "mm/s",
            paper: None,
            tolerance: "< 10 mm/s (mm level)",
            ok: |v| v < 10.0,
            of: |r| {
                let v: Vec<f64> = r
                    .epochs
                    .iter()
                    .flat_map(|e| &e.sats)
                    .filter(|s| s.armed[DIVERGENCE])
                    .flat_map(|s| s.stations.iter().flatten().map(|v| v.b[DIVERGENCE] * 1e3))
                    .collect();
                crate::stats::rms(&v)
            },
            note: "paper 4.2.1: CCD and its B value vary only at mm level",
        },
    ]
}

/// The measures of `case`.
fn measures(case: Case) -> Vec<Measure> {
    match case {
        Case::FaultFree => fault_free_measures(),
        Case::CycleSlip => slip_measures(),
        Case::Multipath => multipath_measures(),
        Case::IonoRampAtC => ramp_at_c_measures(),
        Case::IonoRampCommon => ramp_common_measures(),
    }
}

/// The rows of `case` from its runs on the seeds of `draw` (registered: [`SEEDS`] from
/// [`FIRST_SEED`]).
pub fn case_rows(case: Case, sigma: &Sigmas, draw: Draw) -> Result<Vec<Row>, String> {
    let ms = measures(case);
    let per_seed: Vec<Vec<f64>> = draw
        .seeds(FIRST_SEED, SEEDS)
        .into_par_iter()
        .map(|seed| {
            let run = case_run(case, seed, sigma)?;
            Ok(ms.iter().map(|m| (m.of)(&run)).collect())
        })
        .collect::<Result<_, String>>()?;
    let values = |k: usize| -> Vec<f64> { per_seed.iter().map(|v| v[k]).collect() };
    let mut rows: Vec<Row> = ms
        .iter()
        .enumerate()
        .map(|(k, m)| row(m, &values(k)))
        .collect();
    if case == Case::IonoRampAtC {
        let premise = ms.iter().position(|m| m.row == RAMP_PREMISE_ROW);
        let at_every_seed = premise.is_some_and(|k| values(k).iter().all(|&v| (ms[k].ok)(v)));
        explain_ramp_at_c(&mut rows, at_every_seed);
    }
    Ok(rows)
}

/// One row from the seeds' values of `m`.
fn row(m: &Measure, values: &[f64]) -> Row {
    let inside = values.iter().filter(|&&v| (m.ok)(v)).count();
    let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let across = AcrossRuns::of(&finite);
    let mean = across.map_or(f64::NAN, |a| a.mean);
    let se = across.and_then(|a| a.standard_error).unwrap_or(f64::NAN);
    let verdict = Verdict::from_ok(finite.len() == values.len() && (m.ok)(mean));
    Row::measured(
        TABLE,
        m.row,
        m.quantity,
        m.unit,
        m.paper,
        mean,
        (m.tolerance.to_string(), verdict),
    )
    .with_note(format!(
        "{}; mean over {} seeds (SE {se:.3}), {inside}/{} seeds in tolerance",
        m.note,
        values.len(),
        values.len()
    ))
}

/// Every row of the group with thresholds from `sigma`: each case on the seeds of `draw`.
pub fn rows(sigma: &Sigmas, draw: Draw) -> Result<Vec<Row>, String> {
    let mut rows = Vec::new();
    for case in Case::ALL {
        rows.extend(case_rows(case, sigma, draw)?);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(label: &str, verdict: Verdict) -> Row {
        Row::measured(TABLE, label, "q", "", None, 1.0, ("t".into(), verdict))
    }

    /// The ramp at C's detection is explained only where its premise held at every seed.
    #[test]
    fn a_deviation_is_explained_only_by_its_checked_premise() {
        for (premise, expected) in [(true, Verdict::Explained), (false, Verdict::Deviates)] {
            let mut rows = [
                row("iono ramp at C only: detected", Verdict::Deviates),
                row(RAMP_PREMISE_ROW, Verdict::Reproduced),
            ];
            explain_ramp_at_c(&mut rows, premise);
            assert_eq!(rows[0].verdict, expected);
            assert_eq!(rows[1].verdict, Verdict::Reproduced);
        }
        let mut reproduced = [row("iono ramp at C only: detected", Verdict::Reproduced)];
        explain_ramp_at_c(&mut reproduced, true);
        assert_eq!(reproduced[0].verdict, Verdict::Reproduced);
    }
}
