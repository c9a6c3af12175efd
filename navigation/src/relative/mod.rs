//! The relative-positioning and attitude chain of one epoch: double-difference float
//! baselines ([`crate::baseline`]), integer ambiguities with hold between epochs
//! ([`resolve`], LAMBDA of [`crate::ambiguity`]), fixed baselines, and attitude
//! ([`crate::attitude`]). It runs on observation records, so equally on the receiver's
//! observables, the observation level's and anyone's RINEX.

pub(crate) mod config;
pub(crate) mod files;
pub(crate) mod resolve;
pub(crate) mod reverse;
pub mod search;
pub(crate) mod troposphere;

pub use config::{Constraint, RelativeConfig, ReverseConfig};
pub use files::{EpochChain, EpochOutcome, FilesError, run_files, single_point_fixes};
pub use resolve::{AmbiguityStatus, FixMethod, Resolution, resolve};
pub use reverse::{BaselineMeasurement, ReverseFilter};
use search::ConstrainedSearch;

use crate::attitude::build;
use crate::attitude::filter::{AttitudeFilter, FilterState};
use crate::attitude::frames::ned_baselines_from_ecef;
use crate::attitude::{AttitudeError, BodyGeometry, NedBaselines};
use crate::baseline::{
    AmbiguityHold, BaselineError, DdLayout, DdModel, FixedBaselines, FloatBaselines, FloatMemory,
    LineOfSight,
};
use skyforge_gnss::observation::ObsRecord;
use skyforge_orbits::Vec3;

/// Why an epoch gave no baselines.
#[derive(Debug, thiserror::Error)]
pub enum RelativeError {
    #[error(transparent)]
    Baseline(#[from] BaselineError),
    #[error("ambiguity resolution: {0}")]
    Ambiguity(#[from] crate::ambiguity::AmbiguityError),
    #[error("attitude: {0}")]
    Attitude(#[from] AttitudeError),
    #[error(transparent)]
    Reverse(#[from] reverse::ReverseError),
}

/// What one epoch gave.
#[derive(Debug, Clone)]
pub struct RelativeEpoch {
    pub float: FloatBaselines,
    pub resolution: Resolution,
    /// The baselines with the fixed integers (`None` while float); with the reverse
    /// filter on, its filtered baselines where every ambiguity is fixed.
    pub fixed: Option<FixedBaselines>,
    /// The same in the master's local NED frame (thesis eqs. 2.4-66/2.4-67).
    pub fixed_ned: Option<NedBaselines>,
    /// The attitude stage's state after this epoch (`None` before its first update).
    pub attitude: Option<FilterState>,
    /// Why the attitude stage did not update this epoch, if it did not.
    pub attitude_skipped: Option<String>,
    /// Why the reverse filter failed this epoch (its baselines are the epoch's own, and
    /// the filter starts again at the next fixed epoch), if it did.
    pub reverse_restarted: Option<String>,
}

/// The chain, keeping the held ambiguities and the attitude filter between epochs.
#[derive(Debug)]
pub struct RelativeSolver {
    config: RelativeConfig,
    antennas: usize,
    hold: AmbiguityHold,
    /// The float ambiguities of earlier epochs (used with `config.float_memory`).
    memory: FloatMemory,
    attitude: Box<dyn AttitudeFilter>,
    /// The integer search besides plain LAMBDA (`config.constraint`).
    search: Box<dyn ConstrainedSearch>,
    /// The reverse baseline filter, when configured.
    reverse: Option<ReverseFilter>,
    last_t_s: Option<f64>,
}

impl RelativeSolver {
    /// A solver for antennas whose body-frame positions are `body_positions_m` (master
    /// first; baseline `k` is antenna `k` minus the master).
    pub fn new(config: RelativeConfig, body_positions_m: &[Vec3]) -> Result<Self, RelativeError> {
        let Some((master, others)) = body_positions_m.split_first() else {
            return Err(BaselineError::TooFewAntennas(0).into());
        };
        if others.is_empty() {
            return Err(BaselineError::TooFewAntennas(1).into());
        }
        let baselines: Vec<Vec3> = others.iter().map(|p| p - master).collect();
        let geometry = BodyGeometry::new(&baselines)?;
        let search = search::build(config.constraint, &geometry);
        let attitude = build(&config.attitude, geometry)?;
        let reverse = match config.reverse_filter {
            Some(c) if baselines.len() == reverse::BASELINES => Some(ReverseFilter::new(c)?),
            Some(_) => {
                return Err(BaselineError::Dimension {
                    what: "baselines of the reverse filter (thesis 5.5: 12 states)",
                    expected: reverse::BASELINES,
                    found: baselines.len(),
                }
                .into());
            }
            None => None,
        };
        Ok(Self {
            reverse,
            antennas: body_positions_m.len(),
            config,
            hold: AmbiguityHold::new(),
            memory: FloatMemory::new(),
            attitude,
            search,
            last_t_s: None,
        })
    }

    /// One epoch at time `t_s` (s, any origin): each antenna's records (master first), the
    /// satellites' lines of sight from the master, and the master's position (ECEF, m) for
    /// the local frame of the attitude.
    pub fn epoch(
        &mut self,
        t_s: f64,
        antennas: &[&[ObsRecord]],
        views: &[LineOfSight],
        master_ecef_m: &Vec3,
    ) -> Result<RelativeEpoch, RelativeError> {
        if antennas.len() != self.antennas {
            return Err(BaselineError::Dimension {
                what: "antennas with observations",
                expected: self.antennas,
                found: antennas.len(),
            }
            .into());
        }
        for records in antennas {
            for r in records.iter().filter(|r| r.loss_of_lock()) {
                self.hold.slip(r.sat, r.signal);
                self.memory.slip(r.sat, r.signal);
            }
        }
        let masked: Vec<LineOfSight>;
        let views = match self.config.elevation_mask_deg {
            Some(mask) => {
                let mask_rad = mask.to_radians();
                masked = views
                    .iter()
                    .filter(|v| v.elevation_rad >= mask_rad)
                    .copied()
                    .collect();
                masked.as_slice()
            }
            None => views,
        };
        let layout = DdLayout::select(antennas, views, &self.config.signals)?;
        let model = DdModel::new(layout, antennas.len(), &self.config.noise_model())?;
        let prior = if self.config.float_memory {
            self.memory.prior(&model.layout, model.baseline_count())
        } else {
            None
        };
        let float = FloatBaselines::solve(model, antennas, prior.as_ref())?;
        if self.config.float_memory {
            self.memory.remember(&float);
        }
        let resolution = resolve::resolve(
            &float,
            &mut self.hold,
            &self.config,
            self.search.as_ref(),
            master_ecef_m,
        )?;
        let mut fixed = resolution.fixed_baselines(&float)?;
        if let Some(last) = self.last_t_s {
            let dt_s = (t_s - last).max(0.0);
            self.attitude.predict(dt_s)?;
            if let Some(r) = &mut self.reverse {
                r.predict(dt_s)?;
            }
        }
        self.last_t_s = Some(t_s);
        let mut reverse_restarted = None;
        if let Some(r) = &mut self.reverse
            && let Some(ls) = fixed.take()
        {
            let (baselines, failure) = r.epoch(&float, &resolution, ls);
            fixed = Some(baselines);
            reverse_restarted = failure.map(|e| format!("{e}; the filter restarts"));
        }
        let ned = match &fixed {
            Some(f) => {
                let b: Vec<Vec3> = f.baselines.column_iter().map(|c| c.into_owned()).collect();
                Some(ned_baselines_from_ecef(&b, &f.covariance, master_ecef_m))
            }
            None => None,
        };
        let attitude_skipped = match &ned {
            Some(Ok(ned)) => self.attitude.update(ned).err().map(|e| e.to_string()),
            Some(Err(e)) => Some(e.to_string()),
            None => Some("no fixed baselines".to_string()),
        };
        Ok(RelativeEpoch {
            float,
            resolution,
            fixed,
            fixed_ned: ned.and_then(Result::ok),
            attitude: self.attitude.state(),
            attitude_skipped,
            reverse_restarted,
        })
    }
}
