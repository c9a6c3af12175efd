//! Carrier and code tracking.

pub mod error_budget;
