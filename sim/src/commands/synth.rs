//! `skyforge synth`: scenario -> per-antenna I/Q files (+ SigMF metadata, GNSS-SDR
//! configuration), the geometry truth of the transmitted signals, and a RINEX 3.04
//! navigation file of the ephemerides as broadcast.

use crate::BadInput;
use crate::output::rinex_obs::{Calendar, ObsRecord, ObsWriter};
use crate::output::staged_dir::StagedDir;
use crate::output::truth_h5::{RunMeta, TruthWriter};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::rinex_nav_write::write_nav;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId, System};
use skyforge_orbits::time::{bdt_week_sow, gpst_week_sow};
use skyforge_scenarios::{Scenario, World};
use skyforge_signals::errors::clock::ClockModel;
use skyforge_signals::errors::events::EventSchedule;
use skyforge_signals::errors::ionosphere::{IonoModel, KlobucharCoeffs};
use skyforge_signals::errors::seed::stream_rng;
use skyforge_signals::errors::troposphere::TropoModel;
use skyforge_signals::signal::SignalId;
use skyforge_signals::synth::config::BLOCK_S;
use skyforge_signals::synth::config::SignalConfig;
use skyforge_signals::synth::constellation;
use skyforge_signals::synth::filter::BandFilter;
use skyforge_signals::synth::gnss_sdr::{self, PvtCorrections, SignalsPresent};
use skyforge_signals::synth::link_terms::{AntennaEpoch, LinkTerms};
use skyforge_signals::synth::render::Synthesiser;
use skyforge_signals::synth::sigmf::RecordingMeta;
use skyforge_signals::synth::transmitter::Transmitter;
use skyforge_signals::truth::geometry::{GeometryTruth, epoch_count};
use std::io::Write;
use std::path::Path;
use std::time::Instant;

/// Geometry epochs the renderer interpolates between (s).
const GEOMETRY_STEP_S: f64 = 1.0;
/// Geometry epochs per streamed chunk unless `synth --chunk-epochs` says otherwise.
pub const DEFAULT_CHUNK_EPOCHS: u32 = 10;
/// Acquisition Doppler search written into the GNSS-SDR configuration (Hz): ground / LEO.
const DOPPLER_MAX_GROUND_HZ: f64 = 5_000.0;
const DOPPLER_MAX_LEO_HZ: f64 = 50_000.0;

/// Every satellite's ephemeris at the scenario start (the set its message will carry).
fn ephemerides_at_start(world: &World) -> Vec<BroadcastEphemeris> {
    world
        .satellites
        .iter()
        .filter_map(|&s| world.ephemerides.select(s, 0.0).map(|b| b.eph.clone()))
        .collect()
}

/// Error context naming an output file.
fn writing(path: &Path) -> String {
    format!("cannot write {}", path.display())
}

/// The transmitters of one band, written to one recording per antenna.
struct Band {
    signal: SignalId,
    /// File-name tag: `<antenna>.<tag>.sigmf-data`.
    tag: &'static str,
    /// Index of the band's first transmitter among all transmitters.
    first: usize,
    count: usize,
}

/// Run `scenario`'s signal synthesis into `out`.
pub fn synth(
    scenario: &str,
    out: &Path,
    seed: Option<u64>,
    force: bool,
    chunk_epochs: usize,
) -> anyhow::Result<()> {
    let mut scenario = skyforge_scenarios::resolve(scenario)?;
    if let Some(seed) = seed {
        scenario.seed = seed;
    }
    let Some(signal) = scenario.signal.clone() else {
        return Err(BadInput(format!(
            "{}: the scenario has no [signal] table, so there is nothing to synthesise (see docs/scenario.md)",
            scenario.source
        ))
        .into());
    };
    synthesise(&scenario, &signal, out, force, chunk_epochs)
}

/// Synthesise `scenario` with `signal` into `out`, computing geometry `chunk_epochs`
/// epochs at a time.
pub fn synthesise(
    scenario: &Scenario,
    signal: &SignalConfig,
    out: &Path,
    force: bool,
    chunk_epochs: usize,
) -> anyhow::Result<()> {
    let started = Instant::now();
    let world = scenario.build()?;
    // The world holds only the enabled constellations.
    let ephs = ephemerides_at_start(&world);
    let start = world.origin.start();
    let mut iono = scenario.errors.ionosphere.clone();
    let gps = constellation::gps_l1ca(&ephs, start, &iono.gps).context("GPS transmitters")?;
    let bds = constellation::bds_b1i(&ephs, start, &iono.bds).context("BeiDou transmitters")?;
    // The signal follows the coefficients as broadcast (quantised in the message).
    if let Some((alpha, beta)) = gps.first().and_then(Transmitter::broadcast_iono) {
        iono.gps = KlobucharCoeffs { alpha, beta };
    }
    let bands: Vec<Band> = [
        Band {
            signal: SignalId::GpsL1Ca,
            tag: "gps-l1ca",
            first: 0,
            count: gps.len(),
        },
        Band {
            signal: SignalId::BdsB1I,
            tag: "bds-b1i",
            first: gps.len(),
            count: bds.len(),
        },
    ]
    .into_iter()
    .filter(|b| b.count > 0)
    .collect();
    let transmitters: Vec<Transmitter> = gps.into_iter().chain(bds).collect();
    // The orbits the signals follow are the quantised broadcast ephemerides.
    let quantised: Vec<BroadcastEphemeris> = transmitters
        .iter()
        .map(Transmitter::broadcast_ephemeris)
        .collect();
    let staged = StagedDir::create(out, force)?;
    let nav_path = staged.file("nav.rnx");
    let mut nav = std::io::BufWriter::new(
        std::fs::File::create(&nav_path)
            .with_context(|| format!("cannot create {}", nav_path.display()))?,
    );
    let iono_header: Vec<(System, [f64; 4], [f64; 4])> = if iono.model == IonoModel::Off {
        Vec::new()
    } else {
        vec![
            (System::Gps, iono.gps.alpha, iono.gps.beta),
            (System::Beidou, iono.bds.alpha, iono.bds.beta),
        ]
    };
    write_nav(&quantised, "skyforge", &iono_header, &mut nav)
        .and_then(|()| nav.flush())
        .with_context(|| writing(&nav_path))?;
    let store = EphemerisStore::new(quantised, &world.origin);
    let sats: Vec<SatId> = transmitters.iter().map(|t| t.sat).collect();

    let n_ant = world.antennas.len();
    let errors = &scenario.errors;
    // One oscillator for the receiver, or one per antenna; every band gets a clone, so
    // the bands of one receiver share its clock.
    let clocks: Vec<ClockModel> = match &errors.receiver_clock {
        None => Vec::new(),
        Some(osc) => {
            let h = osc
                .power_law()
                .map_err(|e| scenario.located(e.within("errors.receiver_clock")))?;
            let count = if osc.per_antenna { n_ant } else { 1 };
            (0..count)
                .map(|i| {
                    ClockModel::new(
                        &h,
                        osc.bias_s,
                        osc.drift,
                        BLOCK_S,
                        stream_rng(scenario.seed, "receiver-clock", i as u32),
                    )
                })
                .collect::<Result<_, _>>()
                .context("receiver clock")?
        }
    };
    let antenna_names: Vec<&str> = world.antennas.iter().map(|a| a.name.as_str()).collect();
    let events = EventSchedule::new(&errors.events, &antenna_names, &sats)
        .map_err(|e| scenario.located(e.within("errors.events")))?;
    let filter = signal
        .filter
        .as_ref()
        .map(|f| {
            BandFilter::new(
                f,
                signal.sample_rate_hz,
                signal.if_hz,
                signal.format.is_complex(),
            )
        })
        .transpose()
        .map_err(|e| scenario.located(e.within("signal.filter")))?;
    let mut synths = bands
        .iter()
        .map(|b| {
            let s = Synthesiser::new(
                signal,
                &transmitters[b.first..b.first + b.count],
                n_ant,
                scenario.seed,
            )
            .context("signal configuration")?
            .with_truth_every(signal.truth_every_blocks())
            .with_clocks(clocks.clone())
            .with_events(events.clone());
            match &filter {
                Some(f) => s.with_filter(f.clone()).context("signal configuration"),
                None => Ok(s),
            }
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let terms = LinkTerms {
        signal,
        ionosphere: &iono,
        troposphere: &errors.troposphere,
        multipath: &errors.multipath,
        antennas: &world.antennas,
    };
    // files[band][antenna]
    let mut files = bands
        .iter()
        .map(|b| {
            world
                .antennas
                .iter()
                .map(|a| {
                    let path = staged.file(&format!("{}.{}.sigmf-data", a.name, b.tag));
                    std::fs::File::create(&path)
                        .map(|f| (path.clone(), std::io::BufWriter::new(f)))
                        .with_context(|| format!("cannot create {}", path.display()))
                })
                .collect::<anyhow::Result<Vec<_>>>()
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let meta = RunMeta {
        scenario: scenario.name.clone(),
        source: scenario.source.clone(),
        start_epoch: world.origin.start().to_string(),
        seed: scenario.seed,
        step_s: GEOMETRY_STEP_S,
    };
    let truth_path = staged.file("truth.h5");
    let mut truth_writer = TruthWriter::create(&truth_path, &meta, &sats, &world.antennas)
        .with_context(|| format!("cannot create {}", truth_path.display()))?;
    if signal.truth_rate_hz > 0 {
        truth_writer.create_signal(&world.antennas)?;
    }

    let n_epochs = epoch_count(world.duration_s, GEOMETRY_STEP_S);
    let bar = ProgressBar::new(n_epochs as u64).with_style(
        ProgressStyle::with_template("{spinner} synth [{bar:40}] {pos}/{len} s ({eta} left)")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut platform = world.platform;
    // The platform's state at the start, for the receiver's assistance file.
    let mut start_state: Option<(Vec3, Vec3)> = None;
    let truth = GeometryTruth::new(&store, &sats, &world.antennas, GEOMETRY_STEP_S);
    let mut bufs: Vec<Vec<u8>> = vec![Vec::new(); n_ant];
    // RINEX observation truth per antenna, opened at the first epoch (approximate position).
    type Obs = ObsWriter<std::io::BufWriter<std::fs::File>>;
    let mut obs: Vec<Option<(std::path::PathBuf, Obs)>> = (0..n_ant).map(|_| None).collect();
    let systems: Vec<System> = bands
        .iter()
        .map(|b| match b.signal {
            SignalId::GpsL1Ca => System::Gps,
            SignalId::BdsB1I => System::Beidou,
        })
        .collect();
    let calendar = |t: f64| -> Calendar {
        let (y, mo, d, h, mi, sec, ns) = world
            .origin
            .epoch_at(t)
            .to_gregorian(hifitime::TimeScale::GPST);
        (y, mo, d, h, mi, f64::from(sec) + f64::from(ns) * 1e-9)
    };
    truth
        .stream(
            &mut platform,
            world.duration_s,
            chunk_epochs,
            |chunk| -> anyhow::Result<()> {
                for k in 0..chunk.t_s.len() {
                    let st = &chunk.platform[k];
                    start_state.get_or_insert((st.r_ecef_m, st.v_ecef_mps));
                    let at_antenna: Vec<AntennaEpoch> = world
                        .antennas
                        .iter()
                        .map(|a| AntennaEpoch::new(st, a))
                        .collect();
                    let at = world.origin.epoch_at(chunk.t_s[k]);
                    let sow = |system: System| match system {
                        System::Gps => gpst_week_sow(at).1,
                        System::Beidou => bdt_week_sow(at).1,
                    };
                    let mut whole_second: Vec<Vec<ObsRecord>> = vec![Vec::new(); n_ant];
                    let mut whole_t = None;
                    for ((band, synth), band_files) in bands.iter().zip(&mut synths).zip(&mut files)
                    {
                        let links = (0..n_ant * band.count)
                            .map(|l| {
                                let (a, s) = (l / band.count, band.first + l % band.count);
                                let sat = sats[s];
                                terms.link_end(
                                    chunk.t_s[k],
                                    sow(sat.system),
                                    a,
                                    &at_antenna[a],
                                    sat,
                                    band.signal,
                                    chunk.link(k, a, s),
                                )
                            })
                            .collect();
                        synth.push_epoch(chunk.t_s[k], links, &mut bufs);
                        for ((path, file), buf) in band_files.iter_mut().zip(bufs.iter_mut()) {
                            file.write_all(buf).with_context(|| writing(path))?;
                            buf.clear();
                        }
                        let truth = synth.take_truth();
                        for r in truth.iter().filter(|r| r.t_s.fract() == 0.0) {
                            whole_t = Some(r.t_s);
                            whole_second[r.antenna].push(ObsRecord {
                                sat: sats[band.first + r.tx],
                                pseudorange_m: r.pseudorange_m,
                                carrier_phase_cycles: r.carrier_phase_cycles,
                                doppler_hz: r.doppler_hz,
                                cn0_dbhz: r.cn0_dbhz,
                                loss_of_lock: false,
                            });
                        }
                        for a in 0..n_ant {
                            let records: Vec<_> =
                                truth.iter().filter(|r| r.antenna == a).copied().collect();
                            truth_writer
                                .append_signal(a, &records, band.first)
                                .with_context(|| writing(&truth_path))?;
                        }
                    }
                    if let Some(t) = whole_t {
                        for (a, records) in whole_second.iter_mut().enumerate() {
                            records.sort_by_key(|r| r.sat);
                            let (path, writer) = match &mut obs[a] {
                                Some((p, w)) => (&*p, w),
                                empty => {
                                    let st = &chunk.platform[k];
                                    let r0 = st.r_ecef_m
                                        + st.c_body_ecef * world.antennas[a].true_body_m;
                                    let path =
                                        staged.file(&format!("{}.obs.rnx", world.antennas[a].name));
                                    let file = std::fs::File::create(&path)
                                        .with_context(|| writing(&path))?;
                                    let w = ObsWriter::new(
                                        std::io::BufWriter::new(file),
                                        &world.antennas[a].name,
                                        &r0,
                                        calendar(t),
                                        1.0,
                                        &systems,
                                    )
                                    .with_context(|| writing(&path))?;
                                    let (p, w) = empty.insert((path, w));
                                    (&*p, w)
                                }
                            };
                            writer
                                .epoch(calendar(t), records)
                                .with_context(|| writing(path))?;
                        }
                    }
                }
                bar.inc(chunk.t_s.len() as u64);
                truth_writer
                    .append(&chunk)
                    .with_context(|| writing(&truth_path))?;
                Ok(())
            },
        )
        .map_err(|e| anyhow::anyhow!("{e:#}"))?;
    for (path, f) in files.iter_mut().flatten() {
        f.flush().with_context(|| writing(path))?;
    }
    for (path, w) in obs.into_iter().flatten() {
        w.finish().with_context(|| writing(&path))?;
    }
    truth_writer
        .finish()
        .with_context(|| writing(&truth_path))?;
    bar.finish_and_clear();

    let leo = scenario.platform.leo.is_some();
    let (y, mo, d, h, mi, sec, ns) = world.origin.start().to_gregorian_utc();
    // SigMF core:datetime: ISO-8601 UTC with a trailing Z.
    let start_utc = format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{sec:02}.{ns:09}Z");
    for band in &bands {
        for ant in &world.antennas {
            let name = format!("{}.{}", ant.name, band.tag);
            let data = format!("{name}.sigmf-data");
            let meta = RecordingMeta {
                format: signal.format,
                sample_rate_hz: signal.sample_rate_hz,
                centre_frequency_hz: band.signal.carrier_hz() - signal.if_hz,
                if_hz: signal.if_hz,
                datetime_utc: start_utc.clone(),
                antenna_name: ant.name.clone(),
                antenna_position_body_m: ant.nominal_body_m.into(),
                scenario: scenario.name.clone(),
                seed: scenario.seed,
                description: format!(
                    "SkyForge synthesis of {} for antenna {}: {}",
                    scenario.name,
                    ant.name,
                    band.signal.name()
                ),
            };
            let meta_path = staged.file(&format!("{name}.sigmf-meta"));
            std::fs::write(
                &meta_path,
                serde_json::to_string_pretty(&meta.to_json())? + "\n",
            )
            .with_context(|| writing(&meta_path))?;
            let present = SignalsPresent {
                gps_l1ca: band.signal == SignalId::GpsL1Ca,
                bds_b1i: band.signal == SignalId::BdsB1I,
            };
            let doppler = if leo {
                DOPPLER_MAX_LEO_HZ
            } else {
                DOPPLER_MAX_GROUND_HZ
            };
            // A ground receiver is told to correct the broadcast ionosphere; the LEO (mostly
            // above it) is not.
            let iono_on = iono.model != IonoModel::Off && !leo;
            let corrections = PvtCorrections {
                broadcast_iono: iono_on,
                // The troposphere model applies below its ceiling only, i.e. on the ground.
                troposphere: scenario.errors.troposphere.model != TropoModel::Off && !leo,
            };
            let conf = gnss_sdr::config(signal, &data, present, doppler, corrections, &name);
            let conf_path = staged.file(&format!("{name}.gnss-sdr.conf"));
            std::fs::write(&conf_path, conf).with_context(|| writing(&conf_path))?;
        }
    }
    if let Some((r, v)) = start_state {
        let path = staged.file("receiver.toml");
        std::fs::write(&path, receiver_assistance_toml(&r, &v)).with_context(|| writing(&path))?;
    }
    let clipped: u64 = synths.iter().map(Synthesiser::clipped).sum();
    let dir = staged.commit()?;
    println!("scenario   {} ({})", scenario.name, scenario.source);
    for band in &bands {
        println!(
            "signals    {} from {} satellites, {} antennas",
            band.signal.name(),
            band.count,
            n_ant
        );
    }
    println!(
        "samples    {} Hz {:?}, {} s, clipped components {clipped}",
        signal.sample_rate_hz, signal.format, world.duration_s
    );
    println!("wrote      {}", dir.display());
    println!("elapsed    {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// Position rounding of the assistance file (m): what an orbit prediction or a rough
/// position fix would tell a receiver, not the truth.
const ASSIST_POSITION_ROUNDING_M: f64 = 1000.0;
/// Velocity rounding of the assistance file (m/s).
const ASSIST_VELOCITY_ROUNDING_MPS: f64 = 1.0;

/// `receiver.toml` for `skyforge receive --config`: the approximate state at the start
/// (rounded, with uncertainties that cover the rounding many times over).
fn receiver_assistance_toml(r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> String {
    let round = |x: f64, step: f64| (x / step).round() * step;
    let r = r_ecef_m.map(|x| round(x, ASSIST_POSITION_ROUNDING_M));
    let v = v_ecef_mps.map(|x| round(x, ASSIST_VELOCITY_ROUNDING_MPS));
    format!(
        "# Settings for `skyforge receive --config receiver.toml` on these recordings.\n\
         # [assist]: the approximate state at the first sample a receiver could be told\n\
         # (an orbit prediction, a last fix), rounded to {} m and {} m/s.\n\
         [assist]\n\
         position_ecef_m = [{:.1}, {:.1}, {:.1}]\n\
         velocity_ecef_mps = [{:.1}, {:.1}, {:.1}]\n\
         position_uncertainty_m = 10000.0\n\
         velocity_uncertainty_mps = 10.0\n",
        ASSIST_POSITION_ROUNDING_M, ASSIST_VELOCITY_ROUNDING_MPS, r.x, r.y, r.z, v.x, v.y, v.z
    )
}
