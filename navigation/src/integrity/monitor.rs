//! The multi-station consistency monitor: each epoch, every station's observations of a
//! satellite are mapped to a common point, turned into the four statistics and compared
//! across stations by their B values.

use super::b_value::b_values;
use super::config::MonitorConfig;
use super::divergence::Divergence;
use super::hatch::Hatch;
use super::statistic::{PerStatistic, Statistic};
use crate::pvt::predicted_view;
use crate::pvt::solve::STANDARD_RH0;
use hifitime::Epoch;
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Mat3;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, OrbitClass, SatId};
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::frames::{az_el, c_ecef_ned};
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::troposphere::standard_slant_delay_m;
use std::collections::BTreeMap;

/// A gap longer than this many times the previous epoch spacing restarts a track.
const MAX_GAP_FACTOR: f64 = 1.5;

/// A reference station: a name and its antenna position.
#[derive(Debug, Clone, PartialEq)]
pub struct Station {
    pub name: String,
    pub r_ecef_m: Vec3,
}

/// A point the observations are mapped from or to: its position, latitude and height,
/// and the rotation into its local frame.
#[derive(Debug, Clone)]
struct Place {
    r_ecef_m: Vec3,
    lat_rad: f64,
    h_m: f64,
    c_ned_ecef: Mat3,
}

impl Place {
    fn new(r_ecef_m: Vec3) -> Self {
        let g = ecef_to_geodetic(&r_ecef_m);
        Self {
            r_ecef_m,
            lat_rad: g.lat_rad,
            h_m: g.h_m,
            c_ned_ecef: c_ecef_ned(g.lat_rad, g.lon_rad),
        }
    }

    /// Geometric range (m) and elevation (rad) of a satellite at `r_sat_m`.
    fn range_elevation(&self, r_sat_m: &Vec3) -> (f64, f64) {
        let d = r_sat_m - self.r_ecef_m;
        let range = d.norm();
        (range, az_el(&(self.c_ned_ecef * (d / range))).1)
    }

    /// The standard troposphere's slant delay at elevation `el_rad` (m).
    fn troposphere_m(&self, el_rad: f64) -> f64 {
        standard_slant_delay_m(self.lat_rad, self.h_m, el_rad, STANDARD_RH0)
    }

    /// Range plus (when `troposphere`) the modelled tropospheric delay to a satellite at
    /// `r_sat_m`, and the elevation.
    fn path_m(&self, r_sat_m: &Vec3, troposphere: bool) -> (f64, f64) {
        let (range, el) = self.range_elevation(r_sat_m);
        let tropo = if troposphere {
            self.troposphere_m(el)
        } else {
            0.0
        };
        (range + tropo, el)
    }
}

/// One station's values for one satellite at one epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationValues {
    /// The statistics (units of [`Statistic::unit`]).
    pub statistic: PerStatistic<f64>,
    /// Their B values.
    pub b: PerStatistic<f64>,
    /// Whether each B value exceeds its (armed) threshold.
    pub alarm: PerStatistic<bool>,
    /// The station's receiver flagged a loss of lock at this epoch (RINEX LLI): the
    /// receiver itself reports a possible cycle slip, and the track restarts.
    pub loss_of_lock: bool,
}

/// One satellite (and signal) at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct SatelliteEpoch {
    pub sat: SatId,
    pub signal: Signal,
    /// A BeiDou GEO (its thresholds come from the GEO sigma tables where there are any).
    pub geo: bool,
    /// Elevation at the common point (deg).
    pub elevation_deg: f64,
    /// Thresholds of the B values at this elevation.
    pub threshold: PerStatistic<f64>,
    /// Whether each statistic is tested yet: the smoothed code once the Hatch filter has
    /// run one time constant, the divergence (started then) one of its own time constants
    /// later (the LAAS monitors' start-up); code and carrier from the first epoch.
    pub armed: PerStatistic<bool>,
    /// Seconds since this track (common to the stations below) began.
    pub track_age_s: f64,
    /// Per station (monitor order); `None` where the station has no observation.
    pub stations: Vec<Option<StationValues>>,
}

/// The monitor's output of one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct MonitorEpoch {
    pub time: Epoch,
    /// Seconds since the monitor's time origin.
    pub t_s: f64,
    pub sats: Vec<SatelliteEpoch>,
}

/// Satellite-epochs (a satellite's signal observed at some station at one epoch) the
/// monitor could not monitor, by reason: what `monitor run` reports when it monitored
/// nothing, or only part.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Unmonitored {
    /// No healthy ephemeris of the satellite within its fit interval at the epoch.
    pub no_ephemeris: usize,
    /// Below the elevation mask at the common point.
    pub below_mask: usize,
    /// Code and phase at fewer than two stations.
    pub one_station: usize,
    /// No threshold for the signal (the configuration has no sigma table for it).
    pub no_threshold: usize,
}

impl Unmonitored {
    /// The counts of `other` added to these.
    pub fn add(&mut self, other: &Unmonitored) {
        self.no_ephemeris += other.no_ephemeris;
        self.below_mask += other.below_mask;
        self.one_station += other.one_station;
        self.no_threshold += other.no_threshold;
    }

    /// The reasons that occurred, in words ("no satellite observed" when none did):
    /// `ephemerides` names where the ephemerides came from, `mask_deg` is the elevation
    /// mask.
    pub fn describe(&self, ephemerides: &str, mask_deg: f64) -> String {
        let reasons = [
            (
                self.no_ephemeris,
                format!("without an ephemeris in {ephemerides} valid then"),
            ),
            (
                self.below_mask,
                format!("below the elevation mask ({mask_deg} deg) at the common point"),
            ),
            (
                self.one_station,
                "observed (code and phase) by fewer than two stations".to_string(),
            ),
            (
                self.no_threshold,
                "of a signal the configuration has no thresholds for".to_string(),
            ),
        ];
        let said: Vec<String> = reasons
            .iter()
            .filter(|(n, _)| *n > 0)
            .map(|(n, why)| format!("{n} satellite-epochs {why}"))
            .collect();
        if said.is_empty() {
            "no satellite observed".to_string()
        } else {
            said.join("; ")
        }
    }
}

/// Why the monitor could not start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MonitorError {
    #[error("{0} stations; the B values need at least two")]
    TooFewStations(usize),
    #[error("configuration: {0}")]
    Config(String),
}

/// One station's running state on one satellite.
#[derive(Debug, Clone, Copy)]
struct Channel {
    /// Code and carrier (m) of the track's first epoch: the changes start from them.
    first: [f64; 2],
    /// The smoothed code when the Hatch filter had run one time constant: its change
    /// starts there (from the first epoch it would carry that epoch's raw code noise).
    settled_smoothed_m: Option<f64>,
    hatch: Hatch,
    /// Started when the Hatch filter settles: during its warm-up the smoothed code's
    /// noise shrinks from the raw code's, which would read as divergence.
    divergence: Option<Divergence>,
}

/// A track of one satellite held by the same stations since `start_s`.
#[derive(Debug, Clone)]
struct Track {
    channels: Vec<Option<Channel>>,
    start_s: f64,
    last_s: f64,
    last_dt_s: Option<f64>,
}

/// One station's mapped observation: virtual code (m), virtual phase (m).
type Mapped = Option<(f64, f64)>;

/// The monitor over a fixed set of stations.
#[derive(Debug)]
pub struct Monitor {
    config: MonitorConfig,
    multiplier: f64,
    places: Vec<Place>,
    common: Place,
    origin: TimeOrigin,
    store: EphemerisStore,
    tracks: BTreeMap<(SatId, Signal), Track>,
    unmonitored: Unmonitored,
}

impl Monitor {
    /// A monitor of `stations` mapped to `common_m` (their mean when `None`), with the
    /// satellites of `ephemerides`; epoch times count from `origin`.
    pub fn new(
        config: MonitorConfig,
        stations: Vec<Station>,
        common_m: Option<Vec3>,
        ephemerides: Vec<BroadcastEphemeris>,
        origin: TimeOrigin,
    ) -> Result<Self, MonitorError> {
        if stations.len() < 2 {
            return Err(MonitorError::TooFewStations(stations.len()));
        }
        config.check().map_err(MonitorError::Config)?;
        let mean = stations.iter().map(|s| s.r_ecef_m).sum::<Vec3>() / stations.len() as f64;
        Ok(Self {
            multiplier: config.thresholds.multiplier(),
            config,
            places: stations.iter().map(|s| Place::new(s.r_ecef_m)).collect(),
            common: Place::new(common_m.unwrap_or(mean)),
            store: EphemerisStore::new(ephemerides, &origin),
            origin,
            tracks: BTreeMap::new(),
            unmonitored: Unmonitored::default(),
        })
    }

    /// The common point (ECEF, m).
    pub fn common_point(&self) -> Vec3 {
        self.common.r_ecef_m
    }

    /// The satellite-epochs not monitored so far, by reason.
    pub fn unmonitored(&self) -> Unmonitored {
        self.unmonitored
    }

    /// Process one epoch: `records[m]` is station m's observations at `time` (`None`
    /// when it has no epoch there).
    pub fn epoch(&mut self, time: Epoch, records: &[Option<&[ObsRecord]>]) -> MonitorEpoch {
        let t_s = self.origin.seconds_since_start(time);
        let mut keys: Vec<(SatId, Signal)> = records
            .iter()
            .flatten()
            .flat_map(|rs| rs.iter().map(|r| (r.sat, r.signal)))
            .collect();
        keys.sort();
        keys.dedup();
        let sats = keys
            .into_iter()
            .filter_map(|key| self.satellite(key, t_s, records))
            .collect();
        MonitorEpoch { time, t_s, sats }
    }

    /// One satellite's outcome, `None` when it is not monitored at this epoch.
    fn satellite(
        &mut self,
        key: (SatId, Signal),
        t_s: f64,
        records: &[Option<&[ObsRecord]>],
    ) -> Option<SatelliteEpoch> {
        let Some(eph) = self.store.select(key.0, t_s) else {
            self.tracks.remove(&key);
            self.unmonitored.no_ephemeris += 1;
            return None;
        };
        let r_sat = predicted_view(eph, t_s, &self.common.r_ecef_m).r_ecef_m;
        let troposphere = self.config.troposphere;
        let (common_m, el_rad) = self.common.path_m(&r_sat, troposphere);
        let elevation_deg = el_rad.to_degrees();
        if elevation_deg < self.config.elevation_mask_deg {
            self.tracks.remove(&key);
            self.unmonitored.below_mask += 1;
            return None;
        }
        let mut lost = vec![false; self.places.len()];
        let mapped: Vec<Mapped> = self
            .places
            .iter()
            .zip(records)
            .zip(lost.iter_mut())
            .map(|((place, recs), lost)| {
                let rec = (*recs)?
                    .iter()
                    .find(|r| (r.sat, r.signal) == key && r.pseudorange_m.is_some())?;
                let (code, phase) = (rec.pseudorange_m?, rec.carrier_phase_cycles?);
                *lost = rec.loss_of_lock();
                // The satellite where the common point's signal left it: stations a few
                // hundred metres away see it within a microsecond of that (mm).
                let to_common_m = place.path_m(&r_sat, troposphere).0 - common_m;
                Some((
                    code - to_common_m,
                    phase * key.1.wavelength_m() - to_common_m,
                ))
            })
            .collect();
        if mapped.iter().flatten().count() < 2 {
            self.tracks.remove(&key);
            self.unmonitored.one_station += 1;
            return None;
        }
        let geo = eph.eph.class == OrbitClass::BeidouGeo;
        let Some(threshold) = self
            .config
            .thresholds
            .at(self.multiplier, key.1, geo, elevation_deg)
        else {
            self.unmonitored.no_threshold += 1;
            return None;
        };
        self.track(key, t_s, &mapped, lost.contains(&true));
        let track = self.tracks.get(&key)?;
        let mut outcome = self.outcome(key, geo, elevation_deg, threshold, track, &mapped);
        for (v, lost) in outcome.stations.iter_mut().zip(lost) {
            if let Some(v) = v {
                v.loss_of_lock = lost;
            }
        }
        Some(outcome)
    }

    /// The track of `key` after this epoch's `mapped` observations: continued when the
    /// same stations hold it without loss of lock or gap, restarted otherwise.
    fn track(&mut self, key: (SatId, Signal), t_s: f64, mapped: &[Mapped], lost: bool) {
        let (window, tau) = (self.config.smoothing_s, self.config.divergence_s);
        let continues = self.tracks.get(&key).is_some_and(|tr| {
            let dt = t_s - tr.last_s;
            let same = tr
                .channels
                .iter()
                .zip(mapped)
                .all(|(c, m)| c.is_some() == m.is_some());
            same && !lost && dt > 0.0 && tr.last_dt_s.is_none_or(|p| dt <= MAX_GAP_FACTOR * p)
        });
        let track = match self.tracks.remove(&key) {
            Some(mut tr) if continues => {
                let dt = t_s - tr.last_s;
                let settled = t_s - tr.start_s >= window;
                for (c, m) in tr.channels.iter_mut().zip(mapped) {
                    if let (Some(c), Some((code, phase))) = (c, m) {
                        let smoothed = c.hatch.update(*code, *phase);
                        if let Some(d) = c.divergence.as_mut() {
                            d.update(smoothed - phase, dt);
                        }
                        if settled && c.settled_smoothed_m.is_none() {
                            c.settled_smoothed_m = Some(smoothed);
                            c.divergence = Some(Divergence::start(tau, smoothed - phase));
                        }
                    }
                }
                tr.last_dt_s = Some(dt);
                tr.last_s = t_s;
                tr
            }
            _ => Track {
                channels: mapped
                    .iter()
                    .map(|m| {
                        m.map(|(code, phase)| Channel {
                            first: [code, phase],
                            settled_smoothed_m: None,
                            hatch: Hatch::start(window, code, phase),
                            divergence: None,
                        })
                    })
                    .collect(),
                start_s: t_s,
                last_s: t_s,
                last_dt_s: None,
            },
        };
        self.tracks.insert(key, track);
    }

    /// The statistics, B values and alarms of a track at this epoch.
    fn outcome(
        &self,
        key: (SatId, Signal),
        geo: bool,
        elevation_deg: f64,
        threshold: PerStatistic<f64>,
        track: &Track,
        mapped: &[Mapped],
    ) -> SatelliteEpoch {
        let lambda = key.1.wavelength_m();
        let age_s = track.last_s - track.start_s;
        let statistic: Vec<Option<PerStatistic<f64>>> = track
            .channels
            .iter()
            .zip(mapped)
            .map(|(c, m)| {
                let (c, (code, phase)) = (c.as_ref()?, (*m)?);
                let settled = c.settled_smoothed_m.unwrap_or(c.hatch.smoothed_m());
                Some([
                    code - c.first[0],
                    c.hatch.smoothed_m() - settled,
                    (phase - c.first[1]) / lambda,
                    c.divergence.map_or(0.0, |d| d.rate_mps()),
                ])
            })
            .collect();
        let present: Vec<&PerStatistic<f64>> = statistic.iter().flatten().collect();
        let b: Vec<Vec<f64>> = Statistic::ALL
            .iter()
            .map(|s| b_values(&present.iter().map(|x| x[s.index()]).collect::<Vec<_>>()))
            .collect();
        let armed = Statistic::ALL.map(|s| match s {
            Statistic::Code | Statistic::Carrier => true,
            Statistic::SmoothedCode => age_s >= self.config.smoothing_s,
            Statistic::Divergence => age_s >= self.config.smoothing_s + self.config.divergence_s,
        });
        let mut next = 0;
        let stations = statistic
            .iter()
            .map(|x| {
                let x = (*x)?;
                let i = next;
                next += 1;
                let bi = Statistic::ALL.map(|s| b[s.index()][i]);
                let alarm = Statistic::ALL
                    .map(|s| armed[s.index()] && bi[s.index()].abs() > threshold[s.index()]);
                Some(StationValues {
                    statistic: x,
                    b: bi,
                    alarm,
                    loss_of_lock: false,
                })
            })
            .collect();
        SatelliteEpoch {
            sat: key.0,
            signal: key.1,
            geo,
            elevation_deg,
            threshold,
            armed,
            track_age_s: age_s,
            stations,
        }
    }
}
