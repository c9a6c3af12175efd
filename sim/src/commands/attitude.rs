//! `skyforge attitude`: RINEX observation files of several antennas + navigation file +
//! body geometry -> baselines and attitude per epoch (`receiver::relative`), written to
//! `DIR/attitude.csv`, `DIR/attitude.h5` and `DIR/ambiguities.csv`.

use crate::BadInput;
use crate::cli::AttitudeArgs;
use crate::output::attitude_out::{EpochValues, csv_header, csv_row, integer_rows, write_h5};
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_receiver::relative::files::{BodyGeometryFile, run_files};
use skyforge_receiver::relative::{AmbiguityStatus, RelativeConfig};
use skyforge_signals::observation::read_obs_file;
use std::io::Write;

/// Run `skyforge attitude`.
pub fn attitude(args: &AttitudeArgs) -> anyhow::Result<()> {
    let geometry = BodyGeometryFile::read(&args.geometry).map_err(|e| BadInput(e.to_string()))?;
    if args.files.len() != geometry.antennas.len() {
        return Err(BadInput(format!(
            "{} observation files for the {} antennas of {} (one per antenna, in its order)",
            args.files.len(),
            geometry.antennas.len(),
            args.geometry.display()
        ))
        .into());
    }
    let config = match &args.config {
        Some(path) => RelativeConfig::read(path).map_err(BadInput)?,
        None => RelativeConfig::default(),
    };
    let files = args
        .files
        .iter()
        .map(|p| read_obs_file(p).map_err(|e| BadInput(e.to_string())))
        .collect::<Result<Vec<_>, _>>()?;
    let ephemerides =
        read_nav_file(&args.nav).map_err(|e| BadInput(format!("{}: {e}", args.nav.display())))?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let path = staged.file("attitude.csv");
    let ints_path = staged.file("ambiguities.csv");
    let create = |p: &std::path::Path| {
        std::fs::File::create(p)
            .map(std::io::BufWriter::new)
            .with_context(|| format!("cannot create {}", p.display()))
    };
    let (mut csv, mut ints) = (create(&path)?, create(&ints_path)?);
    let m = geometry.antennas.len() - 1;
    writeln!(csv, "{}", csv_header(m))?;
    writeln!(ints, "time_gpst,baseline,signal,sat,reference,integer")?;
    let (mut epochs, mut fixed, mut attitudes) = (0usize, 0usize, 0usize);
    let mut write_error = None;
    let mut values = Vec::new();
    run_files(&files, ephemerides, &geometry, config, |o| {
        epochs += 1;
        if let Ok(e) = &o.result {
            fixed += usize::from(e.resolution.status == AmbiguityStatus::Fixed);
            attitudes += usize::from(e.attitude.is_some() && e.attitude_skipped.is_none());
        }
        let v = EpochValues::of(&o, m);
        if write_error.is_none() {
            write_error = writeln!(csv, "{}", csv_row(&v, m))
                .and_then(|()| write!(ints, "{}", integer_rows(&o)))
                .err();
        }
        values.push(v);
    })
    .map_err(|e| BadInput(e.to_string()))?;
    if let Some(e) = write_error {
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    for (w, p) in [(csv, &path), (ints, &ints_path)] {
        w.into_inner()
            .map_err(|e| e.into_error())
            .with_context(|| format!("cannot write {}", p.display()))?;
    }
    let h5_path = staged.file("attitude.h5");
    write_h5(&h5_path, &values, m)
        .with_context(|| format!("cannot write {}", h5_path.display()))?;
    let dir = staged.commit()?;
    println!("epochs     {epochs}");
    println!(
        "fixed      {fixed} ({:.1} %)",
        100.0 * fixed as f64 / epochs.max(1) as f64
    );
    println!("attitude   {attitudes} epochs");
    println!("wrote      {}", dir.join("attitude.csv").display());
    Ok(())
}
