//! Assisted acquisition: what a receiver that has ephemerides (or an almanac), its
//! approximate position and velocity and the approximate time can predict for each
//! satellite: visibility, Doppler and Doppler rate, and how far to search around them.
//! A LEO receiver needs this: its Doppler spans about +/-45 kHz and changes by up to
//! 80 Hz/s, too wide for a blind search at every start.

use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::predicted_view;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, GM_GPS, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::visibility::segment_blocked;

/// Half step of the central differences (s).
const DIFF_STEP_S: f64 = 0.05;

/// WGS-84 semi-minor axis (m): a line of sight passing closer to the geocentre is blocked.
const EARTH_POLAR_RADIUS_M: f64 = 6_356_752.3;

/// What the receiver is told.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assistance {
    /// Approximate receive time (s since the ephemeris origin, GPST).
    pub t_s: f64,
    /// Its uncertainty (s).
    pub time_uncertainty_s: f64,
    /// Approximate position and velocity (ECEF).
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    /// Position and velocity uncertainties (m, m/s).
    pub position_uncertainty_m: f64,
    pub velocity_uncertainty_mps: f64,
    /// Receiver oscillator frequency uncertainty (dimensionless, e.g. 1e-6 for 1 ppm).
    pub oscillator_uncertainty: f64,
    /// Satellites below this elevation (rad) are not predicted; ignored above 100 km,
    /// where only the Earth blocks.
    pub elevation_mask_rad: f64,
}

/// A satellite to search for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchHint {
    pub sat: SatId,
    /// Predicted carrier Doppler (Hz, positive when approaching) and its rate (Hz/s).
    pub doppler_hz: f64,
    pub doppler_rate_hzps: f64,
    /// Half-width of the Doppler window that covers the stated uncertainties (Hz).
    pub doppler_window_hz: f64,
    /// Elevation at the approximate position (rad; negative from orbit is fine).
    pub elevation_rad: f64,
}

/// Acceleration (ECEF, m/s^2) of a body in free fall at `r`, `v` (ECEF): two-body
/// gravity, Coriolis and centrifugal terms of the rotating frame.
fn free_fall_ecef(r: &Vec3, v: &Vec3) -> Vec3 {
    let w = Vec3::new(0.0, 0.0, OMEGA_E_GPS);
    -GM_GPS * r / r.norm().powi(3) - 2.0 * w.cross(v) - w.cross(&w.cross(r))
}

/// Whether the segment from `a` to `b` stays clear of a sphere of the Earth's polar radius:
/// inside the ellipsoid everywhere, so that the prediction keeps every satellite the
/// ellipsoid might let through. Used above 100 km, where `a` is outside the sphere.
fn clear_of_earth(a: &Vec3, b: &Vec3) -> bool {
    !segment_blocked(a, b, EARTH_POLAR_RADIUS_M, EARTH_POLAR_RADIUS_M)
}

/// Hints for `signal` of every satellite of its system in `store` that is in view of the
/// assisted receiver, sorted by elevation (highest first).
pub fn search_hints(store: &EphemerisStore, a: &Assistance, signal: Signal) -> Vec<SearchHint> {
    let h_m = ecef_to_geodetic(&a.r_ecef_m).h_m;
    let f = signal.carrier_hz();
    let mut hints: Vec<SearchHint> = store
        .satellites()
        .into_iter()
        .filter(|sat| sat.system == signal.system())
        .filter_map(|sat| {
            let eph = store.select(sat, a.t_s)?;
            // The receiver dt seconds later: coasting in orbit, or moving steadily on the
            // ground.
            let receiver_at = |dt: f64| {
                let acc = if h_m > 100e3 {
                    free_fall_ecef(&a.r_ecef_m, &a.v_ecef_mps)
                } else {
                    Vec3::zeros()
                };
                (
                    a.r_ecef_m + a.v_ecef_mps * dt + acc * (dt * dt / 2.0),
                    a.v_ecef_mps + acc * dt,
                )
            };
            // Doppler by a central difference of the predicted pseudorange (range minus
            // satellite clock), which carries every light-time term.
            let range_at = |dt: f64| {
                let view = predicted_view(eph, a.t_s + dt, &receiver_at(dt).0);
                view.range_m - C_MPS * view.clock_s
            };
            let lambda = C_MPS / f;
            let doppler_at = |dt: f64| {
                -(range_at(dt + DIFF_STEP_S) - range_at(dt - DIFF_STEP_S))
                    / (2.0 * DIFF_STEP_S)
                    / lambda
            };
            let view = predicted_view(eph, a.t_s, &a.r_ecef_m);
            let doppler_hz = doppler_at(0.0);
            let el = view.az_el_rad.map_or(-std::f64::consts::FRAC_PI_2, |x| x.1);
            let visible = if h_m > 100e3 {
                clear_of_earth(&a.r_ecef_m, &view.r_ecef_m)
            } else {
                el >= a.elevation_mask_rad
            };
            if !visible {
                return None;
            }
            let rate = doppler_at(0.5) - doppler_at(-0.5);
            // Window: time error x Doppler rate, velocity error, oscillator error, and the
            // line-of-sight change a position error causes (|v_sat| x dr / range).
            let los_turn = view.v_ecef_mps.norm() * a.position_uncertainty_m / view.range_m;
            let window = (rate * a.time_uncertainty_s).abs()
                + (a.velocity_uncertainty_mps + los_turn) / lambda
                + a.oscillator_uncertainty * f;
            Some(SearchHint {
                sat,
                doppler_hz,
                doppler_rate_hzps: rate,
                doppler_window_hz: window,
                elevation_rad: el,
            })
        })
        .collect();
    hints.sort_by(|x, y| y.elevation_rad.total_cmp(&x.elevation_rad));
    hints
}
