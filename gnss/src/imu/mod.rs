//! Inertial measurements as an IMU delivers them: angle and velocity increments over a
//! sampling interval, in the IMU's body axes, time-tagged in GPS time. The record every
//! IMU file format reads into and writes from; a receiver-side INS reads only these.

mod record;

pub use record::ImuIncrement;
