//! SP3-c/d precise orbit files, plain or gzip-compressed: the reader (GNSS satellites'
//! positions, the external oracle for broadcast orbits and the `precise` satellite
//! errors; any vehicle's states) and the writer (`skyforge od`'s estimated orbit, the
//! truth's orbit of a LEO).
//!
//! Format facts (SP3-c and SP3-d specifications): line 1 starts `#c` or `#d`; the first
//! `%c` line gives the time system in columns 10-12 (`GPS`, `GLO`, `GAL`, `BDT`, `TAI`,
//! `UTC`; GPS when absent); epoch lines start with `*` followed by year, month, day, hour,
//! minute, second; position lines are `P` + satellite id (3 characters, e.g. `G01` or
//! `G 1`) + x, y, z in km (F14.6, columns 5-46) + clock in microseconds (F14.6, columns
//! 47-60). A position of 0.000000 in all three axes is "bad or absent"; a clock of
//! 999999.999999 (or more) is "missing". Velocity lines (`V`, after the position line of
//! the same vehicle) give dx/dt, dy/dt, dz/dt in dm/s and the clock rate in 1e-4 us/s;
//! correlation lines (`EP`/`EV`) are ignored. Vehicle identifiers: a system letter (`G`,
//! `C`, `E`, `R`, `J`, `L` for a LEO) and a two-digit number.

mod read;
mod write;

pub use read::{parse_sp3_vehicle, read_sp3, read_sp3_vehicle};
pub use write::{Sp3Header, Sp3Series, write_sp3};

use super::sat_id::SatId;
use crate::Vec3;
use hifitime::Epoch;

/// SP3 clock values at or above this are "missing" (the format's 999999.999999 sentinel).
const CLOCK_MISSING_US: f64 = 999_999.0;

/// One SP3 position record of a GNSS satellite (ECEF, metres; centre of mass).
#[derive(Debug, Clone, PartialEq)]
pub struct Sp3Record {
    pub epoch: Epoch,
    pub sat: SatId,
    pub r_ecef_m: Vec3,
    /// Clock offset (s), when given.
    pub clock_s: Option<f64>,
}

/// One state of a vehicle at one epoch (ECEF, metres; centre of mass).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sp3State {
    pub epoch: Epoch,
    pub r_ecef_m: Vec3,
    /// Velocity (m/s), where the file has it.
    pub v_ecef_mps: Option<Vec3>,
    /// Clock offset (s), when given.
    pub clock_s: Option<f64>,
}
