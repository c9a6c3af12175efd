//! V-1.2.1: visible-satellite statistics over 24 h for the thesis orbit with a +/-80 deg
//! field of view (thesis section 1.2.1, figures 1.2-1..1.2-3).

use super::ValidateError;
use super::geometry_run::for_each_chunk;
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::Summary;
use skyforge_orbits::ephemeris::System;
use skyforge_orbits::ephemeris::{BeidouSet, ConstellationSource};
use skyforge_scenarios::Scenario;
use std::path::Path;

/// The bundled scenario of this table.
pub const SCENARIO: &str = "thesis/v-1.2.1";
/// The real broadcast file (RINEX 4, all constellations) of the scenario's day.
pub const REAL_NAV_FILE: &str = "nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz";

/// Thesis values: (constellation, max, min, mean).
const THESIS: [(&str, f64, f64, f64); 3] = [
    ("GPS", 16.0, 3.0, 9.0),
    ("BD", 16.0, 5.0, 9.0),
    ("GPS+BD", 30.0, 8.0, 18.0),
];

/// Visible-satellite counts per epoch of the first antenna.
#[derive(Debug, Clone, Default)]
pub struct VisibleCounts {
    pub gps: Vec<f64>,
    pub beidou: Vec<f64>,
    pub all: Vec<f64>,
}

/// Count the visible satellites of each system at every epoch of `scenario`.
pub fn count_visible(scenario: &Scenario) -> Result<VisibleCounts, ValidateError> {
    let mut counts = VisibleCounts::default();
    for_each_chunk(scenario, |chunk, sats| {
        for k in 0..chunk.t_s.len() {
            let (mut gps, mut bds, mut gal) = (0.0, 0.0, 0.0);
            for (s, sat) in sats.iter().enumerate() {
                if chunk.link(k, 0, s).visible {
                    match sat.system {
                        System::Gps => gps += 1.0,
                        System::Beidou => bds += 1.0,
                        System::Galileo => gal += 1.0,
                    }
                }
            }
            counts.gps.push(gps);
            counts.beidou.push(bds);
            counts.all.push(gps + bds + gal);
        }
    })?;
    Ok(counts)
}

fn rows_for(label: &str, counts: &VisibleCounts, systems: &[usize], note: &str) -> Vec<Row> {
    let mut rows = Vec::new();
    for &i in systems {
        let (name, t_max, t_min, t_mean) = THESIS[i];
        let series = [&counts.gps, &counts.beidou, &counts.all][i];
        let Some(s) = Summary::of(series) else {
            continue;
        };
        let mut push = |stat: &str, thesis: f64, ours: f64, tolerance: &str, ok: bool| {
            rows.push(Row {
                table: "V-1.2.1".into(),
                row: format!("{name} {stat} ({label})"),
                quantity: format!("{stat} visible satellites"),
                unit: "satellites".into(),
                thesis: Some(thesis),
                ours: Some(ours),
                tolerance: tolerance.into(),
                verdict: Verdict::from_ok(ok),
                note: note.into(),
                over_seeds: None,
            })
        };
        push(
            "max",
            t_max,
            s.max,
            "+/-3 satellites",
            (s.max - t_max).abs() <= 3.0,
        );
        push(
            "min",
            t_min,
            s.min,
            "+/-3 satellites",
            (s.min - t_min).abs() <= 3.0,
        );
        push(
            "mean",
            t_mean,
            s.mean,
            "+/-25 %",
            (s.mean / t_mean - 1.0).abs() <= 0.25,
        );
    }
    rows
}

/// Between the start epochs of two draws over seeds (`validate thesis --seeds`): the
/// visibility has no noise, its draws are start epochs.
// assumed: a day and an hour, fixed before any run: each draw sees the constellations'
// sidereal-day repeat and the LEO's ground track at a new phase.
pub const DRAW_STEP_S: f64 = 25.0 * 3600.0;

/// Every row of V-1.2.1: embedded constellations (BDS-3 and BDS-2) from the scenario's
/// start plus `draw.offset` x [`DRAW_STEP_S`], and the real broadcast file of the day
/// (always from the scenario's start: the file covers that day) when `data_dir` holds it.
pub fn rows(data_dir: Option<&Path>, draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let registered = skyforge_scenarios::named(SCENARIO)?;
    let mut base = registered.clone();
    base.time.start += hifitime::Duration::from_seconds(DRAW_STEP_S * draw.offset as f64);
    let epochs_note =
        |c: &VisibleCounts| format!("{} epochs at 1 Hz over 24 h, first antenna", c.all.len());

    let embedded = count_visible(&base)?;
    let mut rows = rows_for(
        "embedded GPS + BDS-3",
        &embedded,
        &[0, 1, 2],
        &format!(
            "{}; the thesis does not say which BD constellation it used",
            epochs_note(&embedded)
        ),
    );

    let mut bds2 = base.clone();
    bds2.gnss.gps.enabled = false;
    bds2.gnss.beidou.embedded_set = BeidouSet::Bds2;
    let bds2_counts = count_visible(&bds2)?;
    let combined = VisibleCounts {
        gps: embedded.gps.clone(),
        beidou: bds2_counts.beidou.clone(),
        all: embedded
            .gps
            .iter()
            .zip(&bds2_counts.beidou)
            .map(|(g, b)| g + b)
            .collect(),
    };
    rows.extend(rows_for(
        "embedded GPS + BDS-2",
        &combined,
        &[1, 2],
        &format!(
            "{}; BDS-2 (5 GEO, 7 IGSO, 3 MEO) was the operational BD system in 2018",
            epochs_note(&combined)
        ),
    ));

    match data_dir
        .map(|d| d.join(REAL_NAV_FILE))
        .filter(|p| p.is_file())
    {
        Some(nav) => {
            let mut real = registered.clone();
            for c in [&mut real.gnss.gps, &mut real.gnss.beidou] {
                c.source = ConstellationSource::Rinex;
                c.nav_file = Some(nav.clone());
            }
            let counts = count_visible(&real)?;
            rows.extend(rows_for(
                "broadcast BRD400DLR 2023-03-12",
                &counts,
                &[0, 1, 2],
                &format!(
                    "{}; all healthy GPS and BeiDou (BDS-2 + BDS-3) satellites in the file",
                    epochs_note(&counts)
                ),
            ));
        }
        None => eprintln!(
            "V-1.2.1: real-data folder not found (set SKYFORGE_DATA); the broadcast-file rows are skipped"
        ),
    }
    Ok(rows)
}
