//! Output writers and the all-or-nothing output directory.

mod h5_datasets;
pub mod receiver_out;
pub mod rinex_obs;
pub mod staged_dir;
pub mod truth_h5;
