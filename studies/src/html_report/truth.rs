//! Figures from a run's `truth.h5` (docs/truth-h5.md): satellites in view against time
//! per constellation (thesis figures 1.2-1 to 1.2-3, beside the thesis's numbers), the
//! Doppler shift with its first two derivatives (thesis figures 3.2-1 to 3.2-3) and the
//! carrier-loop errors they cause (thesis figures 3.2-4 to 3.2-23, `loop_errors`).

use super::chart::{Chart, Series};
use super::page::Section;
use super::{MAX_ELEMENTS, ReportError, figure, loop_errors};
use skyforge_formats::truth::{
    DOPPLER_ACCEL_HZPS2, DOPPLER_HZ, DOPPLER_RATE_HZPS, TruthFile, VisibleLinks,
};
use std::collections::BTreeMap;
use std::path::Path;

/// Legends list at most this many curves (a constellation's Doppler fan has more).
const MAX_LEGEND: usize = 12;

/// The truth section of the report for `path`.
pub fn section(path: &Path) -> Result<Section, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let file = TruthFile::open(path)?;
    let t_s = file.times(MAX_ELEMENTS)?;
    let ids = file.satellite_ids(MAX_ELEMENTS)?;
    let antennas = file.antenna_names()?;
    let scenario = file.scenario_name().unwrap_or_default();
    let mut section = Section {
        heading: format!("Truth: scenario {scenario}"),
        paragraphs: vec![format!(
            "{} epochs over {:.0} s, {} satellites, antennas {}.",
            t_s.len(),
            t_s.last().copied().unwrap_or(0.0) - t_s.first().copied().unwrap_or(0.0),
            ids.len(),
            antennas.join(", ")
        )],
        ..Section::default()
    };
    // Every antenna's visibility is held at once: bound the whole, not each dataset.
    let cells = antennas
        .len()
        .checked_mul(t_s.len())
        .and_then(|n| n.checked_mul(ids.len()));
    if cells.is_none_or(|n| n > MAX_ELEMENTS) {
        return Err(err(format!(
            "{} antennas x {} epochs x {} satellites of visibility; at most {} are read",
            antennas.len(),
            t_s.len(),
            ids.len(),
            MAX_ELEMENTS
        )));
    }
    let mut visible = Vec::with_capacity(antennas.len());
    for name in &antennas {
        let v = file.visible(name, t_s.len(), ids.len(), MAX_ELEMENTS)?;
        visible.push((name.as_str(), v));
    }
    for (system, thesis) in systems(&ids) {
        let (chart, counts) = visible_chart(&system, &t_s, &visible);
        section.figures.push(figure(
            &chart,
            format!(
                "{system} satellites in view of each antenna against time; antenna {}: {}. \
                 Thesis section 1.2.1 (its LEO over 24 h, field of view +-80 deg): {thesis}.",
                antennas.first().map_or("", String::as_str),
                counts
            ),
            path,
        )?);
    }
    if let Some(name) = antennas.first() {
        let links = file.links(name, t_s.len(), ids.len(), MAX_ELEMENTS)?;
        let doppler = [
            file.link_values(name, DOPPLER_HZ, &links)?,
            file.link_values(name, DOPPLER_RATE_HZPS, &links)?,
            file.link_values(name, DOPPLER_ACCEL_HZPS2, &links)?,
        ];
        for (values, (title, unit, figure_no)) in doppler.iter().zip([
            ("Doppler shift", "Hz", "3.2-1"),
            ("Doppler rate", "Hz/s", "3.2-2"),
            ("Doppler acceleration", "Hz/s^2", "3.2-3"),
        ]) {
            let chart = links_chart(
                &links,
                &format!("{title}, antenna {name}"),
                &format!("{title} ({unit})"),
                &t_s,
                &ids,
                values,
            );
            section.figures.push(figure(
                &chart,
                format!("{title} of every satellite in view of antenna {name} (thesis figure {figure_no})."),
                path,
            )?);
        }
        let [_, rate, accel] = &doppler;
        let pass = loop_errors::Pass::most_dynamic(&links, &t_s, &ids, rate, accel);
        let (paragraph, figures) = loop_errors::figures(path, name, pass.as_ref())?;
        section.paragraphs.push(paragraph);
        section.figures.extend(figures);
    }
    Ok(section)
}

/// The constellations to count, each as (name, its satellites' columns), with the
/// thesis's figure and numbers: GPS, BeiDou, and both together when both are there.
fn systems(ids: &[String]) -> Vec<(Constellation, &'static str)> {
    let of = |letter: char| -> Vec<usize> {
        ids.iter()
            .enumerate()
            .filter(|(_, id)| id.starts_with(letter))
            .map(|(k, _)| k)
            .collect()
    };
    let (gps, bds) = (of('G'), of('C'));
    let mut out = Vec::new();
    let both = !gps.is_empty() && !bds.is_empty();
    if !gps.is_empty() {
        out.push((
            Constellation::new("GPS", gps),
            "figure 1.2-1, 3 to 16, mean 9",
        ));
    }
    if !bds.is_empty() {
        out.push((
            Constellation::new("BeiDou", bds),
            "figure 1.2-2, 5 to 16, mean 9",
        ));
    }
    if both {
        let all = (0..ids.len()).collect();
        out.push((
            Constellation::new("GPS + BeiDou", all),
            "figure 1.2-3, 8 to 30, mean 18",
        ));
    }
    out
}

/// A constellation: its name and its columns of `satellites/id`.
struct Constellation {
    name: &'static str,
    columns: Vec<usize>,
}

impl Constellation {
    fn new(name: &'static str, columns: Vec<usize>) -> Self {
        Constellation { name, columns }
    }
}

impl std::fmt::Display for Constellation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// Satellites of `system` in view against time, one curve per antenna, and the first
/// antenna's minimum, maximum and mean.
fn visible_chart(
    system: &Constellation,
    t_s: &[f64],
    visible: &[(&str, Vec<u8>)],
) -> (Chart, String) {
    let sats = visible
        .first()
        .map_or(0, |(_, v)| v.len() / t_s.len().max(1));
    let mut chart = Chart::new(
        &format!("{system} satellites in view"),
        "time (s)",
        "satellites",
    );
    chart.y_from_zero = true;
    let mut stats = String::new();
    for (name, v) in visible {
        let counts: Vec<(f64, f64)> = t_s
            .iter()
            .enumerate()
            .map(|(i, &t)| {
                let row = &v[i * sats..(i + 1) * sats];
                let n = system.columns.iter().filter(|&&k| row[k] != 0).count();
                (t, n as f64)
            })
            .collect();
        if stats.is_empty() {
            let n: Vec<f64> = counts.iter().map(|c| c.1).collect();
            let mean = n.iter().sum::<f64>() / n.len().max(1) as f64;
            let (lo, hi) = n.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
            stats = format!("{lo:.0} to {hi:.0}, mean {mean:.1}");
        }
        chart.series.push(Series::line(*name, counts));
    }
    (chart, stats)
}

/// One curve per satellite of `v` (one value per link) against time.
fn links_chart(
    links: &VisibleLinks,
    title: &str,
    y_label: &str,
    t_s: &[f64],
    ids: &[String],
    v: &[f64],
) -> Chart {
    let mut per_sat: BTreeMap<u16, Vec<(f64, f64)>> = BTreeMap::new();
    for ((&e, &s), &value) in links.epoch.iter().zip(&links.sat).zip(v) {
        per_sat.entry(s).or_default().push((t_s[e as usize], value));
    }
    let mut chart = Chart::new(title, "time (s)", y_label);
    let many = per_sat.len() > MAX_LEGEND;
    for (s, points) in per_sat {
        let name = if many {
            String::new()
        } else {
            ids[s as usize].clone()
        };
        chart.series.push(Series::line(name, points));
    }
    chart
}
