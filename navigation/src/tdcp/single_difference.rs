//! The single differences in time of one receiver's two epochs, per satellite, linearised
//! about the a-priori position at the second epoch (module docs, "Observation model").

use super::config::TdcpConfig;
use super::error::TdcpError;
use super::records::{Exclusion, pick, satellites};
use crate::pvt::{Transmitted, local_frame};
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BoundEphemeris, EphemerisStore, SatId};
use skyforge_orbits::frames::az_el;
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::{Mat3, Vec3};

/// Smallest `sin(elevation)` the elevation weighting divides by (about 3 deg): a mask at
/// or below the horizon must not give an infinite or negative sigma.
const MIN_WEIGHTING_SIN: f64 = 0.05;

/// One satellite's single difference in time, linearised about `r2_hat`.
#[derive(Debug, Clone, Copy)]
pub struct SatDifference {
    /// The satellite.
    pub sat: SatId,
    /// The signal differenced.
    pub signal: Signal,
    /// Elevation at `t2` seen from the first `r2_hat` (rad).
    pub elevation_rad: f64,
    /// Unit line of sight receiver -> satellite at `t2`, from `r2_hat` (ECEF).
    pub los: Vec3,
    /// `lambda (phi(t2) - phi(t1))` (m).
    pub delta_phase_m: f64,
    /// Prefit residual `z = dPhi - [rho(t2, r2_hat) - rho(t1, r1)] + c (dt_s(t2) -
    /// dt_s(t1))` (m): `-los . delta_r2 + c ddt_r + noise`.
    pub z_m: f64,
    /// Standard deviation of the single difference (m): `sqrt(2)` times the phase's.
    pub sigma_m: f64,
    /// The satellite at its transmit time for `t2` (the range at another `r2_hat`).
    transmitted: Transmitted,
    /// `z + rho(t2, r2_hat)`: what does not depend on `r2_hat` (m).
    known_m: f64,
}

/// One pair of epochs' single differences.
#[derive(Debug, Clone)]
pub struct TdcpEpoch {
    /// The first epoch's time tag (receiver clock).
    pub t1: Epoch,
    /// The second epoch's time tag.
    pub t2: Epoch,
    /// The antenna at `t1`, taken as known (ECEF, m).
    pub r1_m: Vec3,
    /// The antenna at `t2` the differences are linearised about (ECEF, m).
    pub r2_hat_m: Vec3,
    /// The satellites differenced, in satellite order.
    pub sats: Vec<SatDifference>,
    /// The satellites of the second epoch left out, with the reason.
    pub excluded: Vec<(SatId, Exclusion)>,
}

impl TdcpEpoch {
    /// How many satellites were left out for `reason`.
    pub fn excluded_count(&self, reason: Exclusion) -> usize {
        self.excluded.iter().filter(|(_, r)| *r == reason).count()
    }

    /// The same differences linearised about another `r2_hat_m`: new lines of sight and
    /// prefit residuals; elevations and sigmas stay those of the first linearisation
    /// (a few metres move an elevation by microradians).
    pub fn relinearised(&self, r2_hat_m: Vec3) -> TdcpEpoch {
        let sats = (self.sats.iter())
            .map(|s| {
                let view = s.transmitted.seen_from(&r2_hat_m, None);
                SatDifference {
                    los: view.los,
                    z_m: s.known_m - view.range_m,
                    ..*s
                }
            })
            .collect();
        TdcpEpoch {
            r2_hat_m,
            sats,
            excluded: self.excluded.clone(),
            ..*self
        }
    }
}

/// The place and time of one epoch: its records, time (s since the origin), antenna.
struct At<'a> {
    records: &'a [ObsRecord],
    t_s: f64,
    r_m: Vec3,
}

/// The single differences of `prev` -> `cur` for the antenna at `r1` (known) and about
/// `r2_hat` (a priori), with the satellites of `store` (times since `origin`).
///
/// Errors: a setting out of range, a gap `<= 0` or `> max_gap_s`, a position that is not
/// finite or not near the Earth's surface.
pub fn time_differences(
    prev: &ObsEpoch,
    cur: &ObsEpoch,
    r1: Vec3,
    r2_hat: Vec3,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    config: &TdcpConfig,
) -> Result<TdcpEpoch, TdcpError> {
    config.check()?;
    check_gap(prev.time, cur.time, config.max_gap_s)?;
    let frame = checked_frame(&r1, &r2_hat)?;
    let first = At {
        records: &prev.sats,
        t_s: origin.seconds_since_start(prev.time),
        r_m: r1,
    };
    let second = At {
        records: &cur.sats,
        t_s: origin.seconds_since_start(cur.time),
        r_m: r2_hat,
    };
    let mut epoch = TdcpEpoch {
        t1: prev.time,
        t2: cur.time,
        r1_m: r1,
        r2_hat_m: r2_hat,
        sats: Vec::new(),
        excluded: Vec::new(),
    };
    for sat in satellites(&cur.sats, config.signal) {
        let found = pick((first.records, second.records), sat, config.signal).and_then(|pair| {
            let eph = store
                .select(sat, second.t_s)
                .ok_or(Exclusion::NoEphemeris)?;
            difference(pair, eph, (&first, &second), &frame, config)
        });
        match found {
            Ok(d) => epoch.sats.push(d),
            Err(reason) => epoch.excluded.push((sat, reason)),
        }
    }
    Ok(epoch)
}

/// `Ok` when `t2` is after `t1` by at most `max_gap_s`.
fn check_gap(t1: Epoch, t2: Epoch, max_gap_s: f64) -> Result<(), TdcpError> {
    let gap_s = (t2 - t1).to_seconds();
    if gap_s > 0.0 && gap_s <= max_gap_s {
        Ok(())
    } else {
        Err(TdcpError::Gap {
            t1,
            t2,
            gap_s,
            max_gap_s,
        })
    }
}

/// The local frame at `r2_hat` (for the elevations), both positions checked.
fn checked_frame(r1: &Vec3, r2_hat: &Vec3) -> Result<Mat3, TdcpError> {
    for (what, r) in [("r1", r1), ("r2_hat", r2_hat)] {
        if !r.iter().all(|x| x.is_finite()) {
            return Err(TdcpError::NonFinite { what });
        }
    }
    local_frame(r2_hat).ok_or(TdcpError::NotAPosition { what: "r2_hat" })
}

/// One satellite's difference from its records at both epochs (code and phase checked
/// by `pick`), both epochs with the ephemeris `eph` (the one selected at `t2`).
fn difference(
    (a, b): (&ObsRecord, &ObsRecord),
    eph: &BoundEphemeris,
    (first, second): (&At, &At),
    frame: &Mat3,
    config: &TdcpConfig,
) -> Result<SatDifference, Exclusion> {
    let code = |r: &ObsRecord| r.pseudorange_m.ok_or(Exclusion::MissingPseudorange);
    let phase = |r: &ObsRecord| r.carrier_phase_cycles.ok_or(Exclusion::MissingPhase);
    let view1 = Transmitted::of(eph, first.t_s, code(a)?).seen_from(&first.r_m, None);
    let transmitted = Transmitted::of(eph, second.t_s, code(b)?);
    let view2 = transmitted.seen_from(&second.r_m, None);
    let (_, elevation_rad) = az_el(&(frame * view2.los));
    if elevation_rad < config.elevation_mask_deg.to_radians() {
        return Err(Exclusion::BelowMask);
    }
    let delta_phase_m = b.signal.wavelength_m() * (phase(b)? - phase(a)?);
    let known_m = delta_phase_m + view1.range_m + C_MPS * (view2.clock_s - view1.clock_s);
    let scale = if config.elevation_weighting {
        elevation_rad.sin().max(MIN_WEIGHTING_SIN)
    } else {
        1.0
    };
    Ok(SatDifference {
        sat: b.sat,
        signal: b.signal,
        elevation_rad,
        los: view2.los,
        delta_phase_m,
        z_m: known_m - view2.range_m,
        sigma_m: std::f64::consts::SQRT_2 * config.sigma_phase_m / scale,
        transmitted,
        known_m,
    })
}
