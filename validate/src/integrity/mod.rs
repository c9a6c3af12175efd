//! Integrity monitoring against its references: the B-value monitor on paper 002's lab
//! set-up (its fault cases as patterns, fault-free false alarms, detection curves), and
//! RAIM against Yuan 2000 tables 5-1 and 5-2 ([`raim`], table 5-1 on the en-route leg of
//! `aircraft`).

/// The aircraft trajectory's generator, run by its tests.
#[cfg(test)]
mod aircraft;
pub mod detection;
pub(crate) mod lab;
pub(crate) mod monitor;
pub mod patterns;
pub(crate) mod raim;
pub(crate) mod score;

pub use lab::{Case, FAULT_SATELLITE, MonitoredRun, scenario};
pub use monitor::{
    ELEVATION_BINS_DEG, Sigmas, calibrate, calibrate_files, calibrate_lab, case_run, config,
};
pub use score::{check_same_run, print_score, run_scenario, score};

use crate::draw::Draw;
use crate::report::Row;

/// Both table groups on the seeds of `draw` (registered or shifted): thresholds
/// calibrated on the lab's fault-free seeds, the paper's cases on [`patterns::SEEDS`]
/// seeds, the detection curves on [`detection::SEEDS`] seeds per size.
pub fn rows(draw: Draw, patterns: bool, curves: bool) -> Result<Vec<Row>, String> {
    let sigma = monitor::calibrate_lab(draw.offset)?;
    let mut rows = Vec::new();
    if patterns {
        rows.extend(patterns::rows(&sigma, draw)?);
    }
    if curves {
        rows.extend(detection::rows(&sigma, draw)?);
    }
    Ok(rows)
}
