//! T-5.4-3..5 (thesis tables 5.4-3, 5.4-4 and 5.4-5): real-time attitude from three GPS L1
//! antennas on two 1 m baselines at 1 Hz. The bundled scenario [`SCENARIO`] at the
//! calibrated observation level, the chain of `skyforge attitude` (double differences,
//! the integer search under the body geometry, hold) with the KF attitude stage of
//! eqs. 2.5-16/2.5-17, on [`SEEDS`](crate::attitude::seeds::SEEDS) seeds.
//!
//! Rows: each baseline's error std in ECEF X, Y, Z (table 5.4-3) and in the master's
//! N, E, D (table 5.4-4), the yaw, pitch and roll error std (table 5.4-5), each the mean
//! over runs of a run's std, within a factor 1.6 of the thesis; and per baseline whether
//! the vertical error is larger than the horizontal ones, as the thesis finds. Notes give
//! the standard error over runs, the errors' mean (the thesis's are below 2e-5 m and
//! 4e-4 deg) and RMS, the chain's fix counts and integer checks, and for the attitude the
//! std of epoch-by-epoch LS on the same runs (what the KF's smoothing gains).

use super::attitude_runs::{self, SeriesStats, chain_note, factor_row, seed_runs};
use crate::attitude::ChainComparison;
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use skyforge_navigation::attitude::AttitudeMethod;
use skyforge_navigation::relative::RelativeConfig;

/// Table identifiers: ECEF baseline errors, NED baseline errors, attitude errors (one
/// run serves the three).
pub const TABLES: [&str; 3] = ["T-5.4-3", "T-5.4-4", "T-5.4-5"];
/// The bundled scenario.
pub const SCENARIO: &str = "thesis/t-5.4-3";

/// Tables 5.4-3 and 5.4-4: per baseline, the ECEF X, Y, Z and NED N, E, D error std (m).
pub const BASELINE_ROWS: [[f64; 6]; 2] = [
    [0.0013, 0.0013, 8.4087e-4, 8.0105e-4, 7.8495e-4, 0.0017],
    [0.0013, 0.0013, 8.3888e-4, 8.0197e-4, 7.9072e-4, 0.0017],
];
/// Table 5.4-5: yaw, pitch, roll error std (deg).
pub const ATTITUDE_ROW: [f64; 3] = [0.0410, 0.0741, 0.0806];
/// `THESIS_TARGETS.md`: each std within this factor.
const FACTOR: f64 = 1.6;
const COMPONENTS: [&str; 6] = ["ECEF X", "ECEF Y", "ECEF Z", "NED N", "NED E", "NED D"];
const AXES: [&str; 3] = ["yaw", "pitch", "roll"];

/// The receiver's chain with the real-time KF attitude (thesis 5.4); the double
/// differences weighted as the chain's defaults say (the receiver is not told the
/// simulated noise).
fn config(method: AttitudeMethod) -> RelativeConfig {
    let mut c = RelativeConfig::default();
    c.attitude.method = method;
    c
}

fn stats(
    runs: &[ChainComparison],
    series: impl Fn(&ChainComparison) -> Vec<f64>,
) -> Result<SeriesStats, ValidateError> {
    attitude_runs::stats(SCENARIO, runs, series)
}

/// The rows of tables 5.4-3..5 on the runs of `draw`.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let scenario = skyforge_scenarios::named(SCENARIO)?;
    // The same runs with epoch-by-epoch LS attitude too: how much the KF smooths.
    let [runs, ls_runs] = seed_runs(
        &scenario,
        [
            config(AttitudeMethod::Kf),
            config(AttitudeMethod::LeastSquares),
        ],
        draw,
    )?;
    let chain = chain_note(&runs);
    let mut out = Vec::new();
    for (k, thesis) in BASELINE_ROWS.iter().enumerate() {
        let mut stds = [0.0; 6];
        for (i, name) in COMPONENTS.iter().enumerate() {
            let s = stats(&runs, |r| r.baseline_axis(k, i % 3, i >= 3))?;
            stds[i] = s.std.mean;
            out.push(
                factor_row(
                    TABLES[i / 3],
                    format!("baseline {} {name} error", k + 1),
                    "m",
                    thesis[i],
                    s.std.mean,
                    FACTOR,
                )
                .with_note(format!("{}; {chain}", s.note(1e3, "mm", 3))),
            );
        }
        let (n, e, d) = (stds[3], stds[4], stds[5]);
        out.push(Row::measured(
            TABLES[1],
            format!("baseline {}: D std over the larger of N, E", k + 1),
            "ratio",
            "-",
            Some(thesis[5] / thesis[3].max(thesis[4])),
            d / n.max(e),
            (
                "> 1 (vertical worst)".into(),
                Verdict::from_ok(d > n.max(e)),
            ),
        ));
    }
    for (i, axis) in AXES.iter().enumerate() {
        let s = stats(&runs, |r| r.attitude_axis(i))?;
        let ls = stats(&ls_runs, |r| r.attitude_axis(i))?;
        out.push(
            factor_row(
                TABLES[2],
                format!("{axis} error (KF)"),
                "deg",
                ATTITUDE_ROW[i],
                s.std.mean,
                FACTOR,
            )
            .with_note(format!(
                "{}; epoch-by-epoch LS on the same runs: std {} deg; {chain}",
                s.note(1.0, "deg", 4),
                ls.std.describe(1.0, 4)
            )),
        );
    }
    Ok(out)
}
