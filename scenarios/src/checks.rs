//! Checks that need no file access: each domain table's own check, prefixed with its
//! table path, plus the cross-field and whole-scenario rules the domain crates cannot see.

use crate::schema::{GnssConfig, Scenario, TimeSpan, TruthConfig, VehicleConfig};
use hifitime::Epoch;
use skyforge_gnss::observation::NOISE_SIGMA0_M;
use skyforge_orbits::check::{Allowed, GROUND_RADIUS_M, Invalid, check_position, check_table};
use skyforge_orbits::ephemeris::System;
use skyforge_orbits::platform::{AttitudeConfig, AxisProfileConfig};
use skyforge_orbits::platform::{GroundConfig, PlatformConfig};
use skyforge_orbits::time::{SUPPORTED_RANGE, TimeError, in_supported_range, parse_epoch};
use skyforge_signals::antenna::AntennaConfig;
use skyforge_signals::errors::EventConfig;
use skyforge_signals::imu::ImuConfig;
use skyforge_signals::interference::{JammerWaveform, MAX_JAMMERS};
use skyforge_signals::obs_model::{Level, ObsNoiseConfig};

/// Longest scenario (s): 366 days. Longer spans are outside what the embedded
/// constellations (no station keeping) and broadcast ephemerides describe.
pub(crate) const MAX_DURATION_S: f64 = 366.0 * 86_400.0;
/// Highest truth geometry rate (Hz); the signal stage interpolates between samples.
pub(crate) const MAX_GEOMETRY_RATE_HZ: f64 = 1000.0;
/// Most antennas on one platform: arrays of a few to 16 elements are what attitude and
/// beam-forming receivers carry; each antenna adds a recording per band and its truth.
pub(crate) const MAX_ANTENNAS: usize = 64;
/// Ground-site height limits (m above the WGS-84 ellipsoid): below the lowest dry land
/// (about -430 m) with margin, up to the Karman line. `ecef_m` is checked against
/// `orbits::check::GROUND_RADIUS_M`, these widened by the Earth's radii.
const GROUND_HEIGHT_M: Allowed = Allowed::closed(-1_000.0, 100_000.0, "m above the ellipsoid");
const LATITUDE_DEG: Allowed = Allowed::closed(-90.0, 90.0, "deg");
const LONGITUDE_DEG: Allowed = Allowed::closed(-360.0, 360.0, "deg (east positive)");

/// Most vehicles in one scenario: a chaser and a target, a base and rovers, a formation.
pub(crate) const MAX_VEHICLES: usize = 16;

/// The platform and antennas a scenario runs (or its first vehicle's): exactly one of
/// `[platform]` (with `[[antennas]]`) and `[[vehicles]]` (each with its own).
pub(crate) fn platform_or_vehicles(
    platform: Option<PlatformConfig>,
    antennas: Vec<AntennaConfig>,
    vehicles: &[VehicleConfig],
) -> Result<(PlatformConfig, Vec<AntennaConfig>), Invalid> {
    match (platform, vehicles.first()) {
        (Some(p), None) => Ok((p, antennas)),
        (None, Some(v)) if antennas.is_empty() => Ok((v.platform.clone(), v.antennas.clone())),
        (None, Some(_)) => Err(Invalid::new(
            "antennas",
            format!("{} antennas", antennas.len()),
            "with [[vehicles]], every antenna belongs to one: [[vehicles.antennas]]",
        )),
        (Some(_), Some(_)) => Err(Invalid::new(
            "vehicles",
            format!("{} vehicles beside [platform]", vehicles.len()),
            "either one [platform] with its [[antennas]], or [[vehicles]] each with its platform and antennas",
        )),
        (None, None) => Err(Invalid::new(
            "platform",
            "none",
            "a [platform] table is required (or [[vehicles]] for several platforms)",
        )),
    }
}

/// `[[vehicles]]`: at most [`MAX_VEHICLES`], unique names usable as directory names,
/// each platform, antenna list, oscillator and IMU (its own, or the scenario's
/// `shared_imu`) valid.
fn check_vehicles(
    vehicles: &[VehicleConfig],
    shared_imu: Option<&ImuConfig>,
    duration_s: f64,
) -> Result<(), Invalid> {
    if vehicles.len() > MAX_VEHICLES {
        return Err(Invalid::new(
            format!("vehicles[{MAX_VEHICLES}]"),
            format!("{} vehicles", vehicles.len()),
            format!("at most {MAX_VEHICLES} vehicles"),
        ));
    }
    for (i, v) in vehicles.iter().enumerate() {
        let at = |field: &str| format!("vehicles[{i}].{field}");
        let usable = |c: char| c.is_ascii_alphanumeric() || c == '-' || c == '_';
        if v.name.is_empty() || v.name.len() > 32 || !v.name.chars().all(usable) {
            return Err(Invalid::new(
                at("name"),
                format!("{:?}", v.name),
                "1 to 32 letters, digits, '-' or '_' (it names the vehicle's output directory)",
            ));
        }
        if let Some(j) = vehicles[..i].iter().position(|w| w.name == v.name) {
            return Err(Invalid::new(
                at("name"),
                format!("{:?}", v.name),
                format!("must be unique; vehicles[{j}] already has this name"),
            ));
        }
        check_platform(&v.platform).map_err(|e| e.within(&format!("vehicles[{i}]")))?;
        check_antennas(&v.antennas).map_err(|e| e.within(&format!("vehicles[{i}]")))?;
        if let Some(clock) = &v.receiver_clock {
            clock.check().map_err(|e| e.within(&at("receiver_clock")))?;
        }
        match (&v.imu, shared_imu) {
            (Some(imu), _) => check_imu(imu, &v.platform, duration_s, &at("imu"))?,
            (None, Some(imu)) => check_imu(imu, &v.platform, duration_s, "imu")
                .map_err(|e| e.within(&format!("vehicles[{i}]")))?,
            (None, None) => {}
        }
        let names: Vec<&str> = v.antennas.iter().map(|a| a.name.as_str()).collect();
        let list = format!("vehicles[{i}].antennas");
        check_events(
            &v.events,
            &format!("vehicles[{i}]"),
            &list,
            &names,
            duration_s,
        )?;
    }
    Ok(())
}

/// Every check that needs no file, in file order. [`crate::parse`] runs it on the parsed
/// scenario, [`Scenario::build`] again on whatever the caller may have changed since.
pub(crate) fn check(scenario: &Scenario) -> Result<(), Invalid> {
    check_name(&scenario.name)?;
    check_time(&scenario.time, &scenario.gnss)?;
    check_truth(&scenario.truth, scenario.time.duration_s)?;
    check_gnss(&scenario.gnss)?;
    check_vehicles(
        &scenario.vehicles,
        scenario.imu.as_ref(),
        scenario.time.duration_s,
    )?;
    check_platform(&scenario.platform)?;
    check_antennas(&scenario.antennas)?;
    if let (Some(imu), true) = (&scenario.imu, scenario.vehicles.is_empty()) {
        check_imu(imu, &scenario.platform, scenario.time.duration_s, "imu")?;
    }
    scenario
        .errors
        .ionosphere
        .check()
        .map_err(|e| e.within("errors.ionosphere"))?;
    check_errors(scenario)?;
    check_observation(scenario)?;
    check_jammers(scenario)?;
    if let Some(signal) = &scenario.signal {
        signal.check().map_err(|e| e.within("signal"))?;
        let enabled = scenario.gnss.enabled_systems();
        signal
            .check_signals(&enabled)
            .map_err(|e| e.within("signal"))?;
        for s in enabled.into_iter().flat_map(|sys| signal.signals_of(sys)) {
            signal
                .check_band(s.name(), s.main_lobe_half_width_hz())
                .map_err(|e| e.within("signal"))?;
        }
    }
    Ok(())
}

/// `[[jammers]]`: each entry's values (`JammerConfig::check`), unique names; at the
/// signal level samples of a complex format, at the observation level noise jammers only.
fn check_jammers(scenario: &Scenario) -> Result<(), Invalid> {
    let Some(first) = scenario.jammers.first() else {
        return Ok(());
    };
    if scenario.jammers.len() > MAX_JAMMERS {
        return Err(Invalid::new(
            "jammers",
            format!("{} entries", scenario.jammers.len()),
            format!("at most {MAX_JAMMERS}"),
        ));
    }
    for (k, j) in scenario.jammers.iter().enumerate() {
        j.check(scenario.time.duration_s)
            .map_err(|e| e.within(&format!("jammers[{k}]")))?;
        if scenario.jammers[..k].iter().any(|o| o.name == j.name) {
            return Err(Invalid::new(
                format!("jammers[{k}].name"),
                format!("{:?}", j.name),
                "must differ from the other jammers' names",
            ));
        }
    }
    if scenario.observation.level == Level::Observation {
        let cw = scenario
            .jammers
            .iter()
            .position(|j| j.waveform == JammerWaveform::Cw);
        return match cw {
            Some(k) => Err(Invalid::new(
                format!("jammers[{k}].waveform"),
                "\"cw\"",
                "the observation level models noise jammers only (a CW's effect depends on the code's line spectrum: render samples)",
            )),
            None => Ok(()),
        };
    }
    if scenario.signal.as_ref().map(|s| s.format.is_complex()) != Some(true) {
        return Err(Invalid::new(
            "jammers[0].name",
            format!("{:?}", first.name),
            "jammers need [signal] samples of a complex format",
        ));
    }
    Ok(())
}

/// `[observation]`: the observation level needs the `[signal]` table (its C/N0 settings);
/// observed-only signals need the observation level; noise parameters in their ranges
/// (`gnss::observation::NOISE_SIGMA0_M`, `ElevationNoise::check`).
fn check_observation(scenario: &Scenario) -> Result<(), Invalid> {
    let obs = &scenario.observation;
    if obs.level == Level::Observation && scenario.signal.is_none() {
        return Err(Invalid::new(
            "observation.level",
            "\"observation\"",
            "the observation level draws its noise at the links' C/N0: add a [signal] table",
        ));
    }
    if let Some(rate) = obs.rate_hz {
        if obs.level == Level::Signal {
            return Err(Invalid::new(
                "observation.rate_hz",
                rate,
                "sets the observation level's rate; the signal level's is the receiver's ([observables] rate_hz of its configuration)",
            ));
        }
        if !(1..=100).contains(&rate) || !1000u32.is_multiple_of(rate) {
            return Err(Invalid::new(
                "observation.rate_hz",
                rate,
                "a divisor of 1000 from 1 to 100 (1, 2, 4, 5, 8, 10, 20, 25, 40, 50, 100)",
            ));
        }
        let truth = scenario.signal.as_ref().map_or(0, |s| s.truth_rate_hz);
        if !truth.is_multiple_of(rate) {
            return Err(Invalid::new(
                "signal.truth_rate_hz",
                truth,
                format!(
                    "a multiple of [observation] rate_hz = {rate}: the observations are drawn from the signal truth's records"
                ),
            ));
        }
    }
    if obs.level == Level::Signal
        && let Some(s) = obs.observed_signals.first()
    {
        return Err(Invalid::new(
            "observation.observed_signals",
            s.tag(),
            "observed-only signals are drawn at the observation level alone (level = \"observation\"); the signal level synthesises GPS L1 C/A and BDS B1I",
        ));
    }
    match &obs.noise {
        ObsNoiseConfig::Calibrated { .. } => Ok(()),
        ObsNoiseConfig::Constant {
            phase_m,
            code_m,
            doppler_mps,
        } => {
            NOISE_SIGMA0_M.check("observation.noise.phase_m", *phase_m)?;
            NOISE_SIGMA0_M.check("observation.noise.code_m", *code_m)?;
            match doppler_mps {
                Some(d) if !obs.doppler_noise => Err(Invalid::new(
                    "observation.noise.doppler_mps",
                    d,
                    "draws the Doppler's noise only with [observation] doppler_noise = true",
                )),
                Some(d) => NOISE_SIGMA0_M.check("observation.noise.doppler_mps", *d),
                None => Ok(()),
            }
        }
        ObsNoiseConfig::Elevation { phase, code } => {
            phase.check("observation.noise.phase", NOISE_SIGMA0_M)?;
            code.check("observation.noise.code", NOISE_SIGMA0_M)
        }
    }
}

/// `[errors]` beyond the ionosphere: each table's own check, plus what needs the rest of
/// the scenario (antenna names, the span, the clock staying within the renderer's reach).
fn check_errors(scenario: &Scenario) -> Result<(), Invalid> {
    let errors = &scenario.errors;
    errors
        .troposphere
        .check()
        .map_err(|e| e.within("errors.troposphere"))?;
    if let Some(clock) = &errors.receiver_clock {
        clock
            .check()
            .map_err(|e| e.within("errors.receiver_clock"))?;
        // The deterministic part of the clock offset must stay within one geometry
        // interval of true time (the renderer extrapolates the range at most that far).
        let reach = clock.bias_s.abs() + clock.drift.abs() * scenario.time.duration_s;
        if reach > MAX_RECEIVER_CLOCK_OFFSET_S {
            return Err(Invalid::new(
                "errors.receiver_clock.drift",
                clock.drift,
                format!(
                    "|bias_s| + |drift| x duration_s = {reach:.3} s; must stay below {MAX_RECEIVER_CLOCK_OFFSET_S} s"
                ),
            ));
        }
    }
    if let Some(satellite) = &errors.satellite {
        satellite
            .check(scenario.time.duration_s)
            .map_err(|e| e.within("errors.satellite"))?;
    }
    errors
        .multipath
        .check()
        .map_err(|e| e.within("errors.multipath"))?;
    let names: Vec<&str> = scenario.antennas.iter().map(|a| a.name.as_str()).collect();
    errors
        .multipath
        .check_antennas(&names)
        .map_err(|e| e.within("errors.multipath"))?;
    check_events(
        &errors.events,
        "errors",
        "[[antennas]]",
        &names,
        scenario.time.duration_s,
    )
}

/// Each of `events` (at `{prefix}.events[i]`) valid over `duration_s` and on an antenna
/// of `names` (those of `list`) where it names one.
fn check_events(
    events: &[EventConfig],
    prefix: &str,
    list: &str,
    names: &[&str],
    duration_s: f64,
) -> Result<(), Invalid> {
    for (i, event) in events.iter().enumerate() {
        let within = format!("{prefix}.events[{i}]");
        event.check(duration_s).map_err(|e| e.within(&within))?;
        if let Some(a) = event.antenna.as_deref().filter(|a| !names.contains(a)) {
            return Err(Invalid::new(
                format!("{within}.antenna"),
                format!("{a:?}"),
                format!("must name an antenna of {list}: {}", names.join(", ")),
            ));
        }
    }
    Ok(())
}

/// Largest deterministic receiver clock offset over the span (s): one geometry interval.
const MAX_RECEIVER_CLOCK_OFFSET_S: f64 = 1.0;

/// `time.start` as written: an epoch with its time scale.
pub(crate) fn parse_start(text: &str) -> Result<Epoch, Invalid> {
    parse_epoch(text).map_err(|e| {
        let TimeError::Parse { reason, .. } = e;
        Invalid::new(
            "time.start",
            format!("{text:?}"),
            format!("must be an epoch with its time scale: {reason}"),
        )
    })
}

fn check_name(name: &str) -> Result<(), Invalid> {
    if name.trim().is_empty() || name.chars().any(char::is_control) {
        return Err(Invalid::new(
            "name",
            format!("{name:?}"),
            "must be a non-empty name without control characters",
        ));
    }
    Ok(())
}

/// `[time]`: a start in the supported range (and, with BeiDou, not before the BDT epoch);
/// a duration in (0, 366 days].
fn check_time(time: &TimeSpan, gnss: &GnssConfig) -> Result<(), Invalid> {
    let start = time.start;
    let shown = format!("{:?}", start.to_string());
    let bdt_epoch = Epoch::from_bdt_seconds(0.0);
    let gst_epoch = Epoch::from_gst_seconds(0.0);
    if !in_supported_range(start) {
        return Err(Invalid::new(
            "time.start",
            shown,
            format!("must be {SUPPORTED_RANGE}"),
        ));
    }
    if gnss.galileo.enabled && start < gst_epoch {
        return Err(Invalid::new(
            "time.start",
            shown,
            "must not precede the Galileo epoch (1999-08-22T00:00:00 GST) while gnss.galileo \
             is enabled",
        ));
    }
    if gnss.beidou.enabled && start < bdt_epoch {
        return Err(Invalid::new(
            "time.start",
            shown,
            "must not precede the BeiDou epoch (2006-01-01T00:00:00 BDT) while gnss.beidou is \
             enabled",
        ));
    }
    let d = time.duration_s;
    if !(d > 0.0 && d <= MAX_DURATION_S) {
        return Err(Invalid::new(
            "time.duration_s",
            d,
            format!("must be in (0, {MAX_DURATION_S}] s (a non-empty span of at most 366 days)"),
        ));
    }
    Ok(())
}

/// `[truth]`: a rate in (0, 1000] Hz with at least one step inside the span.
fn check_truth(truth: &TruthConfig, duration_s: f64) -> Result<(), Invalid> {
    let rate = truth.geometry_rate_hz;
    if !(rate > 0.0 && rate <= MAX_GEOMETRY_RATE_HZ) {
        return Err(Invalid::new(
            "truth.geometry_rate_hz",
            rate,
            format!("must be in (0, {MAX_GEOMETRY_RATE_HZ}] Hz"),
        ));
    }
    if 1.0 / rate > duration_s {
        return Err(Invalid::new(
            "truth.geometry_rate_hz",
            rate,
            format!(
                "must be >= 1 / time.duration_s = {} Hz (one step must fit in the span)",
                1.0 / duration_s
            ),
        ));
    }
    Ok(())
}

fn check_gnss(gnss: &GnssConfig) -> Result<(), Invalid> {
    for (system, table, config) in gnss.tables() {
        config
            .check(system.max_prn())
            .and_then(|()| config.check_gst_gps(system == System::Galileo))
            .map_err(|e| e.within(table))?;
    }
    if gnss.enabled_systems().is_empty() {
        return Err(Invalid::new(
            "gnss",
            "gps, beidou and galileo disabled",
            "at least one constellation must be enabled",
        ));
    }
    Ok(())
}

/// Most IMU samples in one run: 10^8, a day at 1 kHz (about 20 GB of CSV).
pub(crate) const MAX_IMU_SAMPLES: f64 = 1e8;

/// An IMU: its own checks, a platform whose motion is twice differentiable (a ground
/// site or generated legs), and at most [`MAX_IMU_SAMPLES`] samples over the run.
/// `at` names the table in errors.
fn check_imu(
    imu: &ImuConfig,
    platform: &PlatformConfig,
    duration_s: f64,
    at: &str,
) -> Result<(), Invalid> {
    imu.check().map_err(|e| e.within(at))?;
    if platform.trajectory.is_some() {
        return Err(Invalid::new(
            at,
            "an IMU on [platform.trajectory]",
            "an IMU needs the platform's acceleration and angular rate, which a ground site, \
             [platform.segments] and a LEO define; a trajectory CSV's interpolation does not",
        ));
    }
    let samples = imu.rate_hz * duration_s;
    if samples > MAX_IMU_SAMPLES {
        return Err(Invalid::new(
            format!("{at}.rate_hz"),
            imu.rate_hz,
            format!("gives {samples:.0} samples over the run; at most {MAX_IMU_SAMPLES:e}"),
        ));
    }
    Ok(())
}

/// `[platform]`: exactly one kind, each checked, plus the attitude profile.
fn check_platform(platform: &PlatformConfig) -> Result<(), Invalid> {
    let kinds: Vec<&str> = [
        ("leo", platform.leo.is_some()),
        ("ground", platform.ground.is_some()),
        ("trajectory", platform.trajectory.is_some()),
        ("segments", platform.segments.is_some()),
    ]
    .into_iter()
    .filter_map(|(name, present)| present.then_some(name))
    .collect();
    if kinds.len() != 1 {
        let value = if kinds.is_empty() {
            "none".to_string()
        } else {
            kinds.join(" + ")
        };
        return Err(Invalid::new(
            "platform",
            value,
            "exactly one of [platform.leo], [platform.ground], [platform.trajectory], [platform.segments] is required",
        ));
    }
    if let Some(leo) = &platform.leo {
        leo.check().map_err(|e| e.within("platform.leo"))?;
    }
    if let Some(ground) = &platform.ground {
        check_ground(ground).map_err(|e| e.within("platform.ground"))?;
    }
    if let Some(trajectory) = &platform.trajectory
        && trajectory.csv.as_os_str().is_empty()
    {
        return Err(Invalid::new(
            "platform.trajectory.csv",
            "\"\"",
            "must name a CSV file",
        ));
    }
    check_attitude(&platform.attitude).map_err(|e| e.within("platform.attitude"))
}

/// `[platform.ground]`: all of latitude/longitude/height, or `ecef_m`, on the Earth's
/// surface give or take the height limits.
fn check_ground(g: &GroundConfig) -> Result<(), Invalid> {
    let geodetic = [
        ("latitude_deg", g.latitude_deg),
        ("longitude_deg", g.longitude_deg),
        ("height_m", g.height_m),
    ];
    let given = geodetic.iter().filter(|(_, v)| v.is_some()).count();
    match (given, g.ecef_m) {
        (0, None) => Err(Invalid::new(
            "",
            "no position",
            "give latitude_deg, longitude_deg and height_m, or ecef_m",
        )),
        (0, Some(ecef)) => check_position("ecef_m", &ecef, GROUND_RADIUS_M),
        (_, Some(_)) => Err(Invalid::new(
            "ecef_m",
            "given with latitude/longitude/height",
            "give either latitude_deg, longitude_deg and height_m, or ecef_m, not both",
        )),
        (3, None) => {
            let (lat, lon, h) = (
                g.latitude_deg.unwrap_or_default(),
                g.longitude_deg.unwrap_or_default(),
                g.height_m.unwrap_or_default(),
            );
            LATITUDE_DEG.check("latitude_deg", lat)?;
            LONGITUDE_DEG.check("longitude_deg", lon)?;
            GROUND_HEIGHT_M.check("height_m", h)
        }
        _ => {
            let missing = geodetic
                .iter()
                .find(|(_, v)| v.is_none())
                .map_or("", |(name, _)| *name);
            Err(Invalid::new(
                missing,
                "(missing)",
                "latitude_deg, longitude_deg and height_m must be given together",
            ))
        }
    }
}

/// An attitude profile's angles (deg): one turn either way.
const PROFILE_ANGLE_DEG: Allowed = Allowed::closed(-360.0, 360.0, "deg");
/// An attitude profile's period (s; 0: a constant offset): assumed up to 1e8 s (three
/// years), a constant over any scenario (at most 366 days).
const PROFILE_PERIOD_S: Allowed = Allowed::closed(0.0, 1e8, "s");

/// `[platform.attitude]`: profile values in their ranges, `period_s > 0` when the axis
/// oscillates, and either a CSV or profiles.
fn check_attitude(attitude: &AttitudeConfig) -> Result<(), Invalid> {
    let axes = [
        ("yaw", &attitude.yaw),
        ("pitch", &attitude.pitch),
        ("roll", &attitude.roll),
    ];
    for (name, axis) in axes {
        check_axis(axis).map_err(|e| e.within(name))?;
    }
    if let Some(csv) = &attitude.csv {
        if csv.as_os_str().is_empty() {
            return Err(Invalid::new("csv", "\"\"", "must name a CSV file"));
        }
        let defaults = AxisProfileConfig::default();
        if let Some((name, _)) = axes.iter().find(|(_, axis)| **axis != defaults) {
            return Err(Invalid::new(
                *name,
                "a profile",
                "give either csv or yaw/pitch/roll profiles, not both",
            ));
        }
    }
    Ok(())
}

fn check_axis(axis: &AxisProfileConfig) -> Result<(), Invalid> {
    let values = [
        ("offset_deg", axis.offset_deg, PROFILE_ANGLE_DEG),
        ("amplitude_deg", axis.amplitude_deg, PROFILE_ANGLE_DEG),
        ("period_s", axis.period_s, PROFILE_PERIOD_S),
        ("phase_deg", axis.phase_deg, PROFILE_ANGLE_DEG),
    ];
    check_table(&values)?;
    if axis.period_s == 0.0 && axis.amplitude_deg != 0.0 {
        return Err(Invalid::new(
            "period_s",
            axis.period_s,
            "must be > 0 when amplitude_deg is non-zero (0 means a constant offset)",
        ));
    }
    Ok(())
}

/// `[[antennas]]`: at least one and at most [`MAX_ANTENNAS`], each checked, unique names.
fn check_antennas(antennas: &[AntennaConfig]) -> Result<(), Invalid> {
    if antennas.is_empty() {
        return Err(Invalid::new(
            "antennas",
            "none",
            "at least one [[antennas]] table is required",
        ));
    }
    if antennas.len() > MAX_ANTENNAS {
        return Err(Invalid::new(
            format!("antennas[{MAX_ANTENNAS}]"),
            format!("{} antennas", antennas.len()),
            format!(
                "at most {MAX_ANTENNAS} antennas (each adds a recording per band and its signal truth: see docs/limits.md)"
            ),
        ));
    }
    for (i, antenna) in antennas.iter().enumerate() {
        antenna
            .check()
            .map_err(|e| e.within(&format!("antennas[{i}]")))?;
        if let Some(j) = antennas[..i].iter().position(|a| a.name == antenna.name) {
            return Err(Invalid::new(
                format!("antennas[{i}].name"),
                format!("{:?}", antenna.name),
                format!("must be unique; antennas[{j}] already has this name"),
            ));
        }
    }
    Ok(())
}
