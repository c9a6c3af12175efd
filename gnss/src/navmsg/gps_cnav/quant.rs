//! CNAV field definitions: bit widths, signedness and scale factors (IS-GPS-705J §20.3.3:
//! message types 10 and 11, Figures 20-1 and 20-2 with Table 20-I; the clock block of
//! types 30-37, Table 20-III; group delays, Table 20-IV; Klobuchar coefficients with the
//! LNAV scale factors; UTC, Table 20-IX), and quantisation of SI values onto them.
//! Widths and scale exponents agree with the CNAV bit table GNSSTk documents
//! (GPSCBits.hpp, from IS-GPS-200 Figures 30-1..30-3, the same layouts).
//!
//! Signed fields are two's complement. Angles are broadcast in semicircles (the LSB below
//! is already in radians: 1 semicircle = pi rad); a value outside its field is an error
//! naming the field, never a silent saturation.

pub use super::super::field::Field;
pub(crate) use super::super::field::{Lsb, OutOfRange, field};

/// A reserved field of `bits` bits, sent as zeros.
pub const fn reserved(bits: u32) -> Field {
    field("Reserved", bits, false, Lsb::Count)
}

/// IS-GPS-705J §20.3.3: the header every message starts with (38 bits).
pub const PREAMBLE: Field = field("Preamble", 8, false, Lsb::Count);
pub const PRN: Field = field("PRN", 6, false, Lsb::Count);
pub const MSG_TYPE: Field = field("Message type ID", 6, false, Lsb::Count);
/// Message TOW count: GPS TOW of the start of the next message, in 6 s units.
pub const TOW: Field = field("Message TOW count", 17, false, Lsb::Value(6.0));
pub const ALERT: Field = field("Alert flag", 1, false, Lsb::Count);

/// IS-GPS-705J Figure 20-1, Table 20-I: message type 10.
pub const WN: Field = field("WN", 13, false, Lsb::Count);
pub const HEALTH_L1: Field = field("L1 health", 1, false, Lsb::Count);
pub const HEALTH_L2: Field = field("L2 health", 1, false, Lsb::Count);
pub const HEALTH_L5: Field = field("L5 health", 1, false, Lsb::Count);
/// Data predict time of week (s), also in the clock block.
pub const TOP: Field = field("top", 11, false, Lsb::Value(300.0));
pub const URA_ED: Field = field("URA_ED index", 5, true, Lsb::Count);
pub const TOE: Field = field("toe", 11, false, Lsb::Value(300.0));
/// Semi-major axis difference from A_REF (m) and its rate (m/s).
pub const DELTA_A: Field = field("Delta A", 26, true, Lsb::Pow2(-9));
pub const A_DOT: Field = field("Adot", 25, true, Lsb::Pow2(-21));
/// Mean motion difference (semicircles/s) and its rate (semicircles/s^2).
pub const DELTA_N0: Field = field("Delta n0", 17, true, Lsb::Semi(-44));
pub const DELTA_N0_DOT: Field = field("Delta n0 dot", 23, true, Lsb::Semi(-57));
pub const M0: Field = field("M0-n", 33, true, Lsb::Semi(-32));
pub const E: Field = field("e-n", 33, false, Lsb::Pow2(-34));
pub const OMEGA: Field = field("omega-n", 33, true, Lsb::Semi(-32));
pub const INTEGRITY: Field = field("Integrity status flag", 1, false, Lsb::Count);
pub const L2C_PHASING: Field = field("L2C phasing", 1, false, Lsb::Count);

/// IS-GPS-705J Figure 20-2, Table 20-I: message type 11 (after toe).
pub const OMEGA0: Field = field("OMEGA0-n", 33, true, Lsb::Semi(-32));
pub const I0: Field = field("i0-n", 33, true, Lsb::Semi(-32));
/// Rate of right ascension difference from OMEGA_DOT_REF (semicircles/s).
pub const DELTA_OMEGA_DOT: Field = field("Delta OMEGAdot", 17, true, Lsb::Semi(-44));
pub const IDOT: Field = field("i0-n-DOT", 15, true, Lsb::Semi(-44));
pub const CIS: Field = field("Cis-n", 16, true, Lsb::Pow2(-30));
pub const CIC: Field = field("Cic-n", 16, true, Lsb::Pow2(-30));
pub const CRS: Field = field("Crs-n", 24, true, Lsb::Pow2(-8));
pub const CRC: Field = field("Crc-n", 24, true, Lsb::Pow2(-8));
pub const CUS: Field = field("Cus-n", 21, true, Lsb::Pow2(-30));
pub const CUC: Field = field("Cuc-n", 21, true, Lsb::Pow2(-30));

/// IS-GPS-705J Figures 20-3..20-10, Table 20-III: the clock block of types 30-37.
pub const URA_NED0: Field = field("URA_NED0 index", 5, true, Lsb::Count);
pub const URA_NED1: Field = field("URA_NED1 index", 3, false, Lsb::Count);
pub const URA_NED2: Field = field("URA_NED2 index", 3, false, Lsb::Count);
pub const TOC: Field = field("toc", 11, false, Lsb::Value(300.0));
pub const AF0: Field = field("af0-n", 26, true, Lsb::Pow2(-35));
pub const AF1: Field = field("af1-n", 20, true, Lsb::Pow2(-48));
pub const AF2: Field = field("af2-n", 10, true, Lsb::Pow2(-60));

/// IS-GPS-705J Figure 20-3, Table 20-IV: group delay differential and inter-signal
/// corrections (s) of message type 30.
pub const TGD: Field = field("TGD", 13, true, Lsb::Pow2(-35));
pub const ISC_L1CA: Field = field("ISC_L1C/A", 13, true, Lsb::Pow2(-35));
pub const ISC_L2C: Field = field("ISC_L2C", 13, true, Lsb::Pow2(-35));
pub const ISC_L5I5: Field = field("ISC_L5I5", 13, true, Lsb::Pow2(-35));
pub const ISC_L5Q5: Field = field("ISC_L5Q5", 13, true, Lsb::Pow2(-35));
/// The raw group delay value "1000000000000" (-4096): not available (IS-GPS-705J
/// §20.3.3.3.1.2).
pub const GROUP_DELAY_NOT_AVAILABLE: i64 = -4096;

/// Klobuchar coefficients of message type 30 (the LNAV scale factors, IS-GPS-200 Table
/// 20-X): alpha_n in s/semicircle^n, beta_n in s/semicircle^n.
pub const ALPHA: [Field; 4] = [
    field("alpha0", 8, true, Lsb::Pow2(-30)),
    field("alpha1", 8, true, Lsb::Pow2(-27)),
    field("alpha2", 8, true, Lsb::Pow2(-24)),
    field("alpha3", 8, true, Lsb::Pow2(-24)),
];
pub const BETA: [Field; 4] = [
    field("beta0", 8, true, Lsb::Pow2(11)),
    field("beta1", 8, true, Lsb::Pow2(14)),
    field("beta2", 8, true, Lsb::Pow2(16)),
    field("beta3", 8, true, Lsb::Pow2(16)),
];
/// Data predict week number (8 LSBs of the week of top).
pub const WN_OP: Field = field("WNop", 8, false, Lsb::Count);

/// IS-GPS-705J Figure 20-6, Table 20-IX: GPS-UTC parameters of message type 33.
pub const A0: Field = field("A0-n", 16, true, Lsb::Pow2(-35));
pub const A1: Field = field("A1-n", 13, true, Lsb::Pow2(-51));
pub const A2: Field = field("A2-n", 7, true, Lsb::Pow2(-68));
pub const DT_LS: Field = field("Delta tLS", 8, true, Lsb::Count);
pub const TOT: Field = field("tot", 16, false, Lsb::Pow2(4));
pub const WN_OT: Field = field("WNot", 13, false, Lsb::Count);
pub const WN_LSF: Field = field("WNLSF", 13, false, Lsb::Count);
pub const DN: Field = field("DN", 4, false, Lsb::Count);
pub const DT_LSF: Field = field("Delta tLSF", 8, true, Lsb::Count);
