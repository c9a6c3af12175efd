//! Configuration checks shared by every domain crate: one invalid field, its path, its
//! value and what is allowed. `scenarios` prefixes the path and adds file/line/column.

/// One invalid configuration value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} = {value}: {allowed}")]
pub struct Invalid {
    /// Dotted field path relative to the table the check ran on, e.g. `forces.mass_kg`.
    pub field: String,
    /// The offending value as the user wrote it (or as parsed).
    pub value: String,
    /// What is allowed, phrased for the user, e.g. "must be > 0".
    pub allowed: String,
}

impl Invalid {
    /// A new invalid-field report.
    pub fn new(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Self {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The same report with `prefix` put in front of the field path.
    pub fn within(mut self, prefix: &str) -> Self {
        if !prefix.is_empty() {
            self.field = if self.field.is_empty() {
                prefix.to_string()
            } else {
                format!("{prefix}.{}", self.field)
            };
        }
        self
    }
}

/// The interval a configuration value must lie in, with its unit: closed `[lo, hi]`, or
/// open below `(lo, hi]` where the lower end itself makes no sense (a rate or a spacing
/// of 0). One table of these per configuration keeps every bound in one place, as
/// docs/limits.md lists them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Allowed {
    pub lo: f64,
    pub hi: f64,
    /// `lo` itself is outside.
    pub lo_open: bool,
    /// The unit as the user reads it after the interval ("m", "Hz", "" for none).
    pub unit: &'static str,
}

impl Allowed {
    /// `[lo, hi]`.
    pub const fn closed(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self {
            lo,
            hi,
            lo_open: false,
            unit,
        }
    }

    /// `(lo, hi]`.
    pub const fn above(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self {
            lo,
            hi,
            lo_open: true,
            unit,
        }
    }

    /// Whether `value` lies inside (NaN never does).
    pub fn contains(&self, value: f64) -> bool {
        let above_lo = if self.lo_open {
            value > self.lo
        } else {
            value >= self.lo
        };
        above_lo && value <= self.hi
    }

    /// `value` of `field` inside, or the report naming both and the interval.
    pub fn check(&self, field: &str, value: f64) -> Result<(), Invalid> {
        if self.contains(value) {
            Ok(())
        } else {
            Err(Invalid::new(
                field,
                shown(value),
                format!("must be in {self}"),
            ))
        }
    }
}

/// Radii (m from the Earth's centre) of a receiver SkyForge simulates or is told about:
/// from 1.75 km below the WGS-84 polar radius (6 356 752 m; the lowest dry land is 430 m
/// below sea level) to the highest orbit apogee SkyForge propagates (100 000 km); deep
/// space is not supported.
pub const NEAR_EARTH_RADIUS_M: Allowed =
    Allowed::closed(6_355_000.0, 100_000e3, "m from the Earth's centre");

/// Radii (m) of a point on the ground (a site, a reference station, a common point): the
/// WGS-84 polar and equatorial radii widened by -1 km and +100 km (up to the Karman line).
pub const GROUND_RADIUS_M: Allowed =
    Allowed::closed(6_355_000.0, 6_480_000.0, "m from the Earth's centre");

/// An ECEF position (m) of `field`: finite, at a radius in `allowed`.
pub fn check_position(field: &str, ecef_m: &[f64; 3], allowed: Allowed) -> Result<(), Invalid> {
    if let Some(i) = ecef_m.iter().position(|x| !x.is_finite()) {
        return Err(Invalid::new(
            format!("{field}[{i}]"),
            ecef_m[i],
            "must be a finite number",
        ));
    }
    let radius = ecef_m.iter().map(|x| x * x).sum::<f64>().sqrt();
    if allowed.contains(radius) {
        return Ok(());
    }
    let [x, y, z] = ecef_m.map(shown);
    Err(Invalid::new(
        field,
        format!("[{x}, {y}, {z}] (radius {} m)", shown(radius)),
        format!("must lie at a radius in {allowed}"),
    ))
}

/// A number as people read it: plain, or in exponent form when very large or small
/// (`1e300`, not its 301 digits).
pub fn shown(value: f64) -> String {
    let a = value.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e7).contains(&a) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

/// Every `(field, value, allowed)` row checked in order; the first value outside its
/// interval is the error.
pub fn check_table(rows: &[(&str, f64, Allowed)]) -> Result<(), Invalid> {
    rows.iter()
        .try_for_each(|(field, value, allowed)| allowed.check(field, *value))
}

impl std::fmt::Display for Allowed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let open = if self.lo_open { '(' } else { '[' };
        write!(f, "{open}{}, {}]", shown(self.lo), shown(self.hi))?;
        if !self.unit.is_empty() {
            write!(f, " {}", self.unit)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_interval_refuses_what_lies_outside_with_field_value_and_bounds() {
        let spacing = Allowed::above(0.0, 2.0, "chips");
        assert!(spacing.check("d", 2.0).is_ok());
        let e = spacing.check("d", 0.0).unwrap_err();
        assert_eq!(e.to_string(), "d = 0: must be in (0, 2] chips");
        assert!(spacing.check("d", f64::NAN).is_err());
        let height = Allowed::closed(-1000.0, 1e5, "m");
        assert!(height.contains(-1000.0) && !height.contains(1e5 + 1.0));
        assert_eq!(Allowed::above(1e-9, 0.5, "").to_string(), "(1e-9, 0.5]");
        assert_eq!(
            Allowed::closed(0.0, 1.0, "")
                .check("p", 1e300)
                .unwrap_err()
                .to_string(),
            "p = 1e300: must be in [0, 1]"
        );
    }
}
