//! A field of a binary navigation message: its ICD name, width, signedness and scale
//! factor, the quantisation of an SI value onto it, and the raw values of a message set
//! by field. Galileo F/NAV and GPS CNAV define their tables with it.
//!
//! Signed fields are two's complement. Angles are broadcast in semicircles (an [`Lsb::Semi`]
//! field's LSB is in radians: 1 semicircle = pi rad); a value outside its field is an error
//! naming the field, never a silent saturation.

use std::f64::consts::PI;

/// How a raw field value converts to SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Lsb {
    /// An integer (counts, flags, indices, weeks): LSB 1.
    Count,
    /// LSB = the given value (s for reference times).
    Value(f64),
    /// LSB = 2^n (s, s/s, m, m/s, m^1/2, rad for harmonic terms, dimensionless).
    Pow2(i32),
    /// LSB = 2^n semicircles (or semicircles/s), converted to rad.
    Semi(i32),
}

/// One field of a message: name as in the ICD, width and signedness, scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Field {
    pub name: &'static str,
    pub bits: u32,
    pub signed: bool,
    pub(crate) lsb: Lsb,
}

/// A value that does not fit its field: the value and the range the field carries, in
/// the field's SI unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OutOfRange {
    pub field: &'static str,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// A field named `name`, `bits` wide, two's complement when `signed`, scaled by `lsb`.
pub(crate) const fn field(name: &'static str, bits: u32, signed: bool, lsb: Lsb) -> Field {
    Field {
        name,
        bits,
        signed,
        lsb,
    }
}

impl Field {
    /// The LSB in SI units (rad for angles).
    pub fn lsb_si(&self) -> f64 {
        match self.lsb {
            Lsb::Count => 1.0,
            Lsb::Value(v) => v,
            Lsb::Pow2(n) => 2f64.powi(n),
            Lsb::Semi(n) => PI * 2f64.powi(n),
        }
    }

    /// Smallest and largest raw value.
    pub fn raw_range(&self) -> (i64, i64) {
        if self.signed {
            (-(1i64 << (self.bits - 1)), (1i64 << (self.bits - 1)) - 1)
        } else {
            (0, (1i64 << self.bits) - 1)
        }
    }

    /// The raw value in SI units.
    pub fn si_value(&self, raw: i64) -> f64 {
        raw as f64 * self.lsb_si()
    }

    /// round(value / LSB), refused outside the field's range.
    pub(crate) fn quantise(&self, value: f64) -> Result<i64, OutOfRange> {
        let lsb = self.lsb_si();
        let (min, max) = self.raw_range();
        let n = (value / lsb).round();
        if n.is_finite() && n >= min as f64 && n <= max as f64 {
            Ok(n as i64)
        } else {
            Err(OutOfRange {
                field: self.name,
                value,
                min: min as f64 * lsb,
                max: max as f64 * lsb,
            })
        }
    }

    /// An angle (rad) wrapped to [-pi, pi) first, on a signed field spanning the full
    /// circle.
    pub(crate) fn quantise_angle(&self, rad: f64) -> Result<i64, OutOfRange> {
        if !rad.is_finite() {
            return self.quantise(rad);
        }
        let half = 1i64 << (self.bits - 1);
        let wrapped = rad - 2.0 * PI * (rad / (2.0 * PI)).round();
        let n = (wrapped / self.lsb_si()).round() as i64;
        // +pi rounds to +2^(bits-1), the same angle as -2^(bits-1).
        Ok(if n >= half { n - 2 * half } else { n })
    }
}

/// Append the `width` low bits of `value` to `bits`, most significant first (two's
/// complement for a negative value; a width above 64, such as I/NAV's 88 spare bits,
/// repeats the sign bit).
pub(crate) fn push_bits(bits: &mut Vec<u8>, value: i64, width: u32) {
    bits.extend((0..width).rev().map(|k| ((value >> k.min(63)) & 1) as u8));
}

/// The raw values of `fields` read in order from `bits` (bit 0 first, most significant
/// bit first; signed fields sign-extended).
pub(crate) fn read_fields<'a>(
    bits: &[u8],
    fields: impl IntoIterator<Item = &'a Field>,
) -> Vec<i64> {
    let mut pos = 0;
    fields
        .into_iter()
        .map(|f| {
            let w = f.bits as usize;
            let u = bits[pos..pos + w]
                .iter()
                .fold(0i64, |acc, &b| (acc << 1) | i64::from(b));
            pos += w;
            if f.signed && w > 0 && (u >> (w - 1)) & 1 == 1 {
                u - (1i64 << w)
            } else {
                u
            }
        })
        .collect()
}

/// Raw values by field name (the field names of one message family are unique; a field
/// repeated in several messages, such as a reference time, holds one value).
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Fields(Vec<(&'static str, i64)>);

impl Fields {
    /// The raw value of `f`, 0 when unset.
    pub(crate) fn get(&self, f: &Field) -> i64 {
        self.0
            .iter()
            .find(|(n, _)| *n == f.name)
            .map_or(0, |&(_, v)| v)
    }

    pub(crate) fn set(&mut self, f: &Field, v: i64) {
        match self.0.iter_mut().find(|(n, _)| *n == f.name) {
            Some(slot) => slot.1 = v,
            None => self.0.push((f.name, v)),
        }
    }

    /// The values of `fields`, unset (spare, reserved) ones 0.
    pub(crate) fn values_for<'a>(&self, fields: impl IntoIterator<Item = &'a Field>) -> Vec<i64> {
        fields.into_iter().map(|f| self.get(f)).collect()
    }

    /// Store the raw values `values` of `fields` (a received page or message).
    pub(crate) fn absorb(&mut self, fields: &[Field], values: &[i64]) {
        for (f, &v) in fields.iter().zip(values) {
            self.set(f, v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantisation_rounds_and_refuses_what_does_not_fit() {
        let f = field("x", 4, true, Lsb::Pow2(-1));
        assert_eq!(f.raw_range(), (-8, 7));
        assert_eq!(f.quantise(1.26), Ok(3));
        assert_eq!(f.quantise(-4.0), Ok(-8));
        let e = f.quantise(3.75).unwrap_err();
        assert_eq!((e.field, e.min, e.max), ("x", -4.0, 3.5));
        assert!(f.quantise(f64::NAN).is_err());
        let u = field("u", 3, false, Lsb::Count);
        assert_eq!((u.raw_range(), u.quantise(-1.0).is_err()), ((0, 7), true));
    }

    #[test]
    fn angles_wrap_onto_the_circle() {
        // 8 bits of 2^-7 semicircles: 256 steps per turn.
        let f = field("a", 8, true, Lsb::Semi(-7));
        assert_eq!(f.quantise_angle(PI), Ok(-128));
        assert_eq!(f.quantise_angle(3.0 * PI / 2.0), Ok(-64));
        assert_eq!(f.quantise_angle(-PI / 2.0), Ok(-64));
        assert!((f.si_value(64) - PI / 2.0).abs() < 1e-15);
    }

    #[test]
    fn bits_read_back_as_written() {
        let fields = [
            field("s", 5, true, Lsb::Count),
            field("u", 3, false, Lsb::Count),
            field("n", 4, true, Lsb::Count),
        ];
        let mut bits = Vec::new();
        for (f, v) in fields.iter().zip([-7i64, 5, 7]) {
            push_bits(&mut bits, v, f.bits);
        }
        // -7 in 5 bits is 11001; 5 in 3 bits 101; 7 in 4 bits 0111.
        assert_eq!(bits, [1, 1, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1]);
        assert_eq!(read_fields(&bits, &fields), [-7, 5, 7]);
    }

    #[test]
    fn fields_hold_one_value_per_name() {
        let (a, b) = (
            field("a", 4, false, Lsb::Count),
            field("b", 4, false, Lsb::Count),
        );
        let mut v = Fields::default();
        v.absorb(&[a, b], &[3, 5]);
        v.set(&a, 9);
        assert_eq!(
            v.values_for(&[b, a, field("c", 1, false, Lsb::Count)]),
            [5, 9, 0]
        );
    }
}
