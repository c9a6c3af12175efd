//! IF/baseband synthesis: per-channel mixing of code, data and carrier into sample blocks,
//! front-end quantisation, and the sample-file formats with their SigMF metadata.

pub mod format;
pub mod mix;
pub mod noise;
pub mod quantise;
pub mod sigmf;
