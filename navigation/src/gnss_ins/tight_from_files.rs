//! The tightly coupled filter on files (book 3.2.2's integration as a post-processing
//! receiver runs it): the INS aligned on a static start at the mean of the single-point
//! fixes meanwhile or on the track ([`Alignment`]), the receiver clock started from the first epoch after it
//! ([`clock_from_epoch`]), then every epoch's pseudoranges and range rates, except inside
//! the configured outages.

use super::config::{InsRunError, LooselyCoupledConfig};
use super::from_files::{
    InsRun, InsSolution, Outages, gnss_fix, gravity_for, navigation, sigma_ned,
};
use super::receiver_states::ReceiverNoise;
use super::start::{Alignment, align, alignment_span};
use super::tightly_coupled::{TightlyCoupled, clock_from_epoch};
use hifitime::Duration;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_gnss::observation::ObsFile;
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::gravity::GravityModel;

/// Settings of [`tightly_coupled_from_files`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TightFilesConfig {
    /// The INS's error model, lever arm and initial errors.
    pub filter: LooselyCoupledConfig,
    /// The receiver's clock and measurement errors (no barometer: files carry none).
    pub receiver: ReceiverNoise,
    /// How the INS aligns.
    pub alignment: Alignment,
    /// The gravity the INS subtracts; `None`: [`gravity_for`] the aligned state.
    pub gravity: Option<GravityModel>,
    /// Satellites below this elevation are not used (deg).
    pub elevation_mask_deg: f64,
    /// GNSS outages made on purpose, if any.
    pub outages: Option<Outages>,
}

/// The tightly coupled solution from the IMU's `increments` (in time order) and one
/// antenna's observations `obs` with the navigation data: one solution per epoch after
/// the alignment (`gnss`: ranges updated it; `no_fix`: epochs with no usable satellite).
pub fn tightly_coupled_from_files(
    increments: &[ImuIncrement],
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    config: &TightFilesConfig,
) -> Result<InsRun, InsRunError> {
    config.filter.check()?;
    config.receiver.check()?;
    let (origin, store, pvt) = navigation(obs, ephemerides, iono, config.elevation_mask_deg)?;
    // The fixes to align on: at rest those of the static start (and a second beyond: a
    // fix's time is its tag less the receiver clock), in motion every epoch's.
    let until = match &config.alignment {
        Alignment::Static(a) => Some(alignment_span(increments, a.span_s)?.1),
        Alignment::Track(_) => None,
    };
    let sigmas = (
        config.receiver.code_sigma_m,
        config.receiver.range_rate_sigma_mps,
    );
    let fixes: Vec<_> = (obs.epochs.iter())
        .take_while(|e| until.is_none_or(|end| e.time <= end + Duration::from_seconds(1.0)))
        .filter_map(|e| gnss_fix(e, &store, &origin, &pvt, sigmas))
        .collect();
    let lever = config.filter.lever_arm_body_m;
    let start = align(increments, &config.alignment, &lever, None, &fixes)?;
    let (initial, aligned_records) = (start.state, start.records);
    let mut epochs = obs
        .epochs
        .iter()
        .skip_while(|e| e.time <= initial.t)
        .peekable();
    let antenna = initial.r_ecef_m + initial.c_body_ecef * lever;
    let clock = (epochs.clone())
        .find_map(|e| clock_from_epoch(e, (&antenna, &initial.v_ecef_mps), &store, &origin, &pvt))
        .ok_or_else(|| InsRunError::Input("no epoch after the alignment has a satellite".into()))?;
    let gravity = config.gravity.unwrap_or_else(|| gravity_for(&initial));
    let mut filter =
        TightlyCoupled::new(initial, config.filter, config.receiver, clock)?.in_gravity(gravity);
    let mut run = InsRun {
        aligned: initial,
        fine: start.fine,
        gravity,
        solutions: Vec::new(),
        no_fix: 0,
    };
    for inc in &increments[aligned_records..] {
        filter.propagate(inc)?;
        let half = Duration::from_seconds(inc.dt_s / 2.0);
        while let Some(epoch) = epochs.next_if(|e| e.time <= filter.state().t + half) {
            let since_s = (epoch.time - initial.t).to_seconds();
            let in_outage = (config.outages).is_some_and(|o| o.covers(since_s));
            let updated = if in_outage {
                false
            } else {
                let update = filter.update_ranges(epoch, &store, &origin, &pvt)?;
                run.no_fix += usize::from(update.is_none());
                update.is_some()
            };
            run.solutions.push(InsSolution {
                state: *filter.state(),
                sigma_ned_m: sigma_ned(&filter),
                gnss: updated,
                in_outage,
            });
        }
    }
    Ok(run)
}
