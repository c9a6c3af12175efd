//! The `least-squares` attitude stage: the LS solution every epoch, no rates.

use super::config::AttitudeMethod;
use super::filter::{AttitudeFilter, FilterState, UpdateInfo};
use super::least_squares::{LsConfig, solve};
use super::{AttitudeError, AttitudeEstimate, BodyGeometry, NedBaselines};
use nalgebra::DMatrix;

/// The `least-squares` stage: eqs. 2.5-9..2.5-13 every epoch from the Wahba start.
#[derive(Debug, Clone)]
pub struct LeastSquaresStage {
    config: LsConfig,
    geometry: BodyGeometry,
    last: Option<AttitudeEstimate>,
}

impl LeastSquaresStage {
    /// The stage for `geometry`.
    pub fn new(config: LsConfig, geometry: BodyGeometry) -> Result<Self, AttitudeError> {
        config.check()?;
        Ok(Self {
            config,
            geometry,
            last: None,
        })
    }
}

impl AttitudeFilter for LeastSquaresStage {
    fn method(&self) -> AttitudeMethod {
        AttitudeMethod::LeastSquares
    }

    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError> {
        if dt_s.is_finite() && dt_s >= 0.0 {
            Ok(())
        } else {
            Err(AttitudeError::Filter(format!(
                "prediction interval {dt_s} s must be finite and >= 0"
            )))
        }
    }

    fn update(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError> {
        let est = solve(&self.geometry, measured, None, &self.config)?;
        let info = UpdateInfo {
            chi_square: est.chi_square,
            dof: 3 * measured.len() - 3,
            initialised: self.last.is_none(),
        };
        self.last = Some(est);
        Ok(info)
    }

    fn state(&self) -> Option<FilterState> {
        self.last.as_ref().map(|e| FilterState {
            angles: e.angles,
            rates_rad_s: None,
            covariance: DMatrix::from_column_slice(3, 3, e.covariance.as_slice()),
        })
    }
}
