//! `skyforge relnav`: two spacecraft's RINEX observation files + navigation file -> the
//! chaser relative to the target in the target's orbit frame
//! (`navigation::relnav::relative_from_files`), written to `DIR/relnav.csv`
//! (`formats::relative`).

use crate::bad_input::BadInput;
use crate::cli::RelnavArgs;
use crate::output::staged_dir::StagedDir;
use hifitime::Unit;
use skyforge_formats::relative::{FixedFloat, RELNAV_CSV, RelativeRow, write_relative_csv};
use skyforge_navigation::relnav::{RelnavConfig, RelnavRun, relative_from_files};

/// Run `skyforge relnav`.
pub fn relnav(args: &RelnavArgs) -> anyhow::Result<()> {
    let config = read_config(args.config.as_deref())?;
    for (flag, name) in [
        ("--target-name", &args.target_name),
        ("--chaser-name", &args.chaser_name),
    ] {
        if name.is_empty() || name.contains(',') || name.chars().any(char::is_control) {
            return Err(BadInput(format!(
                "{flag} {name:?}: a non-empty name without commas or control characters"
            ))
            .into());
        }
    }
    let target = super::read_observations(&args.target)?;
    let chaser = super::read_observations(&args.chaser)?;
    let (ephemerides, iono) = super::attitude::read_nav_with_iono(&args.nav)?;
    let run = relative_from_files(&target, &chaser, ephemerides, &iono, &config)
        .map_err(|e| BadInput(e.to_string()))?;
    if run.estimates.is_empty() {
        return Err(BadInput(format!(
            "{} and {}: no common epoch with both fixes and velocities ({} tried)",
            args.target.display(),
            args.chaser.display(),
            run.missed
        ))
        .into());
    }
    let staged = StagedDir::create(&args.out, args.force)?;
    write_relnav_csv(&staged, &run, (&args.target_name, &args.chaser_name))?;
    let dir = staged.commit()?;
    print_summary(&run, &config);
    let counts = run.estimates.iter().filter_map(|e| e.ambiguities);
    let (fixed, float) = counts.fold((0, 0), |(x, y), a| (x + a.fixed, y + a.float));
    if fixed + float > 0 {
        println!(
            "integers   {fixed} of {} double-difference ambiguities fixed over the epochs ({:.1} %)",
            fixed + float,
            100.0 * fixed as f64 / (fixed + float) as f64
        );
    }
    println!("wrote      {}", dir.join(RELNAV_CSV).display());
    Ok(())
}

/// The settings at `path`, or the documented defaults.
pub(crate) fn read_config(path: Option<&std::path::Path>) -> anyhow::Result<RelnavConfig> {
    Ok(match path {
        Some(path) => RelnavConfig::read(path).map_err(BadInput)?,
        None => RelnavConfig::default(),
    })
}

/// `run`'s estimates as `relnav.csv` in `staged` (the vehicles' names: target, chaser).
pub(crate) fn write_relnav_csv(
    staged: &StagedDir,
    run: &RelnavRun,
    (target, chaser): (&str, &str),
) -> anyhow::Result<()> {
    let rows: Vec<RelativeRow> = (run.estimates.iter())
        .map(|e| RelativeRow {
            time: run.start + Unit::Second * e.t_s,
            vehicle: chaser.to_owned(),
            target: target.to_owned(),
            position_m: e.position_m,
            velocity_mps: e.velocity_mps,
            baseline_ecef_m: e.baseline_ecef_m,
            ambiguities: e.ambiguities.map(|a| FixedFloat {
                fixed: a.fixed,
                float: a.float,
            }),
        })
        .collect();
    write_relative_csv(&staged.file(RELNAV_CSV), run.start, &rows)?;
    Ok(())
}

/// The mode, the filter and the counts of `run`.
pub(crate) fn print_summary(run: &RelnavRun, config: &RelnavConfig) {
    let signals: Vec<String> = run.signals.iter().map(|s| s.to_string()).collect();
    println!("mode       {} ({})", run.mode.name(), signals.join(", "));
    if config.filter.is_some() {
        println!("filter     the book's relative filter (Hill dynamics, eqs. 5-57/5-58)");
    }
    println!(
        "epochs     {} estimates, {} common epochs without both fixes",
        run.estimates.len(),
        run.missed
    );
}
