//! `skyforge attitude`: RINEX observation files of several antennas + navigation file +
//! body geometry -> baselines and attitude per epoch (`receiver::relative`), written to
//! `DIR/attitude.csv`, `DIR/attitude.h5` and `DIR/ambiguities.csv`; with
//! `--estimate-geometry` also the geometry offsets of thesis 4.3
//! (`receiver::geometry_offset::stacked_ukf`) to `DIR/geometry_offsets.{csv,h5}` and the
//! corrected geometry `DIR/geometry_corrected.toml`. [`Chain`] is the same for `skyforge
//! receive --geometry`, which runs it on the receiver's own observations.

use crate::bad_input::BadInput;
use crate::cli::AttitudeArgs;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_formats::attitude::{
    ATTITUDE_CSV, ATTITUDE_H5, EpochFiles, EpochValues, integer_rows, write_h5,
};
use skyforge_formats::geometry_offsets::{
    self, GEOMETRY_CORRECTED_TOML, GEOMETRY_OFFSETS_CSV, GEOMETRY_OFFSETS_H5, OffsetRow,
};
use skyforge_gnss::observation::ObsFile;
use skyforge_gnss::observation::epoch_as_written;
use skyforge_navigation::attitude::BodyGeometry;
use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_navigation::geometry_offset::{OffsetEstimator, Step};
use skyforge_navigation::relative::Constraint;
use skyforge_navigation::relative::{AmbiguityStatus, FixMethod, RelativeConfig};
use skyforge_navigation::relative::{EpochChain, EpochOutcome, FilesError, run_files};
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_orbits::ephemeris::rinex_nav::{read_nav_file, read_nav_file_with_iono};
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_receiver::pipeline::EpochReport;
use std::collections::BTreeMap;
use std::path::Path;

/// Run `skyforge attitude`.
pub fn attitude(args: &AttitudeArgs) -> anyhow::Result<()> {
    let chain = Chain::new(
        &args.geometry,
        args.config.as_deref(),
        args.estimate_geometry,
    )?;
    if args.files.len() != chain.geometry.antennas.len() {
        return Err(BadInput(format!(
            "{} observation files for the {} antennas of {} (one per antenna, in its order)",
            args.files.len(),
            chain.geometry.antennas.len(),
            args.geometry.display()
        ))
        .into());
    }
    let files = args
        .files
        .iter()
        .map(|p| super::read_observations(p))
        .collect::<Result<Vec<_>, _>>()?;
    chain.check_markers(&args.geometry, &files)?;
    let ephemerides = read_nav(&args.nav)?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let summary = chain.run(&files, ephemerides, &args.nav, &staged)?;
    let dir = staged.commit()?;
    summary.print(&dir);
    Ok(())
}

/// The navigation file at `path`, or a located error.
pub(crate) fn read_nav(path: &Path) -> anyhow::Result<Vec<BroadcastEphemeris>> {
    read_nav_file(path).map_err(|e| BadInput(format!("{}: {e}", path.display())).into())
}

/// The navigation file at `path` with its header's ionosphere (`od`, `relnav`), or a
/// located error.
pub(crate) fn read_nav_with_iono(
    path: &Path,
) -> anyhow::Result<(Vec<BroadcastEphemeris>, BroadcastIono)> {
    read_nav_file_with_iono(path).map_err(|e| BadInput(format!("{}: {e}", path.display())).into())
}

/// The chain's set-up: the geometry, the settings and, with `--estimate-geometry`, the
/// offset estimator; checked before any observation is read.
pub(crate) struct Chain {
    geometry: BodyGeometryFile,
    config: RelativeConfig,
    offsets: Option<OffsetEstimator>,
}

/// What the chain did, for the summary lines.
pub(crate) struct ChainSummary {
    epochs: usize,
    fixed: usize,
    attitudes: usize,
    /// Epochs whose integers each method decided (indexed by `FixMethod as usize`).
    methods: [usize; FixMethod::ALL.len()],
    /// Epochs where the constrained search fell back to LAMBDA, and the first reason.
    fallbacks: (usize, Option<String>),
    /// Epochs where the reverse filter failed and restarted, and the first reason.
    reverse_restarts: (usize, Option<String>),
    /// Epochs that gave no result, by reason ([`reason_kind`]), and the first in full.
    none: BTreeMap<String, usize>,
    first_none: Option<(hifitime::Epoch, String)>,
    /// `--estimate-geometry` was given.
    estimating: bool,
    offset_rows: Vec<OffsetRow>,
}

impl Chain {
    /// Read the geometry and the settings (`config_path`: a TOML file with a `[relative]`
    /// table). With `estimate_geometry` the integer search is plain LAMBDA: it must not
    /// lean on the geometry being estimated.
    pub fn new(
        geometry_path: &Path,
        config_path: Option<&Path>,
        estimate_geometry: bool,
    ) -> anyhow::Result<Self> {
        let geometry =
            BodyGeometryFile::read(geometry_path).map_err(|e| BadInput(e.to_string()))?;
        let mut config = match config_path {
            Some(path) => RelativeConfig::read(path).map_err(BadInput)?,
            None => RelativeConfig::default(),
        };
        let offsets = match estimate_geometry {
            false => None,
            true => {
                config.constraint = Constraint::None;
                Some(offset_estimator(&geometry, &config, geometry_path)?)
            }
        };
        Ok(Self {
            geometry,
            config,
            offsets,
        })
    }

    /// The geometry's antenna names, master first.
    pub fn antennas(&self) -> impl Iterator<Item = &str> {
        self.geometry.antennas.iter().map(|a| a.name.as_str())
    }

    /// The geometry's antennas that `recorded` (names) lacks are an error naming the
    /// geometry file at `path` and saying `what` they lack and how the names were `listed`
    /// (`receive --geometry`: the recordings; `attitude`: the files' `MARKER NAME`s).
    pub fn check_recorded(
        &self,
        path: &Path,
        recorded: &[String],
        (what, listed): (&str, &str),
    ) -> Result<(), BadInput> {
        match self.antennas().find(|a| !recorded.iter().any(|n| n == a)) {
            Some(missing) => Err(BadInput(format!(
                "{}: antenna {missing:?} has no {what} ({listed}: {})",
                path.display(),
                recorded.join(", ")
            ))),
            None => Ok(()),
        }
    }

    /// `files` (one per antenna, in the order of the geometry at `path`) whose `MARKER
    /// NAME`s contradict the geometry: where any file names one of its antennas, every
    /// antenna must have its file ([`Self::check_recorded`]: a file given twice), in the
    /// geometry's order (files swapped). Files that name none of them (another
    /// receiver's station names) are taken in the order given.
    fn check_markers(&self, path: &Path, files: &[ObsFile]) -> Result<(), BadInput> {
        let markers: Vec<String> = files
            .iter()
            .map(|f| f.marker.clone().unwrap_or_default())
            .collect();
        if !markers.iter().any(|m| self.antennas().any(|a| a == m)) {
            return Ok(());
        }
        self.check_recorded(path, &markers, ("file", "the files' MARKER NAMEs"))?;
        match self
            .antennas()
            .zip(files)
            .find(|(a, f)| f.marker.as_deref() != Some(*a))
        {
            Some((antenna, f)) => Err(BadInput(format!(
                "{}: MARKER NAME {:?}, but it is given for antenna {antenna:?} of {} (one file per antenna, in its order: {})",
                f.source.display(),
                f.marker.as_deref().unwrap_or(""),
                path.display(),
                self.antennas().collect::<Vec<_>>().join(", ")
            ))),
            None => Ok(()),
        }
    }

    /// Run over `files` (one per antenna, geometry order) with the ephemerides of the
    /// navigation file `nav` and write the outputs into `staged`. Files with which no
    /// epoch can be formed are an error, and so is a run in which none was.
    pub fn run(
        self,
        files: &[ObsFile],
        ephemerides: Vec<BroadcastEphemeris>,
        nav: &Path,
        staged: &StagedDir,
    ) -> anyhow::Result<ChainSummary> {
        let mut outputs = ChainOutputs::create(staged, &self.geometry, self.offsets)?;
        run_files(files, ephemerides, &self.geometry, self.config, |o| {
            outputs.push(&o)
        })
        .map_err(|e| match e {
            FilesError::NoEphemeris { .. } => BadInput(format!("{}: {e}", nav.display())),
            e => BadInput(e.to_string()),
        })?;
        let summary = &outputs.summary;
        if let (true, Some((time, why))) = (
            summary.none.values().sum::<usize>() == summary.epochs,
            &summary.first_none,
        ) {
            return Err(BadInput(format!(
                "{}: no epoch could be formed ({} of {} epochs: {}; the first, at {time}: {why}; the master's position comes from its pseudoranges and the ephemerides of {})",
                files[0].source.display(),
                summary.epochs,
                summary.epochs,
                summary.none_counts(),
                nav.display()
            ))
            .into());
        }
        outputs.finish(staged, &self.geometry)
    }

    /// The chain as an epoch stage of the receiver, whose antennas are `recorded` (the
    /// geometry's must be among them): its outputs go into `staged`.
    pub fn stage(
        self,
        ephemerides: Vec<BroadcastEphemeris>,
        recorded: &[String],
        staged: &StagedDir,
    ) -> anyhow::Result<AttitudeStage> {
        let receiver_index = self
            .antennas()
            .map(|a| recorded.iter().position(|n| n == a))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| BadInput("the geometry names an antenna without a recording".into()))?;
        let chain = EpochChain::new(ephemerides, &self.geometry, self.config)
            .map_err(|e| BadInput(e.to_string()))?;
        Ok(AttitudeStage {
            chain,
            receiver_index,
            outputs: ChainOutputs::create(staged, &self.geometry, self.offsets)?,
            geometry: self.geometry,
        })
    }
}

/// The chain's outputs as its epochs come: the epoch rows written, the counts of the
/// summary, and with `--estimate-geometry` the offsets estimated from the fixed epochs.
struct ChainOutputs {
    /// Baselines (antennas - 1).
    m: usize,
    files: EpochFiles,
    summary: ChainSummary,
    values: Vec<EpochValues>,
    offsets: Option<OffsetEstimator>,
    offset_error: Option<String>,
    /// The estimator's clock starts at the first epoch.
    start: Option<hifitime::Epoch>,
}

impl ChainOutputs {
    fn create(
        staged: &StagedDir,
        geometry: &BodyGeometryFile,
        offsets: Option<OffsetEstimator>,
    ) -> anyhow::Result<Self> {
        let m = geometry.antennas.len() - 1;
        Ok(Self {
            m,
            files: EpochFiles::create(&staged.file(""), m)?,
            summary: ChainSummary {
                epochs: 0,
                fixed: 0,
                attitudes: 0,
                methods: [0; FixMethod::ALL.len()],
                fallbacks: (0, None),
                reverse_restarts: (0, None),
                none: BTreeMap::new(),
                first_none: None,
                estimating: offsets.is_some(),
                offset_rows: Vec::new(),
            },
            values: Vec::new(),
            offsets,
            offset_error: None,
            start: None,
        })
    }

    /// One master epoch's outcome.
    fn push(&mut self, o: &EpochOutcome) {
        let start = *self.start.get_or_insert(o.time);
        let summary = &mut self.summary;
        summary.epochs += 1;
        if let Err(why) = &o.result {
            *summary.none.entry(reason_kind(why, o.time)).or_default() += 1;
            summary
                .first_none
                .get_or_insert_with(|| (o.time, why.clone()));
        }
        if let Ok(e) = &o.result {
            let whole = e.resolution.status == AmbiguityStatus::Fixed;
            summary.fixed += usize::from(whole);
            summary.attitudes += usize::from(e.attitude.is_some() && e.attitude_skipped.is_none());
            summary.methods[e.resolution.method as usize] += 1;
            for (count, why) in [
                (&mut summary.fallbacks, &e.resolution.fallback),
                (&mut summary.reverse_restarts, &e.reverse_restarted),
            ] {
                if let Some(why) = why {
                    count.0 += 1;
                    count.1.get_or_insert_with(|| format!("{}: {why}", o.time));
                }
            }
            if let (Some(f), Some(ned), None, true) = (
                self.offsets.as_mut(),
                &e.fixed_ned,
                &self.offset_error,
                whole,
            ) {
                match f.push((o.time - start).to_seconds(), ned.clone()) {
                    Ok(Step::Updated { chi_square, dof }) => {
                        summary.offset_rows.extend(f.state().map(|state| OffsetRow {
                            time: o.time,
                            state,
                            chi_square,
                            dof,
                        }))
                    }
                    Ok(_) => {}
                    Err(err) => self.offset_error = Some(format!("{}: {err}", o.time)),
                }
            }
        }
        let v = EpochValues::of(o, self.m);
        self.files.write(&v, &integer_rows(o));
        self.values.push(v);
    }

    /// Close the epoch files and write `attitude.h5` and the geometry offsets' files.
    fn finish(
        self,
        staged: &StagedDir,
        geometry: &BodyGeometryFile,
    ) -> anyhow::Result<ChainSummary> {
        self.files.finish()?;
        let h5_path = staged.file(ATTITUDE_H5);
        write_h5(&h5_path, &self.values, self.m)
            .with_context(|| format!("cannot write {}", h5_path.display()))?;
        if let Some(f) = &self.offsets {
            if let Some(e) = self.offset_error {
                return Err(BadInput(format!("geometry offsets: {e}")).into());
            }
            write_offsets(staged, geometry, f, &self.summary.offset_rows)?;
        }
        Ok(self.summary)
    }
}

/// `skyforge receive --geometry`: the chain as an epoch stage of the receiver. At every
/// epoch it takes each antenna's observations as its RINEX file keeps them
/// ([`epoch_as_written`]: what `skyforge attitude` reads back), so both commands write the
/// same outputs; the antennas share the receiver's clock, so their epochs pair exactly.
pub(crate) struct AttitudeStage {
    chain: EpochChain,
    /// Each geometry antenna's index among the receiver's (master first).
    receiver_index: Vec<usize>,
    outputs: ChainOutputs,
    geometry: BodyGeometryFile,
}

impl AttitudeStage {
    /// One epoch of the receiver; an antenna without observations has no epoch (its file
    /// has none), and the chain runs on the master's epochs.
    pub fn epoch(&mut self, report: &EpochReport) -> std::io::Result<()> {
        let epochs = self
            .receiver_index
            .iter()
            .map(|&a| {
                let records = report.records(a);
                (!records.is_empty())
                    .then(|| epoch_as_written(report.t_rx, &records))
                    .transpose()
            })
            .collect::<std::io::Result<Vec<_>>>()?;
        let Some(master) = &epochs[0] else {
            return Ok(());
        };
        let others: Vec<_> = epochs[1..]
            .iter()
            .map(|e| e.as_ref().map(|e| (e.time, e.sats.as_slice())))
            .collect();
        let outcome = self.chain.epoch(master.time, &master.sats, &others);
        self.outputs.push(&outcome);
        Ok(())
    }

    /// Close the outputs; a master antenna that never observed is the error `skyforge
    /// attitude` gives for its empty file.
    pub fn finish(self, staged: &StagedDir) -> anyhow::Result<ChainSummary> {
        if self.outputs.summary.epochs == 0 {
            let master = &self.geometry.antennas[0].name;
            return Err(BadInput(format!("{master}: no observation epochs")).into());
        }
        self.outputs.finish(staged, &self.geometry)
    }
}

/// The kind of reason `why` an epoch at `time` gave no result: its text before the
/// first `": "` (the details), without the epoch's time.
fn reason_kind(why: &str, time: hifitime::Epoch) -> String {
    let kind = why.split(": ").next().unwrap_or(why);
    kind.replace(&format!(" at {time}"), "")
}

impl ChainSummary {
    /// The epochs without a result, counted by reason (`reason 3, other 1`).
    fn none_counts(&self) -> String {
        let mut counts: Vec<(&String, &usize)> = self.none.iter().collect();
        counts.sort_by_key(|(_, n)| std::cmp::Reverse(**n));
        counts
            .iter()
            .map(|(why, n)| format!("{why} ({n})"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The summary lines, with the files' final paths under `dir`.
    pub fn print(&self, dir: &Path) {
        println!("epochs     {}", self.epochs);
        if !self.none.is_empty() {
            println!(
                "none       {} epochs gave no result: {}",
                self.none.values().sum::<usize>(),
                self.none_counts()
            );
        }
        println!(
            "fixed      {} ({:.1} %)",
            self.fixed,
            100.0 * self.fixed as f64 / self.epochs.max(1) as f64
        );
        let methods: Vec<String> = FixMethod::ALL
            .iter()
            .zip(&self.methods)
            .filter(|(_, n)| **n > 0)
            .map(|(m, n)| format!("{} {n}", m.name()))
            .collect();
        println!("method     {}", methods.join(", "));
        for (what, (n, first)) in [
            ("fallback   to LAMBDA", &self.fallbacks),
            ("reverse    filter restarted", &self.reverse_restarts),
        ] {
            if let Some(first) = first {
                println!("{what} at {n} epochs, first {first}");
            }
        }
        println!("attitude   {} epochs", self.attitudes);
        println!("wrote      {}", dir.join(ATTITUDE_CSV).display());
        if !self.estimating {
            return;
        }
        println!(
            "integers   plain LAMBDA (--estimate-geometry: the nominal geometry is not a constraint)"
        );
        let Some(last) = self.offset_rows.last() else {
            println!("geometry   no update: never four consecutive fixed epochs");
            return;
        };
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
                self.offset_rows.len()
            );
        }
        println!("wrote      {}", dir.join(GEOMETRY_CORRECTED_TOML).display());
    }
}

/// The estimator for the file's geometry (two baselines), or a located error.
fn offset_estimator(
    geometry: &BodyGeometryFile,
    config: &RelativeConfig,
    path: &Path,
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
    let csv_path = staged.file(GEOMETRY_OFFSETS_CSV);
    let mut text = geometry_offsets::csv_header() + "\n";
    for r in rows {
        text += &(geometry_offsets::csv_row(r) + "\n");
    }
    std::fs::write(&csv_path, text)
        .with_context(|| format!("cannot write {}", csv_path.display()))?;
    let h5_path = staged.file(GEOMETRY_OFFSETS_H5);
    geometry_offsets::write_h5(&h5_path, rows)
        .with_context(|| format!("cannot write {}", h5_path.display()))?;
    let corrected = estimator
        .corrected_geometry()
        .map_err(|e| BadInput(format!("geometry offsets: {e}")))?;
    let toml_path = staged.file(GEOMETRY_CORRECTED_TOML);
    let file = geometry.corrected(&corrected);
    let text = file
        .to_text("")
        .context("cannot format the corrected geometry")?;
    std::fs::write(&toml_path, text)
        .with_context(|| format!("cannot write {}", toml_path.display()))
}
