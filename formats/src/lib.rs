//! SkyForge's own files, one module per format: its writer, its reader and its column and
//! dataset names, defined once, with a round-trip test. Other people's formats live with
//! their vocabulary (RINEX observations in `skyforge_gnss::observation`, SigMF recording
//! metadata in `skyforge_gnss::sigmf`, navigation files and SP3 in `skyforge_orbits`),
//! `geometry.toml` in `skyforge_navigation::geometry_file`.
//!
//! - [`attitude`]: `attitude.csv`, `attitude.h5` and `ambiguities.csv`, what the attitude
//!   chain (`skyforge attitude`, `skyforge receive --geometry`) writes per epoch;
//! - [`geometry_offsets`]: `geometry_offsets.csv` and `geometry_offsets.h5`, the
//!   geometry-offset estimate (`skyforge attitude --estimate-geometry`);
//! - [`imu`]: `imu.h5`, an IMU's samples with their truth (the error-free increments,
//!   the platform's position, velocity and attitude, the sensors' biases);
//! - [`monitor`]: `monitor.csv`, `monitor.h5` and `summary.json`, what the integrity
//!   monitor writes (`skyforge monitor run`);
//! - [`orbit`]: `orbit.csv`, `orbit.h5` and `orbit.sp3`, the estimated orbit of
//!   `skyforge od`, and `truth.sp3`, the truth's orbit of a LEO beside `truth.h5`;
//! - [`relative`]: `relative.csv`, the relative truth of a scenario with several
//!   vehicles (each relative to the first, in its orbit frame);
//! - [`truth`]: `truth.h5`, the geometry and signal truth of a run (`skyforge run`,
//!   `skyforge synth`), which validate and the report read;
//! - [`receiver`]: what `skyforge receive` writes per epoch besides its RINEX files:
//!   `pvt.csv`, `<antenna>.nmea` and `receiver.h5`;
//! - [`h5`]: resizable HDF5 tables, shared by the HDF5 writers.
//!
//! A study's files (`study.h5`, its shards and journals) live with the study, in
//! `skyforge_studies::study::results`: their rows are the study's types.
//!
//! The crate writes the simulator's truth, so it sits above the simulator and, like it,
//! out of the receiver's and the estimators' reach (the truth firewall,
//! `tests/tests/truth_firewall.rs`).

pub mod attitude;
mod csv;
pub mod geometry_offsets;
pub mod h5;
pub mod imu;
pub mod ins;
pub mod interference;
pub mod monitor;
pub mod orbit;
pub mod receiver;
pub mod relative;
pub mod truth;

pub use csv::FormatError;
