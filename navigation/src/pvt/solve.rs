//! The iterated weighted least-squares position and clock solution.

use super::exclusion::{most_suspect, normalised_residuals};
use super::geometry::{FromEphemeris, SatView, Satellites, Transmitted, local_frame_at};
use super::protection::{protection_levels, slopes};
use super::raim::{detection_parameters, test_threshold};
use super::ranging::{Ranging, per_satellite};
use super::{
    Dop, Fix, IONOSPHERE_USER_CEILING_M, IntegrityStatus, Measurement, Protection, PvtConfig,
    PvtError,
};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, F_BDS_B1I_HZ, F_GPS_L1_HZ};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId, System};
use skyforge_orbits::ephemeris::{bds_klobuchar_b1i_s, gps_klobuchar_l1_s};
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic};
use skyforge_orbits::time::{TimeOrigin, bdt_week_sow, gpst_week_sow};
use skyforge_orbits::troposphere::standard_slant_delay_m;

/// Iterations of the linearised solution; it converges in 4-6 from the geocentre.
const MAX_ITERATIONS: usize = 15;
/// Position step below which the iteration has converged (m).
const CONVERGED_M: f64 = 1e-4;
/// Relative humidity at sea level of the receiver's standard troposphere.
pub(crate) const STANDARD_RH0: f64 = 0.5;

/// Solve the position, receiver clock(s) (one per system: GPS, BeiDou, Galileo) and, with
/// GPS and BeiDou, the inter-system bias
/// from `meas` received at `t_rx_s` (receiver time tag, s since `origin`, GPST), with the
/// ephemerides of `store` (bound to `origin`). `a_priori` starts the iteration (the
/// geocentre otherwise). Applies the residual test of [`super::raim`] and, when it fails,
/// excludes the satellite with the largest normalised residual ([`super::exclusion`]); the
/// fix's [`Protection`] gives the protection levels of the satellites finally used and the
/// test's verdict.
pub fn solve(
    meas: &[Measurement],
    t_rx_s: f64,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    cfg: &PvtConfig,
    a_priori: Option<Vec3>,
) -> Result<Fix, PvtError> {
    solve_with(
        meas,
        t_rx_s,
        store,
        origin,
        cfg,
        a_priori,
        &mut FromEphemeris,
    )
}

/// One measurement's code residual at a known receiver position (m): the pseudorange
/// minus the modelled range, satellite clock, ionosphere and troposphere of `cfg`, so the
/// receiver clock is left in it. With its unit line of sight and elevation, and the
/// satellite's share of the range rate, `los . v_sat - c drift_sat` (m/s), which a
/// range rate `-lambda D` less it leaves `-los . v_rx + c drift_rx`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CodeResidual {
    pub sat: SatId,
    pub omc_m: f64,
    pub los: Vec3,
    pub el_rad: f64,
    pub sat_rate_mps: f64,
}

/// The code residuals of `meas` received at `t_rx_s` by an antenna at `r` (the fix's
/// models, satellites above `cfg`'s mask, one ranging per satellite as [`solve`] forms
/// it): what a filter that knows its position to metres linearises about.
pub fn code_residuals(
    meas: &[Measurement],
    t_rx_s: f64,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    cfg: &PvtConfig,
    r: &Vec3,
) -> Vec<CodeResidual> {
    let ranged = per_satellite(meas, cfg.ionosphere);
    let usable: Vec<(&Ranging, Transmitted)> = (ranged.iter())
        .filter_map(|m| {
            let eph = store.select(m.sat, t_rx_s)?;
            let tx = FromEphemeris.transmitted(eph, t_rx_s, m.pseudorange_m);
            Some((m, tx.clock_shifted(ranging_delay_beyond_tgd_s(m, &eph.eph))))
        })
        .collect();
    let (meas, sats): (Vec<&Ranging>, Vec<Transmitted>) = usable.into_iter().unzip();
    let systems = [System::Gps, System::Beidou, System::Galileo];
    let clocks = [0.0; 3];
    linearise(&meas, &sats, t_rx_s, origin, cfg, r, &clocks, &systems)
        .into_iter()
        .filter_map(|row| {
            Some(CodeResidual {
                sat: row.sat,
                omc_m: row.omc_m,
                los: row.view.los,
                el_rad: row.el_rad?,
                sat_rate_mps: row.view.los.dot(&row.view.v_ecef_mps) - C_MPS * row.view.clock_drift,
            })
        })
        .collect()
}

/// [`solve`] with the satellites at transmit time taken from `satellites`.
pub fn solve_with(
    meas: &[Measurement],
    t_rx_s: f64,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    cfg: &PvtConfig,
    a_priori: Option<Vec3>,
    satellites: &mut dyn Satellites,
) -> Result<Fix, PvtError> {
    let meas = per_satellite(meas, cfg.ionosphere);
    let mut epoch = Epoch {
        meas: &meas,
        t_rx_s,
        store,
        origin,
        cfg,
        satellites,
    };
    let Solution {
        mut fix,
        normalised,
    } = epoch.least_squares(a_priori, &[])?;
    if !(cfg.raim_pfa > 0.0 && fix.dof >= 2) {
        // No test, no protection (RAIM unavailable).
        fix.protection = None;
        return Ok(fix);
    }
    let chi2_all = fix.chi2;
    let alarm = chi2_all > test_threshold(fix.dof, cfg.raim_pfa);
    let r_all_ecef_m = fix.r_ecef_m;
    let mut consistent = !alarm;
    if alarm {
        // Exclude the satellite with the largest normalised residual and solve again.
        let worst = most_suspect(&normalised).and_then(|i| fix.used.get(i).map(|u| u.0));
        if let Some(worst) = worst {
            let mut again = epoch.least_squares(Some(fix.r_ecef_m), &[worst])?.fix;
            again.excluded.push(worst);
            // The exclusion counts as a repair only when the remaining satellites pass the
            // same test.
            consistent = again.dof >= 1 && again.chi2 <= test_threshold(again.dof, cfg.raim_pfa);
            fix = again;
        }
    }
    if let Some(p) = fix.protection.as_mut() {
        p.alarm = alarm;
        p.chi2_all = chi2_all;
        p.r_all_ecef_m = r_all_ecef_m;
        p.status = match (alarm, consistent) {
            (true, true) => IntegrityStatus::Excluded,
            (true, false) => IntegrityStatus::Alarm,
            (false, _) => p.status,
        };
    }
    Ok(fix)
}

/// The protection of a fix with design matrix `h` (ECEF position columns first), weights
/// `w` and `dof` degrees of freedom, before the test's verdict: HPL and VPL (Yuan 2000 eq.
/// 5-10, 5-12 by the slopes of [`super::protection`], in the local NED frame of `c_ned_ecef`)
/// and whether they are within the alarm limits. `None` when the configuration turns the
/// test off, there are no degrees of freedom, or the geometry is singular.
fn protection_of(
    h: &DMatrix<f64>,
    w: &DVector<f64>,
    dof: usize,
    c_ned_ecef: &skyforge_orbits::Mat3,
    cfg: &PvtConfig,
    chi2: f64,
    r: Vec3,
) -> Option<Protection> {
    if !(cfg.raim_pfa > 0.0 && cfg.raim_pmd > 0.0) || dof == 0 {
        return None;
    }
    let (threshold, lambda_det) = detection_parameters(dof, cfg.raim_pfa, cfg.raim_pmd)?;
    let mut h_local = h.clone();
    for i in 0..h.nrows() {
        let row = Vec3::new(h[(i, 0)], h[(i, 1)], h[(i, 2)]);
        let local = c_ned_ecef * row;
        for k in 0..3 {
            h_local[(i, k)] = local[k];
        }
    }
    let slopes = slopes(&h_local, w)?;
    let (hpl_m, vpl_m) = protection_levels(&slopes, lambda_det);
    let within = hpl_m <= cfg.raim_hal_m && cfg.raim_val_m.is_none_or(|val| vpl_m <= val);
    Some(Protection {
        hpl_m,
        vpl_m,
        threshold,
        lambda_det,
        slopes,
        alarm: false,
        chi2_all: chi2,
        r_all_ecef_m: r,
        status: if within {
            IntegrityStatus::Available
        } else {
            IntegrityStatus::Unavailable
        },
    })
}

/// Standard deviation of a pseudorange at elevation `el` (m); 1 before angles exist.
fn sigma_m(cfg: &PvtConfig, el: Option<f64>) -> f64 {
    match el {
        Some(el) => (cfg.sigma_a_m.powi(2) + (cfg.sigma_b_m / el.sin().max(0.05)).powi(2)).sqrt(),
        None => 1.0,
    }
}

/// What the atmosphere models need of the receiver at one linearisation point: its
/// geodetic position and the GPS / BeiDou seconds of week of the receive time.
struct ReceiverPlace {
    g: Geodetic,
    gps_sow: f64,
    bdt_sow: f64,
}

impl ReceiverPlace {
    fn new(r: &Vec3, origin: &TimeOrigin, t_s: f64) -> Self {
        let at = origin.epoch_at(t_s);
        Self {
            g: ecef_to_geodetic(r),
            gps_sow: gpst_week_sow(at).1,
            bdt_sow: bdt_week_sow(at).1,
        }
    }
}

/// Ionospheric delay (m) of a satellite's signal on `carrier_hz` for a receiver at
/// `place`, or 0 when the receiver is above the ground model's reach or no coefficients
/// are known. Each model gives the delay on its own frequency (GPS L1, BeiDou B1I), scaled
/// by `1/f^2` to the signal's.
fn iono_m(
    cfg: &PvtConfig,
    place: &ReceiverPlace,
    sat: SatId,
    carrier_hz: f64,
    (az, el): (f64, f64),
) -> f64 {
    let g = &place.g;
    if g.h_m > IONOSPHERE_USER_CEILING_M {
        return 0.0;
    }
    let on = |seconds: f64, f_model: f64| seconds * (f_model / carrier_hz).powi(2);
    let gps = |c| {
        let s = gps_klobuchar_l1_s(c, g.lat_rad, g.lon_rad, az, el, place.gps_sow);
        on(s, F_GPS_L1_HZ)
    };
    let bds = |c| {
        let s = bds_klobuchar_b1i_s(c, g.lat_rad, g.lon_rad, az, el, place.bdt_sow);
        on(s, F_BDS_B1I_HZ)
    };
    let seconds = match (sat.system, &cfg.iono_gps, &cfg.iono_bds) {
        // Galileo: NeQuick-G, its own model, is not applied; GPS's or BeiDou's stands in.
        (System::Gps | System::Galileo, Some(c), _) | (System::Beidou, Some(c), None) => gps(c),
        (System::Beidou, _, Some(c)) | (System::Gps | System::Galileo, None, Some(c)) => bds(c),
        (_, None, None) => 0.0,
    };
    seconds * C_MPS
}

/// How much later (s) `signal`'s clock runs than the clock with TGD removed that
/// [`Transmitted`] holds: `tgd_s` minus the signal's broadcast group delay
/// ([`Signal::broadcast_group_delay_s`]). 0 for GPS L1 C/A and L5 and for BeiDou B1I,
/// B2a and B1C (TGD_B1Cp); for Galileo E5a `tgd_s - (f_E1 / f_E5a)^2 BGD(E1,E5a)`. Signals SkyForge does not
/// transmit keep TGD (Galileo E1's BGD(E1,E5b) as I/NAV carries it).
fn group_delay_beyond_tgd_s(signal: Signal, eph: &BroadcastEphemeris) -> f64 {
    if signal.is_transmitted() {
        eph.clock.tgd_s - signal.broadcast_group_delay_s(eph)
    } else {
        0.0
    }
}

/// [`group_delay_beyond_tgd_s`] of a ranging: an ionosphere-free combination's group delays
/// combine as its pseudoranges (IS-GPS-705's ISC terms in the L1/L5 correction).
pub(crate) fn ranging_delay_beyond_tgd_s(ranging: &Ranging, eph: &BroadcastEphemeris) -> f64 {
    ranging.combined(|s| group_delay_beyond_tgd_s(s, eph))
}

/// The inputs of [`solve`] that every least-squares pass of one epoch shares.
struct Epoch<'a> {
    meas: &'a [Ranging],
    t_rx_s: f64,
    store: &'a EphemerisStore,
    origin: &'a TimeOrigin,
    cfg: &'a PvtConfig,
    satellites: &'a mut dyn Satellites,
}

impl Epoch<'_> {
    /// One least-squares solution without the satellites of `skip`.
    fn least_squares(
        &mut self,
        a_priori: Option<Vec3>,
        skip: &[SatId],
    ) -> Result<Solution, PvtError> {
        let (meas, t_rx_s, store, origin, cfg) =
            (self.meas, self.t_rx_s, self.store, self.origin, self.cfg);
        let meas: Vec<&Ranging> = meas.iter().filter(|m| !skip.contains(&m.sat)).collect();
        let ephs = meas
            .iter()
            .map(|m| {
                store
                    .select(m.sat, t_rx_s)
                    .ok_or(PvtError::NoEphemeris(m.sat))
            })
            .collect::<Result<Vec<_>, _>>()?;
        // Receiver clock columns: one per system present.
        let systems: Vec<System> = [System::Gps, System::Beidou, System::Galileo]
            .into_iter()
            .filter(|s| meas.iter().any(|m| m.sat.system == *s))
            .collect();
        let n_x = 3 + systems.len();
        // The satellites at transmit time do not move with the receiver estimate; each
        // clock is the one its signal's users apply.
        let sats: Vec<Transmitted> = meas
            .iter()
            .zip(&ephs)
            .map(|(m, eph)| {
                let tx = self.satellites.transmitted(eph, t_rx_s, m.pseudorange_m);
                tx.clock_shifted(ranging_delay_beyond_tgd_s(m, &eph.eph))
            })
            .collect();
        let mut r = a_priori.unwrap_or_else(Vec3::zeros);
        let mut clocks = vec![0.0; systems.len()];
        let mut last_step = f64::INFINITY;
        for _ in 0..MAX_ITERATIONS {
            let rows = linearise(&meas, &sats, t_rx_s, origin, cfg, &r, &clocks, &systems);
            if rows.len() < n_x {
                return Err(PvtError::TooFewSatellites {
                    have: rows.len(),
                    need: n_x,
                    clocks: systems.len(),
                });
            }
            let (h, v, w) = matrices(&rows, n_x);
            let hw = h.transpose() * DMatrix::from_diagonal(&w);
            let n = &hw * &h;
            let dx = n.clone().try_inverse().ok_or(PvtError::Singular)? * (&hw * &v);
            r += Vec3::new(dx[0], dx[1], dx[2]);
            for (c, d) in clocks.iter_mut().zip(dx.iter().skip(3)) {
                *c += d;
            }
            last_step = dx.rows(0, 3).norm();
            if last_step < CONVERGED_M {
                let rows = linearise(&meas, &sats, t_rx_s, origin, cfg, &r, &clocks, &systems);
                return finish(&rows, n_x, r, &clocks, &systems, t_rx_s, cfg);
            }
        }
        Err(PvtError::NoConvergence { step_m: last_step })
    }
}

/// A fix and the normalised residual |v_i| / (sigma_i sqrt(S_ii)) of each satellite it
/// used, in [`Fix::used`] order (empty when the weighted normal matrix is singular): what
/// the exclusion ranks.
struct Solution {
    fix: Fix,
    normalised: Vec<f64>,
}

/// One usable measurement, linearised at the current estimate.
struct Row {
    sat: SatId,
    view: SatView,
    /// Observed minus computed (m).
    omc_m: f64,
    /// Column of the satellite's system clock.
    clock_col: usize,
    weight: f64,
    el_rad: Option<f64>,
}

#[allow(clippy::too_many_arguments)]
fn linearise(
    meas: &[&Ranging],
    sats: &[Transmitted],
    t_rx_s: f64,
    origin: &TimeOrigin,
    cfg: &PvtConfig,
    r: &Vec3,
    clocks: &[f64],
    systems: &[System],
) -> Vec<Row> {
    let mut rows = Vec::with_capacity(meas.len());
    let place = ReceiverPlace::new(r, origin, t_rx_s);
    let frame = local_frame_at(r, || place.g);
    for (m, sat) in meas.iter().zip(sats) {
        let view = sat.seen_from(r, frame.as_ref());
        let el = view.az_el_rad.map(|(_, el)| el);
        if el.is_some_and(|el| el < cfg.elevation_mask_rad) {
            continue;
        }
        let clock_col = systems.iter().position(|s| *s == m.sat.system).unwrap_or(0);
        let mut predicted = view.range_m + clocks[clock_col] - C_MPS * view.clock_s;
        if let Some((az, el)) = view.az_el_rad {
            if m.second.is_none() {
                predicted += iono_m(cfg, &place, m.sat, m.signal.carrier_hz(), (az, el));
            }
            if cfg.troposphere {
                let g = &place.g;
                predicted += standard_slant_delay_m(g.lat_rad, g.h_m, el, STANDARD_RH0);
            }
        }
        rows.push(Row {
            sat: m.sat,
            view,
            omc_m: m.pseudorange_m - predicted,
            clock_col: 3 + clock_col,
            weight: (sigma_m(cfg, el) * m.noise_factor()).powi(-2),
            el_rad: el,
        });
    }
    rows
}

/// Design matrix, observed-minus-computed vector and weights.
fn matrices(rows: &[Row], n_x: usize) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
    let mut h = DMatrix::zeros(rows.len(), n_x);
    for (i, row) in rows.iter().enumerate() {
        for k in 0..3 {
            h[(i, k)] = -row.view.los[k];
        }
        h[(i, row.clock_col)] = 1.0;
    }
    let v = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.omc_m));
    let w = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.weight));
    (h, v, w)
}

/// The fix at the converged estimate: residuals, chi-square, DOP, protection and the
/// normalised residuals.
fn finish(
    rows: &[Row],
    n_x: usize,
    r: Vec3,
    clocks: &[f64],
    systems: &[System],
    t_rx_s: f64,
    cfg: &PvtConfig,
) -> Result<Solution, PvtError> {
    let (h, v, w) = matrices(rows, n_x);
    let q = (h.transpose() * &h)
        .try_inverse()
        .ok_or(PvtError::Singular)?;
    let g = ecef_to_geodetic(&r);
    let c = c_ecef_ned(g.lat_rad, g.lon_rad);
    let q_pos = q.fixed_view::<3, 3>(0, 0).into_owned();
    let q_ned = c * q_pos * c.transpose();
    let pos = q_pos.trace();
    let tdop = q[(3, 3)].sqrt();
    let dop = Dop {
        gdop: (pos + q[(3, 3)]).sqrt(),
        pdop: pos.sqrt(),
        hdop: (q_ned[(0, 0)] + q_ned[(1, 1)]).sqrt(),
        vdop: q_ned[(2, 2)].sqrt(),
        tdop,
    };
    let chi2 = v.iter().zip(w.iter()).map(|(r, w)| r * r * w).sum();
    let dof = rows.len() - n_x;
    let gps_and_bds = systems == [System::Gps, System::Beidou];
    let normalised = normalised_residuals(&h, &w, &v).unwrap_or_default();
    let fix = Fix {
        t_s: t_rx_s - clocks[0] / C_MPS,
        r_ecef_m: r,
        clock_bias_m: clocks[0],
        inter_system_bias_m: gps_and_bds.then(|| clocks[1] - clocks[0]),
        dop,
        used: rows
            .iter()
            .map(|row| (row.sat, row.omc_m, row.el_rad.unwrap_or(f64::NAN)))
            .collect(),
        excluded: Vec::new(),
        chi2,
        dof,
        protection: protection_of(&h, &w, dof, &c, cfg, chi2, r),
    };
    Ok(Solution { fix, normalised })
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::{Epoch, TimeScale};
    use skyforge_orbits::ephemeris::nominal;

    /// The satellite clock follows each signal's group delay: none beyond TGD for GPS L1
    /// C/A and L5 (ISC 0) and BeiDou B1I; Galileo E5a's (f_E1/f_E5a)^2 BGD(E1,E5a) instead
    /// of the BGD itself; signals SkyForge does not transmit keep TGD.
    #[test]
    fn the_clock_is_each_signals_own() {
        let t = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let mut gal = nominal::galileo(t)[0].clone();
        gal.clock.tgd_s = 2e-9;
        let scale = (1575.42f64 / 1176.45).powi(2);
        let d = group_delay_beyond_tgd_s(Signal::GalE5a, &gal);
        assert!((d - (2e-9 - scale * 2e-9)).abs() < 1e-20, "{d}");
        assert_eq!(group_delay_beyond_tgd_s(Signal::GalE1, &gal), 0.0);
        let mut gps = nominal::gps(t)[0].clone();
        gps.clock.tgd_s = -5e-9;
        for s in [Signal::GpsL1Ca, Signal::GpsL5, Signal::GpsL2] {
            assert_eq!(group_delay_beyond_tgd_s(s, &gps), 0.0, "{s}");
        }
        let mut bds = nominal::beidou(skyforge_orbits::ephemeris::BeidouSet::Bds3, t)[0].clone();
        bds.clock.tgd_s = 3e-9;
        for s in [Signal::BdsB1I, Signal::BdsB2a, Signal::BdsB1C] {
            assert_eq!(group_delay_beyond_tgd_s(s, &bds), 0.0, "{s}");
        }
    }
}
