//! Thesis chapter 4: antenna geometry offsets. The antennas are not where the nominal
//! body geometry `B_0` says; these estimators find the offsets `dB_0` and the attitude
//! together (docs/geometry.md).
//!
//! * [`stacked_ukf`]: the on-orbit estimation of section 4.3, a UKF on four stacked
//!   epochs (eqs. 4.3-5..4.3-26).
//! * [`shape`]: the part of the geometry baselines determine (lengths and angle) and the
//!   part they cannot (its orientation in the body frame).

pub mod shape;
pub mod stacked_ukf;
