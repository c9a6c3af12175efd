//! I/NAV field definitions (Galileo OS SIS ICD Issue 2.1 §4.3.5 word layouts, §5.1
//! parameters). The clock, ephemeris, NeQuick, GST-UTC, GST-GPS and almanac parameters are the
//! ones F/NAV carries, with the same widths and scales (the ICD defines each once for both
//! messages), so they are F/NAV's definitions; the fields below are I/NAV's own.

use crate::navmsg::field::{Lsb, field};
pub use crate::navmsg::galileo_fnav::quant::{
    A0, A0G, A1, A1G, AF0, AF1, AF2, AI0, AI1, AI2, ALM_AF0, ALM_AF1, ALM_DI, ALM_DSQRT_A, ALM_E,
    ALM_M0, ALM_OMEGA, ALM_OMEGA_DOT, ALM_OMEGA0, BGD_E1_E5A, CIC, CIS, CRC, CRS, CUC, CUS,
    DELTA_N, DN, DT_LS, DT_LSF, E, Field, I0, IDOT, IODA, IODNAV, M0, OMEGA, OMEGA_DOT, OMEGA0,
    REGION_FLAGS, SQRT_A, SVID, T0A, T0G, T0T, TOC, TOE, TOW, WN, WN_LSF, WN0G, WN0T, WNA, spare,
};

/// Word type (6 bits, §4.3.5).
pub const WORD_TYPE: Field = field("Type", 6, false, Lsb::Count);
/// SISA(E1,E5b) index (the ICD's SISA section), carried as given.
pub const SISA: Field = field("SISA(E1,E5b)", 8, false, Lsb::Count);
/// BGD(E1,E5b) (§5.1.5), s.
pub const BGD_E1_E5B: Field = field("BGD(E1,E5b)", 10, true, Lsb::Pow2(-32));
/// E5b and E1-B signal health status and data validity status (§5.1.9, service
/// parameters).
pub const E5B_HS: Field = field("E5bHS", 2, false, Lsb::Count);
pub const E1B_HS: Field = field("E1BHS", 2, false, Lsb::Count);
pub const E5B_DVS: Field = field("E5bDVS", 1, false, Lsb::Count);
pub const E1B_DVS: Field = field("E1BDVS", 1, false, Lsb::Count);
/// Word type 0's time field (§4.3.5): '10' when its WN and TOW are valid.
pub const TIME: Field = field("Time", 2, false, Lsb::Count);
/// The value of [`TIME`] that validates word type 0's WN and TOW.
pub const TIME_VALID: i64 = 0b10;
