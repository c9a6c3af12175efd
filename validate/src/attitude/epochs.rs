//! An observation-level run epoch by epoch: the chain's fixed baselines in the master's
//! NED frame with their covariance, and the true attitude at every second, for the
//! estimators that start from baselines (thesis chapters 4 and 5.5).

use super::compare::epoch_truth;
use super::nominal_geometry;
use skyforge_navigation::attitude::NedBaselines;
use skyforge_navigation::relative::{AmbiguityStatus, RelativeConfig};
use skyforge_navigation::relative::{FilesError, run_files};
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_runner::ObservationRun;

/// One epoch of the chain.
#[derive(Debug, Clone)]
pub struct FixedEpoch {
    /// Seconds since the run's start.
    pub t_s: f64,
    /// The baselines with every ambiguity fixed (NED, `Q_BB`); `None` otherwise.
    pub baselines: Option<NedBaselines>,
}

/// The chain with `config` over every epoch of `run` (told the nominal geometry).
pub fn fixed_baselines(
    run: &ObservationRun,
    config: RelativeConfig,
) -> Result<Vec<FixedEpoch>, FilesError> {
    let mut out = Vec::new();
    run_files(
        &run.measured,
        run.ephemerides.clone(),
        &nominal_geometry(run),
        config,
        |o| {
            let baselines = o
                .result
                .ok()
                .filter(|e| e.resolution.status == AmbiguityStatus::Fixed)
                .and_then(|e| e.fixed_ned);
            out.push(FixedEpoch {
                t_s: (o.time - run.start).to_seconds(),
                baselines,
            });
        },
    )?;
    Ok(out)
}

/// The true attitude (body against the master's NED) at every whole second of `run`.
pub fn true_attitudes(run: &ObservationRun) -> Vec<YawPitchRoll> {
    run.platform
        .iter()
        .map(|p| epoch_truth(&p.r_ecef_m, &p.c_body_ecef, &run.true_body_m).attitude)
        .collect()
}
