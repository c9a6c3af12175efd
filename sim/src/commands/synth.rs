//! `skyforge synth`: scenario -> per-antenna I/Q files (+ SigMF metadata, GNSS-SDR
//! configuration), the geometry truth of the transmitted signals, and a RINEX 3.04
//! navigation file of the ephemerides as broadcast.

use crate::bad_input::BadInput;
use crate::cli::ScenarioRun;
use crate::output::staged_dir::StagedDir;
use crate::output::synth_sinks::ObsFiles;
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use skyforge_formats::receiver::ReceiverOutputs;
use skyforge_formats::truth::{RunMeta, TRUTH_H5, TruthWriter};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_orbits::Vec3;
use skyforge_receiver::pipeline::assistance_toml;
use skyforge_receiver::session::{Assistance, NavSource, read_config};
use skyforge_runner::{ChainError, StreamSinks, StreamedChain};
use skyforge_scenarios::{Scenario, World};
use skyforge_signals::errors::TropoModel;
use skyforge_signals::obs_model::Level;
use skyforge_signals::synth::RunInfo;
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::gnss_sdr;
use skyforge_signals::synth::{
    Discard, GEOMETRY_STEP_S, Sinks, SynthError, SynthReport, SynthSession,
};
use skyforge_signals::synth::{SigmfRecordings, recording_name};
use skyforge_signals::truth::epoch_count;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Subdirectory of the receiver's outputs of `synth --receive`.
pub const RECEIVE_DIR: &str = "receive";
/// Subdirectory of the observation level's observables (`<antenna>.obs.rnx`, as
/// `skyforge receive` writes them).
pub const OBSERVATIONS_DIR: &str = "observations";
/// Error context naming an output file.
fn writing(path: &Path) -> String {
    format!("cannot write {}", path.display())
}

/// `synth --receive`: the bundled receiver reads the samples as they are rendered.
#[derive(Debug, Clone, Default)]
pub struct ReceiveAlongside {
    /// The receiver configuration file; `None`: its defaults with the rounded start state
    /// (the `receiver.toml` written beside the outputs).
    pub config: Option<PathBuf>,
}

/// Run `scenario`'s signal synthesis into `out`.
pub fn synth(
    args: &ScenarioRun,
    chunk_epochs: usize,
    dry_run: bool,
    receive: Option<&ReceiveAlongside>,
) -> anyhow::Result<()> {
    let scenario = super::resolve(args)?;
    let Some(signal) = scenario.signal.clone() else {
        return Err(BadInput(format!(
            "{}: the scenario has no [signal] table, so there is nothing to synthesise (see docs/scenario.md)",
            scenario.source
        ))
        .into());
    };
    if dry_run {
        for view in scenario.vehicle_views() {
            if let Some(name) = &view.vehicle {
                println!("vehicle {name}");
            }
            let mut world = view.build()?;
            let session = session(&view, &mut world, &signal)?;
            super::dry_run::print(&view, &session, chunk_epochs);
        }
        return Ok(());
    }
    super::vehicles::each_vehicle(&scenario, &args.out, args.force, |view, out, force| {
        synthesise(view, &signal, out, force, chunk_epochs, receive)
    })
}

/// The synthesis session of `scenario` (observation level when it asks for it).
fn session<'a>(
    scenario: &'a Scenario,
    world: &'a mut World,
    signal: &'a SignalConfig,
) -> anyhow::Result<SynthSession<'a>> {
    let model = match scenario.observation.level {
        Level::Observation => {
            Some(scenario.observation_model(world.antennas.len(), scenario.observation.step_s())?)
        }
        Level::Signal => None,
    };
    let session = SynthSession::new(
        world.synth_world(),
        signal,
        &scenario.errors,
        scenario.receiver_seed(),
    )
    .map_err(|e| setup_error(scenario, e))?;
    let session = match model {
        Some(model) => session
            .observation_level(model, &scenario.observation.observed_signals)
            .map_err(|e| setup_error(scenario, e))?,
        None => session,
    };
    (session.with_jammers(&scenario.jammers)).map_err(|e| setup_error(scenario, e))
}

/// Synthesise `scenario` with `signal` into `out`, computing geometry `chunk_epochs`
/// epochs at a time; with `receive`, the samples go to the bundled receiver (outputs in
/// `out/receive/`) instead of recordings.
pub fn synthesise(
    scenario: &Scenario,
    signal: &SignalConfig,
    out: &Path,
    force: bool,
    chunk_epochs: usize,
    receive: Option<&ReceiveAlongside>,
) -> anyhow::Result<()> {
    let started = Instant::now();
    let mut world = scenario.build()?;
    let mut session = session(scenario, &mut world, signal)?;
    let observation_level = !session.renders_samples();
    if observation_level && receive.is_some() {
        return Err(BadInput(format!(
            "{}: --receive needs samples, and the scenario is at the observation level (its observables are written in {OBSERVATIONS_DIR}/)",
            scenario.source
        ))
        .into());
    }
    let (origin, antennas, duration_s) = {
        let w = session.world();
        (w.origin, w.antennas, w.duration_s)
    };
    let bands = session.bands().to_vec();
    let signals = session.signals();
    let info = session.recording_info(&scenario.name, scenario.seed, scenario.vehicle.as_deref());
    let sats = session.satellites().to_vec();
    let n_ant = antennas.len();
    let staged = StagedDir::create(out, force)?;
    let nav_path = staged.file("nav.rnx");
    let mut nav = std::io::BufWriter::new(
        std::fs::File::create(&nav_path)
            .with_context(|| format!("cannot create {}", nav_path.display()))?,
    );
    session
        .write_navigation(&mut nav)
        .and_then(|()| nav.flush())
        .with_context(|| writing(&nav_path))?;
    let streamed_run = receive.is_some();
    let streamed = match receive {
        Some(r) => {
            let start = session
                .start_state()
                .map_err(|e| setup_error(scenario, e))?;
            let assist = write_assistance(&staged, Some(start))?;
            Some((r, assist))
        }
        None => None,
    };
    let mut recordings = if observation_level || streamed.is_some() {
        None
    } else {
        Some(SigmfRecordings::create(&staged.file(""), &bands, antennas)?)
    };
    let meta = RunMeta::new(scenario, origin.start(), GEOMETRY_STEP_S);
    let truth_path = staged.file(TRUTH_H5);
    let mut truth = TruthWriter::create(&truth_path, &meta, &sats, antennas)
        .with_context(|| format!("cannot create {}", truth_path.display()))?;
    if signal.truth_rate_hz > 0 {
        let transmitted: Vec<Signal> = (bands.iter())
            .flat_map(|b| b.signals().iter().copied())
            .collect();
        truth.create_signal(antennas, &transmitted)?;
    }
    let mut obs = ObsFiles::new(&staged.file(""), antennas, &signals);
    let measured_dir = staged.file(OBSERVATIONS_DIR);
    if observation_level {
        std::fs::create_dir(&measured_dir).with_context(|| writing(&measured_dir))?;
    }
    let mut measured = ObsFiles::new(&measured_dir, antennas, &signals);
    let n_epochs = epoch_count(duration_s, GEOMETRY_STEP_S);
    let bar = ProgressBar::new(n_epochs as u64).with_style(
        ProgressStyle::with_template("{spinner} synth [{bar:40}] {pos}/{len} s ({eta} left)")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let iono_on = session.ionosphere_on();
    let mut no_samples = Discard;
    let report = match streamed {
        Some((alongside, assist)) => {
            let sinks = StreamSinks {
                truth: &mut truth,
                observations: &mut obs,
                progress: &mut |n| bar.inc(n as u64),
            };
            let config = alongside.config.as_deref().unwrap_or(&assist);
            receive_alongside(session, &info, &staged, config, chunk_epochs, sinks)?
        }
        None => session
            .run(
                chunk_epochs,
                Sinks {
                    samples: match recordings.as_mut() {
                        Some(r) => r,
                        None => &mut no_samples,
                    },
                    truth: &mut truth,
                    observations: &mut obs,
                    measurements: &mut measured,
                    progress: &mut |n| bar.inc(n as u64),
                },
            )
            .map_err(|e| setup_error(scenario, e))?,
    };
    obs.finish().map_err(|e| anyhow::anyhow!("{e}"))?;
    measured.finish().map_err(|e| anyhow::anyhow!("{e}"))?;
    truth.finish().with_context(|| writing(&truth_path))?;
    super::write_truth_sidecars(scenario, &staged)?;
    bar.finish_and_clear();
    let wrote_recordings = recordings.is_some();
    if let Some(recordings) = recordings {
        recordings.finish(&info)?;
    }
    let leo = scenario.platform.leo.is_some();
    let tropo_on = scenario.errors.troposphere.model != TropoModel::Off;
    for band in bands.iter().filter(|_| wrote_recordings) {
        for ant in antennas {
            let name = recording_name(&ant.name, band);
            let conf =
                gnss_sdr::recording_config(signal, &name, band.signals(), leo, iono_on, tropo_on);
            let conf_path = staged.file(&format!("{name}.gnss-sdr.conf"));
            std::fs::write(&conf_path, conf).with_context(|| writing(&conf_path))?;
        }
    }
    write_geometry(scenario, &staged.file("geometry.toml"))?;
    if !streamed_run {
        // (A streamed run wrote it before the receiver started.)
        write_assistance(&staged, report.start_state)?;
    }
    let dir = staged.commit()?;
    println!("scenario   {} ({})", scenario.name, scenario.source);
    for band in &bands {
        println!(
            "signals    {} from {} satellites, {} antennas",
            band.name(),
            band.count,
            n_ant
        );
    }
    if observation_level {
        println!(
            "observables observation level, {} s, in {}/",
            duration_s, OBSERVATIONS_DIR
        );
    } else {
        println!(
            "samples    {} Hz {:?}, {} s, clipped components {}{}",
            signal.sample_rate_hz,
            signal.format,
            duration_s,
            report.clipped,
            if wrote_recordings {
                ""
            } else {
                ", received as rendered (no recordings)"
            }
        );
    }
    println!("wrote      {}", StagedDir::final_path(&dir).display());
    println!("elapsed    {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}

/// The nominal body geometry of the scenario's antennas (what `skyforge attitude
/// --geometry` reads): positions without the offsets the scenario may add to the truth.
fn write_geometry(scenario: &Scenario, path: &Path) -> anyhow::Result<()> {
    let file = BodyGeometryFile::from_positions(
        scenario
            .antennas
            .iter()
            .map(|a| (a.name.clone(), Vec3::from(a.position_body_m))),
    );
    let header = format!(
        "Nominal body geometry of scenario {} (antenna phase-centre reference points, body\n\
         frame, m; master first), for `skyforge attitude --geometry`.",
        scenario.name
    );
    let text = file
        .to_text(&header)
        .context("cannot encode the geometry")?;
    std::fs::write(path, text).with_context(|| writing(path))
}

/// A session that cannot be set up or run: a located scenario error for a bad setting
/// or a platform the scenario cannot move (an orbit that decays during the run).
fn setup_error(scenario: &Scenario, e: SynthError) -> anyhow::Error {
    match e {
        SynthError::Invalid(invalid) => scenario.located(invalid).into(),
        SynthError::Platform(p) => scenario.platform_error(p).into(),
        e => anyhow::anyhow!("{e:#}"),
    }
}

/// Write `receiver.toml` (the receiver's defaults and the rounded start state) when the
/// start state is known; its path.
fn write_assistance(staged: &StagedDir, start: Option<(Vec3, Vec3)>) -> anyhow::Result<PathBuf> {
    let path = staged.file("receiver.toml");
    if let Some((r, v)) = start {
        std::fs::write(&path, assistance_toml(&r, &v)).with_context(|| writing(&path))?;
    }
    Ok(path)
}

/// Run `session` with the bundled receiver reading its samples as they are rendered
/// (configured by the file `config`, assisted by `nav.rnx`), the receiver's outputs in
/// `receive/` of `staged`; the synthesis report.
fn receive_alongside(
    session: SynthSession<'_>,
    info: &RunInfo,
    staged: &StagedDir,
    config: &Path,
    chunk_epochs: usize,
    sinks: StreamSinks<'_>,
) -> anyhow::Result<SynthReport> {
    let (config, approximate) = read_config(Some(config)).map_err(super::receive::session_error)?;
    let assistance = Assistance {
        nav: Some(NavSource::File(staged.file("nav.rnx"))),
        approximate,
    };
    let chain = StreamedChain::open(session, info, &assistance, config).map_err(chain_error)?;
    let rx_dir = staged.file(RECEIVE_DIR);
    std::fs::create_dir(&rx_dir).with_context(|| writing(&rx_dir))?;
    let receiver = chain.receiver();
    let names = receiver.antenna_names().to_vec();
    let mut outputs = ReceiverOutputs::create(
        &rx_dir,
        &names,
        &receiver.signals(),
        approximate.map(|a| a.r_ecef_m),
        1.0 / receiver.config().observation_rate_hz,
    )?;
    let (report, summary) = chain
        .run(chunk_epochs, sinks, &mut outputs, |_, _| {})
        .map_err(chain_error)?;
    let written = outputs.finish()?;
    super::receive::print_summary(&summary, &names, &written);
    Ok(report)
}

/// A streamed chain's error as the command reports it: the receiver's input errors (no
/// signal, say) are the scenario's fault.
fn chain_error(e: ChainError) -> anyhow::Error {
    match e {
        ChainError::Receive(e) => super::receive::session_error(e),
        e => anyhow::anyhow!("{e}"),
    }
}
