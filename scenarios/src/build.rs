//! From a checked scenario to the simulation's world: time origin, Earth rotation,
//! ephemerides, platform and antennas. Checks that need files run here; nothing is
//! written anywhere.

use crate::checks;
use crate::error::ScenarioError;
use crate::parse::locate_invalid;
use crate::schema::Scenario;
use skyforge_orbits::check::{Invalid, shown};
use skyforge_orbits::ephemeris::read_sp3;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, EphemerisStore, NavMessage, SatId, System, nominal,
};
use skyforge_orbits::ephemeris::{ConstellationConfig, ConstellationSource};
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::platform::{
    EDGE_MARGIN_S, Platform, PlatformError, PlatformKind, PlatformWindow,
};
use skyforge_orbits::propagate::PropagateError;
use skyforge_orbits::time::{GstGpsOffset, TimeOrigin};
use skyforge_signals::antenna::{Antenna, AntennaConfig};
use skyforge_signals::errors::{
    SatelliteErrorConfig, SatelliteErrors, SatelliteModel, precise_orbits,
};
use skyforge_signals::synth::SynthWorld;
use skyforge_signals::truth::{GeometryChunk, GeometryTruth, StreamError};
use std::path::Path;

/// Everything a simulation run needs, built from a [`Scenario`].
#[derive(Debug)]
pub struct World {
    /// `t = 0` of the scenario.
    pub origin: TimeOrigin,
    /// ECI <-> ECEF rotation of the scenario.
    pub earth: EarthRotation,
    /// Ephemerides of every enabled constellation (after the `prns` filters).
    pub ephemerides: EphemerisStore,
    /// Satellites with at least one ephemeris, in order.
    pub satellites: Vec<SatId>,
    /// The receiving platform.
    pub platform: Platform,
    /// The resolved antennas, in file order.
    pub antennas: Vec<Antenna>,
    /// Length of the span (s).
    pub duration_s: f64,
    /// Truth geometry step (s) = 1 / `truth.geometry_rate_hz`.
    pub step_s: f64,
    /// GST - GPST (`[gnss.galileo] gst_gps_ns`, zero by default).
    pub gst_gps: GstGpsOffset,
    /// The satellites' orbit and clock errors (`[errors.satellite]`; none: the signals
    /// follow the broadcast ephemerides).
    pub satellite_errors: Option<SatelliteErrors>,
}

impl World {
    /// Stream the geometry truth of every antenna and satellite at the world's step over
    /// the whole span, `chunk_epochs` epochs at a time, into `sink` (memory bounded by one
    /// chunk); the platform is propagated as it goes.
    pub fn stream_geometry<E>(
        &mut self,
        chunk_epochs: usize,
        sink: impl FnMut(GeometryChunk) -> Result<(), E>,
    ) -> Result<(), StreamError<E>> {
        let truth = GeometryTruth::new(
            &self.ephemerides,
            &self.satellites,
            &self.antennas,
            self.step_s,
        )
        .with_gst_gps(self.gst_gps);
        let truth = match &self.satellite_errors {
            Some(errors) => truth.with_satellite_errors(errors),
            None => truth,
        };
        truth.stream(&mut self.platform, self.duration_s, chunk_epochs, sink)
    }

    /// The world as a synthesis session takes it (the session propagates the platform).
    pub fn synth_world(&mut self) -> SynthWorld<'_> {
        SynthWorld {
            origin: &self.origin,
            ephemerides: &self.ephemerides,
            satellites: &self.satellites,
            platform: &mut self.platform,
            antennas: &self.antennas,
            duration_s: self.duration_s,
            gst_gps: self.gst_gps,
            satellite_errors: self.satellite_errors.as_ref(),
        }
    }
}

impl Scenario {
    /// Build the world: load the constellations (embedded or RINEX, `prns` applied), the
    /// platform and the antennas. Fails, located in the scenario text, on a missing or
    /// unreadable navigation file, a file without any healthy ephemeris of its system
    /// valid at the start, a requested PRN without one, or a platform that cannot be
    /// built (unreadable CSV, unusable TLE, a trajectory or attitude table that does not
    /// cover the span).
    /// The checks of [`crate::parse`] run again first, so a scenario changed after parsing
    /// (a field set by the caller) cannot build an impossible world.
    pub fn build(&self) -> Result<World, ScenarioError> {
        checks::check(self).map_err(|e| self.located(e))?;
        if !self.vehicles.is_empty() {
            return Err(self.located(Invalid::new(
                "vehicles",
                format!("{} vehicles", self.vehicles.len()),
                "a scenario with several vehicles runs one vehicle at a time (`skyforge run` and `synth` do; other commands take one platform)",
            )));
        }
        let origin = TimeOrigin::new(self.time.start);
        let earth = EarthRotation::at_origin(self.time.start);
        let mut ephemerides = EphemerisStore::default();
        for (system, table, config) in self.gnss.tables() {
            if config.enabled {
                ephemerides.extend(self.constellation(system, table, config, &origin)?);
            }
        }
        let satellites = ephemerides.satellites();
        let platform = self.platform(&origin)?;
        let antennas = self.antennas.iter().map(AntennaConfig::resolve).collect();
        let satellite_errors = match &self.errors.satellite {
            None => None,
            Some(c) if c.model == SatelliteModel::Precise => {
                Some(self.precise_errors(c, &origin, &ephemerides, &satellites)?)
            }
            Some(c) => Some(SatelliteErrors::draw(
                c,
                self.seed,
                &satellites,
                self.time.duration_s,
            )),
        };
        Ok(World {
            origin,
            earth,
            ephemerides,
            satellites,
            platform,
            antennas,
            duration_s: self.time.duration_s,
            step_s: 1.0 / self.truth.geometry_rate_hz,
            gst_gps: self.gnss.galileo.gst_gps(&origin),
            satellite_errors,
        })
    }

    /// One constellation's ephemerides, bound to `origin`, filtered and checked.
    fn constellation(
        &self,
        system: System,
        table: &str,
        config: &ConstellationConfig,
        origin: &TimeOrigin,
    ) -> Result<EphemerisStore, ScenarioError> {
        let start = self.time.start;
        let (all, field, value, described) = match config.source {
            ConstellationSource::Embedded => {
                let all = match system {
                    System::Gps => nominal::gps(start),
                    System::Beidou => nominal::beidou(config.embedded_set, start),
                    System::Galileo => nominal::galileo(start),
                };
                let described = "the embedded constellation".to_string();
                (
                    all,
                    format!("{table}.source"),
                    "\"embedded\"".into(),
                    described,
                )
            }
            ConstellationSource::Rinex => {
                let field = format!("{table}.nav_file");
                let Some(nav_file) = &config.nav_file else {
                    return Err(self.located(Invalid::new(
                        field,
                        "(missing)",
                        "required when source = \"rinex\"",
                    )));
                };
                let path = self.base_dir.join(nav_file);
                let value = format!("{:?}", nav_file.display().to_string());
                let all = self.read_nav(&path).map_err(|message| {
                    self.located(Invalid::new(field.clone(), value.clone(), message))
                })?;
                (all, field, value, path.display().to_string())
            }
        };
        // One message per system: the one of the signal SkyForge transmits (Galileo's
        // F/NAV; a file's I/NAV sets, with the same orbits but the E1/E5b clock, are left).
        let message = NavMessage::default_for(system);
        let of_system: Vec<BroadcastEphemeris> = all
            .into_iter()
            .filter(|e| e.sat.system == system && e.message == message)
            .collect();
        let mut store = EphemerisStore::new(of_system, origin);
        let usable_at_start = store
            .satellites()
            .into_iter()
            .any(|sat| store.select(sat, 0.0).is_some());
        if !usable_at_start {
            return Err(self.located(Invalid::new(
                field,
                value,
                format!(
                    "{described} has no healthy {} ephemeris valid at the scenario start \
                     ({start}); use a file for the scenario's day",
                    match system {
                        System::Galileo => "Galileo F/NAV",
                        _ => system.name(),
                    }
                ),
            )));
        }
        if let Some(prns) = &config.prns {
            store.retain(|sat| prns.contains(&sat.prn));
            for (i, &prn) in prns.iter().enumerate() {
                let sat = SatId { system, prn };
                if store.select(sat, 0.0).is_none() {
                    return Err(self.located(Invalid::new(
                        format!("{table}.prns[{i}]"),
                        prn,
                        format!(
                            "{sat} has no healthy ephemeris valid at the scenario start \
                             ({start}) in {described}"
                        ),
                    )));
                }
            }
        }
        Ok(store)
    }

    /// Read a navigation file; a missing or unreadable file becomes a message (a
    /// directory or a device such as `/dev/zero` is named as what it is by the reader).
    fn read_nav(&self, path: &Path) -> Result<Vec<BroadcastEphemeris>, String> {
        if !path.exists() {
            return Err(format!(
                "must name a readable RINEX navigation file; {} does not exist \
                 (relative paths start at {})",
                path.display(),
                self.base_dir.display()
            ));
        }
        read_nav_file(path).map_err(|e| format!("cannot use the navigation file: {e}"))
    }

    /// The precise orbits and clocks of `[errors.satellite] model = "precise"` for
    /// `satellites`, against the broadcast `store`. Fails, located at `sp3`, on a missing
    /// or unreadable file, or one with no satellite of the scenario over the whole span.
    fn precise_errors(
        &self,
        config: &SatelliteErrorConfig,
        origin: &TimeOrigin,
        store: &EphemerisStore,
        satellites: &[SatId],
    ) -> Result<SatelliteErrors, ScenarioError> {
        let sp3 = config.sp3.as_deref().unwrap_or(Path::new(""));
        let path = self.base_dir.join(sp3);
        let invalid = |message: String| {
            self.located(Invalid::new(
                "errors.satellite.sp3",
                format!("{:?}", sp3.display().to_string()),
                message,
            ))
        };
        if !path.is_file() {
            return Err(invalid(format!(
                "must name a readable SP3 file; {} is not one (relative paths start at {})",
                path.display(),
                self.base_dir.display()
            )));
        }
        let records =
            read_sp3(&path).map_err(|e| invalid(format!("cannot use the SP3 file: {e}")))?;
        let orbits = precise_orbits(&records, origin, store, satellites, self.time.duration_s);
        if orbits.is_empty() {
            return Err(invalid(format!(
                "holds no satellite of the scenario from 10 min before its start ({}) to 10 \
                 min after its end; use the SP3 file of the scenario's day",
                origin.start()
            )));
        }
        Ok(SatelliteErrors::precise(orbits))
    }

    /// The platform's motion over the run for its IMU: `None` without `[imu]`. The checks
    /// already refused an IMU on a platform without kinematics (a LEO, a trajectory CSV).
    pub fn imu_motion(&self) -> Result<Option<PlatformWindow>, ScenarioError> {
        if self.imu.is_none() {
            return Ok(None);
        }
        let mut platform = self.platform(&TimeOrigin::new(self.time.start))?;
        (platform.window(0.0, self.time.duration_s))
            .map(Some)
            .map_err(|e| self.platform_error(e))
    }

    /// The platform of `[platform]`, with its CSV tables checked to cover the span.
    fn platform(&self, origin: &TimeOrigin) -> Result<Platform, ScenarioError> {
        let located = |e: PlatformError| self.platform_error(e);
        let mut platform =
            Platform::new(&self.platform, origin, &self.base_dir).map_err(located)?;
        let end_s = self.time.duration_s;
        if let Some((first_s, last_s)) = platform.attitude().span() {
            let covered = first_s - EDGE_MARGIN_S..=last_s + EDGE_MARGIN_S;
            if !covered.contains(&0.0) || !covered.contains(&end_s) {
                return Err(located(PlatformError::OutsideAttitude {
                    t_s: if covered.contains(&0.0) { end_s } else { 0.0 },
                    first_s,
                    last_s,
                }));
            }
        }
        if matches!(
            platform.kind(),
            PlatformKind::Trajectory | PlatformKind::Segments
        ) {
            // Cheap for a trajectory or legs (shared data); checks that they cover the span.
            platform.window(0.0, end_s).map_err(located)?;
        }
        Ok(platform)
    }

    /// A platform error met while building or moving the platform (an orbit that decays
    /// during the run), located at the field that caused it: the scenario's fault.
    pub fn platform_error(&self, error: PlatformError) -> ScenarioError {
        self.located(self.platform_invalid(error))
    }

    /// A platform error, attributed to the field that caused it.
    fn platform_invalid(&self, error: PlatformError) -> Invalid {
        let message = error.to_string();
        let cfg = &self.platform;
        let quoted = |path: &Path| format!("{:?}", path.display().to_string());
        match error {
            PlatformError::Config(invalid) => invalid.within("platform"),
            PlatformError::Csv { path, .. } => {
                let path = Path::new(&path);
                let field = if cfg
                    .trajectory
                    .as_ref()
                    .is_some_and(|t| path.ends_with(&t.csv))
                {
                    "platform.trajectory.csv"
                } else if cfg.attitude.csv.as_ref().is_some_and(|c| path.ends_with(c)) {
                    "platform.attitude.csv"
                } else {
                    "platform"
                };
                Invalid::new(field, quoted(path), message)
            }
            PlatformError::OutsideTrajectory { .. } => {
                let value = cfg.trajectory.as_ref().map(|t| quoted(&t.csv));
                Invalid::new(
                    "platform.trajectory.csv",
                    value.unwrap_or_default(),
                    format!(
                        "must cover the scenario span 0..{} s: {message}",
                        self.time.duration_s
                    ),
                )
            }
            PlatformError::OutsideSegments { last_s, .. } => Invalid::new(
                "platform.segments.legs",
                format!("{} s in all", shown(last_s)),
                format!("must cover the scenario span 0..{} s", self.time.duration_s),
            ),
            PlatformError::OutsideAttitude { .. } => {
                let value = cfg.attitude.csv.as_ref().map(|c| quoted(c));
                Invalid::new(
                    "platform.attitude.csv",
                    value.unwrap_or_default(),
                    format!(
                        "must cover the scenario span 0..{} s: {message}",
                        self.time.duration_s
                    ),
                )
            }
            PlatformError::Propagate(PropagateError::Tle(_)) => {
                Invalid::new("platform.leo.tle", "", message)
            }
            PlatformError::Propagate(_) => Invalid::new("platform.leo", "", message),
        }
    }

    /// `invalid`, placed in this scenario's text.
    pub fn located(&self, invalid: Invalid) -> ScenarioError {
        locate_invalid(&self.text, &self.source, invalid)
    }
}
