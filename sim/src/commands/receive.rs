//! `skyforge receive`: run the bundled receiver over sample recordings.

use crate::BadInput;
use crate::output::receiver_out::{ReceiverOutputs, Summary as OutputSummary};
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_orbits::ephemeris::rinex_nav_iono::read_iono_file;
use skyforge_receiver::input::format::parse_format;
use skyforge_receiver::input::{BlockReader, InputParams, InputReport, Recording};
use skyforge_receiver::pipeline::{
    BandInput, EpochReport, Receiver, ReceiverConfig, ReceiverFile, ReceiverSetup, ReceiverSummary,
};
use skyforge_receiver::signal::Signal;
use std::path::{Path, PathBuf};

/// Samples per block: 20 ms at the sample rate (covers every search of the default
/// settings; longer searches get longer blocks).
const BLOCK_S: f64 = 0.02;

/// What the command line gives.
#[derive(Debug, Clone)]
pub struct ReceiveArgs {
    pub files: Vec<PathBuf>,
    pub params: InputParams,
    pub assist: Option<PathBuf>,
    pub config: Option<PathBuf>,
    pub out: PathBuf,
    pub force: bool,
}

/// The raw-file description given on the command line.
pub fn input_params(
    format: Option<&str>,
    fs: Option<f64>,
    if_hz: Option<f64>,
    signal: Option<&str>,
) -> anyhow::Result<InputParams> {
    let format = format
        .map(|f| parse_format(f, "--format"))
        .transpose()
        .map_err(|e| BadInput(e.to_string()))?;
    let signal = signal
        .map(str::parse::<Signal>)
        .transpose()
        .map_err(|e| BadInput(format!("--signal: {e} (allowed: gps-l1ca, bds-b1i)")))?;
    Ok(InputParams {
        format,
        sample_rate_hz: fs,
        if_hz,
        signal,
    })
}

/// Read and check the receiver configuration file.
fn read_config(
    path: Option<&Path>,
) -> anyhow::Result<(
    ReceiverConfig,
    Option<skyforge_receiver::pipeline::ApproximateState>,
)> {
    let Some(path) = path else {
        return Ok((ReceiverConfig::default(), None));
    };
    let text = std::fs::read_to_string(path)
        .map_err(|e| BadInput(format!("{}: cannot read: {e}", path.display())))?;
    let file: ReceiverFile =
        toml::from_str(&text).map_err(|e| BadInput(format!("{}: {e}", path.display())))?;
    file.resolve()
        .map_err(|e| BadInput(format!("{}: {e}", path.display())).into())
}

/// The recordings grouped by band, each group opened as one block reader.
struct Bands {
    readers: Vec<BlockReader>,
    inputs: Vec<BandInput>,
    reports: Vec<InputReport>,
    antenna_names: Vec<String>,
}

fn open_bands(files: &[PathBuf], params: &InputParams) -> anyhow::Result<Bands> {
    let recordings = files
        .iter()
        .map(|f| Recording::open(f, params).map_err(|e| BadInput(e.to_string())))
        .collect::<Result<Vec<_>, _>>()?;
    let mut groups: Vec<(Signal, Vec<Recording>)> = Vec::new();
    for r in recordings {
        let Some(signal) = r.signal.or(params.signal) else {
            return Err(BadInput(format!(
                "{}: which signal it holds is unknown (no SigMF centre frequency in a GNSS band, no band in the file name): give --signal gps-l1ca or bds-b1i",
                r.source_path().display()
            ))
            .into());
        };
        match groups.iter_mut().find(|g| g.0 == signal) {
            Some(g) => g.1.push(r),
            None => groups.push((signal, vec![r])),
        }
    }
    let mut bands = Bands {
        readers: Vec::new(),
        inputs: Vec::new(),
        reports: Vec::new(),
        antenna_names: Vec::new(),
    };
    let fs = groups
        .first()
        .and_then(|g| g.1.first())
        .map(|r| r.sample_rate_hz)
        .ok_or_else(|| BadInput("no sample files given".into()))?;
    let block_len = (BLOCK_S * fs).round() as usize;
    for (signal, recs) in groups {
        let (reader, report) =
            BlockReader::open(&recs, block_len).map_err(|e| BadInput(e.to_string()))?;
        if (reader.sample_rate_hz() - fs).abs() > 1e-6 * fs {
            return Err(BadInput(format!(
                "the {} recordings are sampled at {} Hz, the {} ones at {fs} Hz: one receive run needs one sample clock",
                signal.name(),
                reader.sample_rate_hz(),
                bands.inputs.first().map_or("first", |b: &BandInput| b.signal.name()),
            ))
            .into());
        }
        let antennas = report
            .antennas
            .iter()
            .map(
                |a| match bands.antenna_names.iter().position(|n| *n == a.antenna) {
                    Some(i) => i,
                    None => {
                        bands.antenna_names.push(a.antenna.clone());
                        bands.antenna_names.len() - 1
                    }
                },
            )
            .collect();
        bands.inputs.push(BandInput {
            signal,
            if_hz: reader.output_if_hz(),
            antennas,
        });
        bands.readers.push(reader);
        bands.reports.push(report);
    }
    Ok(bands)
}

/// What was found in the input, for messages.
fn describe_input(bands: &Bands) -> String {
    let mut s = String::new();
    for (b, r) in bands.inputs.iter().zip(&bands.reports) {
        s.push_str(&format!(
            "  {}: {} recording(s) at {} Hz, {:.1} s in common",
            b.signal.name(),
            r.antennas.len(),
            r.sample_rate_hz,
            r.duration_s()
        ));
        for a in &r.antennas {
            s.push_str(&format!(
                "\n    {} ({}, {} samples)",
                a.antenna,
                a.path.display(),
                a.samples_in_file
            ));
        }
        for f in &r.findings {
            s.push_str(&format!("\n    note: {f}"));
        }
        s.push('\n');
    }
    s
}

/// Run the receiver over `args.files` and write its outputs into `args.out`.
pub fn receive(args: &ReceiveArgs) -> anyhow::Result<()> {
    let (config, approximate) = read_config(args.config.as_deref())?;
    let mut bands = open_bands(&args.files, &args.params)?;
    let (ephemerides, iono_gps, iono_bds) = match &args.assist {
        None => (Vec::new(), None, None),
        Some(path) => {
            let eph = read_nav_file(path).map_err(|e| BadInput(e.to_string()))?;
            let iono = read_iono_file(path).map_err(|e| BadInput(e.to_string()))?;
            (eph, iono.gps, iono.bds)
        }
    };
    let start_time = bands.reports.iter().find_map(|r| r.start_utc);
    let fs = bands.readers[0].sample_rate_hz();
    let setup = ReceiverSetup {
        sample_rate_hz: fs,
        bands: bands.inputs.clone(),
        antenna_names: bands.antenna_names.clone(),
        start_time,
        ephemerides,
        iono_gps,
        iono_bds,
        approximate,
    };
    let mut receiver = Receiver::new(setup, config.clone())
        .map_err(|e| BadInput(format!("receiver settings: {e}")))?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let systems: Vec<_> = bands.inputs.iter().map(|b| b.signal.system()).collect();
    let mut outputs = ReceiverOutputs::create(
        &staged.file(""),
        &bands.antenna_names,
        &systems,
        approximate.map(|a| a.r_ecef_m),
        1.0 / config.observation_rate_hz,
    )?;
    let common = bands
        .readers
        .iter()
        .map(BlockReader::common_samples)
        .min()
        .unwrap_or(0);
    let bar = ProgressBar::new(common).with_style(
        ProgressStyle::with_template("receive {bar:40} {percent}% {msg} eta {eta}")
            .context("progress style")?,
    );
    let mut buffers: Vec<Vec<Vec<_>>> = bands.readers.iter().map(BlockReader::buffers).collect();
    loop {
        let mut block = None;
        for (reader, bufs) in bands.readers.iter_mut().zip(buffers.iter_mut()) {
            let b = reader
                .read_block(bufs)
                .map_err(|e| BadInput(e.to_string()))?;
            block = match (block, b) {
                (None, b) => b,
                (Some(a), Some(b)) => Some(if b.len < a.len { b } else { a }),
                (Some(_), None) => None,
            };
        }
        let Some(block) = block else { break };
        if block.len < receiver.samples_per_search() && block.first_sample == 0 {
            return Err(BadInput(format!(
                "the recordings hold {} common samples; a search needs {}\n{}",
                block.len,
                receiver.samples_per_search(),
                describe_input(&bands)
            ))
            .into());
        }
        let reports: Vec<EpochReport> =
            receiver.process(&buffers, block.first_sample, block.len)?;
        for r in &reports {
            outputs.write_epoch(r)?;
        }
        let s = receiver.summary();
        bar.set_position(block.first_sample + block.len as u64);
        bar.set_message(format!(
            "{} channels timed, {} fixes",
            s.timed.iter().map(Vec::len).sum::<usize>(),
            s.fixes.iter().sum::<usize>()
        ));
    }
    bar.finish_and_clear();
    let summary = receiver.summary();
    if summary.detections == 0 {
        return Err(BadInput(format!(
            "no signal found: {} searches over {} antenna(s), none above the detection threshold.\nWhat was read:\n{}",
            summary.searches,
            bands.antenna_names.len(),
            describe_input(&bands)
        ))
        .into());
    }
    let written = outputs.finish()?;
    print_summary(&summary, &bands, &written);
    let dir = staged.commit()?;
    println!("receive: wrote {}", dir.display());
    Ok(())
}

fn print_summary(s: &ReceiverSummary, bands: &Bands, written: &OutputSummary) {
    for (a, name) in bands.antenna_names.iter().enumerate() {
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
}
