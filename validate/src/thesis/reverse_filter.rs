//! T-5.5 (thesis section 5.5, tables 5.5-1..5.5-4): reverse (inverse) filtering of the
//! baseline vectors. The bundled scenario [`SCENARIO`] (three GPS L1 antennas on two 1 m
//! baselines, constant 10 mm phase noise, attitude swings of 6-10 deg) at the observation
//! level, on [`SEEDS`](crate::attitude::seeds::SEEDS) seeds; each seed's observations go
//! through the chain of `skyforge attitude` twice: with epoch-by-epoch LS baselines
//! (eqs. 2.4-64/2.4-65) and with the reverse baseline UKF of eqs. 5.5-1..5.5-20
//! (`receiver::relative::reverse`), both followed by the KF attitude of eqs.
//! 2.5-16/2.5-17.
//!
//! Rows: per baseline, the ECEF X, Y, Z error std of the LS baselines (table 5.5-1;
//! within a factor 2 of the thesis, the attitude's tolerance, as `THESIS_TARGETS.md`
//! states none for the baselines) and of the filtered ones (table 5.5-2; below the LS
//! std of the same component, the section's claim); the yaw, pitch, roll error std of
//! the KF on the LS baselines (table 5.5-3; within a factor 2) and on the filtered ones
//! (table 5.5-4; at most 0.6 times the LS's). Each value is the mean over runs of a
//! run's std; notes give the standard error over runs, the mean and RMS, the ratio to
//! the LS, the chain's fix counts and, for the attitude, the epoch-by-epoch LS attitude
//! from the same baseline series (the same observations run through the chain with
//! `method = "least-squares"`).
//!
//! Figures ([`rows_and_curves`], from the same runs as the rows): 5.5-2 and 5.5-3 (each
//! baseline's ECEF errors, LS and proposed), 5.5-4 and 5.5-5 (the KF's attitude and rate
//! errors on each), drawn from the first run and quoting the rows' stds.

use super::attitude_noise::config as constant_noise_config;
use super::attitude_runs::{self, SeriesStats, chain_note, factor_row, seed_runs};
use super::curves::{Curve, Decimated, Value};
use crate::attitude::{ChainComparison, EpochErrors};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use skyforge_navigation::attitude::AttitudeMethod;
use skyforge_navigation::relative::{RelativeConfig, ReverseConfig};
use skyforge_signals::obs_model::ObsNoiseConfig;

/// Table identifier.
pub const TABLE: &str = "T-5.5";
/// The bundled scenario.
pub const SCENARIO: &str = "thesis/t-5.5";

/// Tables 5.5-1 (LS) and 5.5-2 (proposed): per baseline, the ECEF X, Y, Z error std (m).
const LS_BASELINES: [[f64; 3]; 2] = [[0.3134, 0.0244, 0.0449], [0.2937, 0.0234, 0.0440]];
const PROPOSED_BASELINES: [[f64; 3]; 2] = [[0.1289, 0.0234, 0.0436], [0.0209, 0.0117, 0.0231]];
/// Tables 5.5-3 (LS) and 5.5-4 (proposed): yaw, pitch, roll error std (deg).
const LS_ATTITUDE: [f64; 3] = [0.9464, 1.1242, 1.1094];
const PROPOSED_ATTITUDE: [f64; 3] = [0.3286, 0.3713, 0.3562];
/// The means the same tables print beside the stds (m, then deg): for the captions of
/// figures 5.5-2..5.5-5.
const LS_BASELINE_MEANS: [[f64; 3]; 2] =
    [[0.0040, 4.6181e-4, 5.7519e-4], [0.0120, 2.3257e-4, 0.0024]];
const PROPOSED_BASELINE_MEANS: [[f64; 3]; 2] = [
    [-0.0038, -5.2319e-4, -0.0020],
    [4.0256e-4, -4.9955e-5, 8.9816e-4],
];
const LS_ATTITUDE_MEANS: [f64; 3] = [0.0375, 0.0107, 0.0114];
const PROPOSED_ATTITUDE_MEANS: [f64; 3] = [0.0162, -0.0208, 0.0928];
/// `THESIS_TARGETS.md`: LS attitude stds within this factor ...
const FACTOR: f64 = 2.0;
/// ... and proposed over LS attitude std below this on every axis.
const RATIO_BOUND: f64 = 0.6;
const AXES: [&str; 3] = ["yaw", "pitch", "roll"];
const COMPONENTS: [&str; 3] = ["X", "Y", "Z"];

/// `S` of the attitude KF (eqs. 2.5-16; rad^2/s^3, yaw, pitch, roll).
// assumed, chosen with the scenario's profile before any run: white angular acceleration
// whose change of rate over one 1 s epoch matches the profile's largest angular
// acceleration a (S = a^2 T, Bar-Shalom's rule for the white-noise acceleration model):
// a = 10/8/6 deg x (2 pi / 120/100/80 s)^2 = 4.8e-4/5.5e-4/6.5e-4 rad/s^2.
const ATTITUDE_PSD_RAD2_S3: [f64; 3] = [2.3e-7, 3.0e-7, 4.2e-7];
/// `S` of the reverse filter (eq. 5.5-7, m^2/s^3, every component).
// assumed, by the same rule: a 1 m baseline's acceleration is at most
// L (|w'| + |w|^2) = 9.8e-4 + 2.3e-4 rad/s^2 x 1 m with the profile's largest rates
// (0.52/0.50/0.47 deg/s) and accelerations combined: 1.2e-3 m/s^2, squared.
const BASELINE_PSD_M2_S3: f64 = 1.5e-6;

/// The chains: the receiver told the prescribed constant noise (as T-1.2-2), the KF
/// attitude stage, without and with the reverse filter; then the same two with
/// epoch-by-epoch LS attitude (for the notes: what each baseline series gives without
/// the KF's smoothing).
fn configs(phase_m: f64, code_m: f64) -> [RelativeConfig; 4] {
    let mut ls = constant_noise_config(phase_m, code_m);
    ls.attitude.method = AttitudeMethod::Kf;
    ls.attitude.rate_psd_rad2_s3 = ATTITUDE_PSD_RAD2_S3;
    let proposed = RelativeConfig {
        reverse_filter: Some(ReverseConfig {
            rate_psd_m2_s3: [BASELINE_PSD_M2_S3; 6],
            ..ReverseConfig::default()
        }),
        ..ls.clone()
    };
    let epoch_by_epoch = |c: &RelativeConfig| {
        let mut c = c.clone();
        c.attitude.method = AttitudeMethod::LeastSquares;
        c
    };
    [epoch_by_epoch(&ls), epoch_by_epoch(&proposed), ls, proposed]
}

fn stats(
    runs: &[ChainComparison],
    series: impl Fn(&ChainComparison) -> Vec<f64>,
) -> Result<SeriesStats, ValidateError> {
    attitude_runs::stats(SCENARIO, runs, series)
}

/// A proposed-method row: `ours` must be below `bound` times the LS's `ls`; the thesis's
/// own value beside it.
fn proposed_row(row: String, unit: &str, thesis: f64, ours: f64, ls: f64, bound: f64) -> Row {
    let tolerance = if bound == 1.0 {
        "below LS".to_string()
    } else {
        format!("below {bound} x LS")
    };
    Row::measured(
        TABLE,
        row,
        "std",
        unit,
        Some(thesis),
        ours,
        (tolerance, Verdict::from_ok(ours < bound * ls)),
    )
}

/// The four chains' runs of one draw (seed order): epoch-by-epoch LS attitude on the LS
/// and on the filtered baselines (the notes), and the KF on each (the rows, the figures).
struct Runs {
    ls_epochwise: Vec<ChainComparison>,
    filtered_epochwise: Vec<ChainComparison>,
    ls: Vec<ChainComparison>,
    proposed: Vec<ChainComparison>,
}

/// The scenario's runs on the seeds of `draw`.
fn runs(draw: Draw) -> Result<Runs, ValidateError> {
    let scenario = skyforge_scenarios::named(SCENARIO)?;
    let ObsNoiseConfig::Constant {
        phase_m, code_m, ..
    } = scenario.observation.noise
    else {
        return Err(ValidateError::Pipeline(format!(
            "{SCENARIO}: the scenario's [observation.noise] is not the constant model"
        )));
    };
    let [ls_epochwise, filtered_epochwise, ls, proposed] =
        seed_runs(&scenario, configs(phase_m, code_m), draw)?;
    Ok(Runs {
        ls_epochwise,
        filtered_epochwise,
        ls,
        proposed,
    })
}

/// Tables 5.5-1 and 5.5-2: the row of baseline `k`'s component `c`, LS or proposed.
fn baseline_row(k: usize, c: &str, proposed: bool) -> String {
    let method = if proposed { "proposed" } else { "LS" };
    format!("baseline {} ECEF {c} error ({method})", k + 1)
}

/// Tables 5.5-3 and 5.5-4: the row of `axis`, the KF on the LS or the filtered baselines.
fn attitude_row(axis: &str, proposed: bool) -> String {
    let baselines = if proposed { "filtered" } else { "LS" };
    format!("{axis} error (KF on {baselines} baselines)")
}

impl Runs {
    /// The rows of tables 5.5-1..5.5-4.
    fn rows(&self) -> Result<Vec<Row>, ValidateError> {
        let (ls_runs, runs) = (&self.ls, &self.proposed);
        let (ls_chain, chain) = (chain_note(ls_runs), chain_note(runs));
        let mut out = Vec::new();
        for k in 0..2 {
            for (i, c) in COMPONENTS.iter().enumerate() {
                let ls = stats(ls_runs, |r| r.baseline_axis(k, i, false))?;
                let filtered = stats(runs, |r| r.baseline_axis(k, i, false))?;
                out.push(
                    factor_row(
                        TABLE,
                        baseline_row(k, c, false),
                        "m",
                        LS_BASELINES[k][i],
                        ls.std.mean,
                        FACTOR,
                    )
                    .with_note(format!("{}; {ls_chain}", ls.note(1e3, "mm", 2))),
                );
                out.push(
                    proposed_row(
                        baseline_row(k, c, true),
                        "m",
                        PROPOSED_BASELINES[k][i],
                        filtered.std.mean,
                        ls.std.mean,
                        1.0,
                    )
                    .with_note(format!(
                        "{}; over LS {:.3} (thesis {:.3}); {chain}",
                        filtered.note(1e3, "mm", 2),
                        filtered.std.mean / ls.std.mean,
                        PROPOSED_BASELINES[k][i] / LS_BASELINES[k][i]
                    )),
                );
            }
        }
        for (i, axis) in AXES.iter().enumerate() {
            let ls = stats(ls_runs, |r| r.attitude_axis(i))?;
            let filtered = stats(runs, |r| r.attitude_axis(i))?;
            let epochwise_note = |runs: &[ChainComparison]| -> Result<String, ValidateError> {
                Ok(format!(
                    "epoch-by-epoch LS attitude on the same baselines: std {} deg",
                    stats(runs, |r| r.attitude_axis(i))?.std.describe(1.0, 4)
                ))
            };
            out.push(
                factor_row(
                    TABLE,
                    attitude_row(axis, false),
                    "deg",
                    LS_ATTITUDE[i],
                    ls.std.mean,
                    FACTOR,
                )
                .with_note(format!(
                    "{}; {}; {ls_chain}",
                    ls.note(1.0, "deg", 4),
                    epochwise_note(&self.ls_epochwise)?
                )),
            );
            out.push(
                proposed_row(
                    attitude_row(axis, true),
                    "deg",
                    PROPOSED_ATTITUDE[i],
                    filtered.std.mean,
                    ls.std.mean,
                    RATIO_BOUND,
                )
                .with_note(format!(
                    "{}; over LS {:.3} (thesis {:.3}); {}; {chain}",
                    filtered.note(1.0, "deg", 4),
                    filtered.std.mean / ls.std.mean,
                    PROPOSED_ATTITUDE[i] / LS_ATTITUDE[i],
                    epochwise_note(&self.filtered_epochwise)?
                )),
            );
        }
        Ok(out)
    }

    /// Figures 5.5-2..5.5-5 of the first run (the registered seed `seed`): per method,
    /// each baseline's ECEF errors and the KF's attitude and rate errors against time.
    /// Each caption quotes the std of the row in `rows` (the mean over runs of a run's
    /// std, over the whole series) and the mean over runs of a run's mean, beside the
    /// thesis's; the rates, of which the thesis prints no number, the same without it.
    fn curves(&self, rows: &[Row], seed: u64) -> Result<Vec<Curve>, ValidateError> {
        let mut out = Vec::new();
        for (proposed, runs, figure) in
            [(false, &self.ls, "5.5-2"), (true, &self.proposed, "5.5-3")]
        {
            let (thesis_std, thesis_mean) = if proposed {
                (PROPOSED_BASELINES, PROPOSED_BASELINE_MEANS)
            } else {
                (LS_BASELINES, LS_BASELINE_MEANS)
            };
            for k in 0..2 {
                let mut series = Vec::new();
                let mut values = Vec::new();
                for (i, c) in COMPONENTS.iter().enumerate() {
                    let pick = |e: &EpochErrors| e.baseline_ecef_m.get(k).map(|v| v[i]);
                    series.push((c.to_string(), plotted(runs)?.along(pick)));
                    let row = baseline_row(k, c, proposed);
                    values.extend(axis_values(
                        c,
                        "m",
                        runs,
                        |r| r.baseline_axis(k, i, false),
                        (Some(quoted(rows, &row)?), &row),
                        [thesis_mean[k][i], thesis_std[k][i]],
                    )?);
                }
                let lines = Decimated::lines(series);
                out.push(Curve {
                    figure: figure.into(),
                    panels: format!("baseline {}", k + 1),
                    title: format!(
                        "ECEF error, {}, seed {seed}, {}",
                        method(proposed),
                        lines.note("fixed epochs")
                    ),
                    x_label: "time since the start (s)".into(),
                    y_label: "estimate - truth (m)".into(),
                    series: lines.series,
                    references: Vec::new(),
                    values,
                });
            }
        }
        for (proposed, runs, figure) in
            [(false, &self.ls, "5.5-4"), (true, &self.proposed, "5.5-5")]
        {
            let (thesis_std, thesis_mean) = if proposed {
                (PROPOSED_ATTITUDE, PROPOSED_ATTITUDE_MEANS)
            } else {
                (LS_ATTITUDE, LS_ATTITUDE_MEANS)
            };
            let mut angles = (Vec::new(), Vec::new());
            let mut rates = (Vec::new(), Vec::new());
            for (i, axis) in AXES.iter().enumerate() {
                let run = plotted(runs)?;
                angles.0.push((
                    axis.to_string(),
                    run.along(|e| e.attitude_deg.map(|a| a[i])),
                ));
                rates
                    .0
                    .push((axis.to_string(), run.along(|e| e.rate_deg_s.map(|a| a[i]))));
                let row = attitude_row(axis, proposed);
                angles.1.extend(axis_values(
                    axis,
                    "deg",
                    runs,
                    |r| r.attitude_axis(i),
                    (Some(quoted(rows, &row)?), &row),
                    [thesis_mean[i], thesis_std[i]],
                )?);
                rates.1.extend(axis_values(
                    &format!("{axis} rate"),
                    "deg/s",
                    runs,
                    |r| r.rate_axis(i),
                    (None, ""),
                    [f64::NAN; 2],
                )?);
            }
            for (panel, what, unit, (series, values)) in [
                ("angles", "attitude", "deg", angles),
                ("rates", "rate", "deg/s", rates),
            ] {
                let lines = Decimated::lines(series);
                out.push(Curve {
                    figure: figure.into(),
                    panels: panel.into(),
                    title: format!(
                        "{what} error, KF on {} baselines, seed {seed}, {}",
                        if proposed { "reverse-UKF" } else { "LS" },
                        lines.note("epochs")
                    ),
                    x_label: "time since the start (s)".into(),
                    y_label: format!("estimate - truth ({unit})"),
                    series: lines.series,
                    references: Vec::new(),
                    values,
                });
            }
        }
        Ok(out)
    }
}

/// "LS" or "proposed (reverse UKF)".
fn method(proposed: bool) -> &'static str {
    if proposed {
        "proposed (reverse UKF)"
    } else {
        "LS"
    }
}

/// The run a figure draws: the first, on the registered seed.
fn plotted(runs: &[ChainComparison]) -> Result<&ChainComparison, ValidateError> {
    runs.first()
        .ok_or_else(|| ValidateError::Pipeline(format!("{SCENARIO}: no run to draw")))
}

/// The value of the row `name` of `rows`.
fn quoted(rows: &[Row], name: &str) -> Result<f64, ValidateError> {
    rows.iter()
        .find(|r| r.table == TABLE && r.row == name)
        .and_then(|r| r.ours)
        .ok_or_else(|| ValidateError::Pipeline(format!("{TABLE}: no row {name:?} for a figure")))
}

/// A caption's mean and std of `what`: the mean over runs of a run's mean of `series`,
/// and the row's std (`row`: its value and name; without a row, the mean over runs of a
/// run's std), beside the thesis's `[mean, std]` (NaN: none printed).
fn axis_values(
    what: &str,
    unit: &str,
    runs: &[ChainComparison],
    series: impl Fn(&ChainComparison) -> Vec<f64>,
    row: (Option<f64>, &str),
    thesis: [f64; 2],
) -> Result<[Value; 2], ValidateError> {
    let s = stats(runs, series)?;
    let n = runs.len();
    let printed = |v: f64| v.is_finite().then_some(v);
    let (std, source) = match row {
        (Some(v), name) => (v, format!(" (row \"{name}\")")),
        (None, _) => (s.std.mean, String::new()),
    };
    Ok([
        Value::new(
            format!("{what} error mean, mean over {n} runs"),
            unit,
            s.mean.mean,
            printed(thesis[0]),
        ),
        Value::new(
            format!("{what} error std, mean over {n} runs{source}"),
            unit,
            std,
            printed(thesis[1]),
        ),
    ])
}

/// The rows of tables 5.5-1..5.5-4 on the runs of `draw`.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    runs(draw)?.rows()
}

/// The data of thesis figures 5.5-2..5.5-5 on the registered seeds (all of them: the
/// captions quote the registered rows).
pub fn curves() -> Result<Vec<Curve>, ValidateError> {
    Ok(rows_and_curves()?.1)
}

/// The rows and the figures' data on the registered seeds, from one set of runs.
pub fn rows_and_curves() -> Result<(Vec<Row>, Vec<Curve>), ValidateError> {
    let seed = skyforge_scenarios::named(SCENARIO)?.seed;
    let runs = runs(Draw::REGISTERED)?;
    let rows = runs.rows()?;
    let curves = runs.curves(&rows, seed)?;
    Ok((rows, curves))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::thesis::attitude_runs;
    use crate::thesis::curves::MAX_POINTS;

    /// A run of 600 fixed epochs: errors of `scale` times +-1 around small biases
    /// (baselines, attitude from the second epoch, rates from the third).
    fn run(scale: f64) -> ChainComparison {
        let fixed = (0..600)
            .map(|k| {
                let e = if k % 2 == 0 { scale } else { -scale };
                EpochErrors {
                    t_s: 10.0 + k as f64,
                    baseline_ecef_m: vec![
                        [0.004 + 0.3 * e, 4e-4 + 0.02 * e, 5e-4 - 0.04 * e],
                        [0.01 + 0.25 * e, 2e-4 - 0.02 * e, 0.002 + 0.045 * e],
                    ],
                    baseline_ned_m: vec![[0.0; 3]; 2],
                    attitude_deg: (k >= 1).then_some([0.04 + e, 0.01 - e, 0.01 + 1.1 * e]),
                    rate_deg_s: (k >= 2).then_some([0.05 * e, -0.05 * e, 0.06 * e]),
                }
            })
            .collect();
        ChainComparison {
            epochs: 600,
            first_fix_s: Some(10.0),
            after_first_fix: 600,
            fixed,
            integers_checked: 100,
            integers_wrong: 0,
            largest_integer_distance_cycles: 0.1,
            fixed_epochs: 600,
            fixed_epochs_wrong: 0,
        }
    }

    #[test]
    fn figures_draw_the_first_run_and_quote_the_rows() {
        let runs = Runs {
            ls_epochwise: vec![run(1.2), run(1.3)],
            filtered_epochwise: vec![run(0.5), run(0.6)],
            ls: vec![run(1.0), run(1.1)],
            proposed: vec![run(0.3), run(0.4)],
        };
        let rows = runs.rows().unwrap();
        let curves = runs.curves(&rows, 5).unwrap();
        let ids: Vec<String> = curves.iter().map(Curve::number).collect();
        assert_eq!(
            ids,
            [
                "5.5-2 baseline 1",
                "5.5-2 baseline 2",
                "5.5-3 baseline 1",
                "5.5-3 baseline 2",
                "5.5-4 angles",
                "5.5-4 rates",
                "5.5-5 angles",
                "5.5-5 rates"
            ]
        );
        let row = |name: &str| {
            rows.iter()
                .find(|r| r.row == name)
                .and_then(|r| r.ours)
                .unwrap()
        };
        let mean_of = |runs: &[ChainComparison], series: &dyn Fn(&ChainComparison) -> Vec<f64>| {
            runs.iter()
                .map(|r| attitude_runs::mean(&series(r)))
                .sum::<f64>()
                / runs.len() as f64
        };
        for c in &curves {
            assert_eq!(c.series.len(), 3, "{}", c.figure);
            assert_eq!(c.values.len(), 6, "{}", c.figure);
            assert!(c.title.contains("seed 5"), "{}", c.title);
            for s in &c.series {
                assert!(s.points.len() >= 598 && s.points.len() <= MAX_POINTS);
                assert!(s.points.iter().all(|p| p.0.is_finite() && p.1.is_finite()));
            }
        }
        for (c, proposed) in curves[..4].iter().zip([false, false, true, true]) {
            let (method, set, thesis_std, thesis_mean) = if proposed {
                (
                    "proposed",
                    &runs.proposed,
                    PROPOSED_BASELINES,
                    PROPOSED_BASELINE_MEANS,
                )
            } else {
                ("LS", &runs.ls, LS_BASELINES, LS_BASELINE_MEANS)
            };
            let k = usize::from(c.panels == "baseline 2");
            for (i, comp) in COMPONENTS.iter().enumerate() {
                // The first run's ECEF errors, every epoch (600: no thinning).
                let drawn: Vec<(f64, f64)> = set[0]
                    .fixed
                    .iter()
                    .map(|e| (e.t_s, e.baseline_ecef_m[k][i]))
                    .collect();
                assert!(c.series[i].points == drawn, "{} {comp}", c.figure);
                let (mean, sd) = (&c.values[2 * i], &c.values[2 * i + 1]);
                let name = format!("baseline {} ECEF {comp} error ({method})", k + 1);
                assert_eq!(sd.ours, Some(row(&name)), "{name}");
                assert_eq!(sd.thesis, Some(thesis_std[k][i]));
                assert_eq!(mean.thesis, Some(thesis_mean[k][i]));
                let m = mean_of(set, &|r| r.baseline_axis(k, i, false));
                assert!((mean.ours.unwrap() - m).abs() < 1e-15, "{mean:?} {m}");
            }
        }
        for (pair, proposed) in curves[4..].chunks(2).zip([false, true]) {
            let (baselines, set, thesis_std, thesis_mean) = if proposed {
                (
                    "filtered",
                    &runs.proposed,
                    PROPOSED_ATTITUDE,
                    PROPOSED_ATTITUDE_MEANS,
                )
            } else {
                ("LS", &runs.ls, LS_ATTITUDE, LS_ATTITUDE_MEANS)
            };
            let [angles, rates] = pair else {
                panic!("two panels")
            };
            for (i, axis) in AXES.iter().enumerate() {
                assert_eq!(angles.series[i].points.len(), 599);
                assert_eq!(rates.series[i].points.len(), 598);
                assert_eq!(
                    angles.series[i].points[0],
                    (11.0, set[0].fixed[1].attitude_deg.unwrap()[i])
                );
                let name = format!("{axis} error (KF on {baselines} baselines)");
                assert_eq!(angles.values[2 * i + 1].ours, Some(row(&name)), "{name}");
                assert_eq!(angles.values[2 * i + 1].thesis, Some(thesis_std[i]));
                assert_eq!(angles.values[2 * i].thesis, Some(thesis_mean[i]));
                // The thesis prints no rate numbers: ours alone, over the whole series.
                let (mean, sd) = (&rates.values[2 * i], &rates.values[2 * i + 1]);
                assert_eq!((mean.thesis, sd.thesis), (None, None));
                let s = runs_std(set, i);
                assert!((sd.ours.unwrap() - s).abs() < 1e-15, "{sd:?} {s}");
            }
        }
    }

    /// The mean over runs of a run's rate-error std of axis `i`.
    fn runs_std(runs: &[ChainComparison], i: usize) -> f64 {
        runs.iter()
            .map(|r| attitude_runs::std(&r.rate_axis(i)))
            .sum::<f64>()
            / runs.len() as f64
    }

    #[test]
    fn proposed_rows_compare_with_the_ls() {
        let r = proposed_row("r".into(), "deg", 0.33, 0.5, 1.0, RATIO_BOUND);
        assert_eq!(r.verdict, Verdict::Reproduced);
        assert_eq!(r.tolerance, "below 0.6 x LS");
        let r = proposed_row("r".into(), "m", 0.1, 0.7, 1.0, RATIO_BOUND);
        assert_eq!(r.verdict, Verdict::Deviates);
        let r = proposed_row("r".into(), "m", 0.1, 0.9, 1.0, 1.0);
        assert_eq!(
            (r.verdict, r.tolerance.as_str()),
            (Verdict::Reproduced, "below LS")
        );
    }

    #[test]
    fn the_two_chains_differ_only_by_the_reverse_filter() {
        let [ls_epochwise, epochwise, ls, proposed] = configs(0.01, 0.0365);
        assert_eq!(ls.reverse_filter, None);
        assert_eq!(ls.attitude.method, AttitudeMethod::Kf);
        assert_eq!(ls.phase.sigma0_m, 0.01);
        assert_eq!(
            RelativeConfig {
                reverse_filter: None,
                ..proposed.clone()
            },
            ls
        );
        for (a, b) in [(ls_epochwise, ls), (epochwise, proposed)] {
            assert_eq!(a.attitude.method, AttitudeMethod::LeastSquares);
            assert_eq!(
                RelativeConfig {
                    attitude: b.attitude,
                    ..a
                },
                b
            );
        }
    }
}
