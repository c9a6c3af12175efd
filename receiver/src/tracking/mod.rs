//! Carrier and code tracking.
