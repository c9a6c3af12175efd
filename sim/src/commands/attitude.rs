//! `skyforge attitude`: RINEX observation files of several antennas + navigation file +
//! body geometry -> baselines and attitude per epoch (`receiver::relative`), written to
//! `DIR/attitude.csv`, `DIR/attitude.h5` and `DIR/ambiguities.csv`; with
//! `--estimate-geometry` also the geometry offsets of thesis 4.3
//! (`receiver::geometry_offset::stacked_ukf`) to `DIR/geometry_offsets.{csv,h5}` and the
//! corrected geometry `DIR/geometry_corrected.toml`.

use crate::BadInput;
use crate::cli::AttitudeArgs;
use crate::output::attitude_out::{EpochValues, csv_header, csv_row, integer_rows, write_h5};
use crate::output::geometry_out::{self, OffsetRow};
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_receiver::attitude::BodyGeometry;
use skyforge_receiver::geometry_offset::stacked_ukf::{OffsetEstimator, Step};
use skyforge_receiver::relative::config::Constraint;
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
    let mut config = match &args.config {
        Some(path) => RelativeConfig::read(path).map_err(BadInput)?,
        None => RelativeConfig::default(),
    };
    if args.estimate_geometry {
        // The integer search must not lean on the geometry being estimated.
        config.constraint = Constraint::None;
        println!(
            "integers   plain LAMBDA (--estimate-geometry: the nominal geometry is not a constraint)"
        );
    }
    let mut offsets = match args.estimate_geometry {
        false => None,
        true => Some(offset_estimator(&geometry, &config, &args.geometry)?),
    };
    let files = args
        .files
        .iter()
        .map(|p| read_obs_file(p).map_err(|e| BadInput(e.to_string())))
        .collect::<Result<Vec<_>, _>>()?;
    let ephemerides =
        read_nav_file(&args.nav).map_err(|e| BadInput(format!("{}: {e}", args.nav.display())))?;
    // The estimator's clock: seconds since the master's first epoch.
    let start = files
        .first()
        .and_then(|f| f.epochs.first())
        .map_or(hifitime::Epoch::from_gpst_seconds(0.0), |e| e.time);
    let mut offset_rows = Vec::new();
    let mut offset_error = None;
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
            let whole = e.resolution.status == AmbiguityStatus::Fixed;
            if let (Some(f), Some(ned), None, true) =
                (offsets.as_mut(), &e.fixed_ned, &offset_error, whole)
            {
                let t_s = (o.time - start).to_seconds();
                match f.push(t_s, ned.clone()) {
                    Ok(Step::Updated { chi_square, dof }) => {
                        offset_rows.extend(f.state().map(|state| OffsetRow {
                            time: o.time,
                            state,
                            chi_square,
                            dof,
                        }))
                    }
                    Ok(_) => {}
                    Err(err) => offset_error = Some(format!("{}: {err}", o.time)),
                }
            }
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
    if let Some(f) = &offsets {
        if let Some(e) = offset_error {
            return Err(BadInput(format!("geometry offsets: {e}")).into());
        }
        write_offsets(&staged, &geometry, f, &offset_rows)?;
    }
    let dir = staged.commit()?;
    println!("epochs     {epochs}");
    println!(
        "fixed      {fixed} ({:.1} %)",
        100.0 * fixed as f64 / epochs.max(1) as f64
    );
    println!("attitude   {attitudes} epochs");
    println!("wrote      {}", dir.join("attitude.csv").display());
    if let Some(last) = offset_rows.last() {
        let (s, p) = (&last.state, &last.state.offsets_covariance_m2);
        for (k, d) in s.offsets_m.iter().enumerate() {
            let sd = |i: usize| 1e3 * p[(3 * k + i, 3 * k + i)].sqrt();
            println!(
                "offset b{} [{:+.2}, {:+.2}, {:+.2}] mm (1 sigma {:.2}, {:.2}, {:.2}) after {} updates",
                k + 1,
                1e3 * d.x,
                1e3 * d.y,
                1e3 * d.z,
                sd(0),
                sd(1),
                sd(2),
                offset_rows.len()
            );
        }
        println!(
            "wrote      {}",
            dir.join("geometry_corrected.toml").display()
        );
    }
    Ok(())
}

/// The estimator for the file's geometry (two baselines), or a located error.
fn offset_estimator(
    geometry: &BodyGeometryFile,
    config: &RelativeConfig,
    path: &std::path::Path,
) -> anyhow::Result<OffsetEstimator> {
    let positions = geometry.positions();
    let baselines: Vec<_> = positions.iter().skip(1).map(|p| p - positions[0]).collect();
    BodyGeometry::new(&baselines)
        .and_then(|g| OffsetEstimator::new(config.geometry_offsets, g))
        .map_err(|e| BadInput(format!("--estimate-geometry with {}: {e}", path.display())).into())
}

/// `geometry_offsets.csv`, `geometry_offsets.h5` and `geometry_corrected.toml`.
fn write_offsets(
    staged: &StagedDir,
    geometry: &BodyGeometryFile,
    estimator: &OffsetEstimator,
    rows: &[OffsetRow],
) -> anyhow::Result<()> {
    let csv_path = staged.file("geometry_offsets.csv");
    let mut text = geometry_out::csv_header() + "\n";
    for r in rows {
        text += &(geometry_out::csv_row(r) + "\n");
    }
    std::fs::write(&csv_path, text)
        .with_context(|| format!("cannot write {}", csv_path.display()))?;
    let h5_path = staged.file("geometry_offsets.h5");
    geometry_out::write_h5(&h5_path, rows)
        .with_context(|| format!("cannot write {}", h5_path.display()))?;
    let corrected = estimator
        .corrected_geometry()
        .map_err(|e| BadInput(format!("geometry offsets: {e}")))?;
    let toml_path = staged.file("geometry_corrected.toml");
    let file = geometry_out::corrected_file(geometry, &corrected);
    let text = toml::to_string(&file).context("cannot format the corrected geometry")?;
    std::fs::write(&toml_path, text)
        .with_context(|| format!("cannot write {}", toml_path.display()))
}
