//! `skyforge run`: scenario -> geometry truth -> `truth.h5`.

use crate::cli::ScenarioRun;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use skyforge_formats::truth::{RunMeta, TRUTH_H5, TruthWriter};
use skyforge_scenarios::Scenario;
use skyforge_signals::truth::{GeometryChunk, StreamError, epoch_count};
use std::path::Path;
use std::sync::mpsc::sync_channel;
use std::time::Instant;

/// Epochs per streamed chunk (10 min at 1 Hz): bounds memory whatever the duration.
const CHUNK_EPOCHS: usize = 600;

/// Run the scenario `args` names and write `out/truth.h5` (with a `[signal]` table, its
/// synthesis); a scenario with several vehicles runs each into its own directory.
pub fn run(args: &ScenarioRun) -> anyhow::Result<()> {
    let scenario = super::resolve(args)?;
    super::vehicles::each_vehicle(
        &scenario,
        &args.out,
        args.force,
        |view, out, force| match view.signal.clone() {
            Some(signal) => super::synth::synthesise(
                view,
                &signal,
                out,
                force,
                crate::cli::DEFAULT_CHUNK_EPOCHS as usize,
                None,
            ),
            None => run_geometry(view, out, force),
        },
    )
}

/// The geometry truth of a single-platform `scenario` into `out/truth.h5`.
fn run_geometry(scenario: &Scenario, out: &Path, force: bool) -> anyhow::Result<()> {
    let started = Instant::now();
    let mut world = scenario.build()?;
    let staged = StagedDir::create(out, force)?;
    let meta = RunMeta::new(scenario, world.origin.start(), world.step_s);
    let path = staged.file(TRUTH_H5);
    let mut writer = TruthWriter::create(&path, &meta, &world.satellites, &world.antennas)
        .with_context(|| format!("cannot create {}", path.display()))?;

    let n_epochs = epoch_count(world.duration_s, world.step_s);
    let bar = ProgressBar::new(n_epochs as u64).with_style(
        ProgressStyle::with_template(
            "{spinner} geometry [{bar:40}] {pos}/{len} epochs ({eta} left)",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let n_ant = world.antennas.len();
    let mut visible_sum = vec![0usize; n_ant];

    // The HDF5 writer runs on its own thread so computing the next chunk overlaps writing.
    let (tx, rx) = sync_channel::<GeometryChunk>(1);
    std::thread::scope(|scope| -> anyhow::Result<()> {
        let writer_thread = scope.spawn(move || -> hdf5::Result<()> {
            for chunk in rx {
                writer.append(&chunk)?;
            }
            writer.finish()
        });
        let streamed = world.stream_geometry(CHUNK_EPOCHS, |chunk| {
            for (a, sum) in visible_sum.iter_mut().enumerate() {
                for k in 0..chunk.t_s.len() {
                    *sum += (0..chunk.n_satellites)
                        .filter(|&s| chunk.link(k, a, s).visible)
                        .count();
                }
            }
            bar.inc(chunk.t_s.len() as u64);
            tx.send(chunk)
        });
        drop(tx);
        let written = writer_thread
            .join()
            .map_err(|_| anyhow::anyhow!("HDF5 writer thread panicked"))?;
        written.with_context(|| format!("writing {}", path.display()))?;
        streamed.map_err(|e| match e {
            StreamError::Platform(p) => scenario.platform_error(p).into(),
            e => anyhow::Error::new(e).context("geometry"),
        })?;
        Ok(())
    })?;
    bar.finish_and_clear();
    super::write_truth_sidecars(scenario, &staged)?;
    let dir = staged.commit()?;

    println!("scenario   {} ({})", scenario.name, scenario.source);
    println!("start      {}", world.origin.start());
    println!(
        "span       {} s, {} epochs every {} s",
        world.duration_s, n_epochs, world.step_s
    );
    println!("satellites {}", world.satellites.len());
    for (ant, sum) in world.antennas.iter().zip(&visible_sum) {
        println!(
            "antenna    {:<10} mean visible {:.2}",
            ant.name,
            *sum as f64 / n_epochs as f64
        );
    }
    println!(
        "wrote      {}",
        StagedDir::final_path(&dir.join(TRUTH_H5)).display()
    );
    println!("elapsed    {:.2} s", started.elapsed().as_secs_f64());
    Ok(())
}
