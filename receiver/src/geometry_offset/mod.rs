//! Thesis chapter 4: antenna geometry offsets. The body-frame antenna geometry `B_0` the
//! attitude of [`crate::attitude`] assumes may be wrong (mounting misalignment, launch
//! shocks, thermal or flight deformation); these estimators work around or estimate the
//! deviation.
//!
//! * [`iterative`]: section 4.2.1, Ardalan's iterative attitude from three antennas whose
//!   (misaligned) body lever coordinates are known (eqs. 4.2-1..4.2-12).

pub mod iterative;
