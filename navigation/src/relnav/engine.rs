//! Every mode as one engine epoch by epoch, behind one trait chosen by the configuration:
//! a pair of epochs (each vehicle's records of the run's signals) in, the chaser relative
//! to the target out. `skyforge relnav` loops it over two files, `receive --relnav` calls
//! it as the chaser's receiver forms each epoch.

use super::estimate::RelativeEstimate;
use crate::pvt::{Fix, records_velocity};
use crate::relative::files::FixStream;
use skyforge_gnss::observation::ObsEpoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::time::TimeOrigin;

/// What every engine reads beside the epochs: the broadcast ephemerides and the run's
/// time origin (the target's first epoch).
pub(crate) struct Context<'a> {
    pub store: &'a EphemerisStore,
    pub origin: &'a TimeOrigin,
}

impl Context<'_> {
    /// Both vehicles' next fixes (target, chaser) from their `streams`.
    pub(crate) fn fixes(
        &self,
        streams: &mut [FixStream; 2],
        (target, chaser): (&ObsEpoch, &ObsEpoch),
        signals: &[Signal],
    ) -> [Result<Fix, String>; 2] {
        [
            streams[0].fix(target, self.store, self.origin, signals),
            streams[1].fix(chaser, self.store, self.origin, signals),
        ]
    }

    /// The Doppler velocity (ECEF) at `fix` from `epoch`'s records.
    pub(crate) fn velocity(&self, epoch: &ObsEpoch, fix: &Fix, signals: &[Signal]) -> Option<Vec3> {
        let t_rx = self.origin.seconds_since_start(epoch.time);
        records_velocity(&epoch.sats, signals, t_rx, self.store, fix)
    }
}

/// One mode epoch by epoch.
pub(crate) trait Engine: std::fmt::Debug {
    /// The pair of epochs (target, chaser): the estimate, or `None` where either vehicle
    /// has no fix and velocity.
    fn epoch(&mut self, pair: (&ObsEpoch, &ObsEpoch), at: &Context) -> Option<RelativeEstimate>;

    /// Epochs without both fixes and velocities so far.
    fn missed(&self) -> usize;
}
