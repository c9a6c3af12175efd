//! Figures of a merged study file (`study.h5`, docs/study.md): each metric's mean against
//! the first parameter that takes more than one value with its 95 % confidence band, one curve per combination of
//! the other parameters, and the 95th percentile beside it (thin, same colour).

use super::chart::{Chart, Series};
use super::page::Section;
use super::{ReportError, figure};
use crate::study::Study;
use crate::study::results::{MEAN, MEAN_CI_HIGH, MEAN_CI_LOW, MergedFile, P95};
use std::collections::BTreeMap;
use std::path::Path;

/// The study section of the report for `path`.
pub fn section(path: &Path) -> Result<Section, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let file = MergedFile::open(path)?;
    let text = file.study_toml()?;
    let study = Study::parse_plan(&text, &path.display().to_string())
        .map_err(|e| err(format!("attribute study_toml: {e}")))?;
    let points = study.points() as usize;
    let along = study
        .parameters
        .iter()
        .position(|p| p.values.len() > 1)
        .unwrap_or(0);
    let (x, x_label) = axis(&study, along);
    let groups = groups(&study, along);
    let mut section = Section {
        heading: format!("Study {}", study.name),
        paragraphs: vec![format!(
            "{} grid points x {} seeds = {} runs of {}. {}",
            points,
            study.seeds,
            study.runs(),
            study.scenario,
            study.description
        )],
        ..Section::default()
    };
    for metric in &study.metrics {
        let name = metric.name();
        let read = |stat: &str| file.summary(name, stat, points);
        let (mean, low, high, p95) = (
            read(MEAN)?,
            read(MEAN_CI_LOW)?,
            read(MEAN_CI_HIGH)?,
            read(P95)?,
        );
        let y_label = format!("{name} ({})", metric.unit());
        let mut chart = Chart::new(&format!("{name} against {x_label}"), &x_label, &y_label);
        chart.y_from_zero = true;
        for (label, members) in &groups {
            let pick =
                |v: &[f64]| -> Vec<(f64, f64)> { members.iter().map(|&p| (x[p], v[p])).collect() };
            chart.series.push(Series {
                name: join(label, "mean"),
                points: pick(&mean),
                band: members.iter().map(|&p| (x[p], low[p], high[p])).collect(),
                companion: false,
                dots: false,
                colour: None,
            });
            chart
                .series
                .push(Series::companion(join(label, "p95"), pick(&p95)));
        }
        let caption = format!(
            "{name}: mean over runs with its 95 % confidence interval (band) and the 95th \
             percentile, at each grid point."
        );
        section.figures.push(figure(&chart, caption, path)?);
    }
    Ok(section)
}

/// The x value of every point (parameter `along`'s value; its position in the list when
/// not a number) and the axis label.
fn axis(study: &Study, along: usize) -> (Vec<f64>, String) {
    let points = study.points();
    let Some(first) = study.parameters.get(along) else {
        return (vec![0.0; points as usize], "(no parameter)".into());
    };
    let numeric = first
        .values
        .iter()
        .all(|v| v.as_float().is_some() || v.as_integer().is_some());
    let x = (0..points)
        .map(|p| {
            let k = study.point_indices(p)[along];
            match (&first.values[k], numeric) {
                (toml::Value::Float(f), true) => *f,
                (toml::Value::Integer(i), true) => *i as f64,
                _ => k as f64,
            }
        })
        .collect();
    let label = if numeric {
        first.key.clone()
    } else {
        format!("{} (position in its list)", first.key)
    };
    (x, label)
}

/// The points grouped by the values of every parameter but `along`.
fn groups(study: &Study, along: usize) -> BTreeMap<String, Vec<usize>> {
    let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for p in 0..study.points() {
        let label = study
            .point_indices(p)
            .iter()
            .zip(&study.parameters)
            .enumerate()
            .filter(|(i, _)| *i != along)
            .map(|(_, (&k, par))| format!("{} = {}", par.key, par.values[k]))
            .collect::<Vec<_>>()
            .join(", ");
        groups.entry(label).or_default().push(p as usize);
    }
    groups
}

fn join(group: &str, what: &str) -> String {
    if group.is_empty() {
        what.into()
    } else {
        format!("{group}: {what}")
    }
}
