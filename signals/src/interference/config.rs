//! `[[jammers]]`: a jammer as the scenario writes it.

use serde::Deserialize;
use skyforge_orbits::check::Invalid;

/// What a jammer transmits.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JammerWaveform {
    /// A continuous wave (an unmodulated carrier) at `frequency_hz`.
    Cw,
    /// White Gaussian noise filling the recorded band (as wide as the sample rate),
    /// centred on `frequency_hz`.
    Noise,
}

/// One `[[jammers]]` entry: a fixed transmitter of interference with an isotropic
/// antenna, switched on from `start_s` to `stop_s`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JammerConfig {
    /// Its name in the truth and in messages.
    pub name: String,
    /// `"cw"` or `"noise"`.
    pub waveform: JammerWaveform,
    /// Its position: geodetic latitude and longitude (deg) and height above the WGS-84
    /// ellipsoid (m).
    pub latitude_deg: f64,
    pub longitude_deg: f64,
    pub height_m: f64,
    /// Its power as the jammer-to-signal ratio J/S (dB) at the platform's body origin at
    /// the scenario's start, received by an isotropic antenna, against a satellite signal
    /// at `[signal] cn0_dbhz`; elsewhere and later it falls with the square of the range
    /// and follows each antenna's gain pattern.
    pub js_db: f64,
    /// The carrier (CW) or the band's centre (noise) (Hz); default GPS L1, 1575.42 MHz.
    /// A recording whose band does not hold it (more than half its sample rate away from
    /// its carrier) does not see the jammer.
    #[serde(default = "default_frequency_hz")]
    pub frequency_hz: f64,
    /// When it switches on and off (s from the scenario's start); default: all along.
    #[serde(default)]
    pub start_s: f64,
    #[serde(default)]
    pub stop_s: Option<f64>,
}

fn default_frequency_hz() -> f64 {
    1_575.42e6
}

/// The most jammers a scenario may hold: each is rendered into every sample of every
/// antenna. # assumed: 16, a dense jamming scene.
pub const MAX_JAMMERS: usize = 16;

/// The most a J/S may be (dB): far above any receiver's loss of lock (about 40-50 dB for
/// GPS L1 C/A) and below a sample buffer's overflow.
pub const MAX_JS_DB: f64 = 120.0;

impl JammerConfig {
    /// Finite values in range: latitude within +/-90 deg, longitude within +/-360 deg,
    /// height within +/-100 km, J/S in [-50, 120] dB, frequency in 1-2 GHz (the L band
    /// every simulated signal lies in), and 0 <= start < stop <= `duration_s`. Field paths
    /// are relative to the entry.
    pub fn check(&self, duration_s: f64) -> Result<(), Invalid> {
        let ranges = [
            ("latitude_deg", self.latitude_deg, -90.0, 90.0),
            ("longitude_deg", self.longitude_deg, -360.0, 360.0),
            ("height_m", self.height_m, -1e5, 1e5),
            ("js_db", self.js_db, -50.0, MAX_JS_DB),
            ("frequency_hz", self.frequency_hz, 1e9, 2e9),
            ("start_s", self.start_s, 0.0, duration_s),
        ];
        for (field, value, lo, hi) in ranges {
            if !(value.is_finite() && (lo..=hi).contains(&value)) {
                return Err(Invalid::new(
                    field,
                    value,
                    format!("must be in [{lo}, {hi}]"),
                ));
            }
        }
        let in_span = |s: f64| s.is_finite() && s > self.start_s && s <= duration_s;
        if let Some(stop) = self.stop_s.filter(|s| !in_span(*s)) {
            return Err(Invalid::new(
                "stop_s",
                stop,
                format!(
                    "must be after start_s and at most the duration, {duration_s} s (left out: on to the end)"
                ),
            ));
        }
        let printable = self.name.chars().all(|c| c.is_ascii_graphic() || c == ' ');
        if self.name.is_empty() || self.name.len() > 64 || !printable {
            return Err(Invalid::new(
                "name",
                format!("{:?}", self.name),
                "must be 1 to 64 printable ASCII characters",
            ));
        }
        Ok(())
    }

    /// Whether a band `bandwidth_hz` wide around `carrier_hz` holds its frequency.
    pub fn in_band(&self, carrier_hz: f64, bandwidth_hz: f64) -> bool {
        (self.frequency_hz - carrier_hz).abs() < bandwidth_hz / 2.0
    }

    /// Whether it transmits at `t_s` (s from the start).
    pub fn on_at(&self, t_s: f64) -> bool {
        t_s >= self.start_s && self.stop_s.is_none_or(|stop| t_s < stop)
    }
}
