//! Tests of the TDCP module on synthetic observations of the nominal GPS constellation:
//! noise-free solutions (static with a clock drift, moving, lever arm), the clock in the
//! single differences and not in the double ones, consistency under noise (NEES and the
//! a-posteriori chi-square), exclusions and errors, and runs over files.

mod exclusions;
mod files;
mod lever_arm;
mod noise;
mod solutions;
pub(crate) mod world;
