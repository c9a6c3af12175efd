//! Navigation messages a real receiver decodes: GPS LNAV and BeiDou D1/D2.

pub(crate) mod bds;
pub mod bds_cnav1;
pub mod bds_cnav2;
mod bds_cnav_eph;
pub mod conv_k7;
pub mod crc24q;
pub mod field;
pub mod galileo_fnav;
pub mod galileo_inav;
pub mod gps_cnav;
pub mod gps_lnav;
pub mod ldpc_gf64;

pub use bds::{BdsExtraFields, BdsNavEncoder, BdsNavError, BdsNavFormat, Klobuchar};
pub use bds_cnav_eph::{A_REF_IGSO_GEO_M, A_REF_MEO_M, BdsCnavError, BdsCnavParams};
