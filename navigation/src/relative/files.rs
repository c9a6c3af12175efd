//! The chain over files: several antennas' RINEX observation files (master first), a
//! navigation file and the body geometry. The master's position comes from its own
//! single-point solution, the lines of sight from the broadcast ephemerides.

use super::troposphere::DelayGradient;
use super::{RelativeConfig, RelativeEpoch, RelativeError, RelativeSolver};
use crate::baseline::LineOfSight;
use crate::geometry_file::BodyGeometryFile;
use crate::pvt::{
    CarrierSmoother, Fix, FromEphemeris, IonosphereCorrection, Measurement, NearAntenna, Predicted,
    PvtConfig, Recorded, Satellites, SmoothingConfig, ViewPoint, solve_with,
};
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeMap;

/// Epochs of different files closer than this (s) are the same epoch: receivers whose
/// clock is not steered tag their epochs on their own clock and let it drift some
/// milliseconds from GPS time before a jump (the GEONET Trimble 5700 files tag from
/// 59.996 to 00.005 s about the whole second). RTKLIB's tolerance (`DTTOL`, 2.4.3); the
/// difference of the sampling instants is corrected ([`ToMasterModel`]).
pub(crate) const SAME_EPOCH_S: f64 = 0.025;

/// Why the files could not be processed.
#[derive(Debug, thiserror::Error)]
pub enum FilesError {
    #[error(
        "{files} observation files for the {geometry} antennas of the geometry file (one file per antenna, in its order)"
    )]
    AntennaCount { files: usize, geometry: usize },
    #[error("{0}: no observation epochs")]
    NoEpochs(String),
    #[error(
        "{file}: none of the signals of [relative] signals ({signals}) has a pseudorange in the file"
    )]
    NoSignal { file: String, signals: String },
    #[error(
        "{file}: no epoch within {SAME_EPOCH_S} s of an epoch of the master's file {master} (this file {span}, the master's {master_span})"
    )]
    NoCommonEpoch {
        file: String,
        master: String,
        /// `from T0 to T1`.
        span: String,
        master_span: String,
    },
    #[error(
        "no ephemeris of the navigation file is valid at an epoch of {master} ({master_span}) for a satellite it observes"
    )]
    NoEphemeris { master: String, master_span: String },
    #[error(
        "{signal}: {first} has it from code {first_code}, {other} from {other_code}; double differences need one tracking of a signal in every file (between trackings RINEX 3.04 table A23 puts phase shifts, and their code biases differ)"
    )]
    MixedTracking {
        signal: Signal,
        first: String,
        first_code: &'static str,
        other: String,
        other_code: &'static str,
    },
    #[error(transparent)]
    Relative(#[from] RelativeError),
}

/// One epoch of the master's file and what became of it.
#[derive(Debug)]
pub struct EpochOutcome {
    pub time: Epoch,
    /// The master's single-point position, when it had one.
    pub master_ecef_m: Option<Vec3>,
    /// The chain's result, or why the epoch gave none (a missing antenna, too few
    /// satellites, no position).
    pub result: Result<RelativeEpoch, String>,
}

/// The time tag and records of `file` at `time`, if it has that epoch (`cursor` advances
/// through the file's time-ordered epochs).
pub(crate) fn records_at<'f>(
    file: &'f ObsFile,
    cursor: &mut usize,
    time: Epoch,
) -> Option<(Epoch, &'f [ObsRecord])> {
    while *cursor < file.epochs.len()
        && (file.epochs[*cursor].time - time).to_seconds() < -SAME_EPOCH_S
    {
        *cursor += 1;
    }
    let e = file.epochs.get(*cursor)?;
    ((e.time - time).to_seconds().abs() <= SAME_EPOCH_S).then_some((e.time, e.sats.as_slice()))
}

/// Each satellite's record of the first of `signals` (in their order) that has a
/// pseudorange; satellites without one are left out.
fn first_per_satellite<'r>(
    records: &'r [ObsRecord],
    signals: &'r [Signal],
) -> impl Iterator<Item = &'r ObsRecord> {
    let mut seen = std::collections::BTreeSet::new();
    signals
        .iter()
        .flat_map(move |s| records.iter().filter(move |r| r.signal == *s))
        .filter(|r| r.pseudorange_m.is_some())
        .filter(move |r| seen.insert(r.sat))
}

/// The single-point solution of one antenna's `records` (with the broadcast ionosphere one
/// pseudorange per satellite, of the first of `signals` that has one; dual-frequency, every
/// one of `signals` for the solver to combine) at `t_s` (s since `origin`) with `config`,
/// the satellites taken from `satellites`.
#[allow(clippy::too_many_arguments)]
fn single_point(
    records: &[ObsRecord],
    signals: &[Signal],
    t_s: f64,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    config: &PvtConfig,
    prior: Option<Vec3>,
    satellites: &mut dyn Satellites,
) -> Result<Fix, String> {
    let chosen: Vec<&ObsRecord> = match config.ionosphere {
        IonosphereCorrection::Broadcast => first_per_satellite(records, signals).collect(),
        IonosphereCorrection::DualFrequency => records
            .iter()
            .filter(|r| signals.contains(&r.signal))
            .collect(),
    };
    let meas: Vec<Measurement> = chosen
        .into_iter()
        .filter(|r| store.select(r.sat, t_s).is_some())
        .filter_map(|r| {
            Some(Measurement {
                sat: r.sat,
                pseudorange_m: r.pseudorange_m?,
                doppler_hz: None,
                signal: r.signal,
            })
        })
        .collect();
    solve_with(&meas, t_s, store, origin, config, prior, satellites).map_err(|e| e.to_string())
}

/// The single-point solution of every epoch of `file` (times in seconds since `origin`)
/// with `config`, each epoch starting from the last position found: how the chain
/// positions its master antenna. With `config.carrier_smoothing` the code is smoothed
/// with the carrier first ([`CarrierSmoother`]), as the receiver's PVT stage does.
pub fn single_point_fixes(
    file: &ObsFile,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    signals: &[Signal],
    config: &PvtConfig,
) -> Vec<Result<Fix, String>> {
    let mut stream = FixStream::new(config);
    (file.epochs.iter())
        .map(|e| stream.fix(e, store, origin, signals))
        .collect()
}

/// The single-point fixes of one receiver's epochs, one after the other: each starts from
/// the last position found, and with `carrier_smoothing` one smoother runs along them
/// ([`single_point_fixes`] over a file; a receiver's stage epoch by epoch).
#[derive(Debug, Clone)]
pub(crate) struct FixStream {
    config: PvtConfig,
    prior: Option<Vec3>,
    smoother: Option<CarrierSmoother>,
}

impl FixStream {
    pub(crate) fn new(config: &PvtConfig) -> Self {
        Self {
            config: config.clone(),
            prior: None,
            smoother: config.carrier_smoothing.map(CarrierSmoother::new),
        }
    }

    /// The fix of the next `epoch`.
    pub(crate) fn fix(
        &mut self,
        epoch: &ObsEpoch,
        store: &EphemerisStore,
        origin: &TimeOrigin,
        signals: &[Signal],
    ) -> Result<Fix, String> {
        let t_s = origin.seconds_since_start(epoch.time);
        let records = match self.smoother.as_mut() {
            Some(s) => std::borrow::Cow::Owned(smoothed(s, &epoch.sats, t_s)),
            None => std::borrow::Cow::Borrowed(epoch.sats.as_slice()),
        };
        let fix = single_point(
            &records,
            signals,
            t_s,
            store,
            origin,
            &self.config,
            self.prior,
            &mut FromEphemeris,
        );
        self.prior = fix.as_ref().ok().map(|f| f.r_ecef_m).or(self.prior);
        fix
    }
}

/// `file` with each pseudorange that has a carrier beside it smoothed along the file's
/// own tracks (book eqs. 5-60..5-64, one [`CarrierSmoother`] over every epoch).
pub(crate) fn carrier_smoothed_file(
    file: &ObsFile,
    origin: &TimeOrigin,
    smoothing: SmoothingConfig,
) -> ObsFile {
    let mut smoother = CarrierSmoother::new(smoothing);
    let epochs = (file.epochs.iter())
        .map(|e| ObsEpoch {
            time: e.time,
            sats: smoothed(&mut smoother, &e.sats, origin.seconds_since_start(e.time)),
        })
        .collect();
    file.with_epochs(epochs)
}

/// `records` with each pseudorange that has a carrier beside it smoothed by `smoother`.
pub(crate) fn smoothed(
    smoother: &mut CarrierSmoother,
    records: &[ObsRecord],
    t_s: f64,
) -> Vec<ObsRecord> {
    records
        .iter()
        .map(|r| ObsRecord {
            pseudorange_m: smoother.smooth_record(r, t_s),
            ..*r
        })
        .collect()
}

/// What moves one antenna's observation of a satellite onto the chain's linear model
/// of the master's epoch (m, added to its code and phase).
#[derive(Debug, Clone, Copy)]
struct ToMasterModel {
    /// Range rate (m/s, this antenna's: the master's differs by about
    /// `|v_sat| |b| / rho`, 0.5 m/s at 3.3 km) times (master's sampling instant - this
    /// antenna's): a receiver
    /// that samples on its own clock samples when that clock reads the tag, so two
    /// receivers' "same" epoch lies their clock difference apart (up to 0.5 ms between
    /// the GEONET stations: 0.2 m of double difference at 800 m/s of range-rate
    /// difference, which does not cancel). The range rate is the satellite's motion along
    /// the line of sight: right for receivers at rest in ECEF; a moving receiver on its
    /// own clock would also need its own velocity here (antennas on one clock, as on the
    /// simulated platforms, have no sampling difference to correct).
    time_m: f64,
    /// `-(rho_k - rho_master + l . b0)`: the range difference beyond the linear `-l . b`
    /// of the double-difference model (eq. 2.3-10), at the antenna's single-point
    /// position (`b0` from the master's). About `|b|^2 / 2 rho` (0.25 m at 3.3 km,
    /// varying by satellite by 0.1 m; 1e-8 m at 1 m); an error `db` in `b0` leaves about
    /// `|b| |db| / rho` (1 mm for 5 m at 3.3 km).
    curvature_m: f64,
}

/// The master's predicted satellites at its sampling instant, computed once per epoch for
/// every other antenna ([`to_master_model`]).
struct MasterPredictions<'a> {
    store: &'a EphemerisStore,
    fix: &'a Fix,
    place: ViewPoint,
    by_sat: BTreeMap<SatId, Option<Predicted>>,
}

impl<'a> MasterPredictions<'a> {
    fn new(store: &'a EphemerisStore, fix: &'a Fix) -> Self {
        Self {
            store,
            fix,
            place: ViewPoint::without_angles(fix.r_ecef_m),
            by_sat: BTreeMap::new(),
        }
    }

    /// The master's view of `sat` (none without an ephemeris).
    fn of(&mut self, sat: SatId) -> Option<Predicted> {
        let (store, t_s, place) = (self.store, self.fix.t_s, &self.place);
        *self
            .by_sat
            .entry(sat)
            .or_insert_with(|| store.select(sat, t_s).map(|eph| place.predict(eph, t_s)))
    }
}

/// The corrections of antenna `k` with single-point solution `fix_k` against the master's
/// predicted satellites, per satellite of `records`. Antenna `k`'s view of a satellite is
/// the master's moved along the satellite's velocity by the flight-time difference
/// `l . b0 / c` ([`Transmitted::later`]; what is left of the difference, the curvature
/// `|b0|^2 / 2 rho c`, moves the satellite by 1e-6 m at 3.3 km).
fn to_master_model(
    records: &[ObsRecord],
    signals: &[Signal],
    master: &mut MasterPredictions,
    fix_k: &Fix,
) -> BTreeMap<SatId, ToMasterModel> {
    let dt = master.fix.t_s - fix_k.t_s;
    let b0 = fix_k.r_ecef_m - master.fix.r_ecef_m;
    let place_k = ViewPoint::without_angles(fix_k.r_ecef_m);
    first_per_satellite(records, signals)
        .filter_map(|rec| {
            let Predicted {
                transmitted,
                view: at_master,
            } = master.of(rec.sat)?;
            let at_k = place_k.see(&transmitted.later(at_master.los.dot(&b0) / C_MPS));
            Some((
                rec.sat,
                ToMasterModel {
                    time_m: at_k.los.dot(&at_k.v_ecef_mps) * dt,
                    curvature_m: -(at_k.range_m - at_master.range_m + at_master.los.dot(&b0)),
                },
            ))
        })
        .collect()
}

/// `records` with code and phase moved by `corrections` (satellites without one are left
/// out).
fn corrected(
    records: &[ObsRecord],
    corrections: &BTreeMap<SatId, ToMasterModel>,
) -> Vec<ObsRecord> {
    records
        .iter()
        .filter_map(|r| {
            let c = corrections.get(&r.sat)?;
            let shift_m = c.time_m + c.curvature_m;
            let mut r = *r;
            r.pseudorange_m = r.pseudorange_m.map(|p| p + shift_m);
            r.carrier_phase_cycles = r
                .carrier_phase_cycles
                .map(|cy| cy + shift_m / r.signal.wavelength_m());
            Some(r)
        })
        .collect()
}

/// Every file that says which code each of `signals` came from ([`ObsFile::codes`]) says
/// the same one.
fn check_trackings(files: &[ObsFile], signals: &[Signal]) -> Result<(), FilesError> {
    for &signal in signals {
        let mut known = files
            .iter()
            .filter_map(|f| Some((f, *f.codes.get(&signal)?)));
        let Some((first, first_code)) = known.next() else {
            continue;
        };
        if let Some((other, other_code)) = known.find(|(_, c)| *c != first_code) {
            return Err(FilesError::MixedTracking {
                signal,
                first: first.source.display().to_string(),
                first_code,
                other: other.source.display().to_string(),
                other_code,
            });
        }
    }
    Ok(())
}

/// The chain fed one master epoch at a time: [`run_files`] feeds it from files,
/// `skyforge receive --geometry` from the receiver's epochs in memory. Every antenna's
/// observations are moved onto the linear model of the master's epoch ([`ToMasterModel`]:
/// its sampling instant, and the range difference beyond `-l . b`) when both have a
/// single-point solution. With `troposphere`, the lines of sight carry the slant delay's
/// gradient ([`super::troposphere`]).
#[derive(Debug)]
pub struct EpochChain {
    /// The broadcast ephemerides until the master's first epoch gives the time origin.
    pending: Vec<BroadcastEphemeris>,
    ready: Option<(TimeOrigin, EphemerisStore)>,
    names: Vec<String>,
    signals: Vec<Signal>,
    troposphere: bool,
    solver: RelativeSolver,
    pvt: PvtConfig,
    /// The master's last position.
    master_prior: Option<Vec3>,
    /// The other antennas' last offsets from the master (index 0 unused).
    offsets: Vec<Option<Vec3>>,
}

/// One other antenna's epoch: its time tag and records.
pub type AntennaEpoch<'r> = (Epoch, &'r [ObsRecord]);

impl EpochChain {
    /// The chain for the antennas of `geometry` (master first) with `config`; the time
    /// origin is the first master epoch given to [`Self::epoch`].
    pub fn new(
        ephemerides: Vec<BroadcastEphemeris>,
        geometry: &BodyGeometryFile,
        config: RelativeConfig,
    ) -> Result<Self, RelativeError> {
        let signals = config.signals.clone();
        let troposphere = config.troposphere;
        let solver = RelativeSolver::new(config, &geometry.positions())?;
        Ok(Self {
            pending: ephemerides,
            ready: None,
            names: geometry.antennas.iter().map(|a| a.name.clone()).collect(),
            signals,
            troposphere,
            solver,
            pvt: PvtConfig::default(),
            master_prior: None,
            offsets: vec![None; geometry.antennas.len()],
        })
    }

    /// One epoch of the master (`time`, its `records`) with every other antenna's epoch
    /// in geometry order (`None` where an antenna has none).
    pub fn epoch(
        &mut self,
        time: Epoch,
        records: &[ObsRecord],
        others: &[Option<AntennaEpoch<'_>>],
    ) -> EpochOutcome {
        let pending = &mut self.pending;
        let (origin, store) = &*self.ready.get_or_insert_with(|| {
            let origin = TimeOrigin::new(time);
            let store = EphemerisStore::new(std::mem::take(pending), &origin);
            (origin, store)
        });
        let origin = *origin;
        let (signals, pvt) = (&self.signals, &self.pvt);
        let t_s = origin.seconds_since_start(time);
        // The master's satellites, which the other antennas' solutions move to their
        // own transmit times.
        let mut satellites = Recorded::new();
        let fix = single_point(
            records,
            signals,
            t_s,
            store,
            &origin,
            pvt,
            self.master_prior,
            &mut satellites,
        );
        let master_ecef_m = fix.as_ref().ok().map(|f| f.r_ecef_m);
        self.master_prior = master_ecef_m.or(self.master_prior);
        let mut aligned_others: Vec<Vec<ObsRecord>> = Vec::with_capacity(others.len());
        let mut missing = None;
        let mut master_predictions = fix.as_ref().ok().map(|f| MasterPredictions::new(store, f));
        for (k, other) in others.iter().enumerate().map(|(i, o)| (i + 1, o)) {
            let Some((time_k, records_k)) = *other else {
                missing = missing.or(Some(k));
                continue;
            };
            let t_k = origin.seconds_since_start(time_k);
            let aligned = match master_predictions.as_mut() {
                Some(master) => {
                    // Start from where the antenna last was relative to the master.
                    let prior = self.offsets[k].map(|b| master.fix.r_ecef_m + b);
                    let near = &mut NearAntenna(&satellites);
                    match single_point(records_k, signals, t_k, store, &origin, pvt, prior, near) {
                        Ok(fix_k) => {
                            self.offsets[k] = Some(fix_k.r_ecef_m - master.fix.r_ecef_m);
                            let c = to_master_model(records_k, signals, master, &fix_k);
                            corrected(records_k, &c)
                        }
                        Err(_) => records_k.to_vec(),
                    }
                }
                None => records_k.to_vec(),
            };
            aligned_others.push(aligned);
        }
        let result = match (missing, master_ecef_m) {
            (Some(k), _) => Err(format!(
                "antenna {} has no epoch at {}",
                self.names[k], time
            )),
            (None, None) => Err(format!(
                "no single-point position of the master: {}",
                fix.err().unwrap_or_default()
            )),
            (None, Some(r)) => {
                let place = ViewPoint::new(r);
                let gradient = self.troposphere.then(|| DelayGradient::at(&r));
                let views: Vec<LineOfSight> = first_per_satellite(records, signals)
                    .filter_map(|rec| {
                        let eph = store.select(rec.sat, t_s)?;
                        let view = place.predict(eph, t_s).view;
                        let mut los = LineOfSight::from_view(rec.sat, &view);
                        if let Some(g) = &gradient {
                            los.delay_gradient = g.towards(&view.r_ecef_m);
                        }
                        Some(los)
                    })
                    .collect();
                let mut antennas: Vec<&[ObsRecord]> = vec![records];
                antennas.extend(aligned_others.iter().map(Vec::as_slice));
                self.solver
                    .epoch(t_s, &antennas, &views, &r)
                    .map_err(|e| e.to_string())
            }
        };
        EpochOutcome {
            time,
            master_ecef_m,
            result,
        }
    }
}

/// Why no epoch of `files` (master first) can be formed, whatever the chain does: a file
/// without epochs or without a pseudorange of `signals`, another file with no epoch at
/// the master's (another day), or no ephemeris valid at any master epoch for the
/// satellites it observes (a navigation file of another day).
fn check_files(
    files: &[ObsFile],
    signals: &[Signal],
    ephemerides: &[BroadcastEphemeris],
) -> Result<(), FilesError> {
    let name = |f: &ObsFile| f.source.display().to_string();
    for f in files {
        if f.epochs.is_empty() {
            return Err(FilesError::NoEpochs(name(f)));
        }
        let observed = |e: &ObsEpoch| first_per_satellite(&e.sats, signals).next().is_some();
        if !f.epochs.iter().any(observed) {
            return Err(FilesError::NoSignal {
                file: name(f),
                signals: signals
                    .iter()
                    .map(|s| s.tag())
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
    }
    let master = &files[0];
    let span = |f: &ObsFile| {
        let (from, to) = (f.epochs[0].time, f.epochs[f.epochs.len() - 1].time);
        format!("from {from} to {to}")
    };
    for f in &files[1..] {
        let mut cursor = 0;
        if !master
            .epochs
            .iter()
            .any(|e| records_at(f, &mut cursor, e.time).is_some())
        {
            return Err(FilesError::NoCommonEpoch {
                file: name(f),
                master: name(master),
                span: span(f),
                master_span: span(master),
            });
        }
    }
    let origin = TimeOrigin::new(master.epochs[0].time);
    let store = EphemerisStore::new(ephemerides.to_vec(), &origin);
    let valid = master.epochs.iter().any(|e| {
        let t_s = origin.seconds_since_start(e.time);
        first_per_satellite(&e.sats, signals).any(|r| store.select(r.sat, t_s).is_some())
    });
    if !valid {
        return Err(FilesError::NoEphemeris {
            master: name(master),
            master_span: span(master),
        });
    }
    Ok(())
}

/// Run the chain over `files` (one per antenna of `geometry`, same order; [`EpochChain`]),
/// handing each master epoch's outcome to `each`; another antenna's epoch is the one
/// within [`SAME_EPOCH_S`] of the master's.
pub fn run_files(
    files: &[ObsFile],
    ephemerides: Vec<BroadcastEphemeris>,
    geometry: &BodyGeometryFile,
    config: RelativeConfig,
    mut each: impl FnMut(EpochOutcome),
) -> Result<(), FilesError> {
    if files.len() != geometry.antennas.len() {
        return Err(FilesError::AntennaCount {
            files: files.len(),
            geometry: geometry.antennas.len(),
        });
    }
    check_trackings(files, &config.signals)?;
    check_files(files, &config.signals, &ephemerides)?;
    let master = &files[0];
    let mut chain = EpochChain::new(ephemerides, geometry, config)?;
    let mut cursors = vec![0usize; files.len()];
    for epoch in &master.epochs {
        let others: Vec<_> = files
            .iter()
            .zip(&mut cursors)
            .skip(1)
            .map(|(file, cursor)| records_at(file, cursor, epoch.time))
            .collect();
        each(chain.epoch(epoch.time, &epoch.sats, &others));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pvt::{Dop, predicted_view};
    use skyforge_orbits::ephemeris::nominal;
    use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};

    fn fix(t_s: f64, r_ecef_m: Vec3) -> Fix {
        Fix {
            t_s,
            r_ecef_m,
            clock_bias_m: 0.0,
            inter_system_bias_m: None,
            dop: Dop {
                gdop: 1.0,
                pdop: 1.0,
                hdop: 1.0,
                vdop: 1.0,
                tdop: 1.0,
            },
            used: Vec::new(),
            excluded: Vec::new(),
            chi2: 0.0,
            dof: 0,
            protection: None,
        }
    }

    /// A rover 3.3 km from the master that samples 0.5 ms before it: its ranges, moved onto
    /// the master's linear model, equal the master's range minus `l . b` at the master's
    /// instant, to a micrometre (what is left: the range's second derivative over 0.5 ms).
    #[test]
    fn rover_ranges_land_on_the_masters_linear_model() {
        let start =
            hifitime::Epoch::from_gregorian(2005, 4, 2, 0, 0, 0, 0, hifitime::TimeScale::GPST);
        let store = nominal::gps_store(start);
        let geo = |lat: f64, lon: f64| geodetic_to_ecef(&Geodetic::from_degrees(lat, lon, 50.0));
        let (master_r, rover_r) = (geo(35.0, 139.0), geo(35.02, 139.025));
        let b0 = rover_r - master_r;
        assert!((3000.0..3500.0).contains(&b0.norm()), "{}", b0.norm());
        let t_m = 600.0;
        let dt = 5e-4;
        let (master_fix, rover_fix) = (fix(t_m, master_r), fix(t_m - dt, rover_r));
        let mut records = Vec::new();
        let mut expected = Vec::new();
        for prn in 1..=32u8 {
            let sat = SatId::gps(prn);
            let Some(eph) = store.select(sat, t_m) else {
                continue;
            };
            let at_master = predicted_view(eph, t_m, &master_r);
            let at_rover = predicted_view(eph, t_m - dt, &rover_r);
            if at_master.az_el_rad.is_none_or(|(_, el)| el < 0.2) {
                continue;
            }
            let range = at_rover.range_m;
            let lambda = Signal::GpsL1Ca.wavelength_m();
            records.push(ObsRecord::complete(
                sat,
                Signal::GpsL1Ca,
                range,
                range / lambda,
                0.0,
                45.0,
            ));
            expected.push(at_master.range_m - at_master.los.dot(&b0));
        }
        assert!(records.len() >= 5, "{} satellites up", records.len());
        let corrections = to_master_model(
            &records,
            &[Signal::GpsL1Ca],
            &mut MasterPredictions::new(&store, &master_fix),
            &rover_fix,
        );
        let moved = corrected(&records, &corrections);
        assert_eq!(moved.len(), records.len());
        for (r, want) in moved.iter().zip(&expected) {
            let code = r.pseudorange_m.unwrap();
            let phase_m = r.carrier_phase_cycles.unwrap() * Signal::GpsL1Ca.wavelength_m();
            assert!(
                (code - want).abs() < 1e-6,
                "{}: {} m off",
                r.sat,
                code - want
            );
            assert!(
                (phase_m - want).abs() < 1e-6,
                "{}: {} m off",
                r.sat,
                phase_m - want
            );
        }
        // The same instant and place: nothing moves.
        let none = to_master_model(
            &records,
            &[Signal::GpsL1Ca],
            &mut MasterPredictions::new(&store, &master_fix),
            &master_fix,
        );
        assert!(
            none.values()
                .all(|c| c.time_m == 0.0 && c.curvature_m.abs() < 1e-9)
        );
    }

    /// The chain over files on two ground stations 3.3 km and 40 m of height apart, every
    /// satellite's code and phase the exact range plus each station's standard slant
    /// troposphere (no noise, no clock, integer ambiguities zero): with the troposphere
    /// modelled the float baseline is 0.76 mm from the truth (what first order leaves,
    /// through the geometry); without, the stations' delay difference pulls it 5.2 cm off.
    /// So the gradient enters the design with the right sign and scale (a wrong sign
    /// doubles the error). Bounds 2 mm and 2 cm, set after the first run (which asked 0.5
    /// mm of the first, not allowing for the geometry's amplification).
    #[test]
    fn the_troposphere_gradient_puts_the_float_baseline_on_the_truth() {
        use super::super::troposphere::Site;
        use crate::relative::config::Constraint;
        use skyforge_gnss::observation::{ObsEpoch, ObsFile};
        let start =
            hifitime::Epoch::from_gregorian(2005, 4, 2, 0, 0, 0, 0, hifitime::TimeScale::GPST);
        let store = nominal::gps_store(start);
        let station =
            |lat: f64, lon: f64, h: f64| geodetic_to_ecef(&Geodetic::from_degrees(lat, lon, h));
        let (master_r, rover_r) = (station(35.0, 139.0, 50.0), station(35.02, 139.025, 90.0));
        let t_s = 600.0;
        let time = start + hifitime::Duration::from_seconds(t_s);
        let file = |r: Vec3| {
            let sats = (1..=32u8)
                .filter_map(|prn| {
                    let sat = SatId::gps(prn);
                    let view = predicted_view(store.select(sat, t_s)?, t_s, &r);
                    let (_, el) = view.az_el_rad?;
                    (el > 15f64.to_radians()).then(|| {
                        let range = view.range_m + Site::at(&r).slant_m(&view.r_ecef_m)
                            - C_MPS * view.clock_s;
                        let lambda = Signal::GpsL1Ca.wavelength_m();
                        ObsRecord::complete(sat, Signal::GpsL1Ca, range, range / lambda, 0.0, 45.0)
                    })
                })
                .collect();
            ObsFile {
                source: "test".into(),
                approx_ecef_m: Some(r),
                codes: Default::default(),
                epochs: vec![ObsEpoch { time, sats }],
                marker: None,
                dropped: Vec::new(),
            }
        };
        let truth = rover_r - master_r;
        let geometry = BodyGeometryFile::from_positions([
            ("master".to_string(), Vec3::zeros()),
            ("rover".to_string(), truth),
        ]);
        let error_m = |troposphere: bool| {
            let config = RelativeConfig {
                signals: vec![Signal::GpsL1Ca],
                constraint: Constraint::None,
                troposphere,
                ..RelativeConfig::default()
            };
            let mut float = None;
            run_files(
                &[file(master_r), file(rover_r)],
                nominal::gps(start),
                &geometry,
                config,
                |o| {
                    float = o
                        .result
                        .ok()
                        .map(|e| Vec3::from(e.float.baselines.column(0)))
                },
            )
            .unwrap();
            (float.expect("an epoch solved") - truth).norm()
        };
        let (with, without) = (error_m(true), error_m(false));
        assert!(with < 2e-3, "with the gradient: {with} m off");
        assert!(without > 2e-2, "without: only {without} m off");
    }

    /// Files that read one signal from different trackings (P(Y) `2W` in one, L2C `2L` in
    /// the other) are refused by name; files that do not say are taken as they are.
    #[test]
    fn mixed_trackings_of_a_signal_are_refused() {
        let file = |name: &str, code: Option<&'static str>| ObsFile {
            source: name.into(),
            approx_ecef_m: None,
            codes: code.map(|c| (Signal::GpsL2, c)).into_iter().collect(),
            epochs: Vec::new(),
            marker: None,
            dropped: Vec::new(),
        };
        let signals = [Signal::GpsL1Ca, Signal::GpsL2];
        let e = check_trackings(&[file("a", Some("2W")), file("b", Some("2L"))], &signals)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("GPS L2: a has it from code 2W, b from 2L"),
            "{e}"
        );
        assert!(check_trackings(&[file("a", Some("2W")), file("b", None)], &signals).is_ok());
        assert!(check_trackings(&[file("a", Some("2W")), file("b", Some("2W"))], &signals).is_ok());
        assert!(
            check_trackings(
                &[file("a", Some("2W")), file("b", Some("2L"))],
                &signals[..1]
            )
            .is_ok()
        );
    }
}
