//! The LEO propagator: integrates forward on demand and hands out dense-output windows, so
//! memory stays bounded however long the scenario is.

use super::PropagateError;
use crate::Vec3;

/// A dense-output trajectory over a time window (ECI).
#[derive(Debug, Clone)]
pub struct DenseTrajectory {}

impl DenseTrajectory {
    /// First and last time covered (s since the scenario start).
    pub fn span(&self) -> (f64, f64) {
        todo!()
    }
    /// ECI position, velocity and acceleration at `t_s` (inside the span).
    pub fn state_eci(&self, t_s: f64) -> (Vec3, Vec3, Vec3) {
        todo!("{t_s}")
    }
}

/// A numerically propagated LEO.
#[derive(Debug, Clone)]
pub struct LeoPropagator {}

impl LeoPropagator {
    /// Dense output covering `[t0_s, t1_s]`. Windows must move forward: `t0_s` may reach
    /// back at most into the last integrator steps kept from the previous window.
    pub fn window(&mut self, t0_s: f64, t1_s: f64) -> Result<DenseTrajectory, PropagateError> {
        todo!("{t0_s} {t1_s}")
    }
}
