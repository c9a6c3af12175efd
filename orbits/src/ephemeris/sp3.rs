//! SP3-c/d precise orbit files (positions only), plain or gzip-compressed; used as an
//! external oracle for broadcast orbits.

use super::{NavError, sat_id::SatId};
use crate::Vec3;
use hifitime::Epoch;
use std::path::Path;

/// One SP3 position record (ECEF, metres; centre of mass).
#[derive(Debug, Clone, PartialEq)]
pub struct Sp3Record {
    pub epoch: Epoch,
    pub sat: SatId,
    pub r_ecef_m: Vec3,
    /// Clock offset (s), when given.
    pub clock_s: Option<f64>,
}

/// Read the GPS and BeiDou position records of an SP3 file.
pub fn read_sp3(path: &Path) -> Result<Vec<Sp3Record>, NavError> {
    todo!("{path:?}")
}
