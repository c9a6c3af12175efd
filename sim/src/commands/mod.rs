//! One module per subcommand.

mod ambiguity;
mod attitude;
mod calibrate;
mod dry_run;
mod imu;
mod ins;
mod jamming;
mod monitor;
mod od;
mod receive;
mod relnav;
mod report;
mod run;
mod scenarios;
mod study;
pub(crate) mod synth;
mod validate;
mod vehicles;

use crate::bad_input::BadInput;
use crate::cli::{
    Cli, Command, MonitorAction, ScenarioRun, ScenariosAction, StudyAction, ValidateSuite,
};
use skyforge_validate::draw::SeedPlan;

/// The scenario `args` name, with its seed overridden when `--seed` is given.
fn resolve(args: &ScenarioRun) -> anyhow::Result<skyforge_scenarios::Scenario> {
    let mut scenario = skyforge_scenarios::resolve(&args.scenario)?;
    if let Some(seed) = args.seed {
        scenario.seed = seed;
    }
    Ok(scenario)
}

/// Run the parsed command line.
pub fn dispatch(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Run { run } => run::run(&run),
        Command::Synth {
            run,
            chunk_epochs,
            dry_run,
            receive,
            receiver_config,
        } => {
            let alongside = receive.then_some(synth::ReceiveAlongside {
                config: receiver_config,
            });
            synth::synth(&run, chunk_epochs as usize, dry_run, alongside.as_ref())
        }
        Command::Calibrate { run } => calibrate::calibrate(&run),
        Command::Study { action } => match action {
            StudyAction::Run {
                study,
                out,
                shard,
                force,
            } => study::run(&study, &out, shard.as_deref(), force),
            StudyAction::Merge { dirs, out, force } => study::merge(&dirs, out.as_deref(), force),
            StudyAction::Slurm {
                study,
                out,
                shards,
                skyforge,
                sbatch,
                force,
            } => study::slurm(&study, &out, shards, skyforge.as_deref(), &sbatch, force),
        },
        Command::Attitude { args } => attitude::attitude(&args),
        Command::Od { args } => od::od(&args),
        Command::Ins { args } => ins::ins(&args),
        Command::Relnav { args } => relnav::relnav(&args),
        Command::Jamming { args } => jamming::jamming(&args),
        Command::Receive { args } => receive::receive(&args),
        Command::Ambiguity {
            file,
            candidates,
            json,
        } => ambiguity::ambiguity(&file, candidates as usize, json),
        Command::Monitor {
            action: MonitorAction::Run { args },
        } => monitor::run(&args),
        Command::Monitor {
            action: MonitorAction::Calibrate { run, seeds },
        } => monitor::calibrate(&run, seeds),
        Command::Monitor {
            action: MonitorAction::CalibrateFiles { args, geo_apart },
        } => monitor::calibrate_files(&args, geo_apart),
        Command::Report {
            dir,
            out,
            force,
            attitude,
            observations,
        } => report::report(
            skyforge_studies::html_report::Inputs {
                dir: &dir,
                attitude: attitude.as_deref(),
                observations: observations.as_deref(),
            },
            out.as_deref(),
            force,
        ),
        Command::Scenarios {
            action: ScenariosAction::List,
        } => scenarios::list(),
        Command::Scenarios {
            action: ScenariosAction::Show { name },
        } => scenarios::show(&name),
        Command::Validate {
            suite:
                ValidateSuite::Thesis {
                    only,
                    out,
                    force,
                    data,
                    seeds,
                    seed_base,
                },
        } => validate::thesis(
            only,
            out.as_deref(),
            force,
            data,
            seeds
                .map(|draws| SeedPlan::new(draws, seed_base.unwrap_or(0)))
                .transpose()
                .map_err(BadInput)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Obs {
                    truth,
                    estimate,
                    json,
                    force,
                    tag_offset_s,
                    from,
                    to,
                },
        } => validate::obs(
            &truth,
            &estimate,
            validate::JsonOut::new(json.as_deref(), force)?,
            tag_offset_s,
            from.zip(to).as_ref(),
        ),
        Command::Validate {
            suite:
                ValidateSuite::Attitude {
                    truth,
                    observations,
                    attitude,
                    json,
                    force,
                },
        } => validate::attitude(
            &truth,
            &observations,
            &attitude,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Monitor {
                    truth,
                    monitor,
                    json,
                    force,
                },
        } => validate::monitor(
            &truth,
            &monitor,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Od {
                    truth,
                    orbit,
                    settle_s,
                    json,
                    force,
                },
        } => validate::od(
            &truth,
            &orbit,
            settle_s,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Ins {
                    truth,
                    ins,
                    json,
                    force,
                },
        } => validate::ins(
            &truth,
            &ins,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Interference {
                    truth,
                    detections,
                    json,
                    force,
                },
        } => validate::interference(
            &truth,
            &detections,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite:
                ValidateSuite::Relnav {
                    truth,
                    relnav,
                    settle_s,
                    json,
                    force,
                },
        } => validate::relnav(
            &truth,
            &relnav,
            settle_s,
            validate::JsonOut::new(json.as_deref(), force)?,
        ),
        Command::Validate {
            suite: ValidateSuite::Agree { first, second },
        } => validate::agree(&first, &second),
    }
}

/// Beside the finished `truth.h5` in `staged`, what `run` and `synth` alike add to the
/// truth: a LEO's orbit as `truth.sp3` and, with `[imu]`, the IMU's files.
fn write_truth_sidecars(
    scenario: &skyforge_scenarios::Scenario,
    staged: &crate::output::staged_dir::StagedDir,
) -> anyhow::Result<()> {
    write_truth_sp3(scenario, staged)?;
    imu::write_imu(scenario, staged)
}

/// A LEO platform's orbit as `truth.sp3` (what `skyforge od`'s `orbit.sp3` is compared
/// with by anyone's SP3 tools).
fn write_truth_sp3(
    scenario: &skyforge_scenarios::Scenario,
    staged: &crate::output::staged_dir::StagedDir,
) -> anyhow::Result<()> {
    use skyforge_formats::orbit::{TRUTH_SP3, write_truth_sp3};
    use skyforge_formats::truth::TRUTH_H5;
    if scenario.platform.leo.is_none() {
        return Ok(());
    }
    write_truth_sp3(&staged.file(TRUTH_H5), &staged.file(TRUTH_SP3))?;
    Ok(())
}

/// The RINEX observation file at `path` (`attitude`, `monitor`, `validate obs`); what the
/// reader left out is a warning on stderr naming the file and the lines, what it refused
/// the one error.
fn read_observations(
    path: &std::path::Path,
) -> Result<skyforge_gnss::observation::ObsFile, crate::bad_input::BadInput> {
    let file = skyforge_gnss::observation::read_obs_file(path)
        .map_err(|e| crate::bad_input::BadInput(e.to_string()))?;
    if let Some(warning) = file.dropped_warning() {
        eprintln!("warning: {warning}");
    }
    Ok(file)
}
