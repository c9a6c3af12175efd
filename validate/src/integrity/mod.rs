//! Integrity monitoring against its references: the B-value monitor on paper 002's lab
//! set-up (its fault cases as patterns, fault-free false alarms, detection curves).

pub mod lab;
pub mod monitor;
pub mod patterns;
