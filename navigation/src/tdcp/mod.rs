//! Time-differenced carrier phase (TDCP): the carrier phase of one receiver, one
//! satellite and one signal differenced between two epochs `t1 < t2` over which lock was
//! kept. The integer ambiguity cancels and what remains measures the antenna's
//! displacement to millimetres, without ambiguity resolution.
//!
//! # Observation model
//! Carrier phase in the RINEX sign (RINEX 3.04: it changes in the same sense as the
//! range), in metres:
//!
//! `lambda phi_i(t) = rho_i(t) + c (dt_r(t) - dt_s_i(t)) + lambda N_i + T_i(t) - I_i(t) + eps_i(t)`
//!
//! with `rho_i` the geometric range from the satellite at its transmit time to the
//! antenna at its receive instant (Sagnac included, IS-GPS-200 20.3.3.4.3.3.2), `dt_r`
//! and `dt_s_i` the receiver and satellite clocks, `N_i` the integer ambiguity,
//! `T_i`, `I_i` the troposphere and ionosphere and `eps_i` the noise (paper 001 eq. (1),
//! as reconstructed in `papers_001_002_digest.md` 2.1).
//!
//! **Single difference in time** ([`time_differences`], paper 001 eq. (2)): while lock
//! is kept `N_i` cancels, and over one epoch interval (seconds) the atmospheric terms
//! change by millimetres at most (the troposphere through the elevation's rate, the
//! ionosphere at its drift rate): they are ignored, as the paper's "common-mode errors".
//!
//! `dPhi_i = lambda (phi_i(t2) - phi_i(t1)) = rho_i(t2) - rho_i(t1) + c ddt_r - c ddt_s_i + eps_i`
//!
//! Linearised about an a-priori antenna position `r2_hat` at `t2`, the position `r1` at
//! `t1` taken as known (the previous solution, or an INS):
//!
//! `z_i = dPhi_i - [rho_i(t2, r2_hat) - rho_i(t1, r1)] + c (dt_s_i(t2) - dt_s_i(t1))
//!      = -e_i . delta_r2 + c ddt_r + eps_i`
//!
//! where `e_i` is the unit line of sight receiver -> satellite at `t2` and
//! `delta_r2 = r2 - r2_hat`: the row of the design matrix is `[-e_i^T, 1]`
//! ([`solve_single`]). Each satellite is placed at its transmit time from that epoch's
//! pseudorange (`crate::pvt::Transmitted`), both epochs with the **same** broadcast set
//! (the one selected at `t2`): a new set at a cut-over would put its decimetre-level
//! discontinuity into the difference. An error of `r1` passes into `r2` almost whole:
//! TDCP measures the displacement `r2 - r1`, not the position. `r1` and `r2` are the
//! antenna at the epochs' true receive instants (a fix's, tag less receiver clock): a
//! position taken at the tag instead is off by the clock offset times the speed (1 ms at
//! 20 m/s: 2 cm). The tags themselves only place the satellites, through the
//! pseudoranges, whatever the receiver clock.
//!
//! **Receiver clock.** `c ddt_r` is in every single difference: the SD of a static
//! receiver shows its oscillator's frequency offset (paper 001 Fig. 2, "very obvious";
//! `c x 1e-7 x 1 s = 30 m` at 1 Hz). The **double difference** against a reference
//! satellite (the highest at `t2`) cancels it ([`TdcpEpoch::double_differences`], paper
//! 001 eq. (7)): `z_ij = z_i - z_ref`, row `-(e_i - e_ref)^T`.
//!
//! **Noise.** With white phase noise `sigma_phi` (m) per epoch and satellite,
//! `Var(SD_i) = 2 sigma_phi^2`, independent between satellites; the `n` double
//! differences against one reference have covariance `2 sigma_phi^2 (I + 1 1^T)`
//! (diagonal `4 sigma^2`, off-diagonal `2 sigma^2`). [`TdcpConfig::elevation_weighting`]
//! uses `sigma_phi / sin(el)` instead (the elevation at `t2` for both epochs).
//! Consecutive pairs `(t0, t1)` and `(t1, t2)` share the epoch `t1`: their SDs are
//! correlated, `Cov = -sigma_phi^2`, a lag-1 correlation of `-1/2`. A filter fed every
//! pair must model it (e.g. a delayed-state or differenced-measurement formulation) or
//! decimate to non-overlapping pairs; each solution here is of one pair alone.
//!
//! **Lever arm** ([`LeverArm`], [`time_differences_imu`]; paper 001 eq. (3)): with `C_b^e(t)` the body-to-ECEF
//! attitude (SkyForge's `c_body_ecef`, `x_ecef = c_body_ecef x_body`) and `l_b` the IMU
//! -> antenna lever arm in body axes, `r_ant = r_imu + C_b^e l_b`, so
//! `Delta r_ant = Delta r_imu + (C_b^e(t2) - C_b^e(t1)) l_b`.
//!
//! # Solutions
//! [`solve_single`] estimates `delta_r2` and `c ddt_r` (>= 4 satellites),
//! [`solve_double`] `delta_r2` alone (>= 3 double differences, 4 satellites), by weighted
//! least squares with Gauss-Newton iterations (re-linearised at the new `r2_hat` until
//! the step is below a micrometre): one iteration leaves `|delta_r2|^2 / (2 rho)`, 1e-5 m
//! for a 20 m a-priori error, the second none. [`tdcp_from_file`] runs over the
//! consecutive epochs of any observation file (SkyForge's or another receiver's RINEX),
//! and [`dead_reckoning`] chains the solutions from a known start.

mod config;
mod displacement;
mod double_difference;
mod error;
mod from_file;
mod least_squares;
mod lever_arm;
mod records;
mod single_difference;
#[cfg(test)]
pub(crate) mod tests;

pub use config::TdcpConfig;
pub use displacement::{Displacement, Solver, solve, solve_double, solve_single};
pub use double_difference::DoubleDifferences;
pub use error::TdcpError;
pub use from_file::{DeadReckoning, TdcpStep, dead_reckoning, tdcp_from_file};
pub use lever_arm::{ImuPose, LeverArm, time_differences_imu};
pub use records::Exclusion;
pub use single_difference::{SatDifference, TdcpEpoch, time_differences};
