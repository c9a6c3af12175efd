//! Fixed-point fields: bit count, scale factor 2^n, two's complement or unsigned
//! (IS-GPS-200 tables 20-I, 20-III, 20-VI, 20-X).

use super::LnavError;

/// One message field: its size and scale factor (LSB = 2^lsb_log2 in ICD units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scale {
    /// Parameter name as in the ICD.
    pub name: &'static str,
    /// Number of bits.
    pub bits: u32,
    /// log2 of the scale factor (LSB).
    pub lsb_log2: i32,
    /// Two's complement (`true`) or unsigned.
    pub signed: bool,
    /// ICD unit (s, m, rad, semicircles, ...).
    pub unit: &'static str,
    /// The ICD table that defines the field.
    pub table: &'static str,
}

impl Scale {
    /// Weight of the least significant bit (ICD units).
    pub fn lsb(&self) -> f64 {
        2f64.powi(self.lsb_log2)
    }

    /// Smallest and largest integer the field holds.
    pub fn int_range(&self) -> (i64, i64) {
        if self.signed {
            (-(1i64 << (self.bits - 1)), (1i64 << (self.bits - 1)) - 1)
        } else {
            (0, (1i64 << self.bits) - 1)
        }
    }

    /// The integer nearest to `value / LSB`, or an error naming `owner` when it does not
    /// fit.
    pub fn quantise(&self, value: f64, owner: &str) -> Result<i64, LnavError> {
        let (lo, hi) = self.int_range();
        let n = (value / self.lsb()).round();
        if n.is_finite() && n >= lo as f64 && n <= hi as f64 {
            Ok(n as i64)
        } else {
            Err(self.out_of_range(value, owner))
        }
    }

    /// An angle (semicircles) on a field that spans exactly one circle
    /// (2^(bits-1) LSB = 1 semicircle): wrapped into [-1, 1) semicircles before rounding.
    pub fn quantise_angle(&self, value_sc: f64, owner: &str) -> Result<i64, LnavError> {
        debug_assert!(self.signed && self.bits as i32 - 1 + self.lsb_log2 == 0);
        let n = (value_sc / self.lsb()).round();
        if !n.is_finite() {
            return Err(self.out_of_range(value_sc, owner));
        }
        let modulus = 1i128 << self.bits;
        let half = modulus / 2;
        Ok(((n as i128 + half).rem_euclid(modulus) - half) as i64)
    }

    /// The field value (ICD units) of integer `n`.
    pub fn value(&self, n: i64) -> f64 {
        n as f64 * self.lsb()
    }

    /// The field bits of integer `n` (two's complement for signed fields), right-aligned.
    pub fn bits_of(&self, n: i64) -> u32 {
        (n as u64 & ((1u64 << self.bits) - 1)) as u32
    }

    fn out_of_range(&self, value: f64, owner: &str) -> LnavError {
        let (lo, hi) = self.int_range();
        LnavError::OutOfRange {
            what: format!("{owner} {}", self.name),
            value,
            min: self.value(lo),
            max: self.value(hi),
            unit: self.unit,
            table: self.table,
        }
    }
}

/// Shorthand for the field tables.
const fn field(
    name: &'static str,
    bits: u32,
    lsb_log2: i32,
    signed: bool,
    unit: &'static str,
    table: &'static str,
) -> Scale {
    Scale {
        name,
        bits,
        lsb_log2,
        signed,
        unit,
        table,
    }
}

const T1: &str = "table 20-I/20-III";
const T3: &str = "table 20-III";
const T6: &str = "table 20-VI";
const T10: &str = "table 20-X";

// Subframe 1 (tables 20-I and 20-III).
pub(crate) const TGD: Scale = field("TGD", 8, -31, true, "s", T1);
pub(crate) const TOC: Scale = field("toc", 16, 4, false, "s", T1);
pub(crate) const AF2: Scale = field("af2", 8, -55, true, "s/s^2", T1);
pub(crate) const AF1: Scale = field("af1", 16, -43, true, "s/s", T1);
pub(crate) const AF0: Scale = field("af0", 22, -31, true, "s", T1);

// Subframes 2 and 3 (table 20-III).
pub(crate) const CRS: Scale = field("Crs", 16, -5, true, "m", T3);
pub(crate) const DELTA_N: Scale = field("delta n", 16, -43, true, "semicircles/s", T3);
pub(crate) const M0: Scale = field("M0", 32, -31, true, "semicircles", T3);
pub(crate) const CUC: Scale = field("Cuc", 16, -29, true, "rad", T3);
pub(crate) const ECC: Scale = field("e", 32, -33, false, "", T3);
pub(crate) const CUS: Scale = field("Cus", 16, -29, true, "rad", T3);
pub(crate) const SQRT_A: Scale = field("sqrt A", 32, -19, false, "m^1/2", T3);
pub(crate) const TOE: Scale = field("toe", 16, 4, false, "s", T3);
pub(crate) const CIC: Scale = field("Cic", 16, -29, true, "rad", T3);
pub(crate) const OMEGA0: Scale = field("OMEGA0", 32, -31, true, "semicircles", T3);
pub(crate) const CIS: Scale = field("Cis", 16, -29, true, "rad", T3);
pub(crate) const I0: Scale = field("i0", 32, -31, true, "semicircles", T3);
pub(crate) const CRC: Scale = field("Crc", 16, -5, true, "m", T3);
pub(crate) const OMEGA: Scale = field("omega", 32, -31, true, "semicircles", T3);
pub(crate) const OMEGA_DOT: Scale = field("OMEGADOT", 24, -43, true, "semicircles/s", T3);
pub(crate) const IDOT: Scale = field("IDOT", 14, -43, true, "semicircles/s", T3);

// Almanac (table 20-VI).
pub(crate) const ALM_E: Scale = field("almanac e", 16, -21, false, "", T6);
pub(crate) const ALM_TOA: Scale = field("toa", 8, 12, false, "s", T6);
pub(crate) const ALM_DELTA_I: Scale = field("almanac delta i", 16, -19, true, "semicircles", T6);
pub(crate) const ALM_OMEGA_DOT: Scale =
    field("almanac OMEGADOT", 16, -38, true, "semicircles/s", T6);
pub(crate) const ALM_SQRT_A: Scale = field("almanac sqrt A", 24, -11, false, "m^1/2", T6);
pub(crate) const ALM_OMEGA0: Scale = field("almanac OMEGA0", 24, -23, true, "semicircles", T6);
pub(crate) const ALM_OMEGA: Scale = field("almanac omega", 24, -23, true, "semicircles", T6);
pub(crate) const ALM_M0: Scale = field("almanac M0", 24, -23, true, "semicircles", T6);
pub(crate) const ALM_AF0: Scale = field("almanac af0", 11, -20, true, "s", T6);
pub(crate) const ALM_AF1: Scale = field("almanac af1", 11, -38, true, "s/s", T6);

// Ionosphere and UTC (table 20-X).
pub(crate) const ALPHA: [Scale; 4] = [
    field("alpha0", 8, -30, true, "s", T10),
    field("alpha1", 8, -27, true, "s/semicircle", T10),
    field("alpha2", 8, -24, true, "s/semicircle^2", T10),
    field("alpha3", 8, -24, true, "s/semicircle^3", T10),
];
pub(crate) const BETA: [Scale; 4] = [
    field("beta0", 8, 11, true, "s", T10),
    field("beta1", 8, 14, true, "s/semicircle", T10),
    field("beta2", 8, 16, true, "s/semicircle^2", T10),
    field("beta3", 8, 16, true, "s/semicircle^3", T10),
];
pub(crate) const UTC_A0: Scale = field("A0", 32, -30, true, "s", T10);
pub(crate) const UTC_A1: Scale = field("A1", 24, -50, true, "s/s", T10);
pub(crate) const UTC_TOT: Scale = field("tot", 8, 12, false, "s", T10);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_wraps_to_half_open_circle() {
        let q = |x| M0.quantise_angle(x, "t").unwrap_or(i64::MAX);
        assert_eq!(q(1.0), -(1 << 31));
        assert_eq!(q(-1.0), -(1 << 31));
        assert_eq!(q(0.5), 1 << 30);
        assert_eq!(q(2.5), 1 << 30);
        assert_eq!(q(-0.5), -(1 << 30));
        assert_eq!(q(1.0 - 2f64.powi(-31)), (1 << 31) - 1);
    }

    #[test]
    fn range_limits_are_the_icd_ones() {
        // IS-GPS-200 table 20-III: af0 22 bits at 2^-31 s spans +-2^-10 s; toe 604784 s
        // is the last 16-s step of the week.
        assert!(AF0.quantise(9.7e-4, "t").is_ok());
        assert!(AF0.quantise(9.8e-4, "t").is_err());
        assert_eq!(TOE.quantise(604_784.0, "t"), Ok(37_799));
        assert!(ECC.quantise(-1e-3, "t").is_err());
        assert!(CRS.quantise(f64::NAN, "t").is_err());
        assert_eq!(AF0.bits_of(-1), 0x3F_FFFF);
        assert_eq!(TGD.bits_of(-2), 0xFE);
    }
}
