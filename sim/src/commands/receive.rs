//! `skyforge receive`: run the bundled receiver over sample recordings.

use crate::bad_input::BadInput;
use crate::cli::ReceiveArgs;
use crate::commands::attitude::{AttitudeStage, Chain, read_nav};
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use hifitime::Unit;
use indicatif::{ProgressBar, ProgressStyle};
use skyforge_formats::receiver::{ReceiverOutputs, Summary as OutputSummary};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::orbit_determination::{EpochFix, OdFilterConfig, OrbitDetermination};
use skyforge_navigation::relnav::{RelnavConfig, RelnavStage};
use skyforge_orbits::constants::C_MPS;
use skyforge_receiver::input::InputParams;
use skyforge_receiver::input::parse_format;
use skyforge_receiver::pipeline::{EpochReport, ReceiverSummary};
use skyforge_receiver::session::{
    Assistance, EpochSink, NavSource, ReceiveSession, SessionError, SinkError, read_config,
};

/// The raw-file description given on the command line.
fn input_params(args: &ReceiveArgs) -> anyhow::Result<InputParams> {
    let format = args
        .format
        .as_deref()
        .map(|f| parse_format(f, "--format"))
        .transpose()
        .map_err(|e| BadInput(e.to_string()))?;
    let signal = args
        .signal
        .as_deref()
        .map(str::parse::<Signal>)
        .transpose()
        .map_err(|e| BadInput(format!("--signal: {e}")))?;
    if let Some(s) = signal.filter(|s| !s.is_received()) {
        let allowed: Vec<&str> = Signal::RECEIVED.iter().map(|s| s.tag()).collect();
        return Err(BadInput(format!(
            "--signal {}: not received by the bundled receiver (allowed: {})",
            s.tag(),
            allowed.join(", ")
        ))
        .into());
    }
    Ok(InputParams {
        format,
        sample_rate_hz: args.fs,
        if_hz: args.if_hz,
        signal,
    })
}

/// A session error as the command reports it: the input's fault is bad input (exit 2).
pub(crate) fn session_error(e: SessionError) -> anyhow::Error {
    match e {
        SessionError::Input(message) | SessionError::NoSignal(message) => BadInput(message).into(),
        e => anyhow::anyhow!("{e}"),
    }
}

/// Run the receiver over `args.files` and write its outputs into `args.out`.
pub fn receive(args: &ReceiveArgs) -> anyhow::Result<()> {
    let (config, approximate) = read_config(args.config.as_deref()).map_err(session_error)?;
    let assistance = Assistance {
        nav: args.assist.clone().map(NavSource::File),
        approximate,
    };
    let params = input_params(args)?;
    let mut session =
        ReceiveSession::open(&args.files, &params, &assistance, config).map_err(session_error)?;
    let chain = attitude_chain(args, session.antenna_names())?;
    let mut relnav = relnav_stage(args)?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let mut outputs = ReceiverOutputs::create(
        &staged.file(""),
        session.antenna_names(),
        &session.signals(),
        approximate.map(|a| a.r_ecef_m),
        1.0 / session.config().observation_rate_hz,
    )?;
    let mut attitude = match (chain, &args.assist) {
        (Some(chain), Some(nav)) => {
            Some(chain.stage(read_nav(nav)?, session.antenna_names(), &staged)?)
        }
        _ => None,
    };
    let od_config = args
        .od
        .as_ref()
        .map(|p| super::od::read_config(p.as_deref()));
    let mut od = match od_config.transpose()? {
        Some(config) => {
            let ephemerides = match (&config.filter, &args.assist) {
                (OdFilterConfig::ReducedDynamic(_), Some(nav)) => read_nav(nav)?,
                _ => Vec::new(),
            };
            let od = OrbitDetermination::new(config, ephemerides)
                .map_err(|e| BadInput(format!("--od: {e} with --assist NAV")))?;
            Some(od)
        }
        None => None,
    };
    let bar = ProgressBar::new(session.common_samples()).with_style(
        ProgressStyle::with_template("receive {bar:40} {percent}% {msg} eta {eta}")
            .context("progress style")?,
    );
    let mut sink = Stages {
        outputs: &mut outputs,
        attitude: attitude.as_mut(),
        od: od.as_mut(),
        relnav: relnav.as_mut().map(|(stage, _)| stage),
    };
    let summary = session
        .run(&mut sink, |sample, s| {
            bar.set_position(sample);
            bar.set_message(format!(
                "{} channels timed, {} fixes",
                s.timed.iter().map(Vec::len).sum::<usize>(),
                s.fixes.iter().sum::<usize>()
            ));
        })
        .map_err(session_error)?;
    bar.finish_and_clear();
    let written = outputs.finish()?;
    print_summary(&summary, session.antenna_names(), &written);
    let chain_summary = attitude.map(|a| a.finish(&staged)).transpose()?;
    let od = od.filter(|od| !od.estimates().is_empty());
    if let Some((od, start)) = od.as_ref().and_then(|od| Some((od, od.start()?))) {
        super::od::write_outputs(&staged, start, od.estimates(), od.config())?;
    } else if args.od.is_some() {
        println!("receive: od: no fix on the orbit-determination grid; no orbit written");
    }
    let relnav = relnav.map(|(stage, config)| (stage.run(), config));
    match &relnav {
        Some((run, _)) if !run.estimates.is_empty() => {
            super::relnav::write_relnav_csv(&staged, run, ("target", "chaser"))?;
        }
        Some(_) => println!("receive: relnav: no epoch with both fixes; no relnav.csv written"),
        None => {}
    }
    let dir = staged.commit()?;
    println!("receive: wrote {}", dir.display());
    if let Some(s) = chain_summary {
        s.print(&dir);
    }
    if let Some(od) = &od {
        super::od::print_summary(&dir, od.estimates(), od.missed(), od.config());
    }
    if let Some((run, config)) = relnav.filter(|(run, _)| !run.estimates.is_empty()) {
        super::relnav::print_summary(&run, &config);
    }
    Ok(())
}

/// With `--relnav OBS`, the relative-navigation stage against the target's observations
/// and its settings; the ephemerides and ionosphere come from `--assist`.
fn relnav_stage(args: &ReceiveArgs) -> anyhow::Result<Option<(RelnavStage, RelnavConfig)>> {
    let Some(target) = &args.relnav else {
        return Ok(None);
    };
    let Some(nav) = &args.assist else {
        return Err(BadInput(
            "--relnav needs --assist NAV: relative navigation reads the ephemerides and the ionosphere from a navigation file".into(),
        )
        .into());
    };
    let config = super::relnav::read_config(args.relnav_config.as_deref())?;
    let (ephemerides, iono) = super::attitude::read_nav_with_iono(nav)?;
    let target = super::read_observations(target)?;
    let stage = RelnavStage::new(target, ephemerides, &iono, &config)
        .map_err(|e| BadInput(format!("--relnav: {e}")))?;
    Ok(Some((stage, config)))
}

/// What runs at every epoch the receiver forms: its output files, then with `--geometry`
/// the attitude chain on the same observations, with `--od` the orbit determination on
/// the first recording's fix, and with `--relnav` relative navigation on the first
/// recording's observations.
struct Stages<'a> {
    outputs: &'a mut ReceiverOutputs,
    attitude: Option<&'a mut AttitudeStage>,
    od: Option<&'a mut OrbitDetermination>,
    relnav: Option<&'a mut RelnavStage>,
}

impl EpochSink for Stages<'_> {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), SinkError> {
        self.outputs.epoch(report)?;
        if let Some(a) = self.attitude.as_mut() {
            a.epoch(report)?;
        }
        if let Some(od) = self.od.as_mut() {
            od.epoch(report.t_rx, || od_fix(report), || report.records(0));
        }
        if let Some(relnav) = self.relnav.as_mut() {
            relnav.epoch(report.t_rx, &report.records(0));
        }
        Ok(())
    }
}

/// The first recording's fix at `report`, as orbit determination takes it: at the epoch
/// tag less the receiver clock's offset.
fn od_fix(report: &EpochReport) -> Option<EpochFix> {
    let first = report.fixes.first()?;
    let fix = first.fix.as_ref().ok()?;
    Some(EpochFix {
        time: report.t_rx - Unit::Second * (fix.clock_bias_m / C_MPS),
        r_ecef_m: fix.r_ecef_m,
        v_ecef_mps: first.velocity.as_ref().map(|v| v.v_ecef_mps),
        gdop: fix.dop.gdop,
    })
}

/// With `--geometry`, the attitude chain to run on the receiver's observations; its
/// antennas must be the recordings' (in any order), and the ephemerides come from
/// `--assist`.
fn attitude_chain(args: &ReceiveArgs, antennas: &[String]) -> anyhow::Result<Option<Chain>> {
    let Some(geometry) = &args.geometry else {
        return Ok(None);
    };
    if args.assist.is_none() {
        return Err(BadInput(
            "--geometry needs --assist NAV: the attitude chain reads the ephemerides from a navigation file".into(),
        )
        .into());
    }
    let chain = Chain::new(geometry, args.attitude_config.as_deref(), false)?;
    chain.check_recorded(geometry, antennas, ("recording", "recorded"))?;
    Ok(Some(chain))
}

pub(crate) fn print_summary(
    s: &ReceiverSummary,
    antenna_names: &[String],
    written: &OutputSummary,
) {
    for (a, name) in antenna_names.iter().enumerate() {
        let list = |v: &Vec<skyforge_orbits::ephemeris::SatId>| {
            v.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "receive: {name}: tracked {} [{}], timed {}, {} fixes",
            s.tracked[a].len(),
            list(&s.tracked[a]),
            s.timed[a].len(),
            s.fixes[a]
        );
    }
    println!(
        "receive: {} epochs ({} written), {} searches, {} detections ({} never locked, dropped), {} losses of lock, {} ephemerides",
        s.epochs,
        written.epochs,
        s.searches,
        s.detections,
        s.unconfirmed_detections,
        s.losses_of_lock,
        s.ephemerides
    );
    if s.clock_steps > 0 {
        println!(
            "receive: receiver clock set to GPS time by the fixes: {} step(s), {:+.6} ms in all",
            s.clock_steps,
            1e3 * s.clock_steered_s
        );
    }
    for (signal, found) in &s.widened {
        println!(
            "receive: note: the first search of {} over +/-10 kHz found {found} satellite(s); later searches span +/-50 kHz (a fast platform; --assist with an approximate state narrows them)",
            signal.tag()
        );
    }
    let most = s.tracked.iter().map(Vec::len).max().unwrap_or(0);
    if most < 5 {
        println!(
            "receive: hint: {most} satellite(s) tracked at most on an antenna, fewer than a checked fix needs (5); check the signal, the sample rate and the IF, or give --assist"
        );
    }
}
