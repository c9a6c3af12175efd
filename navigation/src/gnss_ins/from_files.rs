//! GNSS/INS from files, as a post-processing receiver would run it: the IMU's increments
//! and one antenna's observations with the broadcast navigation data. The INS aligns on
//! a static start (coarse alignment, and optionally fine, its position the mean of the
//! fixes meanwhile) or in motion on the fixes' track (`start::Alignment`), then the loosely coupled filter takes a single-point fix and Doppler
//! velocity at every observation epoch, except inside the configured GNSS outages (fixes
//! dropped on purpose, to measure how the INS bridges them).
//!
//! A fix's covariance comes from its geometry: the per-satellite range sigma `uere_m`
//! (and `range_rate_sigma_mps` for the velocity) times the horizontal and vertical DOP,
//! NED-diagonal, rotated to ECEF. Errors common to successive fixes (satellite orbits
//! and clocks, the ionosphere the broadcast model leaves) are not white: the filter
//! treats them as if they were.

use super::config::{InsRunError, LooselyCoupledConfig};
use super::filter::{InsFilter, LooselyCoupled};
use super::fix::GnssFix;
use super::start::{Alignment, align};
use crate::ins::{FineAlignment, InsState};
use crate::pvt::{Fix, Measurement, PvtConfig, solve, solve_velocity};
use hifitime::Duration;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_gnss::observation::{ObsEpoch, ObsFile};
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::frames::{c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::gravity::GravityModel;
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::{Mat3, Vec3};

/// GNSS outages made on purpose: from `first_s` after the alignment, `length_s` without
/// fixes every `every_s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outages {
    /// Start of the first outage after the end of the alignment (s).
    pub first_s: f64,
    /// Period (s).
    pub every_s: f64,
    /// Length of each (s), less than the period.
    pub length_s: f64,
}

impl Outages {
    /// Whether `t_s` after the alignment lies inside an outage.
    pub(crate) fn covers(&self, t_s: f64) -> bool {
        let into = t_s - self.first_s;
        into >= 0.0 && into % self.every_s < self.length_s
    }
}

/// Settings of [`loosely_coupled_from_files`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FromFilesConfig {
    /// The filter.
    pub filter: LooselyCoupledConfig,
    /// How the INS aligns.
    pub alignment: Alignment,
    /// The gravity the INS subtracts; `None`: [`gravity_for`] the aligned state.
    pub gravity: Option<GravityModel>,
    /// A range's 1-sigma error (m), for the fixes' position covariance.
    pub uere_m: f64,
    /// A range rate's 1-sigma error (m/s), for their velocity covariance.
    pub range_rate_sigma_mps: f64,
    /// Satellites below this elevation are not used (deg).
    pub elevation_mask_deg: f64,
    /// GNSS outages made on purpose, if any.
    pub outages: Option<Outages>,
}

/// The navigation solution at one observation epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InsSolution {
    /// The IMU's state (its time the epoch's, within one IMU interval).
    pub state: InsState,
    /// 1-sigma position error (north, east, down; m) from the filter's covariance.
    pub sigma_ned_m: Vec3,
    /// Whether a GNSS fix updated the filter at this epoch.
    pub gnss: bool,
    /// Whether the epoch lies inside an outage made on purpose.
    pub in_outage: bool,
}

/// What a run made.
#[derive(Debug, Clone, PartialEq)]
pub struct InsRun {
    /// The state the alignment found, at its end.
    pub aligned: InsState,
    /// The fine alignment's diagnostics, where one ran.
    pub fine: Option<FineAlignment>,
    /// The gravity the INS subtracted.
    pub gravity: GravityModel,
    /// One solution per observation epoch after the alignment.
    pub solutions: Vec<InsSolution>,
    /// Epochs with no fix (too few satellites, no convergence).
    pub no_fix: usize,
}

/// A range's and a range rate's 1-sigma errors (m, m/s), which make a fix's covariance
/// with its DOPs.
pub(crate) type FixSigmas = (f64, f64);

/// The single-point fix of `epoch` (its time the receiver clock removed) with its Doppler
/// velocity, if one can be made; covariances from `sigmas` and the DOPs.
pub(crate) fn gnss_fix(
    epoch: &ObsEpoch,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    pvt: &PvtConfig,
    (uere_m, range_rate_sigma_mps): FixSigmas,
) -> Option<GnssFix> {
    let meas = Measurement::of_records(&epoch.sats);
    let tag_s = origin.seconds_since_start(epoch.time);
    let fix = solve(&meas, tag_s, store, origin, pvt, None).ok()?;
    let velocity = solve_velocity(&meas, tag_s, store, &fix).ok();
    let covariance = |sigma: f64| dop_covariance(&fix, sigma);
    Some(GnssFix {
        t: origin.epoch_at(fix.t_s),
        r_ecef_m: fix.r_ecef_m,
        r_cov_m2: covariance(uere_m),
        v_ecef_mps: velocity.map(|v| (v.v_ecef_mps, covariance(range_rate_sigma_mps))),
    })
}

/// `sigma^2` times the squared DOPs: half the HDOP's square on each horizontal axis, the
/// VDOP's square vertically, rotated from NED to ECEF.
fn dop_covariance(fix: &Fix, sigma: f64) -> Mat3 {
    let g = ecef_to_geodetic(&fix.r_ecef_m);
    let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
    let h = 0.5 * (sigma * fix.dop.hdop).powi(2);
    let ned = Mat3::from_diagonal(&Vec3::new(h, h, (sigma * fix.dop.vdop).powi(2)));
    c_ned_ecef * ned * c_ned_ecef.transpose()
}

/// Above this height (m) a run's INS subtracts the orbit's gravity by default.
/// # assumed: 50 km, above any aircraft and below any orbit.
pub const ORBIT_HEIGHT_M: f64 = 50_000.0;

/// The gravity an INS at `state` subtracts unless told otherwise: normal gravity near the
/// Earth, the zonal field J2..J6 (the LEO propagator's, `orbits::gravity`) above
/// [`ORBIT_HEIGHT_M`].
pub fn gravity_for(state: &InsState) -> GravityModel {
    if state.geodetic().h_m > ORBIT_HEIGHT_M {
        GravityModel::Zonal { degree: 6 }
    } else {
        GravityModel::Normal
    }
}

/// The 1-sigma position errors north, east, down of `filter`.
pub(crate) fn sigma_ned<const N: usize>(filter: &InsFilter<N>) -> Vec3 {
    let s = filter.state();
    let g = ecef_to_geodetic(&s.r_ecef_m);
    let c = c_ecef_ned(g.lat_rad, g.lon_rad);
    let p = filter.covariance().fixed_view::<3, 3>(0, 0).into_owned();
    (c * p * c.transpose()).diagonal().map(f64::sqrt)
}

/// What a run on `obs` navigates with: the time origin at its first epoch, the
/// ephemerides bound to it, and the single-point settings (mask, broadcast ionosphere).
pub(crate) fn navigation(
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    elevation_mask_deg: f64,
) -> Result<(TimeOrigin, EphemerisStore, PvtConfig), InsRunError> {
    let first = obs
        .epochs
        .first()
        .ok_or_else(|| InsRunError::Input(format!("{}: no epoch", obs.source.display())))?;
    let origin = TimeOrigin::new(first.time);
    let store = EphemerisStore::new(ephemerides, &origin);
    let pvt = PvtConfig {
        elevation_mask_rad: elevation_mask_deg.to_radians(),
        iono_gps: iono.gps,
        iono_bds: iono.bds,
        ..PvtConfig::default()
    };
    Ok((origin, store, pvt))
}

/// The loosely coupled solution from the IMU's `increments` (in time order) and one
/// antenna's observations `obs` with the navigation data.
pub fn loosely_coupled_from_files(
    increments: &[ImuIncrement],
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    config: &FromFilesConfig,
) -> Result<InsRun, InsRunError> {
    config.filter.check()?;
    let (origin, store, pvt) = navigation(obs, ephemerides, iono, config.elevation_mask_deg)?;
    let sigmas = (config.uere_m, config.range_rate_sigma_mps);
    let fixes: Vec<Option<GnssFix>> = (obs.epochs.iter())
        .map(|e| gnss_fix(e, &store, &origin, &pvt, sigmas))
        .collect();
    let made: Vec<GnssFix> = fixes.iter().flatten().copied().collect();
    let lever = config.filter.lever_arm_body_m;
    let start = align(increments, &config.alignment, &lever, None, &made)?;
    let (initial, aligned_records) = (start.state, start.records);
    let gravity = config.gravity.unwrap_or_else(|| gravity_for(&initial));
    let mut filter = LooselyCoupled::new(initial, config.filter)?.in_gravity(gravity);
    let mut run = InsRun {
        aligned: initial,
        fine: start.fine,
        gravity,
        solutions: Vec::new(),
        no_fix: fixes.iter().filter(|f| f.is_none()).count(),
    };
    // Each epoch at its fix's time (the receiver clock removed), or its tag without one.
    let mut epochs = (obs.epochs.iter().zip(&fixes))
        .map(|(e, f)| (f.map_or(e.time, |f| f.t), *f))
        .skip_while(|(t, _)| *t <= initial.t)
        .peekable();
    for inc in &increments[aligned_records..] {
        filter.propagate(inc)?;
        let half = Duration::from_seconds(inc.dt_s / 2.0);
        while let Some((t, fix)) = epochs.next_if(|(t, _)| *t <= filter.state().t + half) {
            let in_outage =
                (config.outages).is_some_and(|o| o.covers((t - initial.t).to_seconds()));
            let usable = fix.filter(|_| !in_outage);
            if let Some(f) = usable {
                filter.update(&f)?;
            }
            run.solutions.push(InsSolution {
                state: *filter.state(),
                sigma_ned_m: sigma_ned(&filter),
                gnss: usable.is_some(),
                in_outage,
            });
        }
    }
    Ok(run)
}
