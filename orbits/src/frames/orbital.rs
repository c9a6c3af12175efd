//! The orbital frame of thesis section 2.5.1: Xo along the flight direction, Zo towards
//! the Earth centre, Yo completing the right-handed triad.

use crate::{Mat3, Vec3};

/// `c_orbital_eci` (columns are Xo, Yo, Zo in ECI) from an ECI position and velocity.
pub fn c_orbital_eci(r_eci_m: &Vec3, v_eci_mps: &Vec3) -> Mat3 {
    todo!("{r_eci_m} {v_eci_mps}")
}
