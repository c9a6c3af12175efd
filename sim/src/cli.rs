//! Command-line interface definition.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// Geometry epochs per streamed chunk unless `synth --chunk-epochs` says otherwise.
pub const DEFAULT_CHUNK_EPOCHS: u32 = 10;

/// SkyForge: simulate GPS and BeiDou constellations and a receiving platform (a LEO
/// satellite, a ground site or a trajectory), and write what its antennas see.
#[derive(Debug, Parser)]
#[command(name = "skyforge", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// What `run` and `synth` are given: a scenario and where its outputs go.
#[derive(Debug, Args)]
pub struct ScenarioRun {
    /// Scenario file or bundled scenario name, e.g. `thesis-leo`, `interop-gps-static`.
    pub scenario: String,
    /// Output directory; created, must not exist unless --force is given.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Random seed overriding the scenario's `seed` (recorded in the outputs; every noise
    /// stream derives from it).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Replace an existing output directory that skyforge wrote and that holds nothing
    /// else (its .skyforge-manifest lists every file); the old one stays until the new
    /// one is complete.
    #[arg(long)]
    pub force: bool,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run a scenario and write its truth (DIR/truth.h5); with a [signal] table, also its
    /// I/Q samples, exactly as `synth` does.
    ///
    /// SCENARIO is a TOML file or the name of a bundled scenario (see `skyforge scenarios
    /// list`). Nothing is written when the scenario has an error (exit code 2).
    Run {
        #[command(flatten)]
        run: ScenarioRun,
    },
    /// Synthesise the scenario's I/Q samples: one recording per antenna and band
    /// (DIR/<antenna>.gps-l1ca.sigmf-data, DIR/<antenna>.bds-b1i.sigmf-data) with SigMF
    /// metadata and a ready-to-run GNSS-SDR configuration, plus DIR/truth.h5.
    ///
    /// The scenario needs a [signal] table. Nothing is written when the scenario has an
    /// error (exit code 2).
    Synth {
        #[command(flatten)]
        run: ScenarioRun,
        /// Geometry epochs (1 s each) computed per streamed chunk: more costs memory,
        /// fewer costs overhead. Every file but truth.h5 is byte-identical whatever it is;
        /// truth.h5 holds the same datasets and values, but HDF5 places its chunks in the
        /// order they are written, so its bytes differ.
        #[arg(long, value_name = "N", default_value_t = DEFAULT_CHUNK_EPOCHS,
              value_parser = clap::value_parser!(u32).range(1..=3600))]
        chunk_epochs: u32,
        /// Check the scenario and print what the run would write (each recording's size,
        /// bounds of truth.h5 and the RINEX files) and the most memory it needs; write
        /// nothing.
        #[arg(long)]
        dry_run: bool,
        /// Run the bundled receiver on the samples as they are rendered, on a second
        /// thread, instead of writing recordings: the receiver's outputs (as `skyforge
        /// receive` writes them) go to DIR/receive/, assisted by DIR/nav.rnx. For runs
        /// whose I/Q would not fit on disk.
        #[arg(long, conflicts_with = "dry_run")]
        receive: bool,
        /// With --receive: the receiver configuration (as `skyforge receive --config`);
        /// default: its defaults with the rounded start state (DIR/receiver.toml).
        #[arg(long, value_name = "FILE", requires = "receive")]
        receiver_config: Option<PathBuf>,
    },
    /// Run the bundled receiver over sample recordings (SkyForge's SigMF files or raw
    /// files described by --format/--fs/--if/--signal): acquisition, tracking, navigation
    /// decoding, observables and PVT. Writes DIR/<antenna>.obs.rnx (RINEX 3.04),
    /// DIR/receiver.h5, DIR/pvt.csv and DIR/<antenna>.nmea.
    ///
    /// Files of several antennas share one sample clock; GPS L1 and BeiDou B1 recordings
    /// of the same antenna (same SigMF antenna name) give one combined fix.
    Receive {
        #[command(flatten)]
        args: ReceiveArgs,
    },
    /// Measure the bundled receiver's code and carrier-phase noise against the loop
    /// formulas on SCENARIO (synthesised and received at the signal level, compared with
    /// its observation truth after 10 s of settling): writes DIR/calibration.toml, the
    /// factors the observation level's `[observation.noise] model = "calibrated"` uses.
    ///
    /// Multipath and fault events would count as noise: calibrate on a scenario without
    /// them. The recordings are made in DIR/work and removed afterwards.
    Calibrate {
        #[command(flatten)]
        run: ScenarioRun,
    },
    /// Resolve integer ambiguities with LAMBDA: read a float ambiguity vector and its
    /// covariance (cycles, cycles^2), print the best integer candidates with their squared
    /// norms, the ratio of the second-best to the best squared norm, the decorrelating Z
    /// and the bootstrapped success rate.
    ///
    /// FILE is JSON, {"a_hat": [...], "q": [[...], ...]}, or CSV: first data line a_hat,
    /// then one line per row of Q; '#' lines are comments. At most 500 ambiguities and
    /// 4 MiB. Bad input: one error naming the file, exit code 2.
    Ambiguity {
        /// Problem file (.json or .csv).
        file: PathBuf,
        /// Number of integer candidates to print (best first).
        #[arg(long, value_name = "K", default_value_t = 2,
              value_parser = clap::value_parser!(u32)
                  .range(1..=skyforge_navigation::ambiguity::MAX_CANDIDATES as i64))]
        candidates: u32,
        /// Print the result as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Baselines and attitude from several antennas' RINEX observation files: double
    /// differences, LAMBDA with ambiguity hold, fixed baselines (ECEF and NED) and
    /// yaw/pitch/roll. Writes DIR/attitude.csv (columns in docs/attitude.md).
    ///
    /// FILES: one observation file per antenna of the geometry file, in its order (master
    /// first): `skyforge receive` output, the observation level's, or another receiver's.
    Attitude {
        #[command(flatten)]
        args: AttitudeArgs,
    },
    /// Orbit determination of the receiving spacecraft from its own observations: the
    /// single-point fixes of one RINEX observation file (with the navigation file's
    /// ephemerides and ionosphere) into a dynamic filter with J2 and drag (the book's
    /// position filter, section 5.5.4). Writes DIR/orbit.csv, DIR/orbit.h5 (with the
    /// 6 x 6 covariance) and DIR/orbit.sp3 (docs/orbit-determination.md).
    Od {
        #[command(flatten)]
        args: OdArgs,
    },
    /// GNSS/INS: an IMU file (SkyForge's CSV or KF-GINS's text file) and one antenna's
    /// RINEX observation file with a navigation file into the loosely coupled, tightly
    /// coupled or TDCP-aided filter (--mode), after a static alignment; optional GNSS
    /// outages made on purpose. Writes DIR/ins.csv (docs/ins.md).
    Ins {
        #[command(flatten)]
        args: InsArgs,
    },
    /// Jamming detection from one antenna's RINEX observation file: every tracked
    /// satellite's C/N0 against its own reference, an alarm when their median falls by
    /// more than the configured false-alarm probability allows, or when most satellites
    /// are lost at once. Writes DIR/interference.csv (docs/interference.md).
    Jamming {
        #[command(flatten)]
        args: JammingArgs,
    },
    /// Relative navigation of two spacecraft (book section 5.6): the chaser relative to
    /// the target in the target's orbit frame, from their two RINEX observation files and
    /// a navigation file, as the difference of standalone fixes, of fixes on the common
    /// satellites or smoothed ones, a single-difference code filter or a double-difference phase
    /// filter with integer ambiguities (--config). Writes DIR/relnav.csv (the layout of a
    /// multi-vehicle run's relative.csv; docs/orbit-determination.md).
    Relnav {
        #[command(flatten)]
        args: RelnavArgs,
    },
    /// Integrity monitoring with several reference receivers (paper 002's B values):
    /// `run` monitors RINEX observation files, `calibrate` derives the thresholds from
    /// fault-free runs of a scenario (docs/integrity.md).
    Monitor {
        #[command(subcommand)]
        action: MonitorAction,
    },
    /// Monte Carlo studies: a base scenario over a grid of parameter values and seeds, each
    /// run measured against its own truth; run whole or as shards (`--shard i/n`, e.g.
    /// Slurm array tasks), resumable, merged into one HDF5 file (docs/study.md).
    Study {
        #[command(subcommand)]
        action: StudyAction,
    },
    /// Write one self-contained HTML page of the outputs in DIR (inline SVG figures, no
    /// network): the truth of a `synth` or `run` (truth.h5: satellites in view, Doppler and
    /// its rates), a `validate thesis --out` (results.json: the table with verdicts) and a
    /// study (study.h5: each metric against the varied parameter with confidence bands).
    Report {
        /// Directory holding any of truth.h5, results.json and study.h5
        dir: PathBuf,
        /// The page to write (default DIR/report.html); must not exist unless --force is
        /// given, and --force replaces only a page skyforge wrote
        #[arg(long)]
        out: Option<PathBuf>,
        /// Replace an existing report page (only one skyforge wrote)
        #[arg(long)]
        force: bool,
        /// `skyforge attitude`'s output for the run in DIR: adds the baseline and attitude
        /// errors against DIR's truth
        #[arg(long, value_name = "DIR")]
        attitude: Option<PathBuf>,
        /// The observations that attitude run read (default: DIR/observations, those of
        /// an observation-level run)
        #[arg(long, value_name = "DIR", requires = "attitude")]
        observations: Option<PathBuf>,
    },
    /// List or show the bundled scenarios.
    Scenarios {
        #[command(subcommand)]
        action: ScenariosAction,
    },
    /// Compare SkyForge with reference results.
    Validate {
        #[command(subcommand)]
        suite: ValidateSuite,
    },
}

/// What `od` is given.
#[derive(Debug, Args)]
pub struct OdArgs {
    /// The spacecraft's observation file (RINEX 3): `skyforge receive` output, the
    /// observation level's, or another receiver's.
    pub file: PathBuf,
    /// Navigation file (RINEX 2/3/4) with the satellites' broadcast ephemerides.
    #[arg(long, value_name = "NAV")]
    pub nav: PathBuf,
    /// Filter settings (TOML; docs/orbit-determination.md); default: the documented ones.
    #[arg(long, value_name = "TOML")]
    pub config: Option<PathBuf>,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory (only one skyforge wrote).
    #[arg(long)]
    pub force: bool,
}

/// What `ins` is given.
#[derive(Debug, Args)]
pub struct InsArgs {
    /// The antenna's observation file (RINEX 3).
    pub file: PathBuf,
    /// Navigation file (RINEX 2/3/4) with the satellites' broadcast ephemerides.
    #[arg(long, value_name = "NAV")]
    pub nav: PathBuf,
    /// The IMU's increments: SkyForge's IMU CSV (`.csv`) or KF-GINS's text file (any
    /// other name; then --gps-week and --imu-rate-hz say what the file does not).
    #[arg(long, value_name = "FILE")]
    pub imu: PathBuf,
    /// GPS week of a KF-GINS file's first record.
    #[arg(long, value_name = "WEEK")]
    pub gps_week: Option<u32>,
    /// Output rate of a KF-GINS file's IMU (Hz): the first record's interval.
    #[arg(long, value_name = "HZ")]
    pub imu_rate_hz: Option<f64>,
    /// The IMU's grade as its data sheet states it (the filter's noise model): navigation,
    /// tactical, consumer, book-table-3-1 (docs/imu.md).
    #[arg(long, value_name = "GRADE", default_value = "navigation")]
    pub grade: String,
    /// The antenna from the IMU in body axes (m): x,y,z.
    #[arg(long, value_name = "X,Y,Z", value_delimiter = ',', default_values_t = [0.0, 0.0, 0.0], allow_hyphen_values = true)]
    pub lever_arm: Vec<f64>,
    /// The static start the INS aligns on (s).
    #[arg(long, value_name = "S", default_value_t = 60.0)]
    pub alignment_s: f64,
    /// How it aligns: `coarse` (attitude from the static start's mean specific force and
    /// rate), `fine` (then a Kalman filter of zero-velocity updates through the same
    /// start, which prints its heading and tilt sigmas) or `track` (in motion: heading and
    /// pitch from the first fix at 5 m/s or faster, roll zero; any grade; --alignment-s
    /// unused; docs/ins.md).
    #[arg(long, value_name = "HOW", default_value = "coarse")]
    pub align: String,
    /// The gravity the INS subtracts: `normal` (the WGS-84 ellipsoid's, near the Earth),
    /// `zonal` (the orbit's: the point mass, J2..J6 and the centrifugal term, as the LEO
    /// propagator's) or `auto` (normal below 50 km, zonal above). Modes loose and tight.
    #[arg(long, value_name = "MODEL", default_value = "auto")]
    pub gravity: String,
    /// The integration: `loose` (single-point fixes and Doppler velocities), `tight` (book
    /// 3.2.2's: every satellite's pseudorange and range rate, the receiver clock's bias
    /// and drift estimated) or `tdcp` (paper 001's: time-differenced carrier phase double
    /// differences, code differenced between satellites, and the start's height; needs
    /// --start).
    #[arg(long, value_name = "MODE", default_value = "loose")]
    pub mode: String,
    /// The antenna's surveyed position during the alignment (deg, deg, m above the
    /// ellipsoid): LAT,LON,H. Mode tdcp only.
    #[arg(
        long,
        value_name = "LAT,LON,H",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub start: Option<Vec<f64>>,
    /// Mode tdcp: hold the antenna at the start's height to this sigma (m), as paper 001's
    /// altitude aiding; absent: no height constraint.
    #[arg(long, value_name = "M")]
    pub height_sigma: Option<f64>,
    /// GNSS outages made on purpose: FIRST,EVERY,LENGTH in seconds after the alignment.
    #[arg(long, value_name = "FIRST,EVERY,LENGTH", value_delimiter = ',')]
    pub outages: Option<Vec<f64>>,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory (only one skyforge wrote).
    #[arg(long)]
    pub force: bool,
}

/// What `jamming` is given.
#[derive(Debug, Args)]
pub struct JammingArgs {
    /// The antenna's observation file (RINEX 3) with C/N0.
    pub file: PathBuf,
    /// False-alarm probability per epoch (0 < P < 0.5).
    #[arg(long, value_name = "P", default_value_t = 1e-6)]
    pub false_alarm: f64,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory (only one skyforge wrote).
    #[arg(long)]
    pub force: bool,
}

/// What `relnav` is given.
#[derive(Debug, Args)]
pub struct RelnavArgs {
    /// The target's observation file (RINEX 3).
    pub target: PathBuf,
    /// The chaser's observation file (RINEX 3).
    pub chaser: PathBuf,
    /// Navigation file (RINEX 2/3/4) with the satellites' broadcast ephemerides.
    #[arg(long, value_name = "NAV")]
    pub nav: PathBuf,
    /// Settings (TOML: mode = "standalone" | "position-difference" | "carrier-smoothed",
    /// signals, elevation_mask_deg, [smoothing]); default: position-difference.
    #[arg(long, value_name = "TOML")]
    pub config: Option<PathBuf>,
    /// The vehicles' names in relnav.csv (those of the scenario's [[vehicles]], so that
    /// `validate relnav` finds their truth).
    #[arg(long, value_name = "NAME", default_value = "target")]
    pub target_name: String,
    #[arg(long, value_name = "NAME", default_value = "chaser")]
    pub chaser_name: String,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory (only one skyforge wrote).
    #[arg(long)]
    pub force: bool,
}

/// What `attitude` is given.
#[derive(Debug, Args)]
pub struct AttitudeArgs {
    /// Observation files (RINEX 3), one per antenna, master first.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Navigation file (RINEX 2/3/4) with the satellites' broadcast ephemerides.
    #[arg(long, value_name = "NAV")]
    pub nav: PathBuf,
    /// Body geometry (TOML: [[antennas]] name, position_body_m; master first), as
    /// `skyforge synth` writes it (DIR/geometry.toml).
    #[arg(long, value_name = "TOML")]
    pub geometry: PathBuf,
    /// Chain settings (TOML with a [relative] table; docs/attitude.md).
    #[arg(long, value_name = "TOML")]
    pub config: Option<PathBuf>,
    /// Also estimate the antenna geometry offsets (thesis 4.3, three antennas): writes
    /// DIR/geometry_offsets.csv, DIR/geometry_offsets.h5 and the corrected geometry
    /// DIR/geometry_corrected.toml (docs/geometry.md).
    #[arg(long)]
    pub estimate_geometry: bool,
    /// Output directory; created, must not exist unless --force is given.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory that skyforge wrote.
    #[arg(long)]
    pub force: bool,
}

#[derive(Debug, Subcommand)]
pub enum MonitorAction {
    /// Monitor several receivers' RINEX observation files (one per station, all of the
    /// same span): each station's pseudorange and carrier phase are mapped to a common
    /// point; the changes of code, smoothed code and carrier and the code-carrier
    /// divergence are compared across stations by their B values and tested against
    /// thresholds. Writes DIR/monitor.csv, DIR/monitor.h5 and DIR/summary.json; prints the
    /// alarms.
    ///
    /// Station positions come from each file's APPROX POSITION XYZ unless the
    /// configuration lists them ([[stations]]).
    Run {
        #[command(flatten)]
        args: MonitorArgs,
    },
    /// Measure the fault-free spread of the B values on SCENARIO (observation level, no
    /// fault events; its seed and the next ones) and write DIR/monitor.toml: a monitor
    /// configuration with thresholds for `monitor run --config`.
    Calibrate {
        #[command(flatten)]
        run: ScenarioRun,
        /// Independent runs (seeds) to measure on.
        #[arg(long, value_name = "N", default_value_t = 8,
              value_parser = clap::value_parser!(u64).range(1..=1000))]
        seeds: u64,
    },
    /// Measure the fault-free spread of the B values in several receivers' RINEX files
    /// (the same inputs as `monitor run`: a recorded fault-free span) and write
    /// DIR/monitor.toml: the given configuration (or the bundled one) with the measured
    /// thresholds. This is how a ground facility, or the signal-level reference, sets
    /// thresholds that hold for its own receivers' errors.
    CalibrateFiles {
        #[command(flatten)]
        args: MonitorArgs,
        /// Give the BeiDou GEOs sigma tables of their own (thresholds.sigma_geo): a static
        /// station sees their code errors wander far more than the other satellites'.
        #[arg(long)]
        geo_apart: bool,
    },
}

/// What `monitor run` is given.
#[derive(Debug, Args)]
pub struct MonitorArgs {
    /// Observation files (RINEX 2 or 3), one per station; at least two.
    #[arg(required = true, num_args = 2..)]
    pub files: Vec<PathBuf>,
    /// Navigation file (RINEX 2/3/4) with the satellites' broadcast ephemerides.
    #[arg(long, value_name = "NAV")]
    pub nav: PathBuf,
    /// Monitor configuration (TOML, docs/integrity.md); default: the bundled one,
    /// calibrated on the integrity-lab scenario.
    #[arg(long, value_name = "TOML")]
    pub config: Option<PathBuf>,
    /// Output directory; created, must not exist unless --force is given.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory that skyforge wrote.
    #[arg(long)]
    pub force: bool,
}

#[derive(Debug, Subcommand)]
pub enum ScenariosAction {
    /// List bundled scenario names with a one-line summary.
    List,
    /// Print a bundled scenario's TOML text.
    Show {
        /// Bundled scenario name.
        name: String,
    },
}

#[derive(Debug, Subcommand)]
pub enum ValidateSuite {
    /// Reproduce the thesis tables (../shared/reference/THESIS_TARGETS.md).
    ///
    /// Prints thesis value, SkyForge value, ratio, tolerance and verdict for every row;
    /// exits 0 whenever it ran, whatever the verdicts. Tables: V-1.2.1, T-1.2-2, T-1.2-3,
    /// T-3.2, T-3.3-R, T-3.3-S, T-5.4-2, T-5.4-3, T-5.4-4, T-5.4-5, and paper 002's P2-4.2
    /// (its fault cases, 20 seeds) and P2-PD (detection curves, 1000 runs, minutes), and the
    /// RAIM Monte Carlo B-5.2-1 and B-5.2-2 against Yuan 2000 tables 5-1 and 5-2, and
    /// B-5.5, the book's orbit determination of a LEO (table 5-3, four 2 h runs, seconds),
    /// and B-5.6, its relative navigation of two spacecraft (four 600 s runs, seconds), and
    /// paper 001's P1-F2 (Fig. 2: the receiver clock in the carrier phase's single
    /// difference in time, not in the double difference; eight 300 s runs of three GEOs
    /// synthesised and received at 10 Hz, two minutes) and P1-S (its static SINS alone
    /// for 2050 s after a static alignment, 20 seeds, seconds) and P1-D (its boat on a
    /// lake, a closed loop of 4458 s, eight seeds, under a minute), and B-3.2, the book's
    /// GPS/INS flight (the pure INS and the 18-state filter, 20 seeds of 550 s, seconds).
    /// T-5.4-2 synthesises its
    /// bundled scenario (60 s, four recordings, about 2 GB in the temporary directory) and
    /// runs the receiver on it; the attitude tables run observation-level scenarios on
    /// eight seeds (seconds).
    Thesis {
        /// Run only these table IDs (repeatable), e.g. --only V-1.2.1 --only T-5.4-2; a group
        /// such as T-1.2 selects its tables (T-1.2-2, T-1.2-3).
        #[arg(long, value_name = "ID")]
        only: Vec<String>,
        /// Write DIR/results.json.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Replace an existing output directory.
        #[arg(long)]
        force: bool,
        /// Real-data folder for rows that use real broadcast files [env: SKYFORGE_DATA;
        /// default: ../shared/data].
        #[arg(long, value_name = "DIR")]
        data: Option<PathBuf>,
        /// Run every table whose rows are per-run statistics N times, each on one run of
        /// its own seed plus B + k (V-1.2.1: its start epoch moved by k x 25 h), and give
        /// each row its distribution over the draws and a verdict on the fraction of draws
        /// in tolerance (docs/validation.md). Monte Carlo tables (P2-4.2, P2-PD, B-5.2) run
        /// once on their own seeds shifted by B; T-3.2 has no random draw.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=10_000))]
        seeds: Option<u64>,
        /// The first seed offset B of --seeds (default 0: the first draw is the registered
        /// seed); another B gives independent draws.
        #[arg(long, value_name = "B", requires = "seeds")]
        seed_base: Option<u64>,
    },
    /// Compare a receiver's RINEX observations with SkyForge's RINEX truth of the same
    /// recording: pseudorange, carrier-phase, Doppler and C/N0 errors per satellite, per
    /// system and overall (receiver clock and per-satellite/per-arc offsets removed).
    Obs {
        /// SkyForge's truth (DIR/<antenna>.obs.rnx of `skyforge synth`).
        #[arg(long, value_name = "RINEX")]
        truth: PathBuf,
        /// The receiver's RINEX 3 observation file.
        #[arg(long, value_name = "RINEX")]
        estimate: PathBuf,
        /// Also write the full comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
        /// Seconds added to the estimate's time tags (for tags in another time scale than
        /// the header says, e.g. -14 for GPS-time tags in a file labelled BDT).
        #[arg(
            long,
            value_name = "S",
            default_value_t = 0.0,
            allow_hyphen_values = true
        )]
        tag_offset_s: f64,
        /// Only epochs measured at or after this sample time (truth time scale, e.g.
        /// "2023-03-12T00:00:40 GPST"): with --to, the span another receiver's comparison
        /// printed, to compare two receivers over the same epochs.
        #[arg(long, value_name = "EPOCH", requires = "to")]
        from: Option<String>,
        /// Only epochs measured at or before this sample time (see --from).
        #[arg(long, value_name = "EPOCH", requires = "from")]
        to: Option<String>,
    },
    /// Compare `skyforge attitude`'s output with the truth of the run: epochs, first fix,
    /// fraction fixed from the first fix on, every fixed integer against the truth's
    /// double-difference integer, NED baseline and yaw/pitch/roll errors (count, mean,
    /// std, RMS), printed beside the thesis's tables 5.4-4 and 5.4-5 (docs/attitude.md).
    Attitude {
        /// The run's directory (`skyforge run`/`synth --out`): truth.h5, geometry.toml and
        /// <antenna>.obs.rnx (the observation truth).
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// The observations the chain read: `skyforge receive`'s directory, or
        /// SIMDIR/observations at the observation level (<antenna>.obs.rnx).
        #[arg(long, value_name = "OBSDIR")]
        observations: PathBuf,
        /// `skyforge attitude`'s output directory (attitude.csv, ambiguities.csv).
        #[arg(long, value_name = "ATTDIR")]
        attitude: PathBuf,
        /// Also write the comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Compare `skyforge od`'s estimated orbit with the truth of the run: position and
    /// velocity errors per axis in the orbit frame (radial, along-track, cross-track) and
    /// ECEF, 3-D RMS, after a settling time; and how often the truth lies inside the
    /// filter's own 3-sigma (docs/orbit-determination.md).
    Od {
        /// The run's directory (`skyforge run`/`synth --out`): its truth.h5.
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// `skyforge od`'s output directory (orbit.h5).
        #[arg(long, value_name = "ODDIR")]
        orbit: PathBuf,
        /// Leave out the estimates of the first S seconds (the filter's convergence).
        #[arg(long, value_name = "S", default_value_t = 600.0)]
        settle_s: f64,
        /// Also write the comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Compare `skyforge ins`'s solution with the IMU's truth of the run (imu.h5): the
    /// RMS position error while GNSS updates the filter, and the drift over each outage
    /// made on purpose (docs/ins.md).
    Ins {
        /// The run's directory (`skyforge run`/`synth --out`): its imu.h5.
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// `skyforge ins`'s output directory (ins.csv).
        #[arg(long, value_name = "INSDIR")]
        ins: PathBuf,
        /// Also write the comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Score `skyforge jamming`'s alarms against the run's jammers (truth.h5): for each
    /// span with a jammer on, the time to the first alarm; the false alarms outside them
    /// (docs/interference.md).
    Interference {
        /// The run's directory (`skyforge synth --out`): its truth.h5.
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// `skyforge jamming`'s output directory (interference.csv).
        #[arg(long, value_name = "DIR")]
        detections: PathBuf,
        /// Also write the score as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Compare `skyforge relnav`'s estimates with the relative truth of a multi-vehicle
    /// run: per axis of the target's orbit frame the RMS and largest error of position
    /// and velocity, and the 3-D RMS (docs/orbit-determination.md).
    Relnav {
        /// The run's directory (`skyforge run`/`synth --out` of a scenario with
        /// [[vehicles]]): its relative.csv.
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// `skyforge relnav`'s output directory (relnav.csv).
        #[arg(long, value_name = "RELDIR")]
        relnav: PathBuf,
        /// Leave out the estimates of the first S seconds (smoothing's transient).
        #[arg(long, value_name = "S", default_value_t = 0.0)]
        settle_s: f64,
        /// Also write the comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Compare `skyforge monitor run`'s alarms with the fault events of the run's
    /// scenario: per event, whether and when it was detected, by which statistic and
    /// whether the faulted station stood out; alarms no event explains are false alarms.
    Monitor {
        /// The run's directory (`skyforge run`/`synth --out`): its truth.h5 holds the
        /// scenario.
        #[arg(long, value_name = "SIMDIR")]
        truth: PathBuf,
        /// `skyforge monitor run`'s output directory (monitor.csv).
        #[arg(long, value_name = "MONDIR")]
        monitor: PathBuf,
        /// Also write the comparison as JSON to this file.
        #[arg(long, value_name = "FILE")]
        json: Option<PathBuf>,
        /// Replace an existing --json file (only one `validate` wrote).
        #[arg(long, requires = "json")]
        force: bool,
    },
    /// Put two `validate thesis --seeds` runs (other --seed-base) side by side: each row's
    /// verdict and fraction of draws in tolerance in both, and the rows far from the bar
    /// in both whose verdicts differ (there should be none).
    Agree {
        /// The first run's results.json (or its directory).
        first: PathBuf,
        /// The second run's results.json (or its directory).
        second: PathBuf,
    },
}

#[derive(Debug, Subcommand)]
pub enum StudyAction {
    /// Make every run of STUDY, or those of one shard, into DIR: a journal of finished
    /// runs (a rerun after a crash makes only the missing ones), the shard's HDF5 file,
    /// and for a whole study the merged DIR/study.h5 with per-point summaries.
    Run {
        /// The study file (TOML).
        study: PathBuf,
        /// Output directory (created when missing; shared by shards).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Make only shard i of n (1-based): runs r with r % n == i - 1.
        #[arg(long, value_name = "i/n")]
        shard: Option<String>,
        /// Replace another study's files in DIR (this study's own are rewritten by a rerun;
        /// a file skyforge did not write never is).
        #[arg(long)]
        force: bool,
    },
    /// Write Slurm scripts for STUDY into DIR/slurm/: a job array of N tasks (task i runs
    /// `study run --shard i/N`), a merge job, and submit.sh, which submits the array and
    /// the merge after it (`--dependency=afterok`). DIR must be on storage every node
    /// sees.
    Slurm {
        /// The study file (TOML).
        study: PathBuf,
        /// The study's output directory (created when missing).
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Array tasks (shards).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=100_000))]
        shards: u64,
        /// The skyforge binary as the nodes see it (default: this one).
        #[arg(long, value_name = "PATH")]
        skyforge: Option<PathBuf>,
        /// An extra #SBATCH option for both jobs, e.g. --sbatch=--partition=short
        /// (repeatable).
        #[arg(long = "sbatch", value_name = "OPTION", allow_hyphen_values = true)]
        sbatch: Vec<String>,
        /// Replace the scripts of an earlier `study slurm` in DIR/slurm/.
        #[arg(long)]
        force: bool,
    },
    /// Merge the shard files of DIR... (every shard-*-of-*.h5, or files) into one file,
    /// byte-identical to a whole run's study.h5.
    Merge {
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
        /// The merged file (default: the first DIR's study.h5).
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
        /// Replace another study's file at --out (this study's own is rewritten; a file
        /// skyforge did not write never is).
        #[arg(long)]
        force: bool,
    },
}

/// `skyforge receive`'s arguments.
#[derive(Debug, Args)]
pub struct ReceiveArgs {
    /// Recordings: .sigmf-meta/.sigmf-data files or raw sample files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Sample format of raw files: ci8, ci16, cf32 or ri8.
    #[arg(long, value_name = "F")]
    pub format: Option<String>,
    /// Sample rate of raw files (Hz).
    #[arg(long, value_name = "HZ")]
    pub fs: Option<f64>,
    /// Intermediate frequency of raw files (Hz; default 0).
    #[arg(long = "if", value_name = "HZ", allow_negative_numbers = true)]
    pub if_hz: Option<f64>,
    /// Signal of raw files: gps-l1ca or bds-b1i.
    #[arg(long, value_name = "S")]
    pub signal: Option<String>,
    /// Navigation file (RINEX 2/3/4) for assisted acquisition and immediate fixes.
    #[arg(long, value_name = "NAV")]
    pub assist: Option<PathBuf>,
    /// Receiver configuration (TOML: [acquisition], [tracking], [observables], [pvt],
    /// [assist]).
    #[arg(long, value_name = "TOML")]
    pub config: Option<PathBuf>,
    /// Body geometry (TOML as `skyforge synth` writes it, or `skyforge attitude
    /// --estimate-geometry`'s geometry_corrected.toml): also run the attitude chain on
    /// the observations, as `skyforge attitude` does, into DIR/attitude.csv,
    /// DIR/attitude.h5 and DIR/ambiguities.csv. Needs --assist.
    #[arg(long, value_name = "TOML")]
    pub geometry: Option<PathBuf>,
    /// The attitude chain's settings (TOML with a [relative] table; docs/attitude.md).
    #[arg(long, value_name = "TOML", requires = "geometry")]
    pub attitude_config: Option<PathBuf>,
    /// Also determine the orbit from the first recording's fixes as the receiver makes
    /// them (an epoch stage; `skyforge od`'s filter, its settings in TOML when given):
    /// writes DIR/orbit.csv, DIR/orbit.h5 and DIR/orbit.sp3
    /// (docs/orbit-determination.md).
    #[arg(long, value_name = "TOML", num_args = 0..=1)]
    pub od: Option<Option<PathBuf>>,
    /// Also navigate relative to a target spacecraft: this receiver is the chaser, OBS
    /// the target's RINEX observation file (as a link delivers it); at every epoch the
    /// first recording's observations and the target's of the same epoch go through
    /// `skyforge relnav`'s engine in the configured mode (an epoch stage): writes
    /// DIR/relnav.csv. Needs --assist.
    #[arg(long, value_name = "OBS")]
    pub relnav: Option<PathBuf>,
    /// The relnav stage's settings (TOML as `skyforge relnav --config`).
    #[arg(long, value_name = "TOML", requires = "relnav")]
    pub relnav_config: Option<PathBuf>,
    /// Output directory; created, must not exist unless --force is given.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Replace an existing output directory.
    #[arg(long)]
    pub force: bool,
}
