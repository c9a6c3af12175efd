//! The measurements of book eq. 5-59: per satellite the single differences (chaser minus
//! target) of pseudorange and of the Doppler range rate, and their model at a relative
//! state `X = [x y z c dt x' y' z' c dt']` (target orbit frame; `c dt` the receivers'
//! clock difference `c (dt_c - dt_t)`, m).
//!
//! With `e` the line of sight from the chaser to the satellite (ECEF), `P_i = |r_s -
//! r_i| + c dt_i - c dT_s` and `-lambda D_i = e_i . (v_s - v_i) + c dt_i' - c dT_s'` give
//!
//! `SD P = |r_s - r_c| - |r_s - r_t| + c dt`,
//! `SD (-lambda D) = e_c . (v_s - v_c) - e_t . (v_s - v_t) + c dt'`,
//!
//! so `d SD P / d r_c = -e_c` and `d SD(-lambda D) / d v_c = -e_c`: the rows `[-e^T, 1,
//! 0, 0, 0, 0]` and `[0, 0, 0, 0, -e^T, 1]` of eq. 5-59's `H` (derived here; the book
//! prints target minus chaser, the negative of both sides), `e` turned into the target's
//! orbit frame. The satellite's clock cancels (one clock at two instants a millisecond
//! apart differs by its drift times that, picometres), and so does its ephemeris error
//! but for `|b| / rho` of it.
//!
//! The book's linear `Z = H X` holds for baselines of metres; at 32 km it misses by up to
//! 26 m (the range difference's curvature `|b|^2 sin^2 / (2 rho)`) and 46 m/s (the lines
//! of sight turning, `|b| |v_s - v| / rho`, and the frame's rotation, `n |b|` = 35 m/s),
//! measured on the tests' geometry. So the single differences are predicted exactly from
//! both receivers' positions (an extended Kalman filter), and `e` is the chaser's line of
//! sight at its predicted position, which makes `H` the exact Jacobian (the book's, the
//! target's line of sight, differs from it by `|b| / rho`, 0.16 % at 32 km). The rate
//! rows leave out their position partials as the book's `H` does: the lines of sight
//! turn by `|v_s - v| / rho` (4e-4 /s) and the frame by `n` (1.1e-3 /s), so a metre of
//! predicted position error is a millimetre per second of rate, 0.5 % of its noise.
//!
//! Each receiver samples on its own clock: the chaser receives at `t_c = t_t + (tag_c -
//! tag_t) - dt` (microseconds to milliseconds after the target; a millisecond is 7.6 m
//! at LEO speed). As the double-difference mode does, each satellite is taken at each
//! receiver's own transmit time (its tag and pseudorange, `pvt::Transmitted`, Earth
//! rotation during the flight) and the chaser is moved along its velocity from the
//! target's instant by `(tag_c - tag_t) - dt`, so `d SD P / d c dt = 1 + e_c . v_c / c`;
//! its velocity along its acceleration (point-mass gravity and the Earth-fixed frame's
//! terms: 8 m/s^2 over a millisecond is 8 mm/s, which would bias the rate rows).

use crate::pvt::{SatView, Transmitted, ViewPoint};
use crate::relnav::hill_dynamics::TargetState;
use nalgebra::SVector;
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::{C_MPS, GM_GPS};
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::c_orbital_eci;
use skyforge_orbits::{Mat3, Vec3};
use std::collections::BTreeSet;

/// The state of eq. 5-59: `[x y z c dt x' y' z' c dt']`.
pub(crate) type State = SVector<f64, 8>;
/// The state's relative clock `c (dt_c - dt_t)` (m) and its drift (m/s).
pub(crate) const CLOCK: usize = 3;
pub(crate) const DRIFT: usize = 7;

/// One satellite both receivers measured on one signal: its single differences and the
/// satellite at each receiver's own transmit time.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SdSatellite {
    pub sat: SatId,
    at_target: Transmitted,
    at_chaser: Transmitted,
    /// `P_c - P_t` (m).
    pub code_m: f64,
    /// `-lambda (D_c - D_t)` (m/s), where both measured a Doppler.
    pub rate_mps: Option<f64>,
}

/// The record of `sat` on `signal` with a pseudorange.
fn record(records: &[ObsRecord], sat: SatId, signal: Signal) -> Option<&ObsRecord> {
    (records.iter()).find(|r| r.sat == sat && r.signal == signal && r.pseudorange_m.is_some())
}

/// The satellites both receivers measured a pseudorange of, on the first of `signals`
/// they share, with an ephemeris at the target's tag; `tags_s` the two epochs' time tags
/// (target, chaser; s since the ephemerides' origin).
pub(crate) fn satellites(
    (target, chaser): (&[ObsRecord], &[ObsRecord]),
    tags_s: (f64, f64),
    signals: &[Signal],
    store: &EphemerisStore,
) -> Vec<SdSatellite> {
    let sats: BTreeSet<SatId> = target.iter().map(|r| r.sat).collect();
    let pair = |sat| {
        let (t, c) = (signals.iter())
            .find_map(|&f| Some((record(target, sat, f)?, record(chaser, sat, f)?)))?;
        let eph = store.select(sat, tags_s.0)?;
        let (p_t, p_c) = (t.pseudorange_m?, c.pseudorange_m?);
        let rate_mps = (t.doppler_hz.zip(c.doppler_hz))
            .map(|(d_t, d_c)| -t.signal.wavelength_m() * (d_c - d_t));
        Some(SdSatellite {
            sat,
            at_target: Transmitted::of(eph, tags_s.0, p_t),
            at_chaser: Transmitted::of(eph, tags_s.1, p_c),
            code_m: p_c - p_t,
            rate_mps,
        })
    };
    sats.into_iter().filter_map(pair).collect()
}

/// One epoch's frame: the target's state (its orbit filter's, ECI, at its receive
/// instant), the Earth's rotation then and the chaser's time tag less the target's.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EpochFrame {
    pub target: TargetState,
    pub c_eci_ecef: Mat3,
    pub omega_earth_rad_s: Vec3,
    pub tag_difference_s: f64,
}

/// The two receivers where a relative state puts them (ECEF, each at its own receive
/// instant) and the rotation from ECEF to the target's orbit frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Receivers {
    pub target: (Vec3, Vec3),
    pub chaser: (Vec3, Vec3),
    c_orbit_ecef: Mat3,
}

impl EpochFrame {
    /// A vehicle's acceleration in the Earth-fixed frame at `r_eci_m` (`r_ecef_m`,
    /// `v_ecef_mps` in that frame): the point mass's gravity (J2 is 1e-3 of it, 8 um/s
    /// over a millisecond) with the frame's Coriolis and centrifugal terms.
    fn acceleration_ecef(&self, r_eci_m: &Vec3, r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> Vec3 {
        let w = self.omega_earth_rad_s;
        let gravity = -*r_eci_m * (GM_GPS / r_eci_m.norm().powi(3));
        self.c_eci_ecef * gravity - w.cross(v_ecef_mps) * 2.0 - w.cross(&w.cross(r_ecef_m))
    }

    /// The receivers at state `x` (eq. 5-55 inverted: `dr = M^T rho`, `dv = M^T rho' +
    /// w x dr`, `w = r x v / r^2` as `relative_in_frame_of`).
    pub(crate) fn receivers(&self, x: &State) -> Receivers {
        let (r, v) = (self.target.r_eci_m, self.target.v_eci_mps);
        let c = c_orbital_eci(&r, &v);
        let w = r.cross(&v) / r.norm_squared();
        let dr = c * Vec3::new(x[0], x[1], x[2]);
        let dv = c * Vec3::new(x[4], x[5], x[6]) + w.cross(&dr);
        let ecef = |r: Vec3, v: Vec3| {
            let r_ecef = self.c_eci_ecef * r;
            (
                r_ecef,
                self.c_eci_ecef * v - self.omega_earth_rad_s.cross(&r_ecef),
            )
        };
        let (r_c, v_c) = ecef(r + dr, v + dv);
        let shift_s = self.tag_difference_s - x[CLOCK] / C_MPS;
        let a_c = self.acceleration_ecef(&(r + dr), &r_c, &v_c);
        Receivers {
            target: ecef(r, v),
            chaser: (r_c + v_c * shift_s, v_c + a_c * shift_s),
            c_orbit_ecef: c.transpose() * self.c_eci_ecef.transpose(),
        }
    }
}

/// One satellite's single differences at a state and their rows of `H`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Predicted {
    pub code_m: f64,
    pub rate_mps: f64,
    pub h_code: State,
    pub h_rate: State,
}

/// The elevations of `s` at the two receivers (rad; -90 deg without a local frame).
pub(crate) fn elevations(s: &SdSatellite, rx: &Receivers) -> [f64; 2] {
    let el = |t: &Transmitted, r: &Vec3| {
        (ViewPoint::new(*r).see(t).az_el_rad).map_or(-std::f64::consts::FRAC_PI_2, |a| a.1)
    };
    [
        el(&s.at_target, &rx.target.0),
        el(&s.at_chaser, &rx.chaser.0),
    ]
}

/// `s`'s single differences as the state `x` whose receivers are `rx` predicts them
/// (module docs).
pub(crate) fn predict(s: &SdSatellite, x: &State, rx: &Receivers) -> Predicted {
    let view_t = s.at_target.seen_from(&rx.target.0, None);
    let view_c = s.at_chaser.seen_from(&rx.chaser.0, None);
    let rate = |v: &SatView, v_rx: &Vec3| v.los.dot(&(v.v_ecef_mps - v_rx));
    let code_m = view_c.range_m - view_t.range_m + x[CLOCK];
    let rate_mps = rate(&view_c, &rx.chaser.1) - rate(&view_t, &rx.target.1) + x[DRIFT];
    let e = rx.c_orbit_ecef * view_c.los;
    let mut h_code = State::zeros();
    let mut h_rate = State::zeros();
    for k in 0..3 {
        h_code[k] = -e[k];
        h_rate[4 + k] = -e[k];
    }
    h_code[CLOCK] = 1.0 + view_c.los.dot(&rx.chaser.1) / C_MPS;
    h_rate[DRIFT] = 1.0;
    Predicted {
        code_m,
        rate_mps,
        h_code,
        h_rate,
    }
}
