//! F/NAV field definitions: bit widths, signedness and scale factors (Galileo OS SIS ICD
//! §5.1: ephemeris §5.1.1, clock §5.1.3, NeQuick §5.1.6, BGD §5.1.5, GST-UTC §5.1.7,
//! GST-GPS §5.1.8, service parameters §5.1.9, almanac §5.1.10; Issue 1 Tables 61-79),
//! and quantisation of SI values onto them. Widths and scale exponents agree with the
//! ones GNSSTk's F/NAV bit tables give (GalFBits.hpp, which cites the same ICD tables).
//!
//! Signed fields are two's complement. Angles are broadcast in semicircles (the LSB
//! below is already in radians: 1 semicircle = pi rad); a value outside its field is an
//! error naming the field, never a silent saturation.

pub use super::super::field::Field;
pub(crate) use super::super::field::{Lsb, field};
use std::f64::consts::PI;

/// Page type (6 bits).
pub const PAGE_TYPE: Field = field("Type", 6, false, Lsb::Count);
/// Satellite ID (§5.1.9, service parameters).
pub const SVID: Field = field("SVID", 6, false, Lsb::Count);
/// Issue of data of the navigation batch (§5.1.9).
pub const IODNAV: Field = field("IODnav", 10, false, Lsb::Count);
/// Clock (§5.1.3).
pub const TOC: Field = field("t0c", 14, false, Lsb::Value(60.0));
pub const AF0: Field = field("af0", 31, true, Lsb::Pow2(-34));
pub const AF1: Field = field("af1", 21, true, Lsb::Pow2(-46));
pub const AF2: Field = field("af2", 6, true, Lsb::Pow2(-59));
/// SISA(E1,E5a) index (the ICD's SISA section), carried as given.
pub const SISA: Field = field("SISA(E1,E5a)", 8, false, Lsb::Count);
/// NeQuick effective ionisation level coefficients (§5.1.6): sfu, sfu/deg, sfu/deg^2.
pub const AI0: Field = field("ai0", 11, false, Lsb::Pow2(-2));
pub const AI1: Field = field("ai1", 11, true, Lsb::Pow2(-8));
pub const AI2: Field = field("ai2", 14, true, Lsb::Pow2(-15));
/// Ionospheric disturbance flags for regions 1-5, one bit each, sent as zeros.
pub const REGION_FLAGS: Field = field("Region 1-5 flags", 5, false, Lsb::Count);
/// BGD(E1,E5a) (§5.1.5), s.
pub const BGD_E1_E5A: Field = field("BGD(E1,E5a)", 10, true, Lsb::Pow2(-32));
/// E5a signal health status and data validity status (§5.1.9; Issue 1 Tables 74-78).
pub const E5A_HS: Field = field("E5aHS", 2, false, Lsb::Count);
pub const E5A_DVS: Field = field("E5aDVS", 1, false, Lsb::Count);
/// GST week number and time of week (§5.1.2).
pub const WN: Field = field("WN", 12, false, Lsb::Count);
pub const TOW: Field = field("TOW", 20, false, Lsb::Count);
/// Ephemeris (§5.1.1).
pub const M0: Field = field("M0", 32, true, Lsb::Semi(-31));
pub const OMEGA_DOT: Field = field("OMEGAdot", 24, true, Lsb::Semi(-43));
pub const E: Field = field("e", 32, false, Lsb::Pow2(-33));
pub const SQRT_A: Field = field("sqrtA", 32, false, Lsb::Pow2(-19));
pub const OMEGA0: Field = field("OMEGA0", 32, true, Lsb::Semi(-31));
pub const IDOT: Field = field("idot", 14, true, Lsb::Semi(-43));
pub const I0: Field = field("i0", 32, true, Lsb::Semi(-31));
pub const OMEGA: Field = field("omega", 32, true, Lsb::Semi(-31));
pub const DELTA_N: Field = field("Delta n", 16, true, Lsb::Semi(-43));
pub const CUC: Field = field("Cuc", 16, true, Lsb::Pow2(-29));
pub const CUS: Field = field("Cus", 16, true, Lsb::Pow2(-29));
pub const CRC: Field = field("Crc", 16, true, Lsb::Pow2(-5));
pub const CRS: Field = field("Crs", 16, true, Lsb::Pow2(-5));
pub const CIC: Field = field("Cic", 16, true, Lsb::Pow2(-29));
pub const CIS: Field = field("Cis", 16, true, Lsb::Pow2(-29));
pub const TOE: Field = field("t0e", 14, false, Lsb::Value(60.0));
/// GST-UTC conversion (§5.1.7).
pub const A0: Field = field("A0", 32, true, Lsb::Pow2(-30));
pub const A1: Field = field("A1", 24, true, Lsb::Pow2(-50));
pub const DT_LS: Field = field("Delta tLS", 8, true, Lsb::Count);
pub const T0T: Field = field("t0t", 8, false, Lsb::Value(3600.0));
pub const WN0T: Field = field("WN0t", 8, false, Lsb::Count);
pub const WN_LSF: Field = field("WNLSF", 8, false, Lsb::Count);
pub const DN: Field = field("DN", 3, false, Lsb::Count);
pub const DT_LSF: Field = field("Delta tLSF", 8, true, Lsb::Count);
/// GST-GPS conversion (§5.1.8).
pub const T0G: Field = field("t0G", 8, false, Lsb::Value(3600.0));
pub const A0G: Field = field("A0G", 16, true, Lsb::Pow2(-35));
pub const A1G: Field = field("A1G", 12, true, Lsb::Pow2(-51));
pub const WN0G: Field = field("WN0G", 6, false, Lsb::Count);
/// Almanac (§5.1.10).
pub const IODA: Field = field("IODa", 4, false, Lsb::Count);
pub const WNA: Field = field("WNa", 2, false, Lsb::Count);
pub const T0A: Field = field("t0a", 10, false, Lsb::Value(600.0));
pub const ALM_DSQRT_A: Field = field("Delta(A^1/2)", 13, true, Lsb::Pow2(-9));
pub const ALM_E: Field = field("e (almanac)", 11, false, Lsb::Pow2(-16));
pub const ALM_OMEGA: Field = field("omega (almanac)", 16, true, Lsb::Semi(-15));
pub const ALM_DI: Field = field("delta i", 11, true, Lsb::Semi(-14));
pub const ALM_OMEGA0: Field = field("OMEGA0 (almanac)", 16, true, Lsb::Semi(-15));
pub const ALM_OMEGA_DOT: Field = field("OMEGAdot (almanac)", 11, true, Lsb::Semi(-33));
pub const ALM_M0: Field = field("M0 (almanac)", 16, true, Lsb::Semi(-15));
pub const ALM_AF0: Field = field("af0 (almanac)", 16, true, Lsb::Pow2(-19));
pub const ALM_AF1: Field = field("af1 (almanac)", 13, true, Lsb::Pow2(-38));
/// The 4 most significant bits of SVID2's OMEGA0 (page type 5) and the 12 others (6).
pub const ALM_OMEGA0_MSB: Field = field("OMEGA0 (almanac, 1/2)", 4, false, Lsb::Count);
pub const ALM_OMEGA0_LSB: Field = field("OMEGA0 (almanac, 2/2)", 12, false, Lsb::Count);

/// A spare field of `bits` bits, sent as zeros.
pub const fn spare(bits: u32) -> Field {
    field("Spare", bits, false, Lsb::Count)
}

/// Nominal almanac semi-major axis (m) and inclination (rad) the almanac's Delta(A^1/2)
/// and delta i refer to (§5.1.10: 29 600 km, 56 deg).
pub const ALM_A_NOMINAL_M: f64 = 29_600_000.0;
pub const ALM_I_NOMINAL_RAD: f64 = 56.0 * PI / 180.0;
