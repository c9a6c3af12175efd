//! Tables as studies over seeds (`validate thesis --seeds N --seed-base B`).
//!
//! A table evaluated once on its registered seeds gives one verdict per row, and a verdict
//! near its bar can move with the draw. With a [`SeedPlan`], every table whose rows are
//! per-run statistics is evaluated `N` times, each time on one run of its own seed plus
//! `B + k` ([`Draw::one`]); the `N` evaluations of a row are then combined
//! ([`combine`]): its value is the mean over draws, its spread and standard error are
//! taken over draws (independent runs, so the correlation of epochs within a run, e.g.
//! double differences sharing a reference satellite or loop noise correlated over
//! seconds, does not shrink them), and its verdict is decided on the fraction of draws in
//! tolerance against [`BAR`].

use crate::report::{OverSeeds, Row, Verdict};
use serde::{Deserialize, Serialize};
use std::ops::Range;

/// A row is reproduced over seeds when at least this fraction of its draws is.
// assumed: one half, fixed before any run over seeds: a row is reproduced when a draw is
// at least as likely to be in tolerance as not.
pub const BAR: f64 = 0.5;

/// Which runs one evaluation of a table makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Draw {
    /// Added to each of the table's registered seeds (V-1.2.1: the draw's index for its
    /// start epoch).
    pub offset: u64,
    /// Runs of the evaluation: `None` for the table's registered number.
    pub runs: Option<u64>,
}

impl Draw {
    /// The table as registered: its own seeds, its own number of runs.
    pub const REGISTERED: Self = Self {
        offset: 0,
        runs: None,
    };

    /// One run on the table's first seed plus `offset`.
    pub fn one(offset: u64) -> Self {
        Self {
            offset,
            runs: Some(1),
        }
    }

    /// The table's registered seeds shifted by `offset` (Monte Carlo tables under a plan).
    pub fn shifted(offset: u64) -> Self {
        Self { offset, runs: None }
    }

    /// The seeds to run for a table whose registered runs are `first .. first + registered`.
    pub fn seeds(self, first: u64, registered: u64) -> Range<u64> {
        let start = first.wrapping_add(self.offset);
        start..start.saturating_add(self.runs.unwrap_or(registered))
    }

    /// The one seed of a table registered with one run on `seed`.
    pub fn seed(self, seed: u64) -> u64 {
        seed.wrapping_add(self.offset)
    }
}

/// `--seeds N --seed-base B`: `draws` evaluations, offsets `base .. base + draws`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SeedPlan {
    pub draws: u64,
    pub base: u64,
}

/// Largest `base + draws` of a plan.
// assumed: V-1.2.1 moves its start by 25 h per draw offset; 10 000 offsets are 28.5
// years, which keeps every draw's start (2023 + 28.5) inside the scenarios' range (before
// 2100) and every seed far from the end of u64 (a base near it gave no draw at all).
pub const MAX_OFFSET: u64 = 10_000;

impl SeedPlan {
    /// `draws` draws from offset `base`: `base + draws` at most [`MAX_OFFSET`].
    pub fn new(draws: u64, base: u64) -> Result<Self, String> {
        match base.checked_add(draws) {
            Some(end) if draws >= 1 && end <= MAX_OFFSET => Ok(Self { draws, base }),
            _ => Err(format!(
                "--seeds {draws} --seed-base {base}: the draws need 1 <= seeds and seed-base + seeds <= {MAX_OFFSET}"
            )),
        }
    }

    /// The plan's draws, one run each.
    pub fn each(self) -> impl Iterator<Item = Draw> {
        (self.base..self.base.saturating_add(self.draws)).map(Draw::one)
    }
}

/// How a table takes part in a plan over seeds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Rows are per-run statistics: evaluated once per draw, combined over draws.
    PerRun,
    /// No random draw (formulas, geometry): evaluated once.
    Deterministic,
    /// Rows are already rates or statistics over many seeds of the table's own (Monte
    /// Carlo): evaluated once, on its registered seeds shifted by the plan's base.
    MonteCarlo,
}

/// The verdict over draws: reproduced when at least [`BAR`] of the draws are; otherwise
/// explained when more draws are explained than deviate; otherwise deviates.
pub fn verdict_over(in_tolerance: f64, explained: f64) -> Verdict {
    if in_tolerance >= BAR {
        Verdict::Reproduced
    } else if explained > 1.0 - in_tolerance - explained {
        Verdict::Explained
    } else {
        Verdict::Deviates
    }
}

/// Whether a fraction `f` of `n` draws is far from [`BAR`]: more than two binomial
/// standard errors at the bar.
pub fn settled(f: f64, n: u64) -> bool {
    n > 0 && (f - BAR).abs() > 2.0 * (BAR * (1.0 - BAR) / n as f64).sqrt()
}

/// One row from its evaluations in the `total` draws of `plan` (the first evaluation's
/// text and note, the mean over draws as its value); a draw without the row counts as a
/// deviating draw of it.
fn combine_row(plan: SeedPlan, evaluations: &[&Row], total: usize) -> Row {
    let share = |v: Verdict| {
        evaluations.iter().filter(|r| r.verdict == v).count() as f64 / total.max(1) as f64
    };
    let (in_tolerance, explained) = (share(Verdict::Reproduced), share(Verdict::Explained));
    let values: Vec<f64> = evaluations
        .iter()
        .filter_map(|r| r.ours)
        .filter(|v| v.is_finite())
        .collect();
    let first = evaluations[0];
    let spread = crate::observables::ErrorStats::of(&values);
    let n = total as u64;
    let over = OverSeeds {
        draws: n,
        base: plan.base,
        mean: spread.mean.unwrap_or(f64::NAN),
        std: spread.std.unwrap_or(f64::NAN),
        standard_error: spread.std.unwrap_or(f64::NAN) / (values.len().max(1) as f64).sqrt(),
        min: values.iter().copied().fold(f64::INFINITY, f64::min),
        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        in_tolerance,
        explained,
        settled: settled(in_tolerance, n),
    };
    let missing = match total - evaluations.len() {
        0 => String::new(),
        m => format!("{m} draws without this row; "),
    };
    let note = format!(
        "{missing}over {n} seeds: {} draws with a value, mean {:.6} +- {:.6} (std {:.6}, {:.6}..{:.6}), in tolerance in {:.2}; first draw: {}",
        values.len(),
        over.mean,
        over.standard_error,
        over.std,
        over.min,
        over.max,
        in_tolerance,
        first.note
    );
    Row {
        ours: (!values.is_empty()).then_some(over.mean),
        verdict: verdict_over(in_tolerance, explained),
        note,
        over_seeds: Some(over),
        ..first.clone()
    }
}

/// The rows of a table evaluated once per draw of `plan` (`draws[k]`: the rows of draw
/// k), each row combined over the draws ([`combine_row`]), in the order rows first
/// appear.
pub fn combine(plan: SeedPlan, draws: &[Vec<Row>]) -> Vec<Row> {
    let key = |r: &Row| (r.table.clone(), r.row.clone(), r.quantity.clone());
    let mut order: Vec<(String, String, String)> = Vec::new();
    for r in draws.iter().flatten() {
        if !order.contains(&key(r)) {
            order.push(key(r));
        }
    }
    order
        .iter()
        .map(|k| {
            let found: Vec<&Row> = draws
                .iter()
                .filter_map(|rows| rows.iter().find(|r| &key(r) == k))
                .collect();
            combine_row(plan, &found, draws.len())
        })
        .collect()
}

/// A row of a table evaluated once under a plan (deterministic or Monte Carlo), its note
/// saying why.
pub fn once(kind: Kind, plan: SeedPlan, mut row: Row) -> Row {
    let why = match kind {
        Kind::Deterministic => "no random draw: evaluated once".to_string(),
        Kind::MonteCarlo => format!(
            "a Monte Carlo of its own over its registered seeds, shifted by {}: evaluated once",
            plan.base
        ),
        Kind::PerRun => return row,
    };
    row.note = format!("{why}; {}", row.note);
    row
}

/// Two plans' verdicts side by side: every row both give over seeds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Agreement {
    /// (table, row, quantity), verdicts and fractions in tolerance of the first and second
    /// plan, and whether both fractions are far from the bar.
    pub rows: Vec<AgreementRow>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AgreementRow {
    pub table: String,
    pub row: String,
    pub quantity: String,
    pub verdicts: [Verdict; 2],
    pub in_tolerance: [f64; 2],
    pub settled: bool,
}

impl Agreement {
    /// The rows of `a` and `b` (two `results.json` over seeds) matched by table, row and
    /// quantity; rows without a distribution over seeds in either are left out.
    pub fn of(a: &[Row], b: &[Row]) -> Self {
        let rows = a
            .iter()
            .filter_map(|x| {
                let y = b
                    .iter()
                    .find(|y| (&y.table, &y.row, &y.quantity) == (&x.table, &x.row, &x.quantity))?;
                let (ox, oy) = (x.over_seeds.as_ref()?, y.over_seeds.as_ref()?);
                Some(AgreementRow {
                    table: x.table.clone(),
                    row: x.row.clone(),
                    quantity: x.quantity.clone(),
                    verdicts: [x.verdict, y.verdict],
                    in_tolerance: [ox.in_tolerance, oy.in_tolerance],
                    settled: ox.settled && oy.settled,
                })
            })
            .collect();
        Self { rows }
    }

    /// The rows far from the bar in both plans whose verdicts differ: none is what
    /// `validate thesis --seeds` promises.
    pub fn settled_disagreements(&self) -> Vec<&AgreementRow> {
        self.rows
            .iter()
            .filter(|r| r.settled && r.verdicts[0] != r.verdicts[1])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(name: &str, ours: f64, verdict: Verdict) -> Row {
        Row {
            table: "T".into(),
            row: name.into(),
            quantity: "q".into(),
            unit: "m".into(),
            thesis: Some(1.0),
            ours: Some(ours),
            tolerance: "t".into(),
            verdict,
            note: String::new(),
            over_seeds: None,
        }
    }

    const PLAN: SeedPlan = SeedPlan { draws: 4, base: 0 };

    #[test]
    fn draws_run_one_seed_each_and_shift_monte_carlo_seeds() {
        assert_eq!(Draw::REGISTERED.seeds(7, 8), 7..15);
        assert_eq!(Draw::one(3).seeds(7, 8), 10..11);
        assert_eq!(Draw::shifted(100).seeds(7, 8), 107..115);
        assert_eq!(Draw::one(3).seed(33), 36);
        let offsets: Vec<u64> = SeedPlan { draws: 3, base: 10 }
            .each()
            .map(|d| d.offset)
            .collect();
        assert_eq!(offsets, [10, 11, 12]);
    }

    #[test]
    fn the_verdict_follows_the_fraction_in_tolerance() {
        use Verdict::*;
        let draws: Vec<Vec<Row>> = [(1.0, Reproduced), (2.0, Deviates), (3.0, Reproduced)]
            .iter()
            .chain(&[(6.0, Deviates)])
            .map(|&(v, verdict)| vec![row("a", v, verdict)])
            .collect();
        let out = combine(PLAN, &draws);
        assert_eq!(out.len(), 1);
        let over = out[0].over_seeds.clone().unwrap();
        assert_eq!(over.draws, 4);
        assert!((over.mean - 3.0).abs() < 1e-12);
        assert_eq!(out[0].ours, Some(3.0));
        assert!((over.std - (14.0f64 / 3.0).sqrt()).abs() < 1e-12);
        assert!((over.standard_error - over.std / 2.0).abs() < 1e-12);
        assert_eq!((over.min, over.max), (1.0, 6.0));
        assert_eq!(over.in_tolerance, 0.5);
        assert_eq!(out[0].verdict, Reproduced);
        assert!(!over.settled);
        let mostly_off: Vec<Vec<Row>> = [Deviates, Deviates, Explained, Reproduced]
            .iter()
            .map(|&v| vec![row("a", 1.0, v)])
            .collect();
        assert_eq!(combine(PLAN, &mostly_off)[0].verdict, Deviates);
        let explained: Vec<Vec<Row>> = [Explained, Explained, Deviates, Reproduced]
            .iter()
            .map(|&v| vec![row("a", 1.0, v)])
            .collect();
        assert_eq!(combine(PLAN, &explained)[0].verdict, Explained);
    }

    #[test]
    fn a_row_missing_from_a_draw_counts_against_it() {
        let draws = vec![
            vec![
                row("a", 1.0, Verdict::Reproduced),
                row("b", 1.0, Verdict::Reproduced),
            ],
            vec![row("a", 1.0, Verdict::Reproduced)],
            vec![row("b", 1.0, Verdict::Reproduced)],
            vec![row("b", 1.0, Verdict::Reproduced)],
        ];
        let out = combine(PLAN, &draws);
        let names: Vec<&str> = out.iter().map(|r| r.row.as_str()).collect();
        assert_eq!(names, ["a", "b"]);
        let a = out[0].over_seeds.clone().unwrap();
        assert_eq!((a.draws, a.in_tolerance), (4, 0.5));
        assert!(out[0].note.starts_with("2 draws without this row"));
        assert_eq!(out[1].over_seeds.clone().unwrap().in_tolerance, 0.75);
    }

    #[test]
    fn agreement_pairs_rows_and_flags_settled_disagreements() {
        use Verdict::*;
        let plan = SeedPlan { draws: 20, base: 0 };
        let over = |name: &str, verdicts: &[Verdict]| {
            let draws: Vec<Vec<Row>> = verdicts.iter().map(|&v| vec![row(name, 1.0, v)]).collect();
            combine(
                SeedPlan {
                    draws: verdicts.len() as u64,
                    ..plan
                },
                &draws,
            )
        };
        let many = |v: Verdict, n: usize, rest: Verdict| {
            let mut all = vec![v; n];
            all.resize(20, rest);
            all
        };
        // a: settled reproduced in both; b: settled but opposite; c: near the bar in one.
        let first: Vec<Row> = [
            over("a", &many(Reproduced, 20, Deviates)),
            over("b", &many(Reproduced, 18, Deviates)),
            over("c", &many(Reproduced, 12, Deviates)),
        ]
        .concat();
        let second: Vec<Row> = [
            over("a", &many(Reproduced, 19, Deviates)),
            over("b", &many(Reproduced, 2, Deviates)),
            over("c", &many(Reproduced, 8, Deviates)),
            vec![row("d", 1.0, Reproduced)],
        ]
        .concat();
        let agreement = Agreement::of(&first, &second);
        assert_eq!(agreement.rows.len(), 3);
        let settled: Vec<&str> = agreement
            .rows
            .iter()
            .filter(|r| r.settled)
            .map(|r| r.row.as_str())
            .collect();
        assert_eq!(settled, ["a", "b"]);
        let off: Vec<&str> = agreement
            .settled_disagreements()
            .iter()
            .map(|r| r.row.as_str())
            .collect();
        assert_eq!(off, ["b"]);
    }

    #[test]
    fn settled_means_two_binomial_errors_from_the_bar() {
        // At 20 draws the binomial standard error at 0.5 is 0.112.
        assert!(settled(0.75, 20));
        assert!(!settled(0.7, 20));
        assert!(settled(0.25, 20));
        assert!(settled(0.0, 20));
        assert!(!settled(1.0, 3));
    }
}
