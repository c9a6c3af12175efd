//! Validation: compare what SkyForge computes with truth and with the thesis tables.

pub mod report;
pub mod observables;
pub mod stats;
pub mod thesis;
