//! SkyForge's own files, one module per format: its writer, its reader and its column and
//! dataset names, defined once, with a round-trip test. Other people's formats live with
//! their vocabulary (RINEX observations in `skyforge_gnss::observation`, navigation files
//! and SP3 in `skyforge_orbits`), `geometry.toml` in `skyforge_navigation::geometry_file`.
//!
//! - [`attitude`]: `attitude.csv`, `attitude.h5` and `ambiguities.csv`, what the attitude
//!   chain (`skyforge attitude`, `skyforge receive --geometry`) writes per epoch;
//! - [`geometry_offsets`]: `geometry_offsets.csv` and `geometry_offsets.h5`, the
//!   geometry-offset estimate (`skyforge attitude --estimate-geometry`);
//! - [`monitor`]: `monitor.csv`, `monitor.h5` and `summary.json`, what the integrity
//!   monitor writes (`skyforge monitor run`);
//! - [`h5`]: resizable HDF5 tables, shared by the HDF5 writers (those not yet here:
//!   `truth.h5`, `receiver.h5`, `study.h5`).

pub mod attitude;
mod csv;
pub mod geometry_offsets;
pub mod h5;
pub mod monitor;

pub use csv::FormatError;
