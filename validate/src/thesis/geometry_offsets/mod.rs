//! T-4.3 (thesis tables 4.3-2..4.3-6): on-orbit estimation of the antenna geometry
//! offsets. The bundled scenario [`SCENARIO`] puts the antennas at `B0 + dB0` while the
//! receiver is told `B0`; the receiver's chain (double differences, plain LAMBDA as the
//! thesis, hold) gives the fixed baselines of each epoch in NED with `Q_BB`.
//!
//! * Estimation run, the first [`ESTIMATION_EPOCHS`]: the 22-state UKF of eqs.
//!   4.3-5..4.3-26 as the thesis prints it (all six offsets free, `R = Q_BB` in every
//!   window: [`Orientation::Free`], [`WindowWeighting::Thesis`]), `T` = 1 s,
//!   `S_xi'` = 1e-9, `S_Delta'` = 1e-15, kappa = 0.5. Rows: the error of `xi_t` (table
//!   4.3-2), of the rates (4.3-3) and of the six offsets (4.3-4), over every update.
//! * Comparison run, the next [`COMPARISON_EPOCHS`]: the 6-state UKF of eqs.
//!   4.3-27..4.3-32 on `B0` and on `B0' = B0 + dB0_hat` (the last estimate). Rows: the
//!   attitude error std and mean of both (table 4.3-5), the before/after std ratios, and
//!   the rate error std of both (4.3-6).
//! * The chain: every fixed integer of the run against the truth's double-difference
//!   integer, as the other attitude tables check theirs (a SkyForge row: none wrong).
//!
//! Baselines alone do not determine the orientation of the antenna triangle in the body
//! frame (`receiver::geometry_offset::shape`; the test
//! `a_rotation_of_the_antennas_and_the_inverse_rotation_of_the_attitude_measure_alike`).
//! An offset row that misses while the same offset of the estimate turned to the true
//! orientation is within the tolerance is `explained` by that; SkyForge's own rows (no
//! thesis number) give the triangle's shape error and the default estimator's
//! (orientation held at the nominal one) offsets against the truth so turned.
//!
//! Runs on [`SEEDS`](crate::attitude::seeds::SEEDS) seeds; a row's value is the mean over
//! runs of a run's statistic, the standard error over runs in its note.
//!
//! Figures ([`rows_and_curves`], from the same runs as the rows): 4.3-2 and 4.3-3 (the
//! printed filter's `xi_t` and rate errors), 4.3-6 (its offset rate `Delta'`), 4.3-7 and
//! 4.3-8 (the 6-state UKF's attitude and rate errors under `B0`), 4.3-9 and 4.3-10 (under
//! `B0'`), each drawn from the first run and quoting the rows' stds.

mod seed;

use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::AcrossRuns;
use crate::thesis::ValidateError;
use crate::thesis::attitude_runs::{factor_row, mean, std};
use crate::thesis::curves::{Curve, Decimated, Value};
use seed::{AxisSeries, SeedResult};

/// The table.
pub const TABLE: &str = "T-4.3";
/// The bundled scenario.
pub const SCENARIO: &str = "thesis/t-4.3";
/// Thesis 4.3.4: epochs of the estimation run, then of the comparison run.
pub const ESTIMATION_EPOCHS: usize = 30247;
pub const COMPARISON_EPOCHS: usize = 25000;
/// `THESIS_TARGETS.md`: stds within this factor; offsets within 1 mm with std below 1 mm;
/// before/after std ratios at least 4 (yaw, pitch) and 2 (roll).
const FACTOR: f64 = 2.0;
const OFFSET_TOLERANCE_M: f64 = 1e-3;
const RATIO_BARS: [f64; 3] = [4.0, 4.0, 2.0];
const AXES: [&str; 3] = ["yaw", "pitch", "roll"];
const OFFSETS: [&str; 6] = ["dx1", "dy1", "dz1", "dx2", "dy2", "dz2"];

/// Table 4.3-2: std and mean of the `xi_t` error (deg).
const XI_STD: [f64; 3] = [0.0614, 0.0855, 0.0902];
const XI_MEAN: [f64; 3] = [0.0107, 0.0227, 0.0056];
/// Table 4.3-3: std and mean of the rate error (deg/s).
const RATE_STD: [f64; 3] = [0.0053, 0.0064, 0.0066];
const RATE_MEAN: [f64; 3] = [-5.3640e-6, -4.8794e-6, 2.3810e-5];
/// Thesis 4.3.4, beside figure 4.3-6: mean and std of the estimated offset rate (m/s).
const OFFSET_RATE_MEAN: f64 = -1.0084e-8;
const OFFSET_RATE_STD: f64 = 7.7536e-7;
/// Table 4.3-4: mean of the offset errors (m).
const OFFSET_MEAN: [f64; 6] = [
    1.0463e-5, -2.0571e-6, 5.5375e-6, -2.0109e-6, 5.4989e-6, 3.8580e-6,
];
/// Table 4.3-5: attitude error std after and before the correction (deg).
const AFTER_STD: [f64; 3] = [0.0817, 0.1426, 0.1517];
const BEFORE_STD: [f64; 3] = [1.8840, 1.6176, 0.6723];
/// Table 4.3-5: attitude error mean after and before the correction (deg).
const AFTER_MEAN: [f64; 3] = [-0.0007, -0.0023, 0.0026];
const BEFORE_MEAN: [f64; 3] = [0.1357, -0.0064, -0.0694];
// assumed: THESIS_TARGETS.md bounds the stds and ratios of table 4.3-5, not its means.
// Fixed before the first run with the mean rows: a mean reproduces when its magnitude is
// at most the thesis's std of the same axis and run (none of the thesis's own means
// exceeds 0.11 of its std: its errors are spread, not bias), and a mean after the correction
// must besides not exceed in magnitude the same runs' mean before it by more than
// MEAN_GROWTH_SE standard errors (the correction's physical claim: it removes the
// systematic error of the wrong geometry, so it must not add one).
const MEAN_GROWTH_SE: f64 = 2.0;
/// Table 4.3-6: rate error std after and before (deg/s).
const RATE_AFTER_STD: [f64; 3] = [0.0076, 0.0077, 0.0078];
const RATE_BEFORE_STD: [f64; 3] = [0.0091, 0.0090, 0.0092];
/// Table 4.3-6: rate error mean after and before (deg/s).
const RATE_AFTER_MEAN: [f64; 3] = [7.5416e-6, 6.5390e-6, 6.8627e-5];
const RATE_BEFORE_MEAN: [f64; 3] = [7.7267e-5, 7.5923e-5, 5.6257e-5];

/// Builds the rows from the runs.
struct Table<'a> {
    runs: &'a [SeedResult],
    /// The chain's fix counts, for the notes.
    chain: String,
}

/// The note's reason an explained row names.
const ORIENTATION: &str = "turned to the estimate's orientation (which baselines do not see: receiver::geometry_offset::shape)";

impl<'a> Table<'a> {
    fn new(runs: &'a [SeedResult]) -> Self {
        let fixed = |i: usize| runs.iter().map(|r| r.fixed[i]).sum::<usize>();
        let integers = integers(runs);
        let chain = format!(
            "{} runs; fixed epochs {} of {} (estimation) and {} of {} (comparison); {} fixed integers checked against the truth, {} wrong",
            runs.len(),
            fixed(0),
            ESTIMATION_EPOCHS * runs.len(),
            fixed(1),
            COMPARISON_EPOCHS * runs.len(),
            integers.check.checked,
            integers.check.wrong
        );
        Self { runs, chain }
    }

    /// `value(run)` over the runs.
    fn across(&self, value: impl Fn(&SeedResult) -> f64) -> Result<AcrossRuns, ValidateError> {
        AcrossRuns::of(&self.runs.iter().map(value).collect::<Vec<_>>()).ok_or_else(|| {
            ValidateError::Pipeline(format!("{SCENARIO}: a run has too few fixed epochs"))
        })
    }

    /// Per axis: the mean over runs of a run's std, within [`FACTOR`] of `thesis`.
    fn std_rows(
        &self,
        what: &str,
        unit: &str,
        thesis: &[f64; 3],
        series: impl Fn(&SeedResult) -> &AxisSeries,
    ) -> Result<Vec<Row>, ValidateError> {
        AXES.iter()
            .enumerate()
            .map(|(i, axis)| {
                let a = self.across(|r| series(r).std()[i])?;
                Ok(factor_row(
                    TABLE,
                    format!("{what} {axis}"),
                    unit,
                    thesis[i],
                    a.mean,
                    FACTOR,
                )
                .with_note(format!(
                    "std over runs {}; {}",
                    a.describe(1.0, 5),
                    self.chain
                )))
            })
            .collect()
    }

    /// Table 4.3-2: explained where the std against the turned truth is in the factor.
    fn xi_rows(&self) -> Result<Vec<Row>, ValidateError> {
        let (what, unit, thesis, series) = XI;
        let rows = self.std_rows(what, unit, &thesis, series)?;
        rows.into_iter()
            .enumerate()
            .map(|(i, mut row)| {
                let turned = self.across(|r| r.estimation.xi_turned.std()[i])?;
                let ratio = turned.mean / XI_STD[i];
                if row.verdict == Verdict::Deviates && (1.0 / FACTOR..=FACTOR).contains(&ratio) {
                    row.verdict = Verdict::Explained;
                }
                let note = format!(
                    "{}; against the true attitude of the antennas {ORIENTATION} {}",
                    row.note,
                    turned.describe(1.0, 5)
                );
                Ok(row.with_note(note))
            })
            .collect()
    }

    /// Table 4.3-4: each offset's error, mean and std over the run, within 1 mm;
    /// explained where the same against the turned truth is.
    fn offset_rows(&self) -> Result<Vec<Row>, ValidateError> {
        let mean_of = |v: &Vec<f64>| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let within = |m: &AcrossRuns, s: &AcrossRuns| {
            m.mean.abs() < OFFSET_TOLERANCE_M && s.mean < OFFSET_TOLERANCE_M
        };
        OFFSETS
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let mean = self.across(|r| mean_of(&r.estimation.offsets[i]))?;
                let sd = self.across(|r| std(&r.estimation.offsets[i]))?;
                let turned_mean = self.across(|r| mean_of(&r.estimation.offsets_turned[i]))?;
                let turned_sd = self.across(|r| std(&r.estimation.offsets_turned[i]))?;
                let verdict = match (within(&mean, &sd), within(&turned_mean, &turned_sd)) {
                    (true, _) => Verdict::Reproduced,
                    (false, true) => Verdict::Explained,
                    (false, false) => Verdict::Deviates,
                };
                Ok(offset_row(format!("4.3-4 {name} error (mean over the run)"), Some(OFFSET_MEAN[i]), mean.mean, verdict)
                    .with_note(format!(
                        "mean over runs {} mm, std over the run {} mm; against the true geometry {ORIENTATION} mean {} mm, std {} mm; {}",
                        mean.describe(1e3, 3),
                        sd.describe(1e3, 3),
                        turned_mean.describe(1e3, 3),
                        turned_sd.describe(1e3, 3),
                        self.chain
                    )))
            })
            .collect()
    }

    /// SkyForge's own rows: the printed filter's final lengths, the default estimator's
    /// final offsets.
    fn own_rows(&self) -> Result<Vec<Row>, ValidateError> {
        let own = |row: String, a: AcrossRuns, note: &str| {
            offset_row(
                row,
                None,
                a.mean,
                Verdict::from_ok(a.mean.abs() < OFFSET_TOLERANCE_M),
            )
            .with_note(format!("{note}, {} mm", a.describe(1e3, 4)))
        };
        let mut out = Vec::new();
        for (i, name) in ["length 1", "length 2"].iter().enumerate() {
            let a = self.across(|r| r.shape_final[i])?;
            out.push(own(
                format!("4.3-4 final {name} error (SkyForge)"),
                a,
                "the thesis filter's final B0' against the true lengths",
            ));
        }
        for (i, name) in OFFSETS.iter().enumerate() {
            let a = self.across(|r| r.pinned_final[i])?;
            out.push(own(format!("4.3-4 final {name} error, orientation held (SkyForge)"), a, "the default estimator (orientation held at the nominal one, each epoch weighted once) against the true geometry turned to the nominal orientation"));
        }
        Ok(out)
    }

    /// Table 4.3-5: per axis, the mean over runs of a run's mean error after and before the
    /// correction, each in the thesis's std of its axis and run; after it, besides, not
    /// above the mean before it (the assumption at [`MEAN_GROWTH_SE`]).
    fn mean_rows(&self) -> Result<Vec<Row>, ValidateError> {
        let mut out = Vec::new();
        for (after, (column, thesis_mean, thesis_std)) in [
            (true, ("after", AFTER_MEAN, AFTER_STD)),
            (false, ("before", BEFORE_MEAN, BEFORE_STD)),
        ] {
            for (i, axis) in AXES.iter().enumerate() {
                let pick = |r: &SeedResult, turned: bool| -> f64 {
                    let s = match (after, turned) {
                        (true, false) => &r.after,
                        (true, true) => &r.after_turned,
                        (false, false) => &r.before,
                        (false, true) => &r.before_turned,
                    };
                    s.mean()[i]
                };
                let ours = self.across(|r| pick(r, false))?;
                let turned = self.across(|r| pick(r, true))?;
                let within = ours.mean.abs() <= thesis_std[i];
                let mut tolerance = format!("|mean| <= {} (thesis std)", thesis_std[i]);
                let mut note = format!("mean over runs {} deg", ours.describe(1.0, 4));
                let ok = if after {
                    let before = self.across(|r| r.before.mean()[i])?;
                    let se = |a: &AcrossRuns| a.standard_error.unwrap_or(0.0);
                    let bar = before.mean.abs() + MEAN_GROWTH_SE * se(&ours).hypot(se(&before));
                    tolerance.push_str(&format!(
                        " and not above |mean before| + {MEAN_GROWTH_SE} SE"
                    ));
                    note.push_str(&format!(
                        "; before the correction {} deg (|mean| after {} the bar {bar:.4})",
                        before.describe(1.0, 4),
                        if ours.mean.abs() <= bar {
                            "within"
                        } else {
                            "above"
                        }
                    ));
                    within && ours.mean.abs() <= bar
                } else {
                    within
                };
                note.push_str(&format!(
                    "; against the true attitude of the antennas turned to the orientation of {} (which baselines do not see: receiver::geometry_offset::shape) {} deg; {}",
                    if after { "B0'" } else { "B0" },
                    turned.describe(1.0, 4),
                    self.chain
                ));
                out.push(
                    Row::measured(
                        TABLE,
                        format!("4.3-5 attitude error mean {column} correction {axis}"),
                        "mean",
                        "deg",
                        Some(thesis_mean[i]),
                        ours.mean,
                        (tolerance, Verdict::from_ok(ok)),
                    )
                    .with_note(note),
                );
            }
        }
        Ok(out)
    }

    /// SkyForge's row on the chain: its fixed integers against the truth's, none wrong.
    fn integer_row(&self) -> Row {
        let (n, wrong_epochs) = {
            let i = integers(self.runs);
            (i.check, i.wrong_epochs)
        };
        Row::measured(
            TABLE,
            "chain fixed integers wrong (SkyForge)",
            "count",
            "-",
            None,
            n.wrong as f64,
            (
                "0 wrong".into(),
                Verdict::from_ok(n.wrong == 0 && n.checked > 0),
            ),
        )
        .with_note(format!(
            "{} of {} fixed integers wrong against the truth's double-difference integers ({} epochs with every ambiguity fixed had a wrong one; largest distance of an observed double difference from the truth's integer {:.3} cycles); {}",
            n.wrong, n.checked, wrong_epochs, n.largest_distance_cycles, self.chain
        ))
    }

    /// Table 4.3-5: the before/after std ratios against the bars.
    fn ratio_rows(&self) -> Result<Vec<Row>, ValidateError> {
        AXES.iter()
            .enumerate()
            .map(|(i, axis)| {
                let a = self.across(|r| r.before.std()[i] / r.after.std()[i])?;
                Ok(Row::measured(
                    TABLE,
                    format!("4.3-5 before/after std ratio {axis}"),
                    "ratio",
                    "-",
                    Some(BEFORE_STD[i] / AFTER_STD[i]),
                    a.mean,
                    (
                        format!(">= {}", RATIO_BARS[i]),
                        Verdict::from_ok(a.mean >= RATIO_BARS[i]),
                    ),
                )
                .with_note(format!("over runs {}", a.describe(1.0, 2))))
            })
            .collect()
    }
}

/// The chain's integers summed over `runs` (the largest distance the largest).
fn integers(runs: &[SeedResult]) -> seed::Integers {
    runs.iter()
        .map(|r| r.integers)
        .fold(seed::Integers::default(), seed::Integers::merge)
}

/// A row in tolerance of 1 mm: SkyForge's own (`thesis` None) or against the thesis's mean.
fn offset_row(row: String, thesis: Option<f64>, ours: f64, verdict: Verdict) -> Row {
    Row::measured(
        TABLE,
        row,
        "mean",
        "m",
        thesis,
        ours,
        ("|error| < 1 mm, std < 1 mm".into(), verdict),
    )
}

/// A table of per-axis std rows: its name, unit, the thesis's stds and the runs' error
/// series.
type StdTable = (
    &'static str,
    &'static str,
    [f64; 3],
    fn(&SeedResult) -> &AxisSeries,
);

const XI: StdTable = ("4.3-2 xi_t error", "deg", XI_STD, |r| &r.estimation.xi);
const RATES: StdTable = ("4.3-3 rate error", "deg/s", RATE_STD, |r| {
    &r.estimation.rates
});
const ATTITUDE: [StdTable; 2] = [
    (
        "4.3-5 attitude error after correction",
        "deg",
        AFTER_STD,
        |r| &r.after,
    ),
    (
        "4.3-5 attitude error before correction",
        "deg",
        BEFORE_STD,
        |r| &r.before,
    ),
];
const COMPARISON_RATES: [StdTable; 2] = [
    (
        "4.3-6 rate error after correction",
        "deg/s",
        RATE_AFTER_STD,
        |r| &r.rate_after,
    ),
    (
        "4.3-6 rate error before correction",
        "deg/s",
        RATE_BEFORE_STD,
        |r| &r.rate_before,
    ),
];

/// A figure of per-axis errors against time: its number, what the run shows, what a
/// point is, the rows whose stds the caption quotes and the thesis's means beside them.
struct AxisFigure {
    figure: &'static str,
    title: &'static str,
    points: &'static str,
    rows: StdTable,
    thesis_mean: [f64; 3],
}

const AXIS_FIGURES: [AxisFigure; 6] = [
    AxisFigure {
        figure: "4.3-2",
        title: "xi_t error, 22-state UKF",
        points: "updates",
        rows: XI,
        thesis_mean: XI_MEAN,
    },
    AxisFigure {
        figure: "4.3-3",
        title: "rate error, 22-state UKF",
        points: "updates",
        rows: RATES,
        thesis_mean: RATE_MEAN,
    },
    AxisFigure {
        figure: "4.3-7",
        title: "attitude error, 6-state UKF, B0 uncorrected",
        points: "epochs",
        rows: ATTITUDE[1],
        thesis_mean: BEFORE_MEAN,
    },
    AxisFigure {
        figure: "4.3-8",
        title: "rate error, 6-state UKF, B0 uncorrected",
        points: "epochs",
        rows: COMPARISON_RATES[1],
        thesis_mean: RATE_BEFORE_MEAN,
    },
    AxisFigure {
        figure: "4.3-9",
        title: "attitude error, 6-state UKF, B0' corrected",
        points: "epochs",
        rows: ATTITUDE[0],
        thesis_mean: AFTER_MEAN,
    },
    AxisFigure {
        figure: "4.3-10",
        title: "rate error, 6-state UKF, B0' corrected",
        points: "epochs",
        rows: COMPARISON_RATES[0],
        thesis_mean: RATE_AFTER_MEAN,
    },
];

impl Table<'_> {
    /// Every row of tables 4.3-2..4.3-6.
    fn rows(&self) -> Result<Vec<Row>, ValidateError> {
        let std_rows = |tables: &[StdTable]| -> Result<Vec<Row>, ValidateError> {
            let mut out = Vec::new();
            for (what, unit, thesis, series) in tables {
                out.extend(self.std_rows(what, unit, thesis, series)?);
            }
            Ok(out)
        };
        let mut out = self.xi_rows()?;
        out.extend(std_rows(&[RATES])?);
        out.extend(self.offset_rows()?);
        out.extend(self.own_rows()?);
        out.extend(std_rows(&ATTITUDE)?);
        out.extend(self.mean_rows()?);
        out.extend(self.ratio_rows()?);
        out.extend(std_rows(&COMPARISON_RATES)?);
        out.push(self.integer_row());
        Ok(out)
    }

    /// The run a figure draws: the first, on the registered seed.
    fn plotted(&self) -> Result<&SeedResult, ValidateError> {
        self.runs
            .first()
            .ok_or_else(|| ValidateError::Pipeline(format!("{SCENARIO}: no run to draw")))
    }

    /// Figures 4.3-2, 4.3-3, 4.3-6..4.3-10 of the first run; each caption quotes the std
    /// of the row in `rows` (the mean over runs of a run's std, over the whole series)
    /// and the mean over runs of a run's mean, beside the thesis's.
    fn curves(&self, rows: &[Row]) -> Result<Vec<Curve>, ValidateError> {
        let mut out = AXIS_FIGURES[..2]
            .iter()
            .map(|f| self.axis_figure(rows, f))
            .collect::<Result<Vec<_>, _>>()?;
        out.push(self.offset_rate_figure()?);
        for f in &AXIS_FIGURES[2..] {
            out.push(self.axis_figure(rows, f)?);
        }
        Ok(out)
    }

    /// A figure of yaw, pitch and roll errors against time.
    fn axis_figure(&self, rows: &[Row], f: &AxisFigure) -> Result<Curve, ValidateError> {
        let (what, unit, thesis_std, series) = f.rows;
        let run = self.plotted()?;
        let lines = Decimated::lines(
            AXES.iter()
                .enumerate()
                .map(|(i, axis)| (axis.to_string(), series(run).points(i)))
                .collect(),
        );
        let table = what.split(' ').next().unwrap_or(what);
        let n = self.runs.len();
        let mut values = Vec::new();
        for (i, axis) in AXES.iter().enumerate() {
            let row = format!("{what} {axis}");
            let mean = self.across(|r| series(r).mean()[i])?;
            values.push(Value::new(
                format!("{axis} error mean, mean over {n} runs (thesis table {table})"),
                unit,
                mean.mean,
                Some(f.thesis_mean[i]),
            ));
            values.push(Value::new(
                format!("{axis} error std, mean over {n} runs (row \"{row}\")"),
                unit,
                quoted(rows, &row)?,
                Some(thesis_std[i]),
            ));
        }
        Ok(Curve {
            figure: f.figure.into(),
            panels: String::new(),
            title: format!("{}, seed {}, {}", f.title, run.seed, lines.note(f.points)),
            x_label: "time since the start (s)".into(),
            y_label: format!("estimate - truth ({unit})"),
            series: lines.series,
            references: Vec::new(),
            values,
        })
    }

    /// Figure 4.3-6: the estimated offset rate against time, its mean and std beside the
    /// ones the thesis's text prints.
    fn offset_rate_figure(&self) -> Result<Curve, ValidateError> {
        let run = self.plotted()?;
        let lines = Decimated::lines(vec![("Delta'".into(), run.estimation.offset_rate.clone())]);
        let values_of =
            |r: &SeedResult| -> Vec<f64> { r.estimation.offset_rate.iter().map(|p| p.1).collect() };
        let n = self.runs.len();
        let mean = self.across(|r| mean(&values_of(r)))?;
        let sd = self.across(|r| std(&values_of(r)))?;
        Ok(Curve {
            figure: "4.3-6".into(),
            panels: String::new(),
            title: format!(
                "estimated Delta', 22-state UKF, seed {}, {}",
                run.seed,
                lines.note("updates")
            ),
            x_label: "time since the start (s)".into(),
            y_label: "Delta' (m/s)".into(),
            series: lines.series,
            references: Vec::new(),
            values: vec![
                Value::new(
                    format!("Delta' mean, mean over {n} runs (thesis 4.3.4 text)"),
                    "m/s",
                    mean.mean,
                    Some(OFFSET_RATE_MEAN),
                ),
                Value::new(
                    format!("Delta' std, mean over {n} runs (thesis 4.3.4 text)"),
                    "m/s",
                    sd.mean,
                    Some(OFFSET_RATE_STD),
                ),
            ],
        })
    }
}

/// The value of the row `name` of `rows`.
fn quoted(rows: &[Row], name: &str) -> Result<f64, ValidateError> {
    rows.iter()
        .find(|r| r.table == TABLE && r.row == name)
        .and_then(|r| r.ours)
        .ok_or_else(|| ValidateError::Pipeline(format!("{TABLE}: no row {name:?} for a figure")))
}

/// The rows of tables 4.3-2..4.3-6 on the runs of `draw`.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    Table::new(&seed::runs(draw)?).rows()
}

/// The data of thesis figures 4.3-2, 4.3-3 and 4.3-6..4.3-10 on the registered seeds
/// (all of them: the captions quote the registered rows).
pub fn curves() -> Result<Vec<Curve>, ValidateError> {
    Ok(rows_and_curves()?.1)
}

/// The rows and the figures' data on the registered seeds, from one set of runs.
pub fn rows_and_curves() -> Result<(Vec<Row>, Vec<Curve>), ValidateError> {
    let runs = seed::runs(Draw::REGISTERED)?;
    let t = Table::new(&runs);
    let rows = t.rows()?;
    let curves = t.curves(&rows)?;
    Ok((rows, curves))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attitude::compare::IntegerCheck;
    use crate::thesis::curves::MAX_POINTS;
    use seed::Estimation;

    /// `n` values 1 s apart from `t0_s`: `bias` plus `scale` times +-1 (yaw), -+1 (pitch),
    /// +-2 (roll): means exactly `bias` for an even `n`.
    fn axes(n: usize, t0_s: f64, bias: [f64; 3], scale: f64) -> AxisSeries {
        let mut s = AxisSeries::default();
        for k in 0..n {
            let e = if k % 2 == 0 { scale } else { -scale };
            s.push(
                t0_s + k as f64,
                [bias[0] + e, bias[1] - e, bias[2] + 2.0 * e],
            );
        }
        s
    }

    /// A run of 4000 estimation updates and 3000 comparison epochs, its errors scaled by
    /// `scale`.
    fn run(seed: u64, scale: f64) -> SeedResult {
        let (n, m) = (4000, 3000);
        let offsets: [Vec<f64>; 6] =
            std::array::from_fn(|i| (0..n).map(|k| 1e-5 * (i + k % 3) as f64).collect());
        SeedResult {
            seed,
            estimation: Estimation {
                xi: axes(n, 3.0, [0.01, 0.02, 0.005], 0.06 * scale),
                xi_turned: axes(n, 3.0, [0.0; 3], 0.05 * scale),
                rates: axes(n, 3.0, [1e-5, -2e-5, 3e-5], 0.005 * scale),
                offsets_turned: offsets.clone(),
                offsets,
                offset_rate: (0..n)
                    .map(|k| {
                        (
                            3.0 + k as f64,
                            scale * if k % 2 == 0 { 1e-6 } else { -8e-7 },
                        )
                    })
                    .collect(),
            },
            shape_final: [1e-4; 3],
            pinned_final: [2e-4; 6],
            after: axes(m, 5000.0, [-0.001, 0.002, 0.003], 0.08 * scale),
            before: axes(m, 5000.0, [0.1, -0.01, -0.07], 1.5 * scale),
            after_turned: axes(m, 5000.0, [0.0; 3], 0.08 * scale),
            before_turned: axes(m, 5000.0, [0.0; 3], 1.5 * scale),
            rate_after: axes(m, 5000.0, [1e-5; 3], 0.007 * scale),
            rate_before: axes(m, 5000.0, [7e-5; 3], 0.009 * scale),
            fixed: [n, m],
            integers: seed::Integers {
                check: IntegerCheck {
                    checked: 10 * n,
                    wrong: 0,
                    largest_distance_cycles: 0.1,
                },
                wrong_epochs: 0,
            },
        }
    }

    /// The row `name` of `rows`.
    fn find<'r>(rows: &'r [Row], name: &str) -> &'r Row {
        rows.iter().find(|r| r.row == name).unwrap()
    }

    #[test]
    fn means_and_integers_are_graded() {
        // Means near the thesis's: every mean row and the integer row reproduce.
        let runs = [run(7, 1.0), run(8, 1.5)];
        let rows = Table::new(&runs).rows().unwrap();
        for axis in AXES {
            for column in ["after", "before"] {
                let r = find(
                    &rows,
                    &format!("4.3-5 attitude error mean {column} correction {axis}"),
                );
                assert_eq!(r.verdict, Verdict::Reproduced, "{r:?}");
                assert_eq!(r.quantity, "mean");
            }
        }
        let r = find(&rows, "4.3-5 attitude error mean after correction roll");
        assert_eq!(r.thesis, Some(AFTER_MEAN[2]));
        assert!((r.ours.unwrap() - 0.003).abs() < 1e-12, "{r:?}");
        assert!(
            r.note.contains("before the correction -0.0700"),
            "{}",
            r.note
        );
        let r = find(&rows, "chain fixed integers wrong (SkyForge)");
        assert_eq!((r.thesis, r.ours), (None, Some(0.0)));
        assert_eq!(r.verdict, Verdict::Reproduced);
        // Every row whose note gives the chain (all but the final offsets and the ratios).
        let with_chain = rows
            .iter()
            .filter(|r| !(r.row.starts_with("4.3-4 final") || r.row.contains("ratio")));
        assert_eq!(with_chain.clone().count(), 42 - 8 - 3);
        for r in with_chain {
            assert!(
                r.note
                    .contains("80000 fixed integers checked against the truth, 0 wrong"),
                "{r:?}"
            );
        }

        // A constant misalignment of 2 deg in yaw after the correction (and 0.1 deg in
        // roll, above the mean before it but within the thesis's std), one wrong integer.
        let mut runs = [run(7, 1.0), run(8, 1.5)];
        for r in &mut runs {
            r.after = axes(3000, 5000.0, [2.0, 0.002, 0.1], 0.08);
            r.integers.check.wrong = 1;
            r.integers.wrong_epochs = 1;
        }
        let rows = Table::new(&runs).rows().unwrap();
        let verdict = |name: &str| find(&rows, name).verdict;
        assert_eq!(
            verdict("4.3-5 attitude error mean after correction yaw"),
            Verdict::Deviates
        );
        assert_eq!(
            verdict("4.3-5 attitude error mean after correction pitch"),
            Verdict::Reproduced
        );
        // 0.1 deg: within the thesis's 0.1517, above the 0.07 before it.
        assert_eq!(
            verdict("4.3-5 attitude error mean after correction roll"),
            Verdict::Deviates
        );
        let r = find(&rows, "chain fixed integers wrong (SkyForge)");
        assert_eq!((r.ours, r.verdict), (Some(2.0), Verdict::Deviates));
        assert!(
            r.note.contains("2 of 80000 fixed integers wrong"),
            "{}",
            r.note
        );
    }

    #[test]
    fn figures_draw_the_first_run_and_quote_the_rows() {
        let runs = [run(7, 1.0), run(8, 1.5)];
        let t = Table::new(&runs);
        let rows = t.rows().unwrap();
        let curves = t.curves(&rows).unwrap();
        let ids: Vec<&str> = curves.iter().map(|c| c.figure.as_str()).collect();
        assert_eq!(
            ids,
            [
                "4.3-2", "4.3-3", "4.3-6", "4.3-7", "4.3-8", "4.3-9", "4.3-10"
            ]
        );
        for c in &curves {
            assert_eq!(c.series.len(), if c.figure == "4.3-6" { 1 } else { 3 });
            for s in &c.series {
                assert!(!s.points.is_empty() && s.points.len() <= MAX_POINTS);
                assert!(s.points.iter().all(|p| p.0.is_finite() && p.1.is_finite()));
            }
            assert!(c.title.contains("seed 7"), "{}", c.title);
            assert!(
                c.values
                    .iter()
                    .all(|v| v.ours.is_some() && v.thesis.is_some())
            );
        }
        let row = |name: &str| {
            rows.iter()
                .find(|r| r.row == name)
                .and_then(|r| r.ours)
                .unwrap()
        };
        let first = &runs[0];
        type Pick = fn(&SeedResult) -> &AxisSeries;
        /// Figure, the rows it quotes, its series, the thesis's stds and means, the title's
        /// end.
        type Expected = (
            &'static str,
            &'static str,
            Pick,
            [f64; 3],
            [f64; 3],
            &'static str,
        );
        let figures: [Expected; 6] = [
            (
                "4.3-2",
                "4.3-2 xi_t error",
                |r| &r.estimation.xi,
                XI_STD,
                XI_MEAN,
                "every 3rd of 4000 updates",
            ),
            (
                "4.3-3",
                "4.3-3 rate error",
                |r| &r.estimation.rates,
                RATE_STD,
                RATE_MEAN,
                "every 3rd of 4000 updates",
            ),
            (
                "4.3-7",
                "4.3-5 attitude error before correction",
                |r| &r.before,
                BEFORE_STD,
                BEFORE_MEAN,
                "every 2nd of 3000 epochs",
            ),
            (
                "4.3-8",
                "4.3-6 rate error before correction",
                |r| &r.rate_before,
                RATE_BEFORE_STD,
                RATE_BEFORE_MEAN,
                "every 2nd of 3000 epochs",
            ),
            (
                "4.3-9",
                "4.3-5 attitude error after correction",
                |r| &r.after,
                AFTER_STD,
                AFTER_MEAN,
                "every 2nd of 3000 epochs",
            ),
            (
                "4.3-10",
                "4.3-6 rate error after correction",
                |r| &r.rate_after,
                RATE_AFTER_STD,
                RATE_AFTER_MEAN,
                "every 2nd of 3000 epochs",
            ),
        ];
        for (figure, prefix, pick, thesis_std, thesis_mean, points) in figures {
            let c = curves.iter().find(|c| c.figure == figure).unwrap();
            let series = pick(first);
            let n = series.points(0).len();
            let step = n.div_ceil(MAX_POINTS);
            assert!(
                c.title.ends_with(&format!("seed 7, {points}")),
                "{}",
                c.title
            );
            assert_eq!(c.values.len(), 6);
            for (i, axis) in AXES.iter().enumerate() {
                // The first run's whole series, every step-th point.
                let kept: Vec<(f64, f64)> = series.points(i).into_iter().step_by(step).collect();
                assert!(
                    c.series[i].points == kept,
                    "{figure} {axis}: not the first run's"
                );
                let (mean, sd) = (&c.values[2 * i], &c.values[2 * i + 1]);
                // The std is the table's row; the mean the mean over runs of each run's.
                assert_eq!(sd.ours, Some(row(&format!("{prefix} {axis}"))));
                assert_eq!(
                    (sd.thesis, mean.thesis),
                    (Some(thesis_std[i]), Some(thesis_mean[i]))
                );
                let runs_mean = (pick(&runs[0]).mean()[i] + pick(&runs[1]).mean()[i]) / 2.0;
                assert_eq!(mean.ours, Some(runs_mean));
                assert!(sd.what.contains("std") && mean.what.contains("mean"));
            }
        }
        // The stds of the rows: the mean over the two runs of scale 1 and 1.5.
        let before = row("4.3-5 attitude error before correction yaw");
        assert!((before / (1.25 * 1.5) - 1.0).abs() < 1e-3, "{before}");

        let c = &curves[2];
        assert_eq!(c.series[0].points.len(), 4000usize.div_ceil(3));
        assert_eq!(c.series[0].points[1], (6.0, -8e-7));
        let [mean, sd] = &c.values[..] else {
            panic!("two values")
        };
        assert_eq!(
            (mean.thesis, sd.thesis),
            (Some(OFFSET_RATE_MEAN), Some(OFFSET_RATE_STD))
        );
        assert!((mean.ours.unwrap() - 1.25 * 1e-7).abs() < 1e-18, "{mean:?}");
        assert!(sd.ours.unwrap() > 8e-7 * 1.25 && sd.ours.unwrap() < 1e-6 * 1.25);
    }

    #[test]
    fn a_figure_without_its_row_is_an_error() {
        let runs = [run(7, 1.0), run(8, 1.5)];
        let t = Table::new(&runs);
        let mut rows = t.rows().unwrap();
        rows.retain(|r| r.row != "4.3-6 rate error after correction roll");
        let e = t.curves(&rows).unwrap_err().to_string();
        assert!(e.contains("4.3-6 rate error after correction roll"), "{e}");
    }
}
