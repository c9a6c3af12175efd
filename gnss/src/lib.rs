//! The GNSS vocabulary: what every receiver knows. Signal identifiers, ranging codes,
//! navigation-message formats, sample-file formats with their SigMF recording metadata,
//! NCO helpers, and the observation record with its RINEX observation files. Both the simulator (`skyforge-signals`) and the
//! receiver build on it; it knows nothing of truth, so the receiver's truth firewall is a
//! missing Cargo edge (tests/tests/truth_firewall.rs reads the manifests).

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod antenna_name;
pub mod codes;
pub mod imu;
pub mod navmsg;
pub mod nco;
pub mod observation;
pub mod sample_format;
pub mod sigmf;
pub mod signal;
pub mod spread;
pub mod subcarrier;
