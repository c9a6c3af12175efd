//! Integrity monitoring validations: RAIM against Yuan 2000 tables 5-1 and 5-2.

pub mod raim;
