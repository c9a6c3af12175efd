//! `skyforge monitor run` (several receivers' RINEX files -> B values, thresholds and
//! alarms), `skyforge monitor calibrate` (a scenario's fault-free runs -> thresholds) and
//! `skyforge monitor calibrate-files` (fault-free RINEX files -> thresholds).

use crate::bad_input::BadInput;
use crate::cli::{MonitorArgs, ScenarioRun};
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_formats::monitor::{
    AlarmLog, H5Rows, MONITOR_CSV, MONITOR_H5, SUMMARY_JSON, csv_header, csv_rows,
};
use skyforge_gnss::observation::ObsFile;
use skyforge_navigation::integrity::{MonitorConfig, Station, Unmonitored};
use skyforge_navigation::integrity::{run_files, stations};
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_validate::integrity::{
    ELEVATION_BINS_DEG, calibrate as measure, calibrate_files as measure_files, config,
};
use std::io::Write;

/// The configuration `args` names, or the bundled one.
fn read_config(args: &MonitorArgs) -> anyhow::Result<MonitorConfig> {
    match &args.config {
        Some(path) => MonitorConfig::read(path).map_err(|e| BadInput(e).into()),
        None => MonitorConfig::parse(skyforge_scenarios::BUNDLED_MONITOR_CONFIG)
            .map_err(|e| anyhow::anyhow!("bundled monitor configuration: {e}")),
    }
}

/// A station's name from its file: the file name up to its first dot.
fn station_name(path: &std::path::Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    name.split('.').next().unwrap_or(&name).to_string()
}

/// What `monitor run` and `monitor calibrate-files` read: the configuration, the
/// observation files, their stations and the ephemerides.
struct Inputs {
    config: MonitorConfig,
    files: Vec<ObsFile>,
    stations: Vec<Station>,
    ephemerides: Vec<BroadcastEphemeris>,
}

fn read_inputs(args: &MonitorArgs) -> anyhow::Result<Inputs> {
    let config = read_config(args)?;
    let files = args
        .files
        .iter()
        .map(|p| super::read_observations(p))
        .collect::<Result<Vec<_>, _>>()?;
    let names: Vec<String> = args.files.iter().map(|p| station_name(p)).collect();
    let stations = stations(&files, &names, &config).map_err(|e| BadInput(e.to_string()))?;
    let ephemerides =
        read_nav_file(&args.nav).map_err(|e| BadInput(format!("{}: {e}", args.nav.display())))?;
    if ephemerides.is_empty() {
        return Err(BadInput(format!(
            "{}: no GPS or BeiDou ephemeris record; the monitor maps the stations with them",
            args.nav.display()
        ))
        .into());
    }
    Ok(Inputs {
        config,
        files,
        stations,
        ephemerides,
    })
}

/// Run `skyforge monitor run`.
pub fn run(args: &MonitorArgs) -> anyhow::Result<()> {
    let Inputs {
        config,
        files,
        stations: station_list,
        ephemerides,
    } = read_inputs(args)?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let csv_path = staged.file(MONITOR_CSV);
    let mut csv = std::fs::File::create(&csv_path)
        .map(std::io::BufWriter::new)
        .with_context(|| format!("cannot create {}", csv_path.display()))?;
    writeln!(csv, "{}", csv_header())?;
    let (mut log, mut rows) = (AlarmLog::default(), H5Rows::default());
    let mut write_error = None;
    let mut start = None;
    let mask_deg = config.elevation_mask_deg;
    let monitored = run_files(&files, station_list.clone(), ephemerides, config, |e| {
        start.get_or_insert(e.time);
        if write_error.is_none() {
            write_error = write!(csv, "{}", csv_rows(e, &station_list)).err();
        }
        log.add(e, &station_list);
        rows.add(e);
    })
    .map_err(|e| BadInput(e.to_string()))?;
    if log.monitored == 0 {
        return Err(nothing_monitored(args, log.epochs, monitored.unmonitored, mask_deg).into());
    }
    if let Some(e) = write_error {
        return Err(e).with_context(|| format!("cannot write {}", csv_path.display()));
    }
    csv.into_inner()
        .map_err(|e| e.into_error())
        .with_context(|| format!("cannot write {}", csv_path.display()))?;
    let h5_path = staged.file(MONITOR_H5);
    if let Some(start) = start {
        rows.write(&h5_path, start, &station_list)
            .with_context(|| format!("cannot write {}", h5_path.display()))?;
    }
    let summary = log.summary(
        &station_list,
        monitored.common_point_ecef_m.into(),
        monitored.unmonitored,
    );
    let json_path = staged.file(SUMMARY_JSON);
    std::fs::write(&json_path, serde_json::to_string_pretty(&summary)?)
        .with_context(|| format!("cannot write {}", json_path.display()))?;
    let dir = staged.commit()?;
    println!("stations   {}", summary.stations.join(", "));
    println!(
        "epochs     {} ({} station-satellite values)",
        summary.epochs, summary.monitored
    );
    println!(
        "monitored  {} of {} epochs; satellites {}",
        summary.epochs_monitored,
        summary.epochs,
        summary.satellites_monitored.join(" ")
    );
    if summary.unmonitored != Unmonitored::default() {
        println!(
            "not monitored: {}",
            summary
                .unmonitored
                .describe(&args.nav.display().to_string(), mask_deg)
        );
    }
    println!("alarms     {}", summary.alarms.len());
    for a in &summary.alarms {
        println!(
            "  {:<6} {:<4} {:<14} from {} ({:.0} s), {} epochs, peak |B| {:.1} x threshold",
            a.station, a.sat, a.statistic, a.first_gpst, a.first_t_s, a.epochs, a.peak_ratio
        );
    }
    println!("wrote      {}", dir.join(MONITOR_CSV).display());
    Ok(())
}

/// The refusal of a run that monitored no satellite at any epoch (an integrity monitor
/// that watched nothing must not report an all-clear).
fn nothing_monitored(args: &MonitorArgs, epochs: usize, u: Unmonitored, mask_deg: f64) -> BadInput {
    let files: Vec<String> = args.files.iter().map(|p| p.display().to_string()).collect();
    let why = u.describe(&args.nav.display().to_string(), mask_deg);
    BadInput(format!(
        "monitored no satellite in {epochs} epochs of {}: {why}",
        files.join(", ")
    ))
}

/// How a calibrated configuration's thresholds are used, for the header of the files
/// the calibrations write.
const ALARM_RULE: &str = "# code, carrier and divergence alarm beyond their sigma x the normal quantile of\n\
                          # false_alarm, the smoothed code beyond smoothed_code_m (paper 002) or its own\n\
                          # k sigma, whichever is larger.\n";

/// Run `skyforge monitor calibrate`.
pub fn calibrate(args: &ScenarioRun, seeds: u64) -> anyhow::Result<()> {
    let scenario = super::resolve(args)?;
    let first = scenario.seed;
    let last = first.checked_add(seeds - 1).ok_or_else(|| {
        BadInput(format!(
            "seed {first} + {seeds} runs passes the largest seed"
        ))
    })?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let sigma = measure(&scenario, first..=last).map_err(BadInput)?;
    let text = toml::to_string(&config(sigma)).context("cannot encode the configuration")?;
    let header = format!(
        "# Monitor configuration, written by `skyforge monitor calibrate {} --seed {first} --seeds {seeds}`\n\
         # (seeds {first}..={last}, observation level, no fault events). thresholds.sigma: RMS\n\
         # of the fault-free B values per signal and elevation bin (lower edges {:?} deg);\n{ALARM_RULE}",
        args.scenario, ELEVATION_BINS_DEG
    );
    let path = staged.file("monitor.toml");
    std::fs::write(&path, header + &text)
        .with_context(|| format!("cannot write {}", path.display()))?;
    let dir = staged.commit()?;
    println!(
        "scenario   {} ({}), seeds {first}..={last}",
        scenario.name, scenario.source
    );
    println!("wrote      {}", dir.join("monitor.toml").display());
    Ok(())
}

/// Run `skyforge monitor calibrate-files`.
pub fn calibrate_files(args: &MonitorArgs, geo_apart: bool) -> anyhow::Result<()> {
    let inputs = read_inputs(args)?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let calibrated = measure_files(
        &inputs.files,
        inputs.stations,
        inputs.ephemerides,
        &inputs.config,
        geo_apart,
    )
    .map_err(BadInput)?;
    let text = toml::to_string(&calibrated.config).context("cannot encode the configuration")?;
    let names: Vec<String> = args.files.iter().map(|p| p.display().to_string()).collect();
    let base = match &args.config {
        Some(path) => path.display().to_string(),
        None => "the bundled configuration".to_string(),
    };
    let header = format!(
        "# Monitor configuration, written by `skyforge monitor calibrate-files` from the\n\
         # fault-free observation files {} (navigation {}); all but the sigma tables as in\n\
         # {base}. thresholds.sigma: RMS of their B values per signal and elevation bin\n\
         # (lower edges {:?} deg){}.\n{ALARM_RULE}",
        names.join(", "),
        args.nav.display(),
        ELEVATION_BINS_DEG,
        if geo_apart {
            ";\n# thresholds.sigma_geo: the same of the BeiDou GEOs, left out of thresholds.sigma"
        } else {
            ""
        }
    );
    let path = staged.file("monitor.toml");
    std::fs::write(&path, header + &text)
        .with_context(|| format!("cannot write {}", path.display()))?;
    let dir = staged.commit()?;
    println!("calibrated on {}", names.join(", "));
    for (tag, counts) in &calibrated.values_per_bin {
        println!(
            "  {tag:<17} B values per elevation bin {counts:?} (lower edges {ELEVATION_BINS_DEG:?} deg)"
        );
    }
    println!("wrote      {}", dir.join("monitor.toml").display());
    Ok(())
}
