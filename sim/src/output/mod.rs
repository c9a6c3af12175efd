//! Output writers and the all-or-nothing output directory.

pub mod interrupt;
pub mod manifest;
pub mod slurm_scripts;
pub mod staged_dir;
pub mod synth_sinks;
pub mod whole_file;
