//! `[platform.leo]` configuration: initial state, force model, integrator.

use crate::Vec3;
use crate::check::{Allowed, Invalid};
use crate::constants::{GM_GPS, OMEGA_E_GPS, WGS84_A_M};

/// `[platform.leo]`: exactly one of `elements`, `tle`, `state` gives the initial state.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LeoConfig {
    #[serde(default)]
    pub elements: Option<KeplerianElementsConfig>,
    #[serde(default)]
    pub tle: Option<TleConfig>,
    #[serde(default)]
    pub state: Option<StateVectorConfig>,
    #[serde(default)]
    pub forces: ForceModelConfig,
    #[serde(default)]
    pub integrator: IntegratorConfig,
}

/// Osculating Keplerian elements in the scenario ECI frame at the scenario start.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeplerianElementsConfig {
    pub semi_major_axis_km: f64,
    pub eccentricity: f64,
    pub inclination_deg: f64,
    pub raan_deg: f64,
    pub arg_perigee_deg: f64,
    pub mean_anomaly_deg: f64,
}

/// A two-line element set; SGP4 gives the state at the scenario start (TEME taken as the
/// scenario ECI frame, a documented simplification).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TleConfig {
    pub line1: String,
    pub line2: String,
}

/// Frame of a state vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StateFrame {
    Eci,
    Ecef,
}

/// A Cartesian state at the scenario start.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StateVectorConfig {
    pub frame: StateFrame,
    pub position_m: [f64; 3],
    pub velocity_mps: [f64; 3],
}

/// Atmospheric density model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum DensityModel {
    /// Piecewise exponential (Vallado, table 8-4).
    #[default]
    Exponential,
    /// Harris-Priester with diurnal bulge (mean solar activity).
    HarrisPriester,
}

/// Forces acting on the LEO.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceModelConfig {
    #[serde(default = "yes")]
    pub j2: bool,
    /// Add J3..J6 zonal terms.
    #[serde(default)]
    pub higher_zonals: bool,
    #[serde(default = "yes")]
    pub drag: bool,
    #[serde(default)]
    pub density_model: DensityModel,
    #[serde(default = "default_cd")]
    pub drag_coefficient: f64,
    #[serde(default = "default_area")]
    pub area_m2: f64,
    #[serde(default = "default_mass")]
    pub mass_kg: f64,
}

/// Integrator tolerances.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorConfig {
    #[serde(default = "default_rel_tol")]
    pub rel_tol: f64,
    #[serde(default = "default_abs_tol")]
    pub abs_tol_m: f64,
}

fn yes() -> bool {
    true
}
fn default_cd() -> f64 {
    2.2
}
fn default_area() -> f64 {
    1.0
}
fn default_mass() -> f64 {
    100.0
}
fn default_rel_tol() -> f64 {
    1e-12
}
fn default_abs_tol() -> f64 {
    1e-4
}

impl Default for ForceModelConfig {
    fn default() -> Self {
        Self {
            j2: true,
            higher_zonals: false,
            drag: true,
            density_model: DensityModel::default(),
            drag_coefficient: default_cd(),
            area_m2: default_area(),
            mass_kg: default_mass(),
        }
    }
}

impl Default for IntegratorConfig {
    fn default() -> Self {
        Self {
            rel_tol: default_rel_tol(),
            abs_tol_m: default_abs_tol(),
        }
    }
}

impl LeoConfig {
    /// Physical checks: exactly one initial state; e in [0, 1); perigee above the surface;
    /// positive mass, area, Cd; sane tolerances; TLE readable.
    pub fn check(&self) -> Result<(), Invalid> {
        self.check_one_initial_state()?;
        if let Some(elements) = &self.elements {
            elements.check().map_err(|e| e.within("elements"))?;
        }
        if let Some(tle) = &self.tle {
            tle.check().map_err(|e| e.within("tle"))?;
        }
        if let Some(state) = &self.state {
            state.check().map_err(|e| e.within("state"))?;
        }
        self.forces.check().map_err(|e| e.within("forces"))?;
        self.integrator.check().map_err(|e| e.within("integrator"))
    }

    fn check_one_initial_state(&self) -> Result<(), Invalid> {
        const ALLOWED: &str = "exactly one of `elements`, `tle`, `state` gives the initial state";
        let given: Vec<&str> = [
            ("elements", self.elements.is_some()),
            ("tle", self.tle.is_some()),
            ("state", self.state.is_some()),
        ]
        .into_iter()
        .filter_map(|(name, present)| present.then_some(name))
        .collect();
        match given.as_slice() {
            [_] => Ok(()),
            [] => Err(Invalid::new("elements", "missing", ALLOWED)),
            [first, second, ..] => Err(Invalid::new(
                *second,
                format!("given together with `{first}`"),
                ALLOWED,
            )),
        }
    }
}

/// Lowest allowed perigee / initial altitude above the equatorial radius (m): the
/// propagator stops with [`super::PropagateError::Decayed`] below it.
pub const MIN_ALTITUDE_M: f64 = 80e3;

/// Farthest the orbit may reach from the Earth's centre (m): apogee radius `a (1 + e)`.
/// The propagator models the Earth's gravity (J2, zonals) and drag but not the Moon and
/// Sun, whose pull equals J2's near the geostationary radius and is about 60 times J2's at
/// this radius; farther orbits would be fiction (and 1e30 km was read as an orbit).
pub const MAX_APOGEE_RADIUS_M: f64 = 100_000e3;

/// The apogee check shared by elements and state vectors.
fn check_apogee(field: &str, value: String, apogee_radius_m: f64) -> Result<(), Invalid> {
    if apogee_radius_m <= MAX_APOGEE_RADIUS_M {
        return Ok(());
    }
    Err(Invalid::new(
        field,
        value,
        format!(
            "apogee radius a (1 + e) = {:.1} km: must be <= {} km (the propagator has no \
             Moon or Sun, which outweigh the Earth's oblateness beyond the geostationary \
             radius)",
            apogee_radius_m * 1e-3,
            MAX_APOGEE_RADIUS_M * 1e-3
        ),
    ))
}

fn finite(field: &str, value: f64) -> Result<f64, Invalid> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Invalid::new(field, value, "must be a finite number"))
    }
}

fn positive(field: &str, value: f64) -> Result<f64, Invalid> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Invalid::new(field, value, "must be a finite number > 0"))
    }
}

impl KeplerianElementsConfig {
    fn check(&self) -> Result<(), Invalid> {
        let a_m = positive("semi_major_axis_km", self.semi_major_axis_km)? * 1e3;
        let e = finite("eccentricity", self.eccentricity)?;
        if !(0.0..1.0).contains(&e) {
            return Err(Invalid::new(
                "eccentricity",
                e,
                "must be in [0, 1) (a closed orbit)",
            ));
        }
        let i = finite("inclination_deg", self.inclination_deg)?;
        if !(0.0..=180.0).contains(&i) {
            return Err(Invalid::new(
                "inclination_deg",
                i,
                "must be in [0, 180] deg",
            ));
        }
        ANGLE_DEG.check("raan_deg", self.raan_deg)?;
        ANGLE_DEG.check("arg_perigee_deg", self.arg_perigee_deg)?;
        ANGLE_DEG.check("mean_anomaly_deg", self.mean_anomaly_deg)?;
        let perigee_altitude_m = a_m * (1.0 - e) - WGS84_A_M;
        if perigee_altitude_m < MIN_ALTITUDE_M {
            return Err(Invalid::new(
                "semi_major_axis_km",
                self.semi_major_axis_km,
                format!(
                    "perigee altitude a (1 - e) - 6378.137 km = {:.1} km: must be >= 80 km \
                     (above the surface and the lower atmosphere)",
                    perigee_altitude_m * 1e-3
                ),
            ));
        }
        check_apogee(
            "semi_major_axis_km",
            self.semi_major_axis_km.to_string(),
            a_m * (1.0 + e),
        )
    }
}

impl StateVectorConfig {
    fn check(&self) -> Result<(), Invalid> {
        for (k, &x) in self.position_m.iter().enumerate() {
            finite(&format!("position_m[{k}]"), x)?;
        }
        for (k, &x) in self.velocity_mps.iter().enumerate() {
            finite(&format!("velocity_mps[{k}]"), x)?;
        }
        let r = Vec3::from(self.position_m);
        let altitude_m = r.norm() - WGS84_A_M;
        if altitude_m < MIN_ALTITUDE_M {
            return Err(Invalid::new(
                "position_m",
                format!("{:?}", self.position_m),
                format!(
                    "|r| - 6378.137 km = {:.1} km: must be >= 80 km above the surface",
                    altitude_m * 1e-3
                ),
            ));
        }
        // Inertial speed; |v_eci| = |v_ecef + w x r| in any Earth-rotation-only frame.
        let v = Vec3::from(self.velocity_mps);
        let v_inertial = match self.frame {
            StateFrame::Eci => v,
            StateFrame::Ecef => v + Vec3::new(-OMEGA_E_GPS * r.y, OMEGA_E_GPS * r.x, 0.0),
        };
        let v_escape = (2.0 * GM_GPS / r.norm()).sqrt();
        if v_inertial.norm() >= v_escape {
            return Err(Invalid::new(
                "velocity_mps",
                format!("{:?}", self.velocity_mps),
                format!(
                    "inertial speed {:.1} m/s must be below the escape speed {:.1} m/s",
                    v_inertial.norm(),
                    v_escape
                ),
            ));
        }
        // Bound orbit (below the escape speed): vis-viva a, eccentricity vector e.
        let mu = GM_GPS;
        let a_m = 1.0 / (2.0 / r.norm() - v_inertial.norm_squared() / mu);
        let e_vec = (r * (v_inertial.norm_squared() - mu / r.norm())
            - v_inertial * r.dot(&v_inertial))
            / mu;
        check_apogee(
            "position_m",
            format!("{:?}", self.position_m),
            a_m * (1.0 + e_vec.norm()),
        )
    }
}

/// An angle of the elements (deg): one turn either way.
const ANGLE_DEG: Allowed = Allowed::closed(-360.0, 360.0, "deg");
/// assumed: 10, beyond any shape's drag coefficient (2.2 is the usual value).
const DRAG_COEFFICIENT: Allowed = Allowed::above(0.0, 10.0, "");
/// assumed: 10 000 m^2, beyond the ISS's cross-section (about 2 500 m^2 with its arrays).
const AREA_M2: Allowed = Allowed::above(0.0, 1e4, "m^2");
/// assumed: 1 000 t, beyond the ISS's 420 t.
const MASS_KG: Allowed = Allowed::above(0.0, 1e6, "kg");

impl ForceModelConfig {
    fn check(&self) -> Result<(), Invalid> {
        DRAG_COEFFICIENT.check("drag_coefficient", self.drag_coefficient)?;
        AREA_M2.check("area_m2", self.area_m2)?;
        MASS_KG.check("mass_kg", self.mass_kg)
    }
}

impl IntegratorConfig {
    fn check(&self) -> Result<(), Invalid> {
        for (field, value) in [("rel_tol", self.rel_tol), ("abs_tol_m", self.abs_tol_m)] {
            if value.is_nan() || value <= 0.0 || value > 1e-3 {
                return Err(Invalid::new(field, value, "must be in (0, 1e-3]"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::thesis_elements;

    fn leo(elements: KeplerianElementsConfig) -> LeoConfig {
        LeoConfig {
            elements: Some(elements),
            tle: None,
            state: None,
            forces: ForceModelConfig::default(),
            integrator: IntegratorConfig::default(),
        }
    }

    fn iss_tle() -> TleConfig {
        TleConfig {
            line1: "1 25544U 98067A   20194.88612269 -.00002218  00000-0 -31515-4 0  9992".into(),
            line2: "2 25544  51.6461 221.2784 0001413  89.1723 280.4612 15.49507896236008".into(),
        }
    }

    fn field_of(cfg: &LeoConfig) -> String {
        cfg.check().unwrap_err().field
    }

    #[test]
    fn thesis_orbit_with_defaults_is_valid() {
        assert_eq!(leo(thesis_elements()).check(), Ok(()));
    }

    #[test]
    fn empty_table_deserialises_to_the_defaults() {
        use serde::Deserialize;
        use serde::de::value::{Error, MapDeserializer};
        let empty = MapDeserializer::<_, Error>::new(std::iter::empty::<(&str, &str)>());
        let cfg = LeoConfig::deserialize(empty).unwrap();
        assert_eq!(cfg.forces, ForceModelConfig::default());
        assert_eq!(cfg.integrator, IntegratorConfig::default());
        assert_eq!(cfg.check().unwrap_err().field, "elements");
    }

    #[test]
    fn exactly_one_initial_state() {
        let mut cfg = leo(thesis_elements());
        cfg.elements = None;
        let err = cfg.check().unwrap_err();
        assert_eq!(err.field, "elements");
        assert!(err.allowed.contains("exactly one"));
        let mut both = leo(thesis_elements());
        both.tle = Some(iss_tle());
        assert_eq!(field_of(&both), "tle");
        let mut state_too = leo(thesis_elements());
        state_too.state = Some(StateVectorConfig {
            frame: StateFrame::Eci,
            position_m: [7e6, 0.0, 0.0],
            velocity_mps: [0.0, 7.5e3, 0.0],
        });
        assert_eq!(field_of(&state_too), "state");
    }

    #[test]
    fn element_ranges() {
        let bad = |f: fn(&mut KeplerianElementsConfig)| {
            let mut el = thesis_elements();
            f(&mut el);
            field_of(&leo(el))
        };
        assert_eq!(bad(|e| e.eccentricity = 1.0), "elements.eccentricity");
        assert_eq!(bad(|e| e.eccentricity = -0.1), "elements.eccentricity");
        assert_eq!(
            bad(|e| e.semi_major_axis_km = 0.0),
            "elements.semi_major_axis_km"
        );
        assert_eq!(
            bad(|e| e.semi_major_axis_km = f64::NAN),
            "elements.semi_major_axis_km"
        );
        assert_eq!(
            bad(|e| e.inclination_deg = 181.0),
            "elements.inclination_deg"
        );
        assert_eq!(bad(|e| e.raan_deg = f64::INFINITY), "elements.raan_deg");
        assert_eq!(
            bad(|e| e.arg_perigee_deg = f64::NAN),
            "elements.arg_perigee_deg"
        );
        assert_eq!(
            bad(|e| e.mean_anomaly_deg = f64::NAN),
            "elements.mean_anomaly_deg"
        );
    }

    #[test]
    fn perigee_below_80_km_is_rejected() {
        let mut el = thesis_elements();
        // Perigee at 6971.593 (1 - 0.08) - 6378.137 = 35.7 km.
        el.eccentricity = 0.08;
        let err = leo(el).check().unwrap_err();
        assert_eq!(err.field, "elements.semi_major_axis_km");
        assert!(err.allowed.contains("80 km"), "{}", err.allowed);
        let mut ok = thesis_elements();
        ok.semi_major_axis_km = 6378.137 + 81.0;
        ok.eccentricity = 0.0;
        assert_eq!(leo(ok).check(), Ok(()));
    }

    /// Issue #11: `semi_major_axis_km = 1e30` was accepted (and the run wrote no
    /// observation file). Apogee radius at most 100 000 km, for elements and state vectors.
    #[test]
    fn apogee_beyond_100_000_km_is_rejected() {
        for (a_km, e) in [(1e30, 0.0), (100_001.0, 0.0), (60_000.0, 0.7)] {
            let mut el = thesis_elements();
            el.semi_major_axis_km = a_km;
            el.eccentricity = e;
            let err = leo(el).check().unwrap_err();
            assert_eq!(err.field, "elements.semi_major_axis_km");
            assert!(err.allowed.contains("<= 100000 km"), "{}", err.allowed);
        }
        let mut geo = thesis_elements();
        geo.semi_major_axis_km = 42_164.0;
        geo.eccentricity = 0.0;
        assert_eq!(leo(geo).check(), Ok(()));
        // A state at 90 000 km moving at 2.5 km/s: bound (escape 2.98 km/s), apogee beyond.
        let mut state = leo(thesis_elements());
        state.elements = None;
        state.state = Some(StateVectorConfig {
            frame: StateFrame::Eci,
            position_m: [90_000e3, 0.0, 0.0],
            velocity_mps: [0.0, 2.5e3, 0.0],
        });
        assert_eq!(field_of(&state), "state.position_m");
    }

    #[test]
    fn force_and_integrator_ranges() {
        let mut cfg = leo(thesis_elements());
        cfg.forces.mass_kg = 0.0;
        assert_eq!(field_of(&cfg), "forces.mass_kg");
        let mut cfg = leo(thesis_elements());
        cfg.forces.area_m2 = -1.0;
        assert_eq!(field_of(&cfg), "forces.area_m2");
        let mut cfg = leo(thesis_elements());
        cfg.forces.drag_coefficient = f64::NAN;
        assert_eq!(field_of(&cfg), "forces.drag_coefficient");
        let mut cfg = leo(thesis_elements());
        cfg.integrator.rel_tol = 0.0;
        assert_eq!(field_of(&cfg), "integrator.rel_tol");
        let mut cfg = leo(thesis_elements());
        cfg.integrator.abs_tol_m = 2e-3;
        assert_eq!(field_of(&cfg), "integrator.abs_tol_m");
    }

    #[test]
    fn state_vector_checks() {
        let state = |frame, position_m, velocity_mps| LeoConfig {
            elements: None,
            tle: None,
            state: Some(StateVectorConfig {
                frame,
                position_m,
                velocity_mps,
            }),
            forces: ForceModelConfig::default(),
            integrator: IntegratorConfig::default(),
        };
        let ok = state(StateFrame::Ecef, [7.0e6, 0.0, 0.0], [0.0, 7.0e3, 0.0]);
        assert_eq!(ok.check(), Ok(()));
        let inside = state(StateFrame::Eci, [6.4e6, 0.0, 0.0], [0.0, 7.9e3, 0.0]);
        assert_eq!(field_of(&inside), "state.position_m");
        let nan = state(StateFrame::Eci, [7.0e6, f64::NAN, 0.0], [0.0, 7.5e3, 0.0]);
        assert_eq!(field_of(&nan), "state.position_m[1]");
        let nan_v = state(
            StateFrame::Eci,
            [7.0e6, 0.0, 0.0],
            [0.0, 7.5e3, f64::INFINITY],
        );
        assert_eq!(field_of(&nan_v), "state.velocity_mps[2]");
        // Escape speed at 7000 km is 10.67 km/s; in ECEF the Earth rotation adds 0.51 km/s.
        let escaping = state(StateFrame::Eci, [7.0e6, 0.0, 0.0], [0.0, 10.8e3, 0.0]);
        assert_eq!(field_of(&escaping), "state.velocity_mps");
        let escaping_ecef = state(StateFrame::Ecef, [7.0e6, 0.0, 0.0], [0.0, 10.3e3, 0.0]);
        assert_eq!(field_of(&escaping_ecef), "state.velocity_mps");
    }

    #[test]
    fn tle_lines_must_parse() {
        let mut cfg = leo(thesis_elements());
        cfg.elements = None;
        cfg.tle = Some(iss_tle());
        assert_eq!(cfg.check(), Ok(()));
        let mut bad = iss_tle();
        bad.line2.replace_range(8..9, "X");
        cfg.tle = Some(bad);
        let err = cfg.check().unwrap_err();
        assert_eq!(err.field, "tle.line2");
        assert!(err.allowed.contains("two-line element"), "{}", err.allowed);
    }
}
