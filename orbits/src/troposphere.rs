//! The troposphere (the neutral atmosphere) as GNSS users model it: Saastamoinen zenith
//! delays from a standard atmosphere, mapped to the line of sight by Chao's functions. The
//! synthesiser puts this delay into the signal (when the scenario asks); the receiver
//! removes it.
//!
//! - Standard atmosphere (Berg 1948, as given in Hofmann-Wellenhof et al., "GNSS", 2008,
//!   section 5.3.3): `p = 1013.25 (1 - 2.26e-5 h)^5.225` hPa, `T = 291.15 - 0.0065 h` K,
//!   relative humidity `RH0 exp(-6.396e-4 h)` (`h` in m, sea-level `RH0` configurable,
//!   0.5 by default). Above the tropopause (11 km) the temperature is held and the
//!   pressure falls exponentially with the isothermal scale height `R_d T / g`, which
//!   keeps it positive and continuous. Water-vapour pressure `e = RH * 6.1078 *
//!   10^(7.5 t / (t + 237.3))` hPa (Magnus-Tetens, `t` in deg C).
//! - Zenith hydrostatic delay (Saastamoinen 1972 in the form of Davis et al. 1985):
//!   `0.0022768 p / (1 - 0.00266 cos 2 lat - 0.00028 h_km)` m; zenith wet delay
//!   (Saastamoinen 1972): `0.002277 (1255 / T + 0.05) e` m.
//! - Mapping (Chao 1972): `m(E) = 1 / (sin E + a / (tan E + b))` with `a, b = 0.00143,
//!   0.0445` (dry) and `0.00035, 0.017` (wet). Elevation-only; a few % from ray tracing
//!   at 5 deg, worse below; elevations below 1 deg are evaluated at 1 deg.
//! - Above 50 km ([`TROPOSPHERE_CEILING_M`]) the delay is zero: Yuan 2000 section 5.4.1
//!   puts the troposphere below 20 km and calls it negligible for spacecraft. Limb paths of
//!   a LEO receiver (negative elevations) are not modelled.
//!
//! The troposphere is not dispersive: code and carrier are both delayed by the same amount.

/// Height above which the tropospheric delay is zero (m).
pub const TROPOSPHERE_CEILING_M: f64 = 50e3;
const SEA_LEVEL_PRESSURE_HPA: f64 = 1013.25;
const SEA_LEVEL_TEMPERATURE_K: f64 = 291.15;
const LAPSE_RATE_K_PER_M: f64 = 0.0065;
const TROPOPAUSE_M: f64 = 11e3;
/// Specific gas constant of dry air (J/(kg K)) and standard gravity (m/s^2).
const R_DRY: f64 = 287.05;
const G0: f64 = 9.806_65;
/// Elevation floor of the mapping functions (rad): 1 deg.
const MIN_ELEVATION_RAD: f64 = 1.0 * std::f64::consts::PI / 180.0;

/// Meteorological values at the receiver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    pub pressure_hpa: f64,
    pub temperature_k: f64,
    /// Partial pressure of water vapour (hPa).
    pub water_vapour_hpa: f64,
}

/// The standard atmosphere at `height_m` with sea-level relative humidity `rh0` (module
/// docs).
pub fn standard_atmosphere(height_m: f64, rh0: f64) -> Atmosphere {
    let pressure_at = |h: f64| SEA_LEVEL_PRESSURE_HPA * (1.0 - 2.26e-5 * h).powf(5.225);
    let (pressure_hpa, temperature_k) = if height_m <= TROPOPAUSE_M {
        (
            pressure_at(height_m),
            SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_PER_M * height_m,
        )
    } else {
        let t_k = SEA_LEVEL_TEMPERATURE_K - LAPSE_RATE_K_PER_M * TROPOPAUSE_M;
        let scale_height_m = R_DRY * t_k / G0;
        (
            pressure_at(TROPOPAUSE_M) * (-(height_m - TROPOPAUSE_M) / scale_height_m).exp(),
            t_k,
        )
    };
    let t_c = temperature_k - 273.15;
    let saturation_hpa = 6.1078 * 10f64.powf(7.5 * t_c / (t_c + 237.3));
    let rh = rh0 * (-6.396e-4 * height_m).exp();
    Atmosphere {
        pressure_hpa,
        temperature_k,
        water_vapour_hpa: rh * saturation_hpa,
    }
}

/// Saastamoinen zenith (hydrostatic, wet) delays (m) for `atm` at geodetic latitude
/// `lat_rad` and height `height_m`.
pub fn saastamoinen_zenith_m(atm: &Atmosphere, lat_rad: f64, height_m: f64) -> (f64, f64) {
    let hydrostatic = 0.002_276_8 * atm.pressure_hpa
        / (1.0 - 0.002_66 * (2.0 * lat_rad).cos() - 0.000_28 * height_m / 1000.0);
    let wet = 0.002_277 * (1255.0 / atm.temperature_k + 0.05) * atm.water_vapour_hpa;
    (hydrostatic, wet)
}

/// Chao (1972) mapping functions (dry, wet) at elevation `el_rad` (floor 1 deg).
pub fn chao_mapping(el_rad: f64) -> (f64, f64) {
    let el = el_rad.clamp(MIN_ELEVATION_RAD, std::f64::consts::FRAC_PI_2);
    let (sin_e, tan_e) = (el.sin(), el.tan());
    (
        1.0 / (sin_e + 0.00143 / (tan_e + 0.0445)),
        1.0 / (sin_e + 0.00035 / (tan_e + 0.017)),
    )
}

/// The standard atmosphere's Saastamoinen zenith delays at one place: what every
/// satellite's slant delay there shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandardZenith {
    hydrostatic_m: f64,
    wet_m: f64,
}

impl StandardZenith {
    /// At geodetic latitude `lat_rad` and height `height_m`, sea-level relative humidity
    /// `rh0`; zero above [`TROPOSPHERE_CEILING_M`].
    pub fn at(lat_rad: f64, height_m: f64, rh0: f64) -> Self {
        if height_m > TROPOSPHERE_CEILING_M {
            return Self {
                hydrostatic_m: 0.0,
                wet_m: 0.0,
            };
        }
        let atm = standard_atmosphere(height_m, rh0);
        let (hydrostatic_m, wet_m) = saastamoinen_zenith_m(&atm, lat_rad, height_m);
        Self {
            hydrostatic_m,
            wet_m,
        }
    }

    /// The slant delay (m) towards a satellite at `el_rad` (Chao mapping).
    pub fn slant_m(&self, el_rad: f64) -> f64 {
        let (m_dry, m_wet) = chao_mapping(el_rad);
        self.hydrostatic_m * m_dry + self.wet_m * m_wet
    }
}

/// Slant delay (m) of the standard atmosphere with sea-level relative humidity `rh0` for a
/// receiver at geodetic latitude `lat_rad`, height `height_m`, satellite at `el_rad`; zero
/// above [`TROPOSPHERE_CEILING_M`].
pub fn standard_slant_delay_m(lat_rad: f64, height_m: f64, el_rad: f64, rh0: f64) -> f64 {
    StandardZenith::at(lat_rad, height_m, rh0).slant_m(el_rad)
}
