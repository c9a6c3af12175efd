//! The tightly coupled filter (book 3.2.2's pseudorange/pseudorange-rate integration, 18
//! states): the INS's 15 error states, the receiver clock's bias and drift and a
//! barometer's bias, updated by every satellite's pseudorange and range rate (from its
//! Doppler) and by barometric heights.
//!
//! Measurement models (book eqs. 3-84..3-97 and 3-98..3-115 in ECEF form; Groves 2013 eqs.
//! 14.126-14.127 with the lever arm): predicted minus measured pseudorange
//! `b^ - (rho - r_model(r^_a))` with rows `-e^T` on the position error, `e^T [C l x]` on
//! the attitude error and 1 on the clock bias (`e` the unit line of sight to the
//! satellite, `r_model` the geometric range with the satellite clock, ionosphere and
//! troposphere models of `pvt`); the range rate `-lambda D` less the satellite's share
//! `e . v_sat - c drift_sat` against `-e . v^_a + d^` with rows `-e^T` on the velocity
//! error, `e^T [w x]` on the attitude error, `e^T C [l x]` on the gyro bias, 1 on the
//! drift. The barometer reads the IMU's height plus its bias (book: `Z_h = h_INS - h_b`).

use super::config::{IntegrationError, LooselyCoupledConfig};
use super::error_state::{ATT, GYR, POS, VEL, skew};
use super::filter::{InsFilter, Rows, Update};
use super::receiver_states::{BARO, CLOCK, DRIFT, ReceiverNoise, ReceiverStates, TIGHT_STATES};
use crate::ins::InsState;
use crate::pvt::{Measurement, PvtConfig, code_residuals};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::{c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::gravity::earth_rate_ecef;
use skyforge_orbits::time::TimeOrigin;

/// The tightly coupled filter.
pub type TightlyCoupled = InsFilter<TIGHT_STATES>;

/// One row of a range update: predicted minus measured, its error state row and variance.
struct RangeRow {
    y: f64,
    h: [f64; TIGHT_STATES],
    variance: f64,
}

impl TightlyCoupled {
    /// A filter starting at `initial` (the INS as [`super::LooselyCoupled::new`]) with the
    /// receiver clock at `clock` (bias m, drift m/s: from a single-point solution, or
    /// known) and the barometer's bias at zero.
    pub fn new(
        initial: InsState,
        config: LooselyCoupledConfig,
        receiver: ReceiverNoise,
        clock: (f64, f64),
    ) -> Result<Self, IntegrationError> {
        receiver.check()?;
        let states = ReceiverStates {
            noise: receiver,
            clock_m: clock.0,
            drift_mps: clock.1,
            baro_bias_m: 0.0,
        };
        Self::with_receiver(initial, config, Some(states))
    }

    /// The receiver clock's estimate: bias (m) and drift (m/s).
    pub fn clock(&self) -> (f64, f64) {
        self.states()
            .map_or((0.0, 0.0), |r| (r.clock_m, r.drift_mps))
    }

    /// The barometer bias's estimate (m).
    pub fn barometer_bias(&self) -> f64 {
        self.states().map_or(0.0, |r| r.baro_bias_m)
    }

    fn states(&self) -> Option<&ReceiverStates> {
        self.receiver.as_ref()
    }

    /// Updates with every pseudorange of `epoch` (within one IMU interval of the INS's
    /// time) above `pvt`'s mask, and the range rate of each that has a Doppler;
    /// `Ok(None)` when no satellite is usable.
    pub fn update_ranges(
        &mut self,
        epoch: &ObsEpoch,
        store: &EphemerisStore,
        origin: &TimeOrigin,
        pvt: &PvtConfig,
    ) -> Result<Option<Update>, IntegrationError> {
        let Some(receiver) = self.states().copied() else {
            return Ok(None);
        };
        let state = *self.state();
        // The antenna at the true time of reception: the tag less the clock's bias.
        let offset_s = self.offset_s(epoch.time)? - receiver.clock_m / C_MPS;
        let lever = self.lever_arm();
        let c = state.c_body_ecef;
        let c_l = c * lever;
        let antenna = state.r_ecef_m + state.v_ecef_mps * offset_s + c_l;
        let rotating = c * self.omega_ib_body().cross(&lever) - earth_rate_ecef().cross(&c_l);
        let v_antenna = state.v_ecef_mps + rotating;
        let meas = Measurement::of_records(&epoch.sats);
        let tag_s = origin.seconds_since_start(epoch.time);
        let residuals = code_residuals(&meas, tag_s, store, origin, pvt, &antenna);
        let noise = &receiver.noise;
        let mut rows = Vec::with_capacity(2 * residuals.len());
        for res in &residuals {
            let e = res.los;
            let mut h = [0.0; TIGHT_STATES];
            put(&mut h, POS, &-e);
            put(&mut h, ATT, &(skew(&c_l).transpose() * e));
            h[CLOCK] = 1.0;
            rows.push(RangeRow {
                y: receiver.clock_m - res.omc_m,
                h,
                variance: noise.code_sigma_m.powi(2),
            });
            if let Some(rate) = range_rate(&meas, res.sat) {
                let mut h = [0.0; TIGHT_STATES];
                put(&mut h, VEL, &-e);
                put(&mut h, ATT, &(skew(&rotating).transpose() * e));
                put(&mut h, GYR, &((c * skew(&lever)).transpose() * e));
                h[DRIFT] = 1.0;
                rows.push(RangeRow {
                    y: -e.dot(&v_antenna) + receiver.drift_mps - (rate - res.sat_rate_mps),
                    h,
                    variance: noise.range_rate_sigma_mps.powi(2),
                });
            }
        }
        if rows.is_empty() {
            return Ok(None);
        }
        let n = rows.len();
        let update = Rows {
            h: DMatrix::from_fn(n, TIGHT_STATES, |i, k| rows[i].h[k]),
            y: DVector::from_fn(n, |i, _| rows[i].y),
            r: DMatrix::from_fn(n, n, |i, j| if i == j { rows[i].variance } else { 0.0 }),
        };
        self.apply(update, epoch.time).map(Some)
    }

    /// Updates with a barometric height (m above the ellipsoid, at the IMU) read now;
    /// refused without a barometer in the receiver's model.
    pub fn update_barometer(&mut self, height_m: f64) -> Result<Update, IntegrationError> {
        let state = *self.state();
        let baro = self
            .states()
            .and_then(|r| r.noise.barometer.map(|b| (b, r)));
        let Some((noise, receiver)) = baro.filter(|_| height_m.is_finite()) else {
            return Err(IntegrationError::BadFix {
                t: state.t,
                what: "barometric height not finite, or no barometer in the receiver model",
            });
        };
        let g = ecef_to_geodetic(&state.r_ecef_m);
        let up: Vec3 = -c_ecef_ned(g.lat_rad, g.lon_rad).row(2).transpose();
        let mut h = [0.0; TIGHT_STATES];
        put(&mut h, POS, &up);
        h[BARO] = 1.0;
        let rows = Rows {
            h: DMatrix::from_row_slice(1, TIGHT_STATES, &h),
            y: DVector::from_element(1, g.h_m + receiver.baro_bias_m - height_m),
            r: DMatrix::from_element(1, 1, noise.white_m.powi(2)),
        };
        self.apply(rows, state.t)
    }
}

/// The receiver clock's bias (m) and drift (m/s) that explain `epoch`'s pseudoranges and
/// range rates at an antenna at `r_m` moving at `v_mps` (ECEF): the means over its
/// satellites, a start for [`TightlyCoupled::new`] when the clock is not known. The drift
/// is 0 without Dopplers; `None` without a usable satellite.
pub fn clock_from_epoch(
    epoch: &ObsEpoch,
    (r_m, v_mps): (&Vec3, &Vec3),
    store: &EphemerisStore,
    origin: &TimeOrigin,
    pvt: &PvtConfig,
) -> Option<(f64, f64)> {
    let meas = Measurement::of_records(&epoch.sats);
    let tag_s = origin.seconds_since_start(epoch.time);
    let residuals = code_residuals(&meas, tag_s, store, origin, pvt, r_m);
    if residuals.is_empty() {
        return None;
    }
    let bias = residuals.iter().map(|r| r.omc_m).sum::<f64>() / residuals.len() as f64;
    let drifts: Vec<f64> = (residuals.iter())
        .filter_map(|r| Some(range_rate(&meas, r.sat)? - r.sat_rate_mps + r.los.dot(v_mps)))
        .collect();
    let drift = if drifts.is_empty() {
        0.0
    } else {
        drifts.iter().sum::<f64>() / drifts.len() as f64
    };
    Some((bias, drift))
}

/// The range rate `-lambda D` (m/s) of `sat`'s first measurement with a Doppler.
fn range_rate(meas: &[Measurement], sat: SatId) -> Option<f64> {
    let m = meas
        .iter()
        .find(|m| m.sat == sat && m.doppler_hz.is_some())?;
    Some(-m.doppler_hz? * C_MPS / m.signal.carrier_hz())
}

/// Writes the row vector `v^T` into `h` from column `at`.
fn put(h: &mut [f64; TIGHT_STATES], at: usize, v: &Vec3) {
    h[at..at + 3].copy_from_slice(v.as_slice());
}
