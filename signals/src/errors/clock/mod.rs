//! Receiver oscillator: power-law noise coefficients, presets, the streaming clock model and
//! Allan-deviation tools.
//!
//! The fractional-frequency one-sided PSD is `S_y(f) = h0 + h_minus1 / f + h_minus2 / f^2`
//! (white FM, flicker FM, random-walk FM; IEEE Std 1139-2008). One [`ClockModel`] serves a
//! whole receiver: every antenna of that receiver sees the same clock. When a scenario has
//! several receivers, each gets its own model seeded from
//! [`stream_seed`](crate::errors::seed::stream_seed)`(seed, Stream::ReceiverClock, receiver_index)`.

mod allan;
mod model;
mod relativity;

pub use allan::{overlapping_adev, overlapping_avar, predicted_adev, predicted_avar};
pub use model::{ClockModel, ClockSample};
pub use relativity::{OffsetPoint, RelativisticOffset, interpolate, proper_rate};

use skyforge_orbits::check::{Allowed, Invalid};

/// Power-law coefficients h0, h_-1, h_-2 of the fractional-frequency noise: assumed up to
/// 1e-15, 5000 times the noisiest preset's (2e-19, the low-quality TCXO).
const H_COEFFICIENT: Allowed = Allowed::closed(0.0, 1e-15, "");

/// Power-law coefficients of the fractional-frequency PSD (`h0` in s, `h_minus1`
/// dimensionless, `h_minus2` in 1/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    pub h0: f64,
    pub h_minus1: f64,
    pub h_minus2: f64,
}

/// Oscillator presets: the table "Oscillator noise presets in common use" of
/// `reference/ANCHORS.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OscillatorPreset {
    /// Row "high-quality TCXO": 2e-21, 1e-22, 2e-20.
    Tcxo,
    /// Row "low-quality TCXO (Brown & Hwang)": 2e-19, 7e-21, 2e-20.
    TcxoLow,
    /// Row "OCXO": 2e-25, 7e-25, 6e-25.
    Ocxo,
    /// Row "rubidium (Brown & Hwang)": 2e-22, 4.5e-26, 1e-30. (The row "rubidium (same
    /// book, monitor clock)", 2.0e-22, 4.0e-26, 1.5e-33, differs only in the slow terms;
    /// its h-2 equals the cesium value, so the Brown & Hwang row is used.)
    Rubidium,
    /// Row "quartz (book by Yuan et al., user clock)": 9.4e-20, 1.8e-19, 3.8e-21
    /// (Yuan 2000, table 2-19 note 2).
    Quartz,
    /// Row "cesium": 2e-22, 5e-27, 1.5e-33.
    Cesium,
}

impl OscillatorPreset {
    /// Every preset, in declaration order.
    pub const ALL: [OscillatorPreset; 6] = [
        OscillatorPreset::Tcxo,
        OscillatorPreset::TcxoLow,
        OscillatorPreset::Ocxo,
        OscillatorPreset::Rubidium,
        OscillatorPreset::Quartz,
        OscillatorPreset::Cesium,
    ];

    /// The preset's coefficients.
    pub fn power_law(self) -> PowerLaw {
        let (h0, h_minus1, h_minus2) = match self {
            OscillatorPreset::Tcxo => (2e-21, 1e-22, 2e-20),
            OscillatorPreset::TcxoLow => (2e-19, 7e-21, 2e-20),
            OscillatorPreset::Ocxo => (2e-25, 7e-25, 6e-25),
            OscillatorPreset::Rubidium => (2e-22, 4.5e-26, 1e-30),
            OscillatorPreset::Quartz => (9.4e-20, 1.8e-19, 3.8e-21),
            OscillatorPreset::Cesium => (2e-22, 5e-27, 1.5e-33),
        };
        PowerLaw {
            h0,
            h_minus1,
            h_minus2,
        }
    }

    /// The TOML spelling (`"tcxo-low"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            OscillatorPreset::Tcxo => "tcxo",
            OscillatorPreset::TcxoLow => "tcxo-low",
            OscillatorPreset::Ocxo => "ocxo",
            OscillatorPreset::Rubidium => "rubidium",
            OscillatorPreset::Quartz => "quartz",
            OscillatorPreset::Cesium => "cesium",
        }
    }
}

/// Largest accepted |initial bias| (s).
const MAX_ABS_BIAS_S: f64 = 1.0;
/// Largest accepted |initial fractional frequency offset| (1000 ppm).
const MAX_ABS_DRIFT: f64 = 1e-3;

/// `[errors.receiver_clock]`: a `preset`, or explicit `h0` / `h_minus1` / `h_minus2`
/// (absent ones are 0), plus the initial clock state and whether the antennas share it.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscillatorConfig {
    #[serde(default)]
    pub preset: Option<OscillatorPreset>,
    /// White-FM coefficient (s).
    #[serde(default)]
    pub h0: Option<f64>,
    /// Flicker-FM coefficient.
    #[serde(default)]
    pub h_minus1: Option<f64>,
    /// Random-walk-FM coefficient (1/s).
    #[serde(default)]
    pub h_minus2: Option<f64>,
    /// Initial clock bias: receiver clock minus true time (s).
    #[serde(default)]
    pub bias_s: f64,
    /// Initial fractional frequency offset, i.e. clock drift (s/s).
    #[serde(default)]
    pub drift: f64,
    /// `false` (default): one oscillator drives every antenna's front end (one receiver);
    /// `true`: each antenna has its own, independent oscillator (one receiver each).
    #[serde(default)]
    pub per_antenna: bool,
    /// `true`: the clock keeps its platform's proper time, the relativistic offset of a
    /// moving clock against GPS time added (book eqs. 5-16/5-17; [`RelativisticOffset`]).
    /// `false` (default): the oscillator alone, as every scenario before.
    #[serde(default)]
    pub relativity: bool,
}

impl OscillatorConfig {
    /// Checks: exactly one of `preset` or explicit coefficients; coefficients finite and
    /// >= 0; `|bias_s| <= 1 s`; `|drift| <= 1e-3`.
    pub fn check(&self) -> Result<(), Invalid> {
        let explicit = [
            ("h0", self.h0),
            ("h_minus1", self.h_minus1),
            ("h_minus2", self.h_minus2),
        ];
        let any_explicit = explicit.iter().any(|(_, v)| v.is_some());
        match (self.preset, any_explicit) {
            (Some(p), true) => {
                return Err(Invalid::new(
                    "preset",
                    format!("{:?}", p.name()),
                    "give either a preset or h0/h_minus1/h_minus2, not both",
                ));
            }
            (None, false) => {
                return Err(Invalid::new(
                    "preset",
                    "(missing)",
                    "give a preset (tcxo, tcxo-low, ocxo, rubidium, quartz, cesium) \
                     or at least one of h0, h_minus1, h_minus2",
                ));
            }
            _ => {}
        }
        for (name, value) in explicit {
            if let Some(h) = value {
                H_COEFFICIENT.check(name, h)?;
            }
        }
        if !(self.bias_s.is_finite() && self.bias_s.abs() <= MAX_ABS_BIAS_S) {
            return Err(Invalid::new(
                "bias_s",
                self.bias_s,
                "must be finite with |bias_s| <= 1 s",
            ));
        }
        if !(self.drift.is_finite() && self.drift.abs() <= MAX_ABS_DRIFT) {
            return Err(Invalid::new(
                "drift",
                self.drift,
                "must be finite with |drift| <= 1e-3 (1000 ppm)",
            ));
        }
        Ok(())
    }

    /// The checked coefficients (preset table or explicit values, absent ones 0).
    pub fn power_law(&self) -> Result<PowerLaw, Invalid> {
        self.check()?;
        Ok(match self.preset {
            Some(p) => p.power_law(),
            None => PowerLaw {
                h0: self.h0.unwrap_or(0.0),
                h_minus1: self.h_minus1.unwrap_or(0.0),
                h_minus2: self.h_minus2.unwrap_or(0.0),
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use serde::Deserialize;
    use serde::de::IntoDeserializer;
    use serde::de::value::{Error, MapDeserializer};

    /// A preset spelled as in TOML (serde's string deserialiser stands in for `toml`,
    /// which `scenarios` uses).
    fn preset(name: &str) -> Result<OscillatorPreset, Error> {
        OscillatorPreset::deserialize(name.into_deserializer())
    }

    #[test]
    fn presets_resolve_to_the_anchor_table() {
        assert_eq!(preset("tcxo-low").ok(), Some(OscillatorPreset::TcxoLow));
        assert!(preset("crystal").is_err());
        for p in OscillatorPreset::ALL {
            assert_eq!(preset(p.name()).ok(), Some(p));
        }
        let h = OscillatorPreset::TcxoLow.power_law();
        assert_eq!((h.h0, h.h_minus1, h.h_minus2), (2e-19, 7e-21, 2e-20));
        let q = OscillatorPreset::Quartz.power_law();
        assert_eq!((q.h0, q.h_minus1, q.h_minus2), (9.4e-20, 1.8e-19, 3.8e-21));
    }

    #[test]
    fn unknown_fields_are_rejected() {
        let de: MapDeserializer<'_, _, Error> =
            MapDeserializer::new(std::iter::once(("h_minus3", "1")));
        let err = OscillatorConfig::deserialize(de)
            .err()
            .map(|e| e.to_string());
        assert!(err.is_some_and(|e| e.contains("unknown field `h_minus3`")));
    }

    #[test]
    fn check_names_the_bad_field() {
        let base = OscillatorConfig {
            preset: None,
            h0: Some(1e-20),
            h_minus1: None,
            h_minus2: None,
            bias_s: 0.0,
            drift: 0.0,
            per_antenna: false,
            relativity: false,
        };
        assert!(base.check().is_ok());
        let field = |c: OscillatorConfig| c.check().err().map(|e| e.field);
        let both = OscillatorConfig {
            preset: Some(OscillatorPreset::Ocxo),
            ..base.clone()
        };
        assert_eq!(field(both), Some("preset".into()));
        let neither = OscillatorConfig {
            h0: None,
            ..base.clone()
        };
        assert_eq!(field(neither), Some("preset".into()));
        let negative = OscillatorConfig {
            h_minus2: Some(-1e-20),
            ..base.clone()
        };
        assert_eq!(field(negative), Some("h_minus2".into()));
        let nan_bias = OscillatorConfig {
            bias_s: f64::NAN,
            ..base.clone()
        };
        assert_eq!(field(nan_bias), Some("bias_s".into()));
        let fast = OscillatorConfig {
            drift: 2e-3,
            ..base.clone()
        };
        assert_eq!(field(fast), Some("drift".into()));
        let explicit = base.power_law().unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((explicit.h_minus1, explicit.h_minus2), (0.0, 0.0));
    }
}
