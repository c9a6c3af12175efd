//! Thesis chapter 4: antenna geometry offsets. The body-frame antenna geometry `B_0` the
//! attitude of [`crate::attitude`] assumes may be wrong (mounting misalignment, launch
//! shocks, thermal or flight deformation); these estimators work around or estimate the
//! deviation.
//!
//! * [`iterative`]: section 4.2.1, Ardalan's iterative attitude from three antennas whose
//!   (misaligned) body lever coordinates are known (eqs. 4.2-1..4.2-12).
//! * [`joint_ls`]: section 4.2.2, the joint least squares of the attitude and a few
//!   deformation parameters of `B_0` (Cohen/Cannon, Tsujii; eqs. 4.2-13..4.2-22).

pub mod iterative;
pub mod joint_ls;
