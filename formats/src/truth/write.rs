//! The `truth.h5` writer: geometry truth streamed chunk by chunk into resizable HDF5
//! datasets, and the signal truth beside it.

use super::jammers::JammerSets;
use super::{
    ANTENNAS_GROUP, DOPPLER_ACCEL_HZPS2, DOPPLER_HZ, DOPPLER_RATE_HZPS, EPOCH_INDEX,
    NOMINAL_BODY_ATTR, PLATFORM_GROUP, POSITION, ROTATION, SAT_INDEX, SATELLITE_ID,
    SATELLITES_GROUP, SCENARIO_ATTR, SCENARIO_TOML_ATTR, START_EPOCH_ATTR, T_S, TIME_GROUP,
    TRUE_BODY_ATTR, VELOCITY, VISIBLE,
};
use crate::h5::{append_rows, create_group, create_rows, create_versioned_file, text_attr};
use hdf5::types::VarLenUnicode;
use hdf5::{Dataset, Group, H5Type, Location};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use skyforge_signals::antenna::Antenna;
use skyforge_signals::interference::{Jammer, JammerLink};
use skyforge_signals::synth::render::LinkTruth;
use skyforge_signals::synth::{SinkError, TruthSink};
use skyforge_signals::truth::{GeometryChunk, LinkGeometry};
use std::path::{Path, PathBuf};

/// Schema version written to the root attribute `schema_version`.
pub const SCHEMA_VERSION: &str = "1";

/// Rows per HDF5 chunk along the time axis.
const TIME_CHUNK: usize = 600;
/// Values per HDF5 chunk of the per-link datasets.
const LINK_CHUNK: usize = 8192;

/// A dataset of per-record values: name, unit, description, accessor.
type Field<R> = (&'static str, &'static str, &'static str, fn(&R) -> f64);

/// Per-link datasets of an antenna: one value per visible link, in row-major order of the
/// `[epoch, satellite]` `visible` mask (so `dense[visible == 1] = field`).
const LINK_FIELDS: &[Field<LinkGeometry>] = &[
    (
        "range_m",
        "m",
        "geometric range c*tau, antenna phase centre to satellite APC",
        |l| l.range_m,
    ),
    ("range_rate_mps", "m/s", "d(range)/dt", |l| l.range_rate_mps),
    ("range_accel_mps2", "m/s^2", "d2(range)/dt2", |l| {
        l.range_accel_mps2
    }),
    ("range_jerk_mps3", "m/s^3", "d3(range)/dt3", |l| {
        l.range_jerk_mps3
    }),
    (
        DOPPLER_HZ,
        "Hz",
        "geometric Doppler -range_rate/lambda at the satellite's carrier",
        |l| l.doppler_hz,
    ),
    (DOPPLER_RATE_HZPS, "Hz/s", "d(doppler)/dt", |l| {
        l.doppler_rate_hzps
    }),
    (DOPPLER_ACCEL_HZPS2, "Hz/s^2", "d2(doppler)/dt2", |l| {
        l.doppler_accel_hzps2
    }),
    ("light_time_s", "s", "signal travel time tau", |l| {
        l.light_time_s
    }),
    (
        "azimuth_rad",
        "rad",
        "azimuth in the local NED frame of the antenna",
        |l| l.azimuth_rad,
    ),
    (
        "elevation_rad",
        "rad",
        "elevation above the local horizon of the antenna",
        |l| l.elevation_rad,
    ),
    (
        "antenna_azimuth_rad",
        "rad",
        "azimuth in the antenna frame",
        |l| l.antenna_azimuth_rad,
    ),
    (
        "antenna_elevation_rad",
        "rad",
        "90 deg minus the off-boresight angle",
        |l| l.antenna_elevation_rad,
    ),
    (
        "sat_clock_s",
        "s",
        "satellite clock offset at transmit time incl. relativity, excl. TGD",
        |l| l.sat_clock_s,
    ),
    (
        "sat_clock_drift",
        "s/s",
        "satellite clock drift at transmit time",
        |l| l.sat_clock_drift,
    ),
];

/// Per-link datasets written only for runs with `[errors.satellite]` (same layout as
/// [`LINK_FIELDS`]).
const SATELLITE_ERROR_FIELDS: &[Field<LinkGeometry>] = &[
    (
        "sat_orbit_error_m",
        "m",
        "satellite orbit error (true - broadcast APC at transmit time) along the line of sight: added to the range",
        |l| l.sat_orbit_error_m,
    ),
    (
        "sat_clock_error_m",
        "m",
        "c x satellite clock error (true - broadcast, in sat_clock_s): taken off the pseudorange",
        |l| l.sat_clock_error_m,
    ),
];

/// The per-link datasets of a run, with or without the satellite-error ones.
fn link_fields(satellite_errors: bool) -> impl Iterator<Item = &'static Field<LinkGeometry>> {
    let extra = if satellite_errors {
        SATELLITE_ERROR_FIELDS
    } else {
        &[]
    };
    LINK_FIELDS.iter().chain(extra)
}

/// Run metadata written as root attributes.
#[derive(Debug, Clone)]
pub struct RunMeta {
    pub scenario: String,
    pub source: String,
    /// The scenario file's text, so that the truth says what was run (fault events).
    pub text: String,
    pub start_epoch: String,
    pub seed: u64,
    pub step_s: f64,
    /// The run has satellite-side errors: their per-link truth is written.
    pub satellite_errors: bool,
}

impl RunMeta {
    /// The metadata of a run of `scenario` from `start` with geometry step `step_s`.
    pub fn new(
        scenario: &skyforge_scenarios::Scenario,
        start: hifitime::Epoch,
        step_s: f64,
    ) -> Self {
        Self {
            scenario: scenario.name.clone(),
            source: scenario.source.clone(),
            text: scenario.text.clone(),
            start_epoch: start.to_string(),
            seed: scenario.seed,
            step_s,
            satellite_errors: scenario.errors.satellite.is_some(),
        }
    }
}

/// Streams geometry chunks into `truth.h5`; a synthesis session's truth sink.
#[derive(Debug)]
pub struct TruthWriter {
    path: PathBuf,
    file: hdf5::File,
    t_s: Dataset,
    platform: [Dataset; 4],
    antennas: Vec<AntennaSets>,
    /// Per antenna: the signal-truth datasets, once created.
    signal: Vec<SignalSets>,
    rows: usize,
    n_sat: usize,
    /// The `jammers` group, once a run with jammers writes it.
    jammers: Option<JammerSets>,
    /// The antennas' names, in the run's order.
    antenna_names: Vec<String>,
}

/// Signal truth of one antenna: one row per link and truth epoch.
#[derive(Debug)]
struct SignalSets {
    t_s: Dataset,
    sat_index: Dataset,
    /// Row of the group's `signals` attribute, when a satellite transmits several.
    signal_index: Option<(Dataset, Vec<Signal>)>,
    /// One dataset per entry of [`SIGNAL_FIELDS`].
    fields: Vec<Dataset>,
    rows: usize,
}

/// Signal-truth datasets (docs/truth-h5.md).
const SIGNAL_FIELDS: &[Field<LinkTruth>] = &[
    (
        "pseudorange_m",
        "m",
        "c (receive time in receiver time - transmit time in satellite time), direct path",
        |r| r.pseudorange_m,
    ),
    (
        "carrier_phase_cycles",
        "cycles",
        "accumulated carrier phase, RINEX sign, integer ambiguity zero, direct path",
        |r| r.carrier_phase_cycles,
    ),
    ("doppler_hz", "Hz", "minus the carrier-phase rate", |r| {
        r.doppler_hz
    }),
    (
        "cn0_dbhz",
        "dB-Hz",
        "C/N0 of the direct path, events included",
        |r| r.cn0_dbhz,
    ),
    (
        "iono_m",
        "m",
        "ionospheric group delay in the pseudorange; the carrier phase carries -iono_m",
        |r| r.iono_m,
    ),
    (
        "tropo_m",
        "m",
        "tropospheric delay (code and carrier)",
        |r| r.tropo_m,
    ),
    (
        "antenna_m",
        "m",
        "phase-centre offset and variation delay (code and carrier)",
        |r| r.antenna_m,
    ),
    (
        "rx_clock_m",
        "m",
        "c x receiver clock offset (code and carrier)",
        |r| r.rx_clock_m,
    ),
    (
        "sat_clock_m",
        "m",
        "c x satellite clock offset at transmit time (subtracted)",
        |r| r.sat_clock_m,
    ),
    ("event_code_m", "m", "code delay of active events", |r| {
        r.event_code_m
    }),
    (
        "event_carrier_cycles",
        "cycles",
        "carrier phase of active events",
        |r| r.event_carrier_cycles,
    ),
    (
        "multipath_code_m",
        "m",
        "DLL error from reflections, non-coherent early-minus-late, 1 chip spacing",
        |r| r.multipath_code_m,
    ),
    (
        "multipath_carrier_m",
        "m",
        "carrier-phase error from reflections, prompt on the direct path",
        |r| r.multipath_carrier_m,
    ),
];

/// The datasets of one antenna and how many links they hold.
#[derive(Debug)]
struct AntennaSets {
    visible: Dataset,
    epoch_index: Dataset,
    sat_index: Dataset,
    fields: Vec<Dataset>,
    links: usize,
}

fn f64_attr(loc: &Location, name: &str, values: &[f64]) -> hdf5::Result<()> {
    loc.new_attr::<f64>()
        .shape([values.len()])
        .create(name)?
        .write_raw(values)
}

/// Create a resizable dataset: 1-D (`width == 0`) or `[epoch, width]`; 1-D datasets other
/// than `t_s` hold one value per link and are chunked by [`LINK_CHUNK`].
fn series<T: H5Type>(
    group: &Group,
    name: &str,
    width: usize,
    unit: &str,
    description: &str,
) -> hdf5::Result<Dataset> {
    let chunk_rows = if width == 0 && name != T_S {
        LINK_CHUNK
    } else {
        TIME_CHUNK
    };
    create_rows::<T>(group, name, width, chunk_rows, unit, description)
}

/// Upper bound of the bytes of a `truth.h5` of `epochs` geometry epochs, `n_ant` antennas,
/// `n_sats` satellites (every link counted as visible) and `signal_records` signal-truth
/// records, with the satellite-error datasets where `satellite_errors`: the raw values
/// (integer masks and indices counted uncompressed), one partly filled chunk per dataset
/// and 1 MiB of metadata. Saturates at `u64::MAX`.
pub fn size_bound(
    epochs: u64,
    n_ant: u64,
    n_sats: u64,
    signal_records: u64,
    satellite_errors: bool,
) -> u64 {
    let platform = epochs * 8 * (1 + 3 + 3 + 4 + 3);
    let n_fields = link_fields(satellite_errors).count() as u64;
    let link = 4 + 2 + 8 * n_fields;
    let geometry = epochs * n_ant * n_sats * (1 + link);
    let signal = signal_records.saturating_mul(8 + 2 + 8 * SIGNAL_FIELDS.len() as u64);
    let datasets = 5 + n_ant * (3 + n_fields + 2 + SIGNAL_FIELDS.len() as u64);
    let partial_chunks = datasets * (LINK_CHUNK.max(TIME_CHUNK * n_sats as usize) as u64 * 8);
    [platform, geometry, partial_chunks, 1 << 20]
        .into_iter()
        .fold(signal, u64::saturating_add)
}

impl TruthWriter {
    /// Create the file and its (empty, resizable) datasets.
    pub fn create(
        path: &Path,
        meta: &RunMeta,
        sats: &[SatId],
        antennas: &[Antenna],
    ) -> hdf5::Result<Self> {
        let file = create_versioned_file(
            path,
            SCHEMA_VERSION,
            concat!("skyforge ", env!("CARGO_PKG_VERSION")),
        )?;
        text_attr(&file, SCENARIO_ATTR, &meta.scenario)?;
        text_attr(&file, "scenario_source", &meta.source)?;
        text_attr(&file, SCENARIO_TOML_ATTR, &meta.text)?;
        text_attr(&file, START_EPOCH_ATTR, &meta.start_epoch)?;
        file.new_attr::<u64>()
            .create("seed")?
            .write_scalar(&meta.seed)?;
        f64_attr(&file, "step_s", &[meta.step_s])?;

        let time = create_group(&file, TIME_GROUP)?;
        let t_s = series::<f64>(
            &time,
            T_S,
            0,
            "s",
            "receive time, seconds since start_epoch (GPST)",
        )?;
        let pg = create_group(&file, PLATFORM_GROUP)?;
        let platform = [
            series::<f64>(
                &pg,
                POSITION,
                3,
                "m",
                "centre-of-mass position, ECEF (WGS-84)",
            )?,
            series::<f64>(&pg, VELOCITY, 3, "m/s", "centre-of-mass velocity, ECEF")?,
            series::<f64>(
                &pg,
                ROTATION,
                4,
                "1",
                "body-to-ECEF rotation quaternion (w, x, y, z)",
            )?,
            series::<f64>(
                &pg,
                "attitude_ypr_rad",
                3,
                "rad",
                "yaw, pitch, roll (3-2-1) of the body relative to the reference frame (orbital for a LEO, NED otherwise)",
            )?,
        ];
        let sg = create_group(&file, SATELLITES_GROUP)?;
        let ids: Vec<VarLenUnicode> = sats
            .iter()
            .filter_map(|s| s.to_string().parse().ok())
            .collect();
        sg.new_dataset_builder()
            .obj_track_times(false)
            .with_data(&ids)
            .create(SATELLITE_ID)?;
        let carriers: Vec<f64> = sats
            .iter()
            .map(|s| Signal::of_system(s.system).carrier_hz())
            .collect();
        let ds = sg
            .new_dataset_builder()
            .with_data(&carriers)
            .create("carrier_hz")?;
        text_attr(&ds, "units", "Hz")?;

        let ag = create_group(&file, ANTENNAS_GROUP)?;
        let mut ants = Vec::new();
        for ant in antennas {
            let g = create_group(&ag, ant.name.as_str())?;
            f64_attr(&g, NOMINAL_BODY_ATTR, ant.nominal_body_m.as_slice())?;
            f64_attr(&g, TRUE_BODY_ATTR, ant.true_body_m.as_slice())?;
            f64_attr(&g, "boresight_body", ant.boresight_body.as_slice())?;
            f64_attr(&g, "fov_half_angle_rad", &[ant.fov_half_angle_rad])?;
            f64_attr(&g, "elevation_mask_rad", &[ant.elevation_mask_rad])?;
            f64_attr(&g, "pco_m", ant.pco_m.as_slice())?;
            let fields = link_fields(meta.satellite_errors)
                .map(|(name, unit, desc, _)| series::<f64>(&g, name, 0, unit, desc))
                .collect::<hdf5::Result<Vec<_>>>()?;
            ants.push(AntennaSets {
                visible: series::<u8>(
                    &g,
                    VISIBLE,
                    sats.len(),
                    "1",
                    "1 when inside field of view and mask and not Earth-blocked",
                )?,
                epoch_index: series::<u32>(
                    &g,
                    EPOCH_INDEX,
                    0,
                    "1",
                    "row of time/t_s of each visible link",
                )?,
                sat_index: series::<u16>(
                    &g,
                    SAT_INDEX,
                    0,
                    "1",
                    "row of satellites/id of each visible link",
                )?,
                fields,
                links: 0,
            });
        }
        Ok(Self {
            path: path.to_path_buf(),
            file,
            t_s,
            platform,
            antennas: ants,
            signal: Vec::new(),
            rows: 0,
            n_sat: sats.len(),
            jammers: None,
            antenna_names: antennas.iter().map(|a| a.name.clone()).collect(),
        })
    }

    /// Create the signal-truth datasets `antennas/<name>/signal/*` (one row per visible
    /// link, signal and truth epoch) for the transmitted `signals`; when a satellite
    /// transmits several, each row says which (`signal_index`, a row of the group's
    /// `signals` attribute).
    pub fn create_signal(&mut self, antennas: &[Antenna], signals: &[Signal]) -> hdf5::Result<()> {
        let several = signals
            .iter()
            .enumerate()
            .any(|(i, s)| signals[..i].iter().any(|o| o.system() == s.system()));
        for ant in antennas {
            let antenna = self.file.group(&format!("{ANTENNAS_GROUP}/{}", ant.name))?;
            let g = create_group(&antenna, "signal")?;
            let signal_index = if several {
                let tags: Vec<&str> = signals.iter().map(|s| s.tag()).collect();
                text_attr(&g, "signals", &tags.join(" "))?;
                let ds = series::<u8>(&g, "signal_index", 0, "1", "row of the signals attribute")?;
                Some((ds, signals.to_vec()))
            } else {
                None
            };
            self.signal.push(SignalSets {
                signal_index,
                t_s: series::<f64>(
                    &g,
                    T_S,
                    0,
                    "s",
                    "receive time in receiver-clock time (block start)",
                )?,
                sat_index: series::<u16>(&g, SAT_INDEX, 0, "1", "row of satellites/id")?,
                fields: SIGNAL_FIELDS
                    .iter()
                    .map(|(name, unit, desc, _)| series::<f64>(&g, name, 0, unit, desc))
                    .collect::<hdf5::Result<_>>()?,
                rows: 0,
            });
        }
        Ok(())
    }

    /// Append signal-truth records of antenna `a`; a record's transmitter `tx` is
    /// satellite `sat_index[tx]` of `satellites/id`.
    pub fn append_signal(
        &mut self,
        a: usize,
        records: &[LinkTruth],
        sat_index: &[usize],
    ) -> hdf5::Result<()> {
        let Some(sets) = self.signal.get_mut(a) else {
            return Ok(());
        };
        let rows = sets.rows;
        let col = |f: fn(&LinkTruth) -> f64| records.iter().map(f).collect::<Vec<f64>>();
        append_rows(&sets.t_s, rows, &col(|r| r.t_s), 0)?;
        let sats: Vec<u16> = records.iter().map(|r| sat_index[r.tx] as u16).collect();
        append_rows(&sets.sat_index, rows, &sats, 0)?;
        if let Some((ds, signals)) = &sets.signal_index {
            let index: Vec<u8> = records
                .iter()
                .map(|r| signals.iter().position(|&s| s == r.signal).unwrap_or(0) as u8)
                .collect();
            append_rows(ds, rows, &index, 0)?;
        }
        for (ds, (_, _, _, get)) in sets.fields.iter().zip(SIGNAL_FIELDS) {
            append_rows(ds, rows, &col(*get), 0)?;
        }
        sets.rows += records.len();
        Ok(())
    }

    /// Append one chunk of epochs.
    pub fn append(&mut self, chunk: &GeometryChunk) -> hdf5::Result<()> {
        let rows = self.rows;
        append_rows(&self.t_s, rows, &chunk.t_s, 0)?;
        let mut r = Vec::with_capacity(3 * chunk.t_s.len());
        let mut v = Vec::with_capacity(3 * chunk.t_s.len());
        let mut q = Vec::with_capacity(4 * chunk.t_s.len());
        let mut ypr = Vec::with_capacity(3 * chunk.t_s.len());
        for st in &chunk.platform {
            r.extend(st.r_ecef_m.iter());
            v.extend(st.v_ecef_mps.iter());
            let quat = nalgebra::UnitQuaternion::from_matrix(&st.c_body_ecef);
            q.extend([quat.w, quat.i, quat.j, quat.k]);
            ypr.extend([
                st.attitude.yaw_rad,
                st.attitude.pitch_rad,
                st.attitude.roll_rad,
            ]);
        }
        for (ds, data, w) in [
            (&self.platform[0], &r, 3),
            (&self.platform[1], &v, 3),
            (&self.platform[2], &q, 4),
            (&self.platform[3], &ypr, 3),
        ] {
            append_rows(ds, rows, data, w)?;
        }
        let n = chunk.t_s.len();
        let mut vis = vec![0u8; n * self.n_sat];
        for (a, sets) in self.antennas.iter_mut().enumerate() {
            let (mut epochs, mut sats) = (Vec::new(), Vec::new());
            for k in 0..n {
                for s in 0..self.n_sat {
                    let visible = chunk.link(k, a, s).visible;
                    vis[k * self.n_sat + s] = u8::from(visible);
                    if visible {
                        epochs.push((rows + k) as u32);
                        sats.push(s as u16);
                    }
                }
            }
            append_rows(&sets.visible, rows, &vis, self.n_sat)?;
            append_rows(&sets.epoch_index, sets.links, &epochs, 0)?;
            append_rows(&sets.sat_index, sets.links, &sats, 0)?;
            let mut values = Vec::with_capacity(epochs.len());
            for ((_, _, _, get), ds) in link_fields(true).zip(&sets.fields) {
                values.clear();
                values.extend(
                    epochs
                        .iter()
                        .zip(&sats)
                        .map(|(&k, &s)| get(chunk.link(k as usize - rows, a, s as usize))),
                );
                append_rows(ds, sets.links, &values, 0)?;
            }
            sets.links += epochs.len();
        }
        self.rows += n;
        Ok(())
    }

    /// Flush and close.
    pub fn finish(self) -> hdf5::Result<()> {
        self.file.flush()?;
        self.file.close()
    }

    /// `error` with the file it concerns.
    fn writing(&self, error: hdf5::Error) -> SinkError {
        format!("cannot write {}: {error}", self.path.display()).into()
    }
}

impl TruthSink for TruthWriter {
    fn signal(
        &mut self,
        antenna: usize,
        records: &[LinkTruth],
        sat_index: &[usize],
    ) -> Result<(), SinkError> {
        self.append_signal(antenna, records, sat_index)
            .map_err(|e| self.writing(e))
    }

    fn geometry(&mut self, chunk: &GeometryChunk) -> Result<(), SinkError> {
        self.append(chunk).map_err(|e| self.writing(e))
    }

    fn jammers(
        &mut self,
        t_s: f64,
        jammers: &[Jammer],
        links: &[JammerLink],
    ) -> Result<(), SinkError> {
        let sets = match self.jammers.as_mut() {
            Some(sets) => sets,
            None => {
                let made = JammerSets::create(&self.file, jammers, &self.antenna_names);
                self.jammers.insert(made.map_err(|e| self.writing(e))?)
            }
        };
        let on: Vec<bool> = jammers.iter().map(|j| j.config.on_at(t_s)).collect();
        let appended = sets.append(t_s, &on, links);
        appended.map_err(|e| self.writing(e))
    }
}
