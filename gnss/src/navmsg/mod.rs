//! Navigation messages a real receiver decodes: GPS LNAV and BeiDou D1/D2.

pub mod bds;
pub mod gps_lnav;
