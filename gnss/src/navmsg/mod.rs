//! Navigation messages a real receiver decodes: GPS LNAV and BeiDou D1/D2.

pub(crate) mod bds;
pub mod conv_k7;
pub mod crc24q;
pub mod field;
pub mod galileo_fnav;
pub mod galileo_inav;
pub mod gps_cnav;
pub mod gps_lnav;
pub mod ldpc_gf64;

pub use bds::{BdsExtraFields, BdsNavEncoder, BdsNavError, BdsNavFormat, Klobuchar};
