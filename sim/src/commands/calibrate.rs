//! `skyforge calibrate`: the observation level's noise factors, measured on a signal-level
//! run of a scenario (`validate::calibrate`), written to `DIR/calibration.toml`.

use crate::cli::ScenarioRun;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_orbits::check::Invalid;
use skyforge_studies::calibrate::{MIN_DURATION_S, SETTLING_S, calibrate as measure};

/// Calibrate on the scenario `args` names.
pub fn calibrate(args: &ScenarioRun) -> anyhow::Result<()> {
    let scenario = super::resolve(args)?;
    let duration_s = scenario.time.duration_s;
    if duration_s < MIN_DURATION_S {
        return Err(scenario
            .located(Invalid::new(
                "time.duration_s",
                duration_s,
                format!(
                    "at least {MIN_DURATION_S} s to calibrate on ({SETTLING_S} s of settling, then observations)"
                ),
            ))
            .into());
    }
    let staged = StagedDir::create(&args.out, args.force)?;
    let work = staged.file("work");
    std::fs::create_dir(&work).with_context(|| format!("cannot create {}", work.display()))?;
    let calibration = measure(&scenario, &work).map_err(|e| anyhow::anyhow!("{e}"))?;
    std::fs::remove_dir_all(&work).with_context(|| format!("cannot remove {}", work.display()))?;
    let text = toml::to_string(&calibration).context("cannot encode the calibration")?;
    let header = format!(
        "# Observation-level noise calibration, written by `skyforge calibrate {}`\n\
         # (seed {}; the first {SETTLING_S} s of tracking left out). Factors: the bundled\n\
         # receiver's code / phase / Doppler noise std over the loop formulas' at each\n\
         # satellite's C/N0.\n",
        args.scenario, scenario.seed
    );
    let path = staged.file("calibration.toml");
    std::fs::write(&path, header + &text)
        .with_context(|| format!("cannot write {}", path.display()))?;
    let dir = staged.commit()?;
    println!("scenario   {} ({})", scenario.name, scenario.source);
    for s in &calibration.signals {
        let doppler = s
            .doppler_factor
            .map_or_else(String::new, |d| format!(", Doppler x{d:.3}"));
        println!(
            "{:<10} code x{:.3}, phase x{:.3}{doppler} ({} observations, C/N0 {:.1}..{:.1} dB-Hz)",
            s.signal, s.code_factor, s.phase_factor, s.samples, s.cn0_dbhz[0], s.cn0_dbhz[1]
        );
    }
    println!("wrote      {}", dir.join("calibration.toml").display());
    Ok(())
}
