//! IF/baseband synthesis: per-channel mixing of code, data and carrier into sample blocks.

pub mod mix;
