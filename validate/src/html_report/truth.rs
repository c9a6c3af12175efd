//! Figures from a run's `truth.h5` (docs/truth-h5.md): visible satellites against time
//! (thesis figures 1.2-1 to 1.2-3) and the Doppler shift with its first two derivatives
//! (thesis figures 3.2-1 to 3.2-3).

use super::chart::{Chart, Series};
use super::page::{Figure, Section};
use super::{ReportError, read_dataset};
use hdf5::types::VarLenUnicode;
use std::collections::BTreeMap;
use std::path::Path;

/// Legends list at most this many curves (a constellation's Doppler fan has more).
const MAX_LEGEND: usize = 12;

/// The truth section of the report for `path`.
pub fn section(path: &Path) -> Result<Section, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let file = hdf5::File::open(path).map_err(|e| err(format!("not readable as HDF5: {e}")))?;
    let t_s: Vec<f64> = read_dataset(&file, path, "time/t_s")?;
    let ids: Vec<VarLenUnicode> = read_dataset(&file, path, "satellites/id")?;
    let ids: Vec<String> = ids.iter().map(|s| s.as_str().to_string()).collect();
    let antennas = file
        .group("antennas")
        .and_then(|g| g.member_names())
        .map_err(|e| err(format!("group antennas: {e}")))?;
    let scenario: String = file
        .attr("scenario")
        .and_then(|a| a.read_scalar::<VarLenUnicode>())
        .map(|s| s.as_str().to_string())
        .unwrap_or_default();
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
    for name in &antennas {
        let visible: Vec<u8> = read_dataset(&file, path, &format!("antennas/{name}/visible"))?;
        if visible.len() != t_s.len() * ids.len() {
            return Err(err(format!(
                "antennas/{name}/visible has {} values, not epochs x satellites = {}",
                visible.len(),
                t_s.len() * ids.len()
            )));
        }
        let chart = visible_chart(name, &t_s, &ids, &visible);
        section.figures.push(figure(
            &chart,
            format!(
                "Satellites in view of antenna {name} against time, per constellation \
                 (thesis figures 1.2-1 to 1.2-3)."
            ),
        )?);
    }
    if let Some(name) = antennas.first() {
        let links = Links::read(&file, path, name, t_s.len(), ids.len())?;
        for (dataset, title, unit, figure_no) in [
            ("doppler_hz", "Doppler shift", "Hz", "3.2-1"),
            ("doppler_rate_hzps", "Doppler rate", "Hz/s", "3.2-2"),
            (
                "doppler_accel_hzps2",
                "Doppler acceleration",
                "Hz/s^2",
                "3.2-3",
            ),
        ] {
            let values: Vec<f64> =
                read_dataset(&file, path, &format!("antennas/{name}/{dataset}"))?;
            if values.len() != links.epoch.len() {
                return Err(err(format!(
                    "antennas/{name}/{dataset} has {} values for {} links",
                    values.len(),
                    links.epoch.len()
                )));
            }
            let chart = links.chart(
                &format!("{title}, antenna {name}"),
                &format!("{title} ({unit})"),
                &t_s,
                &ids,
                &values,
            );
            section.figures.push(figure(
                &chart,
                format!("{title} of every satellite in view of antenna {name} (thesis figure {figure_no})."),
            )?);
        }
    }
    Ok(section)
}

fn figure(chart: &Chart, caption: String) -> Result<Figure, ReportError> {
    let svg = chart
        .to_svg()
        .map_err(|e| ReportError::new(Path::new("report"), e.to_string()))?;
    Ok(Figure { caption, svg })
}

/// Satellites in view against time: one curve per constellation (RINEX letter of the
/// ID) and, with more than one, their total.
fn visible_chart(antenna: &str, t_s: &[f64], ids: &[String], visible: &[u8]) -> Chart {
    let mut systems: BTreeMap<char, Vec<usize>> = BTreeMap::new();
    for (k, id) in ids.iter().enumerate() {
        systems
            .entry(id.chars().next().unwrap_or('?'))
            .or_default()
            .push(k);
    }
    let count = |cols: &[usize]| -> Vec<(f64, f64)> {
        t_s.iter()
            .enumerate()
            .map(|(i, &t)| {
                let row = &visible[i * ids.len()..(i + 1) * ids.len()];
                (t, cols.iter().filter(|&&k| row[k] != 0).count() as f64)
            })
            .collect()
    };
    let mut chart = Chart::new(
        &format!("Satellites in view, antenna {antenna}"),
        "time (s)",
        "satellites",
    );
    chart.y_from_zero = true;
    for (letter, cols) in &systems {
        chart
            .series
            .push(Series::line(system_name(*letter), count(cols)));
    }
    if systems.len() > 1 {
        let all: Vec<usize> = (0..ids.len()).collect();
        chart.series.push(Series::line("all", count(&all)));
    }
    chart
}

fn system_name(letter: char) -> String {
    match letter {
        'G' => "GPS".into(),
        'C' => "BeiDou".into(),
        other => other.to_string(),
    }
}

/// The visible links of one antenna: epoch row and satellite column of each.
struct Links {
    epoch: Vec<u32>,
    sat: Vec<u16>,
}

impl Links {
    fn read(
        file: &hdf5::File,
        path: &Path,
        antenna: &str,
        epochs: usize,
        sats: usize,
    ) -> Result<Self, ReportError> {
        let epoch: Vec<u32> = read_dataset(file, path, &format!("antennas/{antenna}/epoch_index"))?;
        let sat: Vec<u16> = read_dataset(file, path, &format!("antennas/{antenna}/sat_index"))?;
        let bad = epoch.len() != sat.len()
            || epoch.iter().any(|&e| e as usize >= epochs)
            || sat.iter().any(|&s| s as usize >= sats);
        if bad {
            return Err(ReportError::new(
                path,
                format!(
                    "antennas/{antenna}: epoch_index and sat_index do not index the epochs and satellites"
                ),
            ));
        }
        Ok(Links { epoch, sat })
    }

    /// One curve per satellite of `values` (one per link) against time.
    fn chart(&self, title: &str, y_label: &str, t_s: &[f64], ids: &[String], v: &[f64]) -> Chart {
        let mut per_sat: BTreeMap<u16, Vec<(f64, f64)>> = BTreeMap::new();
        for ((&e, &s), &value) in self.epoch.iter().zip(&self.sat).zip(v) {
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
}
