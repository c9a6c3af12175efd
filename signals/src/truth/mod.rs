//! Truth for every antenna x satellite: geometry now; clocks, atmosphere and antenna terms
//! join it with the synthesiser.

pub(crate) mod geometry;
pub(crate) mod interp;
pub mod light_time;
pub(crate) mod true_satellite;

pub use geometry::{GeometryChunk, GeometryTruth, LinkGeometry, StreamError, epoch_count};

pub use interp::QuinticHermite;
pub use true_satellite::TrueSatellite;
