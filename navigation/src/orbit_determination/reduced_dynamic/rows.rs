//! The reduced-dynamic filter's measurement rows, linearised at the predicted state
//! (receiver ECEF position `r_e = R r`, velocity `v_e = R v - w x R r`, `R` the ECI to
//! ECEF rotation of the receive instant).

use crate::orbit_determination::position_filter::cross_matrix;
use crate::pvt::SatView;
use nalgebra::DVector;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::{Mat3, Vec3};

/// The receiver at the receive instant: what every row's partials need.
pub(super) struct Receiver {
    /// `R`, ECI to ECEF.
    pub rot: Mat3,
    pub omega: Vec3,
    pub v_e: Vec3,
}

/// One linearised measurement: `innovation = z - h(x)`, `h` its partials.
#[derive(Debug, Clone)]
pub(super) struct Row {
    pub h: DVector<f64>,
    pub innovation: f64,
    pub variance: f64,
}

impl Receiver {
    /// The partials of a range `|r_s - r_e|` by the receiver's ECI position, written
    /// into a row of `n` states.
    pub fn range_row(&self, n: usize, view: &SatView) -> DVector<f64> {
        let mut h = DVector::zeros(n);
        h.rows_mut(0, 3)
            .copy_from(&-(self.rot.transpose() * view.los));
        h
    }

    /// The range rate `e . (v_s - v_e) - c ddt_s` (without the receiver's drift) and its
    /// partials by the ECI position and velocity; the line of sight `e` turns with the
    /// position (`d(e . dv)/dr_e = -(dv - e (e . dv)) / range`).
    pub fn rate_row(&self, n: usize, view: &SatView) -> (f64, DVector<f64>) {
        let e = view.los;
        let dv = view.v_ecef_mps - self.v_e;
        let rate = e.dot(&dv) - C_MPS * view.clock_drift;
        let by_r_e = -(dv - e * e.dot(&dv)) / view.range_m;
        let by_v_e = -e;
        let by_r = self.rot.transpose() * by_r_e
            - (cross_matrix(&self.omega) * self.rot).transpose() * by_v_e;
        let by_v = self.rot.transpose() * by_v_e;
        let mut h = DVector::zeros(n);
        h.rows_mut(0, 3).copy_from(&by_r);
        h.rows_mut(3, 3).copy_from(&by_v);
        (rate, h)
    }
}
