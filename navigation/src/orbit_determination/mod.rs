//! Orbit determination of the receiving spacecraft from its own GNSS measurements.
//!
//! Today: the book's position filter (section 5.5.4) on single-point fixes, with
//! Clohessy-Wiltshire dynamics about a refreshed reference circle.

pub(crate) mod clohessy_wiltshire;
pub(crate) mod from_files;
pub(crate) mod position_filter;

pub use clohessy_wiltshire::{input, transition};
pub use from_files::position_filter_on_file;
pub use position_filter::{FixInput, OrbitEstimate, PositionFilter, PositionFilterConfig};
