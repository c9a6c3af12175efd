//! Orbit determination on observation files: the receiver's single-point fixes (velocity
//! from the Doppler where it was measured) every `interval_s`, into the position filter.
//! Reads only what a receiver could: observations, broadcast ephemerides, the filter's
//! own settings.

use super::{FixInput, OrbitEstimate, PositionFilter, PositionFilterConfig};
use crate::pvt::{Measurement, PvtConfig, solve_velocity};
use crate::relative::single_point_fixes;
use skyforge_gnss::observation::ObsFile;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::time::TimeOrigin;

/// Epoch tags within this of a multiple of the interval are sampled (s).
const ON_GRID_S: f64 = 1e-3;

/// The filter's estimates at every epoch of `file` on the grid `k interval_s` (seconds
/// since `origin`) that has a fix on `signals`.
pub fn position_filter_on_file(
    file: &ObsFile,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    signals: &[Signal],
    pvt: &PvtConfig,
    filter: PositionFilterConfig,
    interval_s: f64,
) -> Vec<OrbitEstimate> {
    let fixes = single_point_fixes(file, store, origin, signals, pvt);
    let mut od = PositionFilter::new(filter, origin.start());
    let mut out = Vec::new();
    for (epoch, fix) in file.epochs.iter().zip(fixes) {
        let t_s = origin.seconds_since_start(epoch.time);
        let on_grid =
            (t_s / interval_s - (t_s / interval_s).round()).abs() * interval_s < ON_GRID_S;
        let Ok(fix) = fix.as_ref() else { continue };
        if !on_grid {
            continue;
        }
        let meas: Vec<Measurement> = epoch
            .sats
            .iter()
            .filter(|r| signals.contains(&r.signal))
            .filter_map(|r| {
                Some(Measurement {
                    sat: r.sat,
                    pseudorange_m: r.pseudorange_m?,
                    doppler_hz: r.doppler_hz,
                    signal: r.signal,
                })
            })
            .collect();
        let velocity = solve_velocity(&meas, t_s, store, fix).ok();
        out.push(od.update(&FixInput {
            t_s: fix.t_s,
            r_ecef_m: fix.r_ecef_m,
            v_ecef_mps: velocity.map(|v| v.v_ecef_mps),
            gdop: fix.dop.gdop,
        }));
    }
    out
}
