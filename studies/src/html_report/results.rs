//! The validation table of a `validate thesis` run (`results.json`): every row with the
//! thesis value, SkyForge's, the tolerance and the verdict, the counts of verdicts, and
//! one figure of SkyForge's value over the thesis's for every row that has both.

use super::chart::{Chart, Series};
use super::page::{Cell, Section, Table};
use super::{ReportError, figure, read_text};
use skyforge_validate::report::{Row, Verdict, parse_results};
use std::path::Path;

/// Largest `results.json` read (bytes): a whole thesis run writes a few hundred kB.
const MAX_BYTES: u64 = 64 << 20;

/// The validation section of the report for `path` (a `results.json`).
pub fn section(path: &Path) -> Result<Section, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let text = read_text(path, MAX_BYTES)?;
    let (provenance, rows) = parse_results(&text).map_err(|e| {
        err(format!(
            "line {}, column {}: {e} (expected the rows `skyforge validate thesis --out` writes)",
            e.line(),
            e.column()
        ))
    })?;
    let count = |v: Verdict| rows.iter().filter(|r| r.verdict == v).count();
    let number = |x: Option<f64>| x.map(|v| format!("{v:.4}")).unwrap_or_else(|| "-".into());
    let over_seeds = rows.iter().any(|r| r.over_seeds.is_some());
    let mut table = Table {
        header: [
            "table",
            "row",
            "quantity",
            "unit",
            "thesis",
            "SkyForge",
            "tolerance",
            "verdict",
            "note",
        ]
        .map(String::from)
        .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                let verdict = match r.verdict {
                    Verdict::Reproduced => "reproduced",
                    Verdict::Deviates => "deviates",
                    Verdict::Explained => "explained",
                };
                let short = |text: String| Cell {
                    text,
                    class: Some("n"),
                };
                vec![
                    short(r.table.clone()),
                    Cell::from(r.row.as_str()),
                    Cell::from(r.quantity.as_str()),
                    short(r.unit.clone()),
                    short(number(r.thesis)),
                    short(number(r.ours)),
                    Cell::from(r.tolerance.as_str()),
                    Cell {
                        text: verdict.into(),
                        class: Some(verdict),
                    },
                    Cell::from(r.note.as_str()),
                ]
            })
            .collect(),
    };
    if over_seeds {
        table.header.insert(7, "in tolerance".into());
        for (cells, r) in table.rows.iter_mut().zip(&rows) {
            let text = r.over_seeds.as_ref().map_or_else(
                || "once".to_string(),
                |o| {
                    let unsure = if o.settled { "" } else { " (near the bar)" };
                    format!("{:.2} of {}{unsure}", o.in_tolerance, o.draws)
                },
            );
            cells.insert(7, Cell::from(text.as_str()));
        }
    }
    let mut figures = Vec::new();
    if let Some(chart) = ratio_chart(&rows) {
        let caption = format!(
            "SkyForge's value over the thesis's (log scale) for every row that has both \
             numbers, by row number in the table below and coloured by verdict; each row's \
             own tolerance is in the table. Ratios beyond a factor of {:.0} are drawn at the \
             edge.",
            10f64.powf(MAX_LOG_RATIO)
        );
        figures.push(figure(&chart, caption, path)?);
    }
    Ok(Section {
        heading: "Validation against the thesis".into(),
        figures,
        paragraphs: vec![
            format!(
                "{} rows: {} reproduced, {} explained, {} deviate.",
                rows.len(),
                count(Verdict::Reproduced),
                count(Verdict::Explained),
                count(Verdict::Deviates)
            ),
            provenance_text(provenance.as_ref()),
        ],
        tables: vec![table],
    })
}

/// What the run was: commit, seeds, scenarios.
fn provenance_text(p: Option<&skyforge_validate::thesis::Provenance>) -> String {
    let Some(p) = p else {
        return "This results.json records no provenance (written before SkyForge recorded it)."
            .into();
    };
    let seeds = p.plan.map_or_else(
        || "each table once on its registered seeds".to_string(),
        |plan| {
            format!(
                "each table whose rows are per-run statistics over {} seeds (offsets {} to {}), verdict on the fraction of draws in tolerance (bar {})",
                plan.draws,
                plan.base,
                plan.base + plan.draws.saturating_sub(1),
                skyforge_validate::draw::BAR
            )
        },
    );
    let scenarios: Vec<String> = p
        .scenarios
        .iter()
        .map(|s| format!("{} ({})", s.name, s.origin))
        .collect();
    format!(
        "SkyForge {} at commit {}; {seeds}; scenarios: {}.",
        p.version,
        p.commit,
        if scenarios.is_empty() {
            "none".to_string()
        } else {
            scenarios.join(", ")
        }
    )
}

/// Largest |log10(SkyForge / thesis)| drawn where it is; beyond, at the edge.
const MAX_LOG_RATIO: f64 = 3.0;

/// log10(SkyForge / thesis) against the row number (1-based), one dot series per verdict;
/// `None` when no row has two numbers of the same sign.
fn ratio_chart(rows: &[Row]) -> Option<Chart> {
    let mut chart = Chart::new(
        "SkyForge against the thesis, row by row",
        "row",
        "log10(SkyForge / thesis)",
    );
    // The page's verdict colours, darker.
    for (verdict, name, colour) in [
        (Verdict::Reproduced, "reproduced", (44, 160, 44)),
        (Verdict::Explained, "explained", (230, 160, 0)),
        (Verdict::Deviates, "deviates", (214, 39, 40)),
    ] {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .enumerate()
            .filter(|(_, r)| r.verdict == verdict)
            .filter_map(|(i, r)| {
                let q = r.ratio()?;
                (q > 0.0).then(|| {
                    let y = q.log10().clamp(-MAX_LOG_RATIO, MAX_LOG_RATIO);
                    ((i + 1) as f64, y)
                })
            })
            .collect();
        chart.series.push(Series {
            colour: Some(colour),
            ..Series::dots(name, points)
        });
    }
    if chart.series.iter().all(|s| s.points.is_empty()) {
        return None;
    }
    chart.references = vec![
        ("equal".into(), 0.0),
        ("factor 2".into(), 2f64.log10()),
        (String::new(), -(2f64.log10())),
    ];
    Some(chart)
}
