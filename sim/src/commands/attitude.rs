//! `skyforge attitude`: RINEX observation files of several antennas + navigation file +
//! body geometry -> baselines and attitude per epoch (`receiver::relative`), written to
//! `DIR/attitude.csv`.

use crate::BadInput;
use crate::cli::AttitudeArgs;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_receiver::relative::files::{BodyGeometryFile, EpochOutcome, run_files};
use skyforge_receiver::relative::{AmbiguityStatus, RelativeConfig};
use skyforge_signals::observation::read_obs_file;
use std::io::Write;

/// The CSV header for `m` baselines.
fn header(m: usize) -> String {
    let mut cols = vec![
        "time_gpst".to_string(),
        "status".into(),
        "ambiguities".into(),
        "fixed_combinations".into(),
        "held".into(),
        "ratio".into(),
        "success_rate".into(),
    ];
    for k in 1..=m {
        for c in [
            "x_m", "y_m", "z_m", "n_m", "e_m", "d_m", "sn_m", "se_m", "sd_m",
        ] {
            cols.push(format!("b{k}_{c}"));
        }
    }
    for c in ["yaw", "pitch", "roll"] {
        cols.push(format!("{c}_deg"));
    }
    for c in ["yaw", "pitch", "roll"] {
        cols.push(format!("{c}_std_deg"));
    }
    for c in ["yaw", "pitch", "roll"] {
        cols.push(format!("{c}_rate_dps"));
    }
    cols.push("note".into());
    cols.join(",")
}

/// One CSV row (empty fields for what the epoch did not give).
fn row(o: &EpochOutcome, m: usize) -> String {
    let blank = |n: usize| vec![String::new(); n];
    let mut f = vec![o.time.to_string()];
    let Ok(e) = &o.result else {
        f.push("none".into());
        f.extend(blank(5 + 9 * m + 9));
        f.push(
            o.result
                .as_ref()
                .err()
                .cloned()
                .unwrap_or_default()
                .replace(',', ";"),
        );
        return f.join(",");
    };
    let r = &e.resolution;
    let (status, combos) = match r.status {
        AmbiguityStatus::Float => ("float", 0),
        AmbiguityStatus::Partial { combinations } => ("partial", combinations),
        AmbiguityStatus::Fixed => ("fixed", e.float.ambiguities.len()),
    };
    f.push(status.into());
    f.push(e.float.ambiguities.len().to_string());
    f.push(combos.to_string());
    f.push(r.held.to_string());
    f.push(r.ratio.map_or(String::new(), |v| format!("{v:.3}")));
    f.push(format!("{:.6}", r.success_rate));
    for k in 0..m {
        let b = e.fixed.as_ref().map_or_else(
            || e.float.baselines.column(k).into_owned(),
            |x| x.baselines.column(k).into_owned(),
        );
        f.extend(b.iter().map(|v| format!("{v:.4}")));
        match &e.fixed_ned {
            Some(ned) => {
                let v = ned.baselines()[k];
                f.extend(v.iter().map(|x| format!("{x:.4}")));
                let q = ned.covariance();
                f.extend((0..3).map(|i| format!("{:.5}", q[(3 * k + i, 3 * k + i)].sqrt())));
            }
            None => f.extend(blank(6)),
        }
    }
    match &e.attitude {
        Some(s) => {
            let a = [s.angles.yaw_rad, s.angles.pitch_rad, s.angles.roll_rad];
            f.extend(a.iter().map(|v| format!("{:.5}", v.to_degrees())));
            f.extend((0..3).map(|i| format!("{:.5}", s.covariance[(i, i)].sqrt().to_degrees())));
            match s.rates_rad_s {
                Some(r) => f.extend(r.iter().map(|v| format!("{:.5}", v.to_degrees()))),
                None => f.extend(blank(3)),
            }
        }
        None => f.extend(blank(9)),
    }
    f.push(
        e.attitude_skipped
            .clone()
            .unwrap_or_default()
            .replace(',', ";"),
    );
    f.join(",")
}

/// The fixed integers of an epoch, one CSV row each (baselines numbered from 1).
fn integer_rows(o: &EpochOutcome) -> String {
    let Ok(e) = &o.result else {
        return String::new();
    };
    let layout = &e.float.model.layout;
    let ids: Vec<_> = layout.ambiguity_ids().collect();
    let mut out = String::new();
    for (i, value) in e.resolution.integers.iter().enumerate() {
        if let Some(v) = value {
            let (signal, sat, reference) = ids[i % ids.len()];
            out += &format!(
                "{},{},{},{sat},{reference},{v}\n",
                o.time,
                i / ids.len() + 1,
                signal.tag()
            );
        }
    }
    out
}

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
    writeln!(csv, "{}", header(m))?;
    writeln!(ints, "time_gpst,baseline,signal,sat,reference,integer")?;
    let (mut epochs, mut fixed, mut attitudes) = (0usize, 0usize, 0usize);
    let mut write_error = None;
    run_files(&files, ephemerides, &geometry, config, |o| {
        epochs += 1;
        if let Ok(e) = &o.result {
            fixed += usize::from(e.resolution.status == AmbiguityStatus::Fixed);
            attitudes += usize::from(e.attitude.is_some() && e.attitude_skipped.is_none());
        }
        if write_error.is_none() {
            write_error = writeln!(csv, "{}", row(&o, m))
                .and_then(|()| write!(ints, "{}", integer_rows(&o)))
                .err();
        }
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
