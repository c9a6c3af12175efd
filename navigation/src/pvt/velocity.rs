//! Velocity and clock drift from Doppler, at a known position.

use super::geometry::sat_view;
use super::{Fix, Measurement, PvtError, VelocityFix};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::EphemerisStore;

/// The Doppler velocity (ECEF) beside `fix` from an epoch's `records` on `signals`,
/// received at `t_rx_s`, where it solves.
pub fn records_velocity(
    records: &[ObsRecord],
    signals: &[Signal],
    t_rx_s: f64,
    store: &EphemerisStore,
    fix: &Fix,
) -> Option<Vec3> {
    let meas: Vec<Measurement> = (records.iter())
        .filter(|r| signals.contains(&r.signal))
        .filter_map(Measurement::of_record)
        .collect();
    solve_velocity(&meas, t_rx_s, store, fix)
        .ok()
        .map(|v| v.v_ecef_mps)
}

/// Least-squares velocity and receiver clock drift from the Doppler of `meas` (those that
/// have one and are in `fix`), received at `t_rx_s`: the range rate `-lambda D` equals
/// `los . (v_sat - v_rx) + c drift_rx - c drift_sat` (one receiver oscillator for every
/// system).
pub fn solve_velocity(
    meas: &[Measurement],
    t_rx_s: f64,
    store: &EphemerisStore,
    fix: &Fix,
) -> Result<VelocityFix, PvtError> {
    let mut rows: Vec<([f64; 4], f64)> = Vec::new();
    for m in meas {
        let (Some(doppler), true) = (m.doppler_hz, fix.used.iter().any(|u| u.0 == m.sat)) else {
            continue;
        };
        let eph = store
            .select(m.sat, t_rx_s)
            .ok_or(PvtError::NoEphemeris(m.sat))?;
        let view = sat_view(eph, t_rx_s, m.pseudorange_m, &fix.r_ecef_m);
        let range_rate = -doppler * C_MPS / m.signal.carrier_hz();
        let omc = range_rate - view.los.dot(&view.v_ecef_mps) + C_MPS * view.clock_drift;
        rows.push(([-view.los.x, -view.los.y, -view.los.z, 1.0], omc));
    }
    if rows.len() < 4 {
        return Err(PvtError::TooFewSatellites {
            have: rows.len(),
            need: 4,
            clocks: 1,
        });
    }
    let h = DMatrix::from_fn(rows.len(), 4, |i, k| rows[i].0[k]);
    let y = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.1));
    let x = (h.transpose() * &h)
        .try_inverse()
        .ok_or(PvtError::Singular)?
        * (h.transpose() * y);
    Ok(VelocityFix {
        v_ecef_mps: Vec3::new(x[0], x[1], x[2]),
        clock_drift_mps: x[3],
    })
}
