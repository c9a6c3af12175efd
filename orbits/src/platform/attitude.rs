//! Attitude profiles: yaw/pitch/roll relative to the platform's reference frame, constant,
//! per-axis sinusoid, or read from CSV.
//!
//! Degrees from the configuration are converted to radians once, here. The angles are the
//! 3-2-1 angles of thesis section 2.5.2 ([`YawPitchRoll`]) of the body frame relative to
//! the platform's reference frame (orbital frame for a LEO, NED otherwise).

use crate::Vec3;
use crate::angles::wrap_pi_upper;
use crate::check::Invalid;
use crate::frames::euler::YawPitchRoll;
use crate::platform::PlatformError;
use crate::platform::csv_table::read_numeric_csv;
use crate::platform::hermite::Hermite3;
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// One axis: `offset + amplitude * sin(2 pi t / period + phase)`; `period_s = 0` means
/// constant `offset`.
#[derive(Debug, Clone, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisProfileConfig {
    #[serde(default)]
    pub offset_deg: f64,
    #[serde(default)]
    pub amplitude_deg: f64,
    #[serde(default)]
    pub period_s: f64,
    #[serde(default)]
    pub phase_deg: f64,
}

/// `[platform.attitude]`: per-axis profiles, or a CSV `t_s,yaw_deg,pitch_deg,roll_deg`.
#[derive(Debug, Clone, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttitudeConfig {
    #[serde(default)]
    pub yaw: AxisProfileConfig,
    #[serde(default)]
    pub pitch: AxisProfileConfig,
    #[serde(default)]
    pub roll: AxisProfileConfig,
    #[serde(default)]
    pub csv: Option<PathBuf>,
}

/// One axis of a sinusoidal profile, in radians: `offset + amplitude * sin(rate t + phase)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisSinusoid {
    pub offset_rad: f64,
    pub amplitude_rad: f64,
    /// `2 pi / period` (rad/s); 0 for a constant axis.
    pub rate_rad_s: f64,
    pub phase_rad: f64,
}

impl AxisSinusoid {
    /// The angle (rad) at `t_s`.
    pub fn at(&self, t_s: f64) -> f64 {
        if self.rate_rad_s == 0.0 {
            self.offset_rad
        } else {
            self.offset_rad + self.amplitude_rad * (self.rate_rad_s * t_s + self.phase_rad).sin()
        }
    }

    /// The angle's rate (rad/s) at `t_s`: the derivative of [`Self::at`].
    pub fn rate(&self, t_s: f64) -> f64 {
        self.amplitude_rad * self.rate_rad_s * (self.rate_rad_s * t_s + self.phase_rad).cos()
    }
}

/// Attitude angles read from CSV, interpolated per axis (cubic Hermite on unwrapped angles).
#[derive(Debug, Clone, PartialEq)]
pub struct AttitudeTable {
    /// Yaw, pitch, roll (rad, unwrapped) as the three components.
    angles: Hermite3,
}

impl AttitudeTable {
    /// Reads `t_s,yaw_deg,pitch_deg,roll_deg` rows (header line allowed, `#` comments).
    pub fn from_csv(path: &Path) -> Result<Self, PlatformError> {
        let rows = read_numeric_csv(path, &["t_s", "yaw_deg", "pitch_deg", "roll_deg"], &[4])?;
        let t_s = rows.iter().map(|r| r.values[0]).collect();
        let mut angles: Vec<Vec3> = Vec::with_capacity(rows.len());
        for row in &rows {
            let raw = Vec3::new(row.values[1], row.values[2], row.values[3]).map(f64::to_radians);
            // Unwrap: each step is taken as the shortest turn, so 359 deg -> 1 deg is +2 deg.
            let a = match angles.last() {
                Some(prev) => prev + (raw - prev).map(wrap_pi_upper),
                None => raw,
            };
            angles.push(a);
        }
        Ok(Self {
            angles: Hermite3::with_estimated_slopes(t_s, angles),
        })
    }
    /// First and last time covered (s since the scenario start).
    pub fn span(&self) -> (f64, f64) {
        self.angles.span()
    }
    /// Interpolated angles at `t_s`; outside the span, the angles continue at their end
    /// rates (meant for a few seconds of margin, see [`crate::platform::EDGE_MARGIN_S`]).
    pub fn at(&self, t_s: f64) -> YawPitchRoll {
        let (a, _) = self.angles.eval(t_s);
        YawPitchRoll::new(a.x, a.y, a.z)
    }
}

/// A resolved attitude profile.
#[derive(Debug, Clone)]
pub enum AttitudeProfile {
    /// Fixed angles.
    Constant(YawPitchRoll),
    /// Independent sinusoids for yaw, pitch and roll.
    Sinusoid {
        yaw: AxisSinusoid,
        pitch: AxisSinusoid,
        roll: AxisSinusoid,
    },
    /// Interpolated table (shared, cheap to clone).
    Table(Arc<AttitudeTable>),
}

impl AttitudeProfile {
    /// Resolves `[platform.attitude]`; a relative CSV path is taken from `base_dir` (the
    /// scenario file's folder). The CSV excludes the per-axis profiles.
    pub fn from_config(
        cfg: &AttitudeConfig,
        base_dir: &Path,
    ) -> Result<AttitudeProfile, PlatformError> {
        let axes = [
            ("yaw", &cfg.yaw),
            ("pitch", &cfg.pitch),
            ("roll", &cfg.roll),
        ];
        if let Some(csv) = &cfg.csv {
            if let Some((name, _)) = axes
                .iter()
                .find(|(_, a)| **a != AxisProfileConfig::default())
            {
                return Err(Invalid::new(
                    format!("attitude.{name}"),
                    "(set)",
                    "cannot be combined with attitude.csv; give either the CSV or per-axis profiles",
                )
                .into());
            }
            let path = base_dir.join(csv);
            return Ok(Self::Table(Arc::new(AttitudeTable::from_csv(&path)?)));
        }
        let mut sinusoids = [AxisSinusoid {
            offset_rad: 0.0,
            amplitude_rad: 0.0,
            rate_rad_s: 0.0,
            phase_rad: 0.0,
        }; 3];
        for ((name, axis), out) in axes.iter().zip(sinusoids.iter_mut()) {
            *out = axis_sinusoid(name, axis)?;
        }
        let [yaw, pitch, roll] = sinusoids;
        if sinusoids
            .iter()
            .all(|s| s.rate_rad_s == 0.0 || s.amplitude_rad == 0.0)
        {
            return Ok(Self::Constant(YawPitchRoll::new(
                yaw.offset_rad,
                pitch.offset_rad,
                roll.offset_rad,
            )));
        }
        Ok(Self::Sinusoid { yaw, pitch, roll })
    }

    /// Attitude at `t_s`. Angles are returned as configured (a table's unwrapped angles
    /// are wrapped back to (-pi, pi]). A table continues at its end rates outside its
    /// span; [`Self::span`] tells the covered interval.
    pub fn at(&self, t_s: f64) -> YawPitchRoll {
        match self {
            Self::Constant(a) => *a,
            Self::Sinusoid { yaw, pitch, roll } => {
                YawPitchRoll::new(yaw.at(t_s), pitch.at(t_s), roll.at(t_s))
            }
            Self::Table(table) => {
                let a = table.at(t_s);
                YawPitchRoll::new(
                    wrap_pi_upper(a.yaw_rad),
                    wrap_pi_upper(a.pitch_rad),
                    wrap_pi_upper(a.roll_rad),
                )
            }
        }
    }

    /// The angles' rates (rad/s) at `t_s`, as a [`YawPitchRoll`] of rates: the exact
    /// derivative of [`Self::at`] (a table's, its interpolant's).
    pub fn rates(&self, t_s: f64) -> YawPitchRoll {
        match self {
            Self::Constant(_) => YawPitchRoll::default(),
            Self::Sinusoid { yaw, pitch, roll } => {
                YawPitchRoll::new(yaw.rate(t_s), pitch.rate(t_s), roll.rate(t_s))
            }
            Self::Table(table) => {
                let (_, rate) = table.angles.eval(t_s);
                YawPitchRoll::new(rate.x, rate.y, rate.z)
            }
        }
    }

    /// The interval a table covers; `None` for profiles defined at all times.
    pub fn span(&self) -> Option<(f64, f64)> {
        match self {
            Self::Table(table) => Some(table.span()),
            Self::Constant(_) | Self::Sinusoid { .. } => None,
        }
    }
}

/// Checks one `[platform.attitude.<axis>]` and converts it to radians.
fn axis_sinusoid(name: &str, axis: &AxisProfileConfig) -> Result<AxisSinusoid, Invalid> {
    let fields = [
        ("offset_deg", axis.offset_deg),
        ("amplitude_deg", axis.amplitude_deg),
        ("period_s", axis.period_s),
        ("phase_deg", axis.phase_deg),
    ];
    if let Some((field, value)) = fields.iter().find(|(_, v)| !v.is_finite()) {
        return Err(Invalid::new(
            format!("attitude.{name}.{field}"),
            value,
            "must be a finite number",
        ));
    }
    if axis.period_s < 0.0 {
        return Err(Invalid::new(
            format!("attitude.{name}.period_s"),
            axis.period_s,
            "must be >= 0 (0 = constant offset)",
        ));
    }
    Ok(AxisSinusoid {
        offset_rad: axis.offset_deg.to_radians(),
        amplitude_rad: axis.amplitude_deg.to_radians(),
        rate_rad_s: if axis.period_s == 0.0 {
            0.0
        } else {
            TAU / axis.period_s
        },
        phase_rad: axis.phase_deg.to_radians(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;
    use std::io::Write;

    fn axis(
        offset_deg: f64,
        amplitude_deg: f64,
        period_s: f64,
        phase_deg: f64,
    ) -> AxisProfileConfig {
        AxisProfileConfig {
            offset_deg,
            amplitude_deg,
            period_s,
            phase_deg,
        }
    }

    fn profile(cfg: &AttitudeConfig) -> AttitudeProfile {
        match AttitudeProfile::from_config(cfg, Path::new(".")) {
            Ok(p) => p,
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn default_is_zero_constant() {
        let p = profile(&AttitudeConfig::default());
        assert!(matches!(p, AttitudeProfile::Constant(_)));
        assert_eq!(p.at(123.0), YawPitchRoll::default());
        assert_eq!(p.span(), None);
    }

    #[test]
    fn sinusoid_at_known_times() {
        // yaw = 10 + 5 sin(2 pi t / 100 + 30 deg), pitch constant 2 deg, roll = -3 sin(2 pi t / 40).
        let cfg = AttitudeConfig {
            yaw: axis(10.0, 5.0, 100.0, 30.0),
            pitch: axis(2.0, 7.0, 0.0, 0.0),
            roll: axis(0.0, -3.0, 40.0, 0.0),
            csv: None,
        };
        let p = profile(&cfg);
        let deg = |a: YawPitchRoll| {
            (
                a.yaw_rad.to_degrees(),
                a.pitch_rad.to_degrees(),
                a.roll_rad.to_degrees(),
            )
        };
        let close = |a: (f64, f64, f64), b: (f64, f64, f64)| {
            (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12 && (a.2 - b.2).abs() < 1e-12
        };
        // t = 0: sin(30 deg) = 1/2.
        assert!(close(deg(p.at(0.0)), (12.5, 2.0, 0.0)));
        // t = 10: yaw phase 36 + 30 = 66 deg; roll phase 90 deg.
        assert!(close(
            deg(p.at(10.0)),
            (10.0 + 5.0 * 66f64.to_radians().sin(), 2.0, -3.0)
        ));
        // t = 250: yaw phase 900 + 30 deg -> sin = -1/2; roll phase 2250 deg -> sin = 1.
        assert!(close(deg(p.at(250.0)), (7.5, 2.0, -3.0)));
    }

    #[test]
    fn config_errors_name_the_field() {
        let bad = AttitudeConfig {
            roll: axis(0.0, 1.0, -5.0, 0.0),
            ..AttitudeConfig::default()
        };
        let Err(PlatformError::Config(inv)) = AttitudeProfile::from_config(&bad, Path::new("."))
        else {
            panic!("negative period accepted")
        };
        assert_eq!(inv.field, "attitude.roll.period_s");
        let bad = AttitudeConfig {
            yaw: axis(f64::NAN, 0.0, 0.0, 0.0),
            ..AttitudeConfig::default()
        };
        assert!(AttitudeProfile::from_config(&bad, Path::new(".")).is_err());
        let both = AttitudeConfig {
            pitch: axis(1.0, 0.0, 0.0, 0.0),
            csv: Some(PathBuf::from("att.csv")),
            ..AttitudeConfig::default()
        };
        let Err(PlatformError::Config(inv)) = AttitudeProfile::from_config(&both, Path::new("."))
        else {
            panic!("csv + axis accepted")
        };
        assert_eq!(inv.field, "attitude.pitch");
    }

    fn write_temp(name: &str, text: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("skyforge-attitude-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
        let path = dir.join(name);
        let mut f = std::fs::File::create(&path).unwrap_or_else(|e| panic!("{e}"));
        f.write_all(text.as_bytes())
            .unwrap_or_else(|e| panic!("{e}"));
        path
    }

    #[test]
    fn table_interpolates_and_unwraps() {
        // Yaw crosses 180 deg: 170 -> -170 (= 190) -> -150 (= 210); linear in time, so the
        // interpolant (exact for polynomials up to degree 3) gives 180 at t = 0.5.
        let path = write_temp(
            "table.csv",
            "# attitude\nt_s,yaw_deg,pitch_deg,roll_deg\n0,170,0,1\n1,-170,1,1\n2,-150,2,1\n3,-130,3,1 # last\n",
        );
        let cfg = AttitudeConfig {
            csv: Some(PathBuf::from("table.csv")),
            ..AttitudeConfig::default()
        };
        let dir = path.parent().unwrap_or(Path::new("."));
        let p = match AttitudeProfile::from_config(&cfg, dir) {
            Ok(p) => p,
            Err(e) => panic!("{e}"),
        };
        assert_eq!(p.span(), Some((0.0, 3.0)));
        let a = p.at(0.5);
        assert!((a.yaw_rad.abs() - PI).abs() < 1e-12, "{a:?}");
        assert!((a.pitch_rad - 0.5f64.to_radians()).abs() < 1e-12);
        assert!((a.roll_rad - 1f64.to_radians()).abs() < 1e-12);
        let a = p.at(1.25);
        assert!((a.yaw_rad - (-165f64).to_radians()).abs() < 1e-12, "{a:?}");
        // Continued at the end rate (1 deg/s in pitch) beyond the data.
        assert!((p.at(4.0).pitch_rad - 4f64.to_radians()).abs() < 1e-12);
    }

    #[test]
    fn table_errors_carry_file_and_line() {
        let path = write_temp(
            "bad.csv",
            "t_s,yaw_deg,pitch_deg,roll_deg\n0,1,2,3\n1,2,3\n",
        );
        let cfg = AttitudeConfig {
            csv: Some(path.clone()),
            ..AttitudeConfig::default()
        };
        match AttitudeProfile::from_config(&cfg, Path::new("/elsewhere")) {
            Err(PlatformError::Csv { path: p, line, .. }) => {
                assert_eq!(p, path.display().to_string());
                assert_eq!(line, 3);
            }
            other => panic!("{other:?}"),
        }
    }
}
