//! Result rows of a validation run, their verdicts, the printed table and `results.json`.

use crate::thesis::{Provenance, Results};
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::Path;

/// Outcome of one compared row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Inside the tolerance.
    Reproduced,
    /// Outside the tolerance; the measured value is reported.
    Deviates,
    /// Outside the tolerance with a physical reason checked by a test.
    Explained,
}

impl Verdict {
    /// `Reproduced` when `ok`, else `Deviates`.
    pub fn from_ok(ok: bool) -> Self {
        if ok {
            Verdict::Reproduced
        } else {
            Verdict::Deviates
        }
    }
}

/// One row of a thesis table: the keys of `results.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    pub table: String,
    pub row: String,
    pub quantity: String,
    pub unit: String,
    /// The thesis value (`None` where the thesis prints a word, e.g. "fail").
    pub thesis: Option<f64>,
    pub ours: Option<f64>,
    pub tolerance: String,
    pub verdict: Verdict,
    pub note: String,
    /// The row's distribution over the draws of `validate thesis --seeds N` (absent for
    /// one evaluation on the registered seeds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub over_seeds: Option<OverSeeds>,
}

impl Row {
    /// A row of `table` with our number and no note; `check` is (tolerance text, verdict).
    pub fn measured(
        table: &str,
        row: impl Into<String>,
        quantity: &str,
        unit: &str,
        thesis: Option<f64>,
        ours: f64,
        check: (String, Verdict),
    ) -> Self {
        let (tolerance, verdict) = check;
        Row {
            table: table.into(),
            row: row.into(),
            quantity: quantity.into(),
            unit: unit.into(),
            thesis,
            ours: Some(ours),
            tolerance,
            verdict,
            note: String::new(),
            over_seeds: None,
        }
    }

    /// This row with `note`.
    pub fn with_note(self, note: String) -> Self {
        Row { note, ..self }
    }

    /// ours / thesis, when both are numbers and thesis is non-zero.
    pub fn ratio(&self) -> Option<f64> {
        match (self.thesis, self.ours) {
            (Some(t), Some(o)) if t != 0.0 => Some(o / t),
            _ => None,
        }
    }
}

fn cell(v: Option<f64>) -> String {
    match v {
        Some(x) if x != 0.0 && (x.abs() >= 1e5 || x.abs() < 1e-3) => format!("{x:.4e}"),
        Some(x) => format!("{x:.5}"),
        None => "-".to_string(),
    }
}

/// Print the rows as an aligned table; rows over seeds add the fraction of draws in
/// tolerance and the number of draws, with `?` where that fraction is within two binomial
/// standard errors of the bar (another set of seeds may turn the verdict).
pub fn print_table(rows: &[Row], out: &mut impl Write) -> std::io::Result<()> {
    writeln!(
        out,
        "table    {:<44} {:>12} {:>12} {:>8} {:<26} verdict",
        "row", "thesis", "skyforge", "ratio", "tolerance"
    )?;
    for r in rows {
        let ratio = r.ratio().map_or("-".to_string(), |x| format!("{x:.3}"));
        let verdict = serde_json::to_value(r.verdict)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string));
        let over = r.over_seeds.as_ref().map_or(String::new(), |o| {
            let unsure = if o.settled { "" } else { " ?" };
            format!(" {:.2} of {}{unsure}", o.in_tolerance, o.draws)
        });
        writeln!(
            out,
            "{:<8} {:<44} {:>12} {:>12} {:>8} {:<26} {}{over}",
            r.table,
            format!("{} [{}]", r.row, r.unit),
            cell(r.thesis),
            cell(r.ours),
            ratio,
            r.tolerance,
            verdict.unwrap_or_default()
        )?;
    }
    Ok(())
}

/// Write `results` to `path` as JSON (via a temporary file, renamed when complete).
pub fn write_json(results: &Results, path: &Path) -> std::io::Result<()> {
    let tmp = path.with_extension("json.partial");
    let text = serde_json::to_string_pretty(results).map_err(std::io::Error::other)?;
    std::fs::write(&tmp, text + "\n")?;
    std::fs::rename(&tmp, path)
}

/// Parse a `results.json`: its rows, and its provenance when it records one (an object
/// of provenance and rows, as written now; an array of rows, as written before SkyForge
/// recorded provenance). Errors carry their line and column.
pub fn parse_results(text: &str) -> serde_json::Result<(Option<Provenance>, Vec<Row>)> {
    if text.trim_start().starts_with('[') {
        return Ok((None, serde_json::from_str(text)?));
    }
    let r: Results = serde_json::from_str(text)?;
    Ok((Some(r.provenance), r.rows))
}

/// A row's distribution over the draws of a plan (`results.json` key `over_seeds`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OverSeeds {
    /// Draws that gave this row.
    pub draws: u64,
    /// The plan's base: the draws' offsets are `base .. base + draws` of the plan.
    pub base: u64,
    pub mean: f64,
    /// Standard deviation of the draws' values (`n - 1`).
    pub std: f64,
    /// `std / sqrt(draws)`: draws are independent runs.
    pub standard_error: f64,
    pub min: f64,
    pub max: f64,
    /// Fraction of draws reproduced.
    pub in_tolerance: f64,
    /// Fraction of draws explained.
    pub explained: f64,
    /// Whether the fraction in tolerance is more than two binomial standard errors (at the
    /// bar) from [`BAR`]: a second plan with other seeds should give the same verdict.
    pub settled: bool,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_has_the_documented_keys() {
        let row = Row {
            table: "T-3.2".into(),
            row: "r".into(),
            quantity: "q".into(),
            unit: "deg".into(),
            thesis: None,
            ours: Some(1.0),
            tolerance: "t".into(),
            verdict: Verdict::Explained,
            note: String::new(),
            over_seeds: None,
        };
        let v = serde_json::to_value(vec![row]).unwrap();
        let obj = v[0].as_object().unwrap();
        let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
        keys.sort();
        assert_eq!(
            keys,
            [
                "note",
                "ours",
                "quantity",
                "row",
                "table",
                "thesis",
                "tolerance",
                "unit",
                "verdict"
            ]
        );
        assert_eq!(obj["verdict"], "explained");
        assert!(obj["thesis"].is_null());
    }
}
