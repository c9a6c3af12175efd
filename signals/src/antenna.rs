//! Antennas on the platform: lever arm, true-minus-nominal geometry offset, boresight,
//! field of view, elevation mask, phase-centre offset/variation and gain pattern (carried
//! as data for the signal stage).

use skyforge_gnss::antenna_name::check_antenna_name;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::check::{Allowed, Invalid};

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
    /// `[[antennas.phase_centres]]`: the phase centre of named signals (ANTEX gives one per
    /// frequency), replacing `pco_m` and `pcv_m` for them.
    #[serde(default)]
    pub phase_centres: Vec<SignalPhaseCentreConfig>,
}

/// `[[antennas.phase_centres]]`: one signal's phase-centre offset and variation.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SignalPhaseCentreConfig {
    pub signal: Signal,
    /// Phase-centre offset in the antenna frame (m).
    #[serde(default)]
    pub pco_m: [f64; 3],
    /// Phase-centre variation (m) over the antenna frame.
    #[serde(default)]
    pub pcv_m: Option<AntennaGrid>,
}

/// A phase centre: offset and variation.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseCentre {
    pub pco_m: Vec3,
    pub pcv_m: Option<AntennaGrid>,
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
    /// The phase centres of signals whose own differs from `pco_m` and `pcv_m`.
    pub phase_centres: Vec<(Signal, PhaseCentre)>,
}

impl AntennaConfig {
    /// Checks: finite numbers, non-zero boresight, FOV in (0, 180], mask in [-90, 90],
    /// grids rectangular and sorted.
    ///
    /// Field paths are relative to the `[[antennas]]` entry (`boresight_body`,
    /// `position_body_m[2]`, `pcv_m.values`, ...).
    pub fn check(&self) -> Result<(), Invalid> {
        if let Err(rule) = check_antenna_name(&self.name) {
            return Err(Invalid::new("name", format!("{:?}", self.name), rule));
        }
        check_vec3("position_body_m", &self.position_body_m, LEVER_ARM_M)?;
        check_vec3("offset_body_m", &self.offset_body_m, OFFSET_M)?;
        check_vec3("boresight_body", &self.boresight_body, BORESIGHT)?;
        check_vec3("pco_m", &self.pco_m, PCO_M)?;
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
            grid.check(PCV_M).map_err(|e| e.within("pcv_m"))?;
        }
        if let Some(grid) = &self.gain_dbi {
            grid.check(GAIN_DBI).map_err(|e| e.within("gain_dbi"))?;
        }
        for (i, pc) in self.phase_centres.iter().enumerate() {
            let within = |e: Invalid| e.within(&format!("phase_centres[{i}]"));
            if self.phase_centres[..i]
                .iter()
                .any(|o| o.signal == pc.signal)
            {
                return Err(within(Invalid::new(
                    "signal",
                    pc.signal.tag(),
                    "is given twice (one phase centre per signal)",
                )));
            }
            check_vec3("pco_m", &pc.pco_m, PCO_M).map_err(within)?;
            if let Some(grid) = &pc.pcv_m {
                grid.check(PCV_M).map_err(|e| within(e.within("pcv_m")))?;
            }
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
            phase_centres: (self.phase_centres.iter())
                .map(|pc| {
                    let centre = PhaseCentre {
                        pco_m: Vec3::from(pc.pco_m),
                        pcv_m: pc.pcv_m.clone(),
                    };
                    (pc.signal, centre)
                })
                .collect(),
        }
    }
}

/// Shortest boresight vector accepted before normalisation (dimensionless).
const MIN_BORESIGHT_NORM: f64 = 1e-9;

impl AntennaGrid {
    /// Checks: both axes non-empty, finite and strictly increasing, zenith in [0, 180],
    /// azimuth in [0, 360], `values` in `allowed` with `zenith x azimuth` entries.
    pub fn check(&self, allowed: Allowed) -> Result<(), Invalid> {
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
        for (i, v) in self.values.iter().enumerate() {
            allowed.check(&format!("values[{i}]"), *v)?;
        }
        Ok(())
    }
}

impl AntennaGrid {
    /// Bilinear interpolation at (`zenith_deg`, `azimuth_deg`) (call after [`Self::check`]).
    ///
    /// - Zenith: clamped to the first and last rows.
    /// - Azimuth: taken modulo 360, then periodic when the axis covers the circle, i.e. when
    ///   the wrap gap `azimuth[0] + 360 - azimuth[last]` is no wider than the widest step of
    ///   the axis (ANTEX `0:5:360`, or `0:5:355`): across the gap the values of the last and
    ///   first columns are blended. Otherwise (a sector grid) the azimuth is clamped to the
    ///   axis ends.
    /// - A single row or column means the value is constant along that axis (ANTEX NOAZI).
    pub fn value_at(&self, zenith_deg: f64, azimuth_deg: f64) -> f64 {
        let n_az = self.azimuth_deg.len();
        let (i0, i1, wz) = clamped_bracket(&self.zenith_deg, zenith_deg);
        let (j0, j1, wa) = self.azimuth_bracket(azimuth_deg);
        let at = |i: usize, j: usize| self.values.get(i * n_az + j).copied().unwrap_or(f64::NAN);
        let row0 = at(i0, j0) * (1.0 - wa) + at(i0, j1) * wa;
        let row1 = at(i1, j0) * (1.0 - wa) + at(i1, j1) * wa;
        row0 * (1.0 - wz) + row1 * wz
    }

    /// Neighbouring azimuth columns and the weight of the second (rules in [`Self::value_at`]).
    fn azimuth_bracket(&self, azimuth_deg: f64) -> (usize, usize, f64) {
        let axis = &self.azimuth_deg;
        let (Some(&first), Some(&last)) = (axis.first(), axis.last()) else {
            return (0, 0, 0.0);
        };
        if axis.len() < 2 {
            return (0, 0, 0.0);
        }
        let widest_step = axis.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
        let wrap_gap = first + 360.0 - last;
        if wrap_gap > widest_step {
            return clamped_bracket(axis, azimuth_deg.rem_euclid(360.0));
        }
        // Periodic: express the azimuth in [first, first + 360).
        let az = first + (azimuth_deg - first).rem_euclid(360.0);
        if az > last {
            let w = if wrap_gap > 0.0 {
                (az - last) / wrap_gap
            } else {
                0.0
            };
            return (axis.len() - 1, 0, w.clamp(0.0, 1.0));
        }
        clamped_bracket(axis, az)
    }
}

/// The delay of [`Antenna::phase_centre_delay_m`] for offset `pco_m` and variation `pcv_m`.
fn centre_delay_m(pco_m: &Vec3, pcv_m: Option<&AntennaGrid>, az_rad: f64, el_rad: f64) -> f64 {
    let (sin_el, cos_el) = el_rad.sin_cos();
    let (sin_az, cos_az) = az_rad.sin_cos();
    let u = Vec3::new(cos_el * cos_az, cos_el * sin_az, sin_el);
    let pcv_m = pcv_m.map_or(0.0, |grid| {
        grid.value_at(90.0 - el_rad.to_degrees(), az_rad.to_degrees())
    });
    -pco_m.dot(&u) + pcv_m
}

/// Indices `(k0, k1)` of the axis entries around `x` and the weight of `k1`; `x` outside the
/// axis is clamped to its ends.
fn clamped_bracket(axis: &[f64], x: f64) -> (usize, usize, f64) {
    let n = axis.len();
    match (axis.first(), axis.last()) {
        (Some(&first), Some(&last)) if n >= 2 && x > first => {
            if x >= last {
                return (n - 1, n - 1, 0.0);
            }
            // First entry strictly above x; 1 <= k1 <= n - 1 here.
            let k1 = axis.partition_point(|&a| a <= x).clamp(1, n - 1);
            let (a0, a1) = (axis[k1 - 1], axis[k1]);
            (k1 - 1, k1, (x - a0) / (a1 - a0))
        }
        _ => (0, 0, 0.0),
    }
}

impl Antenna {
    /// Carrier and code delay (m) of `signal` caused by its phase-centre offset and
    /// variation ([`Self::phase_centres`], else `pco_m` and `pcv_m`) for a line of sight at
    /// antenna-frame azimuth `az_rad` (from X towards Y) and elevation `el_rad` (above the XY
    /// plane, Z = boresight): `-pco . u + pcv(90 deg - el, az)` with
    /// `u = (cos el cos az, cos el sin az, sin el)`.
    ///
    /// ANTEX 1.4 convention (with X, Y, Z read as North, East, Up): the offset is the vector
    /// from the reference point to the mean phase centre, so an offset towards the satellite
    /// shortens the path; the variation is added to the range measured to the mean phase
    /// centre. Positive result = longer apparent range. The same value applies to code and
    /// carrier (no separate group-delay pattern is modelled).
    pub fn phase_centre_delay_m(&self, signal: Signal, az_rad: f64, el_rad: f64) -> f64 {
        match self.phase_centres.iter().find(|(s, _)| *s == signal) {
            Some((_, centre)) => {
                centre_delay_m(&centre.pco_m, centre.pcv_m.as_ref(), az_rad, el_rad)
            }
            None => centre_delay_m(&self.pco_m, self.pcv_m.as_ref(), az_rad, el_rad),
        }
    }

    /// Gain (dBi) towards antenna-frame azimuth `az_rad` and elevation `el_rad` (angles as
    /// in [`Self::phase_centre_delay_m`]): the pattern interpolated at zenith
    /// `90 deg - el`, or 0 dBi without a pattern.
    pub fn gain_dbi_at(&self, az_rad: f64, el_rad: f64) -> f64 {
        self.gain_dbi.as_ref().map_or(0.0, |grid| {
            grid.value_at(90.0 - el_rad.to_degrees(), az_rad.to_degrees())
        })
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

/// Lever-arm components (m): assumed up to 10 km, beyond the largest platform (a ship of
/// 400 m) and the reference stations of one lab placed as antennas of one site (hundreds
/// of metres apart).
const LEVER_ARM_M: Allowed = Allowed::closed(-10e3, 10e3, "m");
/// Components of the true position's offset from the nominal one (m): assumed up to
/// 100 m (a geometry error of centimetres is what the thesis estimates).
const OFFSET_M: Allowed = Allowed::closed(-100.0, 100.0, "m");
/// Boresight components: any length (it is normalised) short of overflowing its norm.
const BORESIGHT: Allowed = Allowed::closed(-1e6, 1e6, "");
/// Phase-centre offset components (m): assumed up to 1 m (real antennas: centimetres).
const PCO_M: Allowed = Allowed::closed(-1.0, 1.0, "m");
/// Phase-centre variations (m): as the offset, up to 1 m (real antennas: millimetres).
const PCV_M: Allowed = PCO_M;
/// Gain pattern (dBi): assumed from -100 dBi (no signal) to 30 dBi (a dish).
const GAIN_DBI: Allowed = Allowed::closed(-100.0, 30.0, "dBi");

/// Every component in `allowed`; the failing component is named `field[i]`.
fn check_vec3(field: &str, v: &[f64; 3], allowed: Allowed) -> Result<(), Invalid> {
    for (i, x) in v.iter().enumerate() {
        allowed.check(&format!("{field}[{i}]"), *x)?;
    }
    Ok(())
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
            phase_centres: Vec::new(),
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

    /// A 3 x 4 grid whose value at (zenith z, azimuth a) is `1 + 0.01 z + 0.001 a +
    /// 1e-5 z a`: bilinear in (z, a), so bilinear interpolation must reproduce it exactly.
    fn bilinear_grid() -> AntennaGrid {
        let zenith_deg = vec![0.0, 30.0, 90.0];
        let azimuth_deg = vec![0.0, 90.0, 200.0, 360.0];
        let values = zenith_deg
            .iter()
            .flat_map(|&z| azimuth_deg.iter().map(move |&a| bilinear(z, a)))
            .collect();
        AntennaGrid {
            zenith_deg,
            azimuth_deg,
            values,
        }
    }

    fn bilinear(z: f64, a: f64) -> f64 {
        1.0 + 0.01 * z + 0.001 * a + 1e-5 * z * a
    }

    #[test]
    fn grid_is_exact_at_nodes_and_linear_along_edges() {
        let g = bilinear_grid();
        assert_eq!(g.check(GAIN_DBI), Ok(()));
        for &z in &g.zenith_deg {
            for &a in &g.azimuth_deg[..3] {
                assert!((g.value_at(z, a) - bilinear(z, a)).abs() < 1e-12, "{z} {a}");
            }
        }
        // Along the zenith edge at azimuth 90 and the azimuth edge at zenith 90.
        for (z, a) in [
            (15.0, 90.0),
            (60.0, 90.0),
            (90.0, 45.0),
            (90.0, 280.0),
            (0.0, 359.0),
        ] {
            assert!((g.value_at(z, a) - bilinear(z, a)).abs() < 1e-12, "{z} {a}");
        }
        // Zenith clamped beyond the last row (a LEO antenna sees below its horizon).
        assert!((g.value_at(120.0, 90.0) - bilinear(90.0, 90.0)).abs() < 1e-12);
        assert!((g.value_at(-5.0, 90.0) - bilinear(0.0, 90.0)).abs() < 1e-12);
    }

    #[test]
    fn azimuth_wraps_when_the_axis_covers_the_circle() {
        // 0..350 step 10 (no 360 column): the gap 350 -> 360 is one step, so it wraps.
        // Column j holds 10 j; row values differ by 1000 so rows cannot be confused.
        let azimuth_deg: Vec<f64> = (0..36).map(|j| 10.0 * f64::from(j)).collect();
        let values = [0.0, 1000.0]
            .iter()
            .flat_map(|&row| azimuth_deg.iter().map(move |&a| row + a))
            .collect();
        let g = AntennaGrid {
            zenith_deg: vec![0.0, 90.0],
            azimuth_deg,
            values,
        };
        assert_eq!(g.check(Allowed::closed(0.0, 1350.0, "")), Ok(()));
        // 359 deg: 0.9 of the way from the 350 column (350) to the 0 column (0): 35.
        assert!((g.value_at(0.0, 359.0) - 35.0).abs() < 1e-9);
        assert!((g.value_at(0.0, 355.0) - 175.0).abs() < 1e-9);
        // -1 deg is 359 deg; 360 is 0; 725 is 5.
        assert!((g.value_at(0.0, -1.0) - 35.0).abs() < 1e-9);
        assert!(g.value_at(0.0, 360.0).abs() < 1e-9);
        assert!((g.value_at(0.0, 725.0) - 5.0).abs() < 1e-9);
        // Second row, half-way in zenith.
        assert!((g.value_at(45.0, 359.0) - 535.0).abs() < 1e-9);
    }

    #[test]
    fn sector_grid_clamps_and_single_axis_is_constant() {
        let sector = AntennaGrid {
            zenith_deg: vec![0.0, 90.0],
            azimuth_deg: vec![0.0, 45.0, 90.0],
            values: vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
        };
        assert_eq!(sector.check(GAIN_DBI), Ok(()));
        assert!((sector.value_at(0.0, 180.0) - 3.0).abs() < 1e-12);
        assert!((sector.value_at(90.0, 300.0) - 6.0).abs() < 1e-12);
        assert!((sector.value_at(45.0, 22.5) - 3.0).abs() < 1e-12);
        // ANTEX NOAZI: one azimuth column.
        let noazi = AntennaGrid {
            zenith_deg: vec![0.0, 10.0, 20.0],
            azimuth_deg: vec![0.0],
            values: vec![0.0, -1.0, -4.0],
        };
        for az in [0.0, 90.0, 359.0] {
            assert!((noazi.value_at(15.0, az) + 2.5).abs() < 1e-12);
        }
        // One zenith row: constant in zenith.
        let one_row = AntennaGrid {
            zenith_deg: vec![30.0],
            azimuth_deg: vec![0.0, 180.0],
            values: vec![2.0, 4.0],
        };
        assert!((one_row.value_at(80.0, 90.0) - 3.0).abs() < 1e-12);
    }

    #[test]
    fn phase_centre_delay_and_gain_by_hand() {
        let mut a = antenna().resolve();
        a.pco_m = Vec3::new(0.02, -0.01, 0.1);
        // Boresight: u = Z, delay = -pco_z.
        let zenith = a.phase_centre_delay_m(L1, 0.0, std::f64::consts::FRAC_PI_2);
        assert!((zenith + 0.1).abs() < 1e-15);
        // Horizon towards +Y (az 90 deg): u = Y, delay = -pco_y = +0.01.
        let east = a.phase_centre_delay_m(L1, std::f64::consts::FRAC_PI_2, 0.0);
        assert!((east - 0.01).abs() < 1e-15);
        // 30 deg elevation at az 0: u = (cos 30, 0, sin 30): -(0.02 * 0.866.. + 0.05).
        let el = 30f64.to_radians();
        let expected = -(0.02 * 3f64.sqrt() / 2.0 + 0.1 * 0.5);
        assert!((a.phase_centre_delay_m(L1, 0.0, el) - expected).abs() < 1e-15);
        assert_eq!(a.gain_dbi_at(0.0, el), 0.0);
        // With a PCV grid (zenith 60 deg = elevation 30 deg) and a gain pattern.
        a.pcv_m = Some(AntennaGrid {
            zenith_deg: vec![0.0, 90.0],
            azimuth_deg: vec![0.0],
            values: vec![0.0, 0.009],
        });
        a.gain_dbi = Some(AntennaGrid {
            zenith_deg: vec![0.0, 90.0],
            azimuth_deg: vec![0.0],
            values: vec![3.0, -3.0],
        });
        assert!((a.phase_centre_delay_m(L1, 0.0, el) - (expected + 0.006)).abs() < 1e-15);
        assert!((a.gain_dbi_at(1.0, el) - (-1.0)).abs() < 1e-12);
    }

    const L1: Signal = Signal::GpsL1Ca;

    /// A signal with a phase centre of its own ranges to it; the others to the antenna's.
    #[test]
    fn a_signal_with_its_own_phase_centre_ranges_to_it() {
        let mut config = antenna();
        config.phase_centres = vec![SignalPhaseCentreConfig {
            signal: Signal::GpsL5,
            pco_m: [0.0, 0.0, 0.12],
            pcv_m: Some(AntennaGrid {
                zenith_deg: vec![0.0, 90.0],
                azimuth_deg: vec![0.0],
                values: vec![0.0, 0.003],
            }),
        }];
        config.check().unwrap();
        let a = config.resolve();
        let zenith = std::f64::consts::FRAC_PI_2;
        assert!((a.phase_centre_delay_m(L1, 0.0, zenith) + 0.1).abs() < 1e-15);
        assert!((a.phase_centre_delay_m(Signal::GpsL5, 0.0, zenith) + 0.12).abs() < 1e-15);
        // 30 deg elevation: -0.12 x sin 30 deg, plus the grid's 0.002 at zenith 60 deg.
        let el = 30f64.to_radians();
        let l5 = a.phase_centre_delay_m(Signal::GpsL5, 0.0, el);
        assert!((l5 - (-0.06 + 0.002)).abs() < 1e-15, "{l5}");

        let twice = AntennaConfig {
            phase_centres: vec![config.phase_centres[0].clone(); 2],
            ..antenna()
        };
        let e = twice.check().unwrap_err().to_string();
        assert!(
            e.contains("phase_centres[1].signal") && e.contains("given twice"),
            "{e}"
        );
        let mut far = config.clone();
        far.phase_centres[0].pco_m = [0.0, 0.0, f64::NAN];
        let e = far.check().unwrap_err().to_string();
        assert!(e.contains("phase_centres[0].pco_m"), "{e}");
    }

    proptest::proptest! {
        /// Bilinear data is reproduced exactly anywhere inside the grid.
        #[test]
        fn bilinear_data_is_reproduced(z in 0.0..90.0f64, a in 0.0..360.0f64) {
            let g = bilinear_grid();
            proptest::prop_assert!((g.value_at(z, a) - bilinear(z, a)).abs() < 1e-9);
        }
    }
}
