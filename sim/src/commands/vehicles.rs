//! `run` and `synth` of a scenario with several vehicles (`[[vehicles]]`): each vehicle
//! runs as a single-platform scenario (`Scenario::vehicle_views`: its platform, antennas
//! and oscillator, its own receiver-side random streams, the satellites' errors shared)
//! into `DIR/<vehicle>/`, and `DIR/relative.csv` holds every vehicle's truth relative to
//! the first (`formats::relative`). A single-platform scenario runs as before, into `DIR`.

use crate::output::staged_dir::StagedDir;
use skyforge_formats::relative::{RELATIVE_CSV, write_relative_truth};
use skyforge_formats::truth::TRUTH_H5;
use skyforge_scenarios::Scenario;
use std::path::{Path, PathBuf};

/// Run `each(view, dir, force)` for every vehicle of `scenario` (once, into `out`, for a
/// single platform), then the relative truth.
pub fn each_vehicle(
    scenario: &Scenario,
    out: &Path,
    force: bool,
    mut each: impl FnMut(&Scenario, &Path, bool) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    if scenario.vehicles.is_empty() {
        return each(scenario, out, force);
    }
    let staged = StagedDir::create(out, force)?;
    let mut dirs: Vec<(String, PathBuf)> = Vec::new();
    for view in scenario.vehicle_views() {
        let name = view.vehicle.clone().unwrap_or_default();
        println!("vehicle    {name}");
        let dir = staged.file(&name);
        each(&view, &dir, false)?;
        dirs.push((name, dir));
    }
    let truth: Vec<(&str, PathBuf)> = (dirs.iter())
        .map(|(name, dir)| (name.as_str(), dir.join(TRUTH_H5)))
        .collect();
    let others: Vec<(&str, &Path)> = (truth[1..].iter())
        .map(|(name, path)| (*name, path.as_path()))
        .collect();
    write_relative_truth(
        &staged.file(RELATIVE_CSV),
        (truth[0].0, &truth[0].1),
        &others,
    )?;
    let dir = staged.commit()?;
    println!(
        "relative   {} relative to {}: {}",
        others.iter().map(|o| o.0).collect::<Vec<_>>().join(", "),
        truth[0].0,
        dir.join(RELATIVE_CSV).display()
    );
    Ok(())
}
