//! Inertial measurements as an IMU delivers them: angle and velocity increments over a
//! sampling interval, in the IMU's body axes, time-tagged in GPS time. The record every
//! IMU file format reads into and writes from; a receiver-side INS reads only these.
//!
//! The text files ([`read_csv`], [`write_csv`]: SkyForge's IMU CSV; [`read_kf_gins`],
//! [`write_kf_gins`]: KF-GINS's increment file) read record by record with [`CsvReader`]
//! and [`KfGinsReader`].

mod record;
mod text;

pub use record::ImuIncrement;
pub use text::{
    CSV_HEADER, CsvReader, CsvWriter, DT_S, DTHETA_RAD, DV_MPS, ImuTextError, KF_GINS_GAP_S,
    KfGinsReader, KfGinsWriter, MAX_LINE_BYTES, MAX_RECORDS, read_csv, read_kf_gins, write_csv,
    write_kf_gins,
};
