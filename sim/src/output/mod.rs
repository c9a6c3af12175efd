//! Output writers and the all-or-nothing output directory.

pub mod interrupt;
pub mod manifest;
pub mod receiver_out;
pub mod slurm_scripts;
pub mod staged_dir;
pub mod study_files;
pub mod synth_sinks;
pub mod truth_h5;
pub mod whole_file;
