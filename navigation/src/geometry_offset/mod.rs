//! Thesis chapter 4: antenna geometry offsets. The body-frame antenna geometry `B_0` the
//! attitude of [`crate::attitude`] assumes may be wrong (mounting misalignment, launch
//! shocks, thermal or flight deformation); these estimators work around or estimate the
//! deviation (docs/geometry.md).
//!
//! * [`iterative`]: section 4.2.1, Ardalan's iterative attitude from three antennas whose
//!   (misaligned) body lever coordinates are known (eqs. 4.2-1..4.2-12).
//! * [`joint_ls`]: section 4.2.2, the joint least squares of the attitude and a few
//!   deformation parameters of `B_0` (Cohen/Cannon, Tsujii; eqs. 4.2-13..4.2-22).
//! * [`stacked_ukf`]: section 4.3, the on-orbit estimation of all offsets `dB_0` by a UKF
//!   on four stacked epochs (eqs. 4.3-5..4.3-26).
//! * [`shape`]: the part of the geometry baselines determine (lengths and angle) and the
//!   part they cannot (its orientation in the body frame).

pub mod iterative;
pub mod joint_ls;
pub(crate) mod shape;
pub(crate) mod stacked_ukf;

pub use shape::{align, invariants};
pub use stacked_ukf::{
    OffsetConfig, OffsetEstimator, OffsetState, Orientation, Step, THESIS_OFFSET_RATE_PSD,
    THESIS_RATE_PSD, WindowWeighting,
};
