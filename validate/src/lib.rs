//! Validation: compare what SkyForge computes with truth and with the thesis tables.

pub mod observables;
pub mod pipeline;
pub mod report;
pub mod stats;
pub mod thesis;
