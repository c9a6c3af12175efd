//! `skyforge od`: one spacecraft's RINEX observation file + navigation file -> its
//! orbit, estimated by the filter the configuration chooses
//! (`navigation::orbit_determination`), written to `DIR/orbit.csv`, `DIR/orbit.h5` and
//! `DIR/orbit.sp3` (`formats::orbit`).

use crate::bad_input::BadInput;
use crate::cli::OdArgs;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use hifitime::Epoch;
use skyforge_formats::orbit::{
    ORBIT_CSV, ORBIT_H5, ORBIT_SP3, write_csv, write_h5, write_orbit_sp3,
};
use skyforge_navigation::orbit_determination::{
    EcefEstimate, OdConfig, OdFilterConfig, orbit_from_file,
};
use std::path::Path;

/// The configuration's filter as `orbit.h5` names it.
fn filter_name(config: &OdConfig) -> &'static str {
    match config.filter {
        OdFilterConfig::PositionFilter(_) => "position-filter",
        OdFilterConfig::ReducedDynamic(_) => "reduced-dynamic",
    }
}

/// Run `skyforge od`.
pub fn od(args: &OdArgs) -> anyhow::Result<()> {
    let config = read_config(args.config.as_deref())?;
    let file = super::read_observations(&args.file)?;
    let (ephemerides, iono) = super::attitude::read_nav_with_iono(&args.nav)?;
    let run =
        orbit_from_file(&file, ephemerides, &iono, &config).map_err(|e| BadInput(e.to_string()))?;
    if run.estimates.is_empty() {
        return Err(BadInput(format!(
            "{}: no estimate on the {} s grid ({} epochs without one): no single-point fix to start from",
            args.file.display(),
            config.interval_s,
            run.missed
        ))
        .into());
    }
    let staged = StagedDir::create(&args.out, args.force)?;
    write_outputs(&staged, run.start, &run.estimates, &config)?;
    let dir = staged.commit()?;
    let signals: Vec<String> = run.signals.iter().map(|s| s.to_string()).collect();
    println!(
        "filter     {} ({})",
        filter_name(&config),
        signals.join(", ")
    );
    print_summary(&dir, &run.estimates, run.missed, &config);
    Ok(())
}

/// The configuration `--config` or `receive --od` names, or the documented defaults.
pub(crate) fn read_config(path: Option<&Path>) -> anyhow::Result<OdConfig> {
    Ok(match path {
        Some(path) => OdConfig::read(path).map_err(BadInput)?,
        None => OdConfig::default(),
    })
}

/// The three files of the estimates (`t_s` since `start`) into `staged`.
pub(crate) fn write_outputs(
    staged: &StagedDir,
    start: Epoch,
    estimates: &[EcefEstimate],
    config: &OdConfig,
) -> anyhow::Result<()> {
    let filter = filter_name(config);
    let writing = |p: &Path| format!("writing {}", p.display());
    let csv = staged.file(ORBIT_CSV);
    write_csv(&csv, start, estimates).with_context(|| writing(&csv))?;
    let h5 = staged.file(ORBIT_H5);
    write_h5(&h5, start, filter, estimates).with_context(|| writing(&h5))?;
    let sp3 = staged.file(ORBIT_SP3);
    write_orbit_sp3(&sp3, start, filter, estimates).with_context(|| writing(&sp3))
}

/// The summary lines of a run with at least one estimate.
pub(crate) fn print_summary(
    dir: &Path,
    estimates: &[EcefEstimate],
    missed: usize,
    config: &OdConfig,
) {
    let (first, last) = (&estimates[0], &estimates[estimates.len() - 1]);
    let sigma = |from: usize| {
        (from..from + 3)
            .map(|i| last.covariance[(i, i)])
            .sum::<f64>()
            .sqrt()
    };
    println!(
        "estimates  {} every {} s from {:.1} s to {:.1} s; {} epochs on the grid without one",
        estimates.len(),
        config.interval_s,
        first.t_s,
        last.t_s,
        missed
    );
    println!(
        "last       3-D sigma {:.2} m, {:.4} m/s (the filter's own)",
        sigma(0),
        sigma(3)
    );
    for name in [ORBIT_CSV, ORBIT_H5, ORBIT_SP3] {
        println!("wrote      {}", dir.join(name).display());
    }
}
