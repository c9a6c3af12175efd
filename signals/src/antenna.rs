//! Antennas on the platform: lever arm, true-minus-nominal geometry offset, boresight,
//! field of view, elevation mask, phase-centre offset/variation and gain pattern (carried
//! as data for the signal stage).

use skyforge_orbits::Vec3;
use skyforge_orbits::check::Invalid;

/// A phase-centre-variation or gain grid over the antenna frame: values at
/// `zenith_deg[i]` x `azimuth_deg[j]`, row-major (`values[i * azimuth.len() + j]`).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntennaGrid {
    pub zenith_deg: Vec<f64>,
    pub azimuth_deg: Vec<f64>,
    pub values: Vec<f64>,
}

/// `[[antennas]]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AntennaConfig {
    /// Unique name, used in output paths.
    pub name: String,
    /// Nominal phase-centre reference point in the body frame, from the centre of mass (m):
    /// what the receiver is told.
    pub position_body_m: [f64; 3],
    /// True minus nominal position (m), body frame (thesis chapter 4 geometry offsets).
    #[serde(default)]
    pub offset_body_m: [f64; 3],
    /// Boresight in the body frame (default -Zb: away from the Earth for an earth-pointing LEO,
    /// up for a ground platform whose body frame is NED).
    #[serde(default = "default_boresight")]
    pub boresight_body: [f64; 3],
    /// Field-of-view half-angle about the boresight (deg).
    #[serde(default = "default_fov")]
    pub fov_half_angle_deg: f64,
    /// Elevation mask above the local horizon (deg); -90 disables it.
    #[serde(default = "default_mask")]
    pub elevation_mask_deg: f64,
    /// Phase-centre offset in the antenna frame (m).
    #[serde(default)]
    pub pco_m: [f64; 3],
    /// Phase-centre variation (m) over the antenna frame.
    #[serde(default)]
    pub pcv_m: Option<AntennaGrid>,
    /// Gain pattern (dBi) over the antenna frame.
    #[serde(default)]
    pub gain_dbi: Option<AntennaGrid>,
}

fn default_boresight() -> [f64; 3] {
    [0.0, 0.0, -1.0]
}
fn default_fov() -> f64 {
    90.0
}
fn default_mask() -> f64 {
    -90.0
}

/// A resolved antenna.
#[derive(Debug, Clone, PartialEq)]
pub struct Antenna {
    pub name: String,
    /// Nominal lever arm (body, m).
    pub nominal_body_m: Vec3,
    /// True lever arm = nominal + offset (body, m).
    pub true_body_m: Vec3,
    /// Unit boresight (body).
    pub boresight_body: Vec3,
    pub fov_half_angle_rad: f64,
    pub elevation_mask_rad: f64,
    pub pco_m: Vec3,
    pub pcv_m: Option<AntennaGrid>,
    pub gain_dbi: Option<AntennaGrid>,
}

impl AntennaConfig {
    /// Checks: finite numbers, non-zero boresight, FOV in (0, 180], mask in [-90, 90],
    /// grids rectangular and sorted.
    ///
    /// Field paths are relative to the `[[antennas]]` entry (`boresight_body`,
    /// `position_body_m[2]`, `pcv_m.values`, ...).
    pub fn check(&self) -> Result<(), Invalid> {
        if self.name.trim().is_empty() {
            return Err(Invalid::new(
                "name",
                format!("{:?}", self.name),
                "must be a non-empty name",
            ));
        }
        check_finite3("position_body_m", &self.position_body_m)?;
        check_finite3("offset_body_m", &self.offset_body_m)?;
        check_finite3("boresight_body", &self.boresight_body)?;
        check_finite3("pco_m", &self.pco_m)?;
        let boresight_norm = Vec3::from(self.boresight_body).norm();
        if boresight_norm < MIN_BORESIGHT_NORM {
            return Err(Invalid::new(
                "boresight_body",
                format_vec3(&self.boresight_body),
                "must be a non-zero direction (any length; it is normalised)",
            ));
        }
        let fov = self.fov_half_angle_deg;
        if !(fov > 0.0 && fov <= 180.0) {
            return Err(Invalid::new(
                "fov_half_angle_deg",
                fov,
                "must be in (0, 180] degrees",
            ));
        }
        let mask = self.elevation_mask_deg;
        if !(-90.0..=90.0).contains(&mask) {
            return Err(Invalid::new(
                "elevation_mask_deg",
                mask,
                "must be in [-90, 90] degrees (-90 disables the mask)",
            ));
        }
        if let Some(grid) = &self.pcv_m {
            grid.check().map_err(|e| e.within("pcv_m"))?;
        }
        if let Some(grid) = &self.gain_dbi {
            grid.check().map_err(|e| e.within("gain_dbi"))?;
        }
        Ok(())
    }

    /// The resolved antenna (call after `check`): the true lever arm is the nominal one
    /// plus the offset, the boresight is normalised, angles are converted to radians.
    pub fn resolve(&self) -> Antenna {
        let nominal_body_m = Vec3::from(self.position_body_m);
        Antenna {
            name: self.name.clone(),
            nominal_body_m,
            true_body_m: nominal_body_m + Vec3::from(self.offset_body_m),
            boresight_body: Vec3::from(self.boresight_body).normalize(),
            fov_half_angle_rad: self.fov_half_angle_deg.to_radians(),
            elevation_mask_rad: self.elevation_mask_deg.to_radians(),
            pco_m: Vec3::from(self.pco_m),
            pcv_m: self.pcv_m.clone(),
            gain_dbi: self.gain_dbi.clone(),
        }
    }
}

/// Shortest boresight vector accepted before normalisation (dimensionless).
const MIN_BORESIGHT_NORM: f64 = 1e-9;

impl AntennaGrid {
    /// Checks: both axes non-empty, finite and strictly increasing, zenith in [0, 180],
    /// azimuth in [0, 360], `values` finite with `zenith x azimuth` entries.
    pub fn check(&self) -> Result<(), Invalid> {
        check_axis("zenith_deg", &self.zenith_deg, 180.0)?;
        check_axis("azimuth_deg", &self.azimuth_deg, 360.0)?;
        let expected = self.zenith_deg.len() * self.azimuth_deg.len();
        if self.values.len() != expected {
            return Err(Invalid::new(
                "values",
                format!("{} entries", self.values.len()),
                format!(
                    "must hold zenith_deg x azimuth_deg = {} x {} = {expected} entries, row-major",
                    self.zenith_deg.len(),
                    self.azimuth_deg.len()
                ),
            ));
        }
        if let Some(i) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(Invalid::new(
                format!("values[{i}]"),
                self.values[i],
                "must be a finite number",
            ));
        }
        Ok(())
    }
}

/// A grid axis: non-empty, finite, strictly increasing, within `[0, max_deg]`.
fn check_axis(field: &str, axis: &[f64], max_deg: f64) -> Result<(), Invalid> {
    if axis.is_empty() {
        return Err(Invalid::new(field, "[]", "must list at least one angle"));
    }
    for (i, &angle) in axis.iter().enumerate() {
        if !(0.0..=max_deg).contains(&angle) {
            return Err(Invalid::new(
                format!("{field}[{i}]"),
                angle,
                format!("must be in [0, {max_deg}] degrees"),
            ));
        }
        if i > 0 && angle <= axis[i - 1] {
            return Err(Invalid::new(
                format!("{field}[{i}]"),
                angle,
                format!("must be greater than the previous entry ({})", axis[i - 1]),
            ));
        }
    }
    Ok(())
}

/// Every component finite; the failing component is named `field[i]`.
fn check_finite3(field: &str, v: &[f64; 3]) -> Result<(), Invalid> {
    match v.iter().position(|x| !x.is_finite()) {
        Some(i) => Err(Invalid::new(
            format!("{field}[{i}]"),
            v[i],
            "must be a finite number",
        )),
        None => Ok(()),
    }
}

fn format_vec3(v: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn antenna() -> AntennaConfig {
        AntennaConfig {
            name: "ant1".into(),
            position_body_m: [1.0, 0.0, 0.0],
            offset_body_m: [0.0, 0.005, 0.0],
            boresight_body: [0.0, 0.0, -2.0],
            fov_half_angle_deg: 80.0,
            elevation_mask_deg: 5.0,
            pco_m: [0.0, 0.0, 0.1],
            pcv_m: None,
            gain_dbi: None,
        }
    }

    fn grid() -> AntennaGrid {
        AntennaGrid {
            zenith_deg: vec![0.0, 45.0, 90.0],
            azimuth_deg: vec![0.0, 180.0],
            values: vec![0.0; 6],
        }
    }

    #[test]
    fn valid_antenna_resolves_to_si() {
        let a = antenna();
        assert_eq!(a.check(), Ok(()));
        let r = a.resolve();
        assert_eq!(r.nominal_body_m, Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(r.true_body_m, Vec3::new(1.0, 0.005, 0.0));
        assert_eq!(r.boresight_body, Vec3::new(0.0, 0.0, -1.0));
        assert!((r.fov_half_angle_rad - 80f64.to_radians()).abs() < 1e-15);
        assert!((r.elevation_mask_rad - std::f64::consts::PI / 36.0).abs() < 1e-15);
        assert_eq!(r.pco_m, Vec3::new(0.0, 0.0, 0.1));
    }

    #[test]
    fn rejects_bad_values_with_field_paths() {
        let cases: Vec<(AntennaConfig, &str)> = vec![
            (
                AntennaConfig {
                    name: " ".into(),
                    ..antenna()
                },
                "name",
            ),
            (
                AntennaConfig {
                    boresight_body: [0.0; 3],
                    ..antenna()
                },
                "boresight_body",
            ),
            (
                AntennaConfig {
                    position_body_m: [0.0, f64::NAN, 0.0],
                    ..antenna()
                },
                "position_body_m[1]",
            ),
            (
                AntennaConfig {
                    offset_body_m: [f64::INFINITY, 0.0, 0.0],
                    ..antenna()
                },
                "offset_body_m[0]",
            ),
            (
                AntennaConfig {
                    fov_half_angle_deg: 0.0,
                    ..antenna()
                },
                "fov_half_angle_deg",
            ),
            (
                AntennaConfig {
                    fov_half_angle_deg: f64::NAN,
                    ..antenna()
                },
                "fov_half_angle_deg",
            ),
            (
                AntennaConfig {
                    fov_half_angle_deg: 180.5,
                    ..antenna()
                },
                "fov_half_angle_deg",
            ),
            (
                AntennaConfig {
                    elevation_mask_deg: -91.0,
                    ..antenna()
                },
                "elevation_mask_deg",
            ),
        ];
        for (config, field) in cases {
            let err = config.check().expect_err(field);
            assert_eq!(err.field, field);
        }
        let full_sphere = AntennaConfig {
            fov_half_angle_deg: 180.0,
            elevation_mask_deg: -90.0,
            ..antenna()
        };
        assert_eq!(full_sphere.check(), Ok(()));
    }

    #[test]
    fn rejects_bad_grids() {
        let ok = AntennaConfig {
            pcv_m: Some(grid()),
            gain_dbi: Some(grid()),
            ..antenna()
        };
        assert_eq!(ok.check(), Ok(()));
        let cases: Vec<(AntennaGrid, &str)> = vec![
            (
                AntennaGrid {
                    values: vec![0.0; 5],
                    ..grid()
                },
                "pcv_m.values",
            ),
            (
                AntennaGrid {
                    zenith_deg: vec![0.0, 90.0, 45.0],
                    ..grid()
                },
                "pcv_m.zenith_deg[2]",
            ),
            (
                AntennaGrid {
                    azimuth_deg: vec![0.0, 361.0],
                    ..grid()
                },
                "pcv_m.azimuth_deg[1]",
            ),
            (
                AntennaGrid {
                    azimuth_deg: vec![],
                    values: vec![],
                    ..grid()
                },
                "pcv_m.azimuth_deg",
            ),
            (
                AntennaGrid {
                    values: vec![0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0],
                    ..grid()
                },
                "pcv_m.values[2]",
            ),
        ];
        for (bad, field) in cases {
            let config = AntennaConfig {
                pcv_m: Some(bad),
                ..antenna()
            };
            assert_eq!(config.check().expect_err(field).field, field);
        }
    }
}
