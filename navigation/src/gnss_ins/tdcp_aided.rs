//! Paper 001's integration run: the INS corrected at every observation epoch by the
//! time-differenced carrier phase between that epoch and the one before (double
//! differences), by the code differenced between satellites and by a known height. Its
//! filter is this crate's 15-state one (the paper's 12 states plus position; the paper
//! corrects position through its "three pseudoranges plus altitude" fix, done here as the
//! code and height updates).

use super::LooselyCoupledConfig;
use super::config::InsRunError;
use super::config::IntegrationError;
use super::filter::LooselyCoupled;
use super::from_files::{InsRun, InsSolution, navigation, sigma_ned};
use super::start::{Alignment, StaticAlignment, align};
use crate::ins::InsState;
use crate::pvt::PvtConfig;
use crate::tdcp::TdcpConfig;
use hifitime::Duration;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_gnss::observation::{ObsEpoch, ObsFile};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::gravity::GravityModel;
use skyforge_orbits::time::TimeOrigin;

/// Settings of [`tdcp_aided`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TdcpAidedConfig {
    /// The filter.
    pub filter: LooselyCoupledConfig,
    /// The time differences (signal, mask, phase sigma, largest gap).
    pub tdcp: TdcpConfig,
    /// A pseudorange's error (m) for the code differences; `None`: no code updates.
    pub code_sigma_m: Option<f64>,
    /// The antenna's known height above the ellipsoid and its sigma (m), if any.
    pub height_m: Option<(f64, f64)>,
}

/// Runs the INS from `initial` over `increments` (beginning at its time), updated at every
/// epoch of `epochs` (receiver tags in GPS time) that falls inside them: one solution per
/// epoch, after its updates (`gnss`: a time difference or the code updated it).
pub fn tdcp_aided(
    initial: InsState,
    increments: &[ImuIncrement],
    epochs: &[ObsEpoch],
    (store, origin, pvt): (&EphemerisStore, &TimeOrigin, &PvtConfig),
    config: &TdcpAidedConfig,
) -> Result<Vec<InsSolution>, IntegrationError> {
    let mut filter = LooselyCoupled::new(initial, config.filter)?;
    let mut pending = epochs.iter().skip_while(|e| e.time <= initial.t).peekable();
    let mut previous: Option<(&ObsEpoch, crate::tdcp::ImuPose)> = None;
    let mut solutions = Vec::new();
    for inc in increments {
        filter.propagate(inc)?;
        let half = Duration::from_seconds(inc.dt_s / 2.0);
        while let Some(epoch) = pending.next_if(|e| e.time <= filter.state().t + half) {
            let mut gnss = false;
            if let Some((prev, pose)) = &previous {
                // A gap or too few satellites in lock: no time difference this epoch.
                match filter.update_tdcp((prev, epoch), pose, store, origin, &config.tdcp) {
                    Ok(update) => gnss |= update.is_some(),
                    Err(IntegrationError::Tdcp(_)) => {}
                    Err(e) => return Err(e),
                }
            }
            if let Some(sigma) = config.code_sigma_m {
                gnss |= filter
                    .update_code(epoch, store, origin, pvt, sigma)?
                    .is_some();
            }
            if let Some((h, sigma)) = config.height_m {
                filter.update_height(h, sigma)?;
            }
            solutions.push(InsSolution {
                state: *filter.state(),
                sigma_ned_m: sigma_ned(&filter),
                gnss,
                in_outage: false,
            });
            previous = Some((epoch, filter.pose()));
        }
    }
    Ok(solutions)
}

/// Settings of [`tdcp_aided_from_files`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TdcpFilesConfig {
    /// The run's updates.
    pub aided: TdcpAidedConfig,
    /// The static start the INS aligns on.
    pub alignment: StaticAlignment,
    /// Where the antenna stood during it (ECEF, m): surveyed, as paper 001's site was
    /// (three satellites cannot fix it).
    pub start_antenna_m: Vec3,
}

/// Paper 001's integration on files: the IMU's `increments` aligned on the static start
/// at the surveyed point, then [`tdcp_aided`] over `obs`'s epochs with the navigation
/// data.
pub fn tdcp_aided_from_files(
    increments: &[ImuIncrement],
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    config: &TdcpFilesConfig,
) -> Result<InsRun, InsRunError> {
    config.aided.filter.check()?;
    let mask_deg = config.aided.tdcp.elevation_mask_deg;
    let (origin, store, pvt) = navigation(obs, ephemerides, iono, mask_deg)?;
    let lever = config.aided.filter.lever_arm_body_m;
    let antenna = Some(config.start_antenna_m);
    let start = align(
        increments,
        &Alignment::Static(config.alignment),
        &lever,
        antenna,
        &[],
    )?;
    let (initial, n) = (start.state, start.records);
    let solutions = tdcp_aided(
        initial,
        &increments[n..],
        &obs.epochs,
        (&store, &origin, &pvt),
        &config.aided,
    )?;
    Ok(InsRun {
        aligned: initial,
        fine: start.fine,
        gravity: GravityModel::Normal,
        solutions,
        no_fix: 0,
    })
}
