//! Fault events for integrity and robustness tests (`[[errors.events]]`): signal outage,
//! power step, code-only step, ionospheric ramp and carrier phase jump, each on a set of
//! antenna x satellite links over a time window `[start_s, end_s)` of receive time from the
//! scenario start.
//!
//! The kinds follow the fault models of the multi-reference-station integrity paper
//! (`papers_001_002_digest.md` section 1.7): step faults on pseudorange (`l`) and carrier
//! (`theta`), and ionospheric gradients modelled as ramps that make code and carrier
//! diverge (code delayed, carrier advanced by the same amount, as the first-order
//! ionosphere does). Every effect lasts for its window only: at `end_s` the link returns
//! to normal (a permanent fault uses an `end_s` at or beyond the scenario end).
//!
//! Overlapping events combine: power steps add in dB, an outage wins over any power step,
//! code steps, ramps and phase jumps add.

use skyforge_orbits::check::{Allowed, Invalid, shown};
use skyforge_orbits::ephemeris::SatId;

/// The kind of a fault event; the unit of [`EventConfig::value`] depends on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EventKind {
    /// The signal disappears (amplitude 0); `value` is ignored.
    Outage,
    /// The received power changes by `value` dB (negative: weaker).
    PowerStep,
    /// The code (pseudorange) is delayed by `value` m; the carrier is untouched.
    CodeStep,
    /// Ionospheric ramp of `value` m/s from `start_s`: the code is delayed and the carrier
    /// advanced by `value (t - start_s)` m.
    IonoRamp,
    /// The carrier phase jumps by `value` cycles (a cycle slip when integer); code untouched.
    PhaseJump,
}

impl EventKind {
    /// The TOML name of the kind (`power-step`, ...).
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Outage => "outage",
            EventKind::PowerStep => "power-step",
            EventKind::CodeStep => "code-step",
            EventKind::IonoRamp => "iono-ramp",
            EventKind::PhaseJump => "phase-jump",
        }
    }

    /// The range of `value` for this kind, with its unit (`None` for an outage, which has
    /// no value).
    pub fn value_range(self) -> Option<Allowed> {
        match self {
            EventKind::Outage => None,
            // assumed: 100 dB down is an outage in all but name; 40 dB up is past any
            // signal a receiver sees outdoors.
            EventKind::PowerStep => Some(Allowed::closed(-100.0, 40.0, "dB")),
            // assumed: 100 km, far beyond the metres to kilometres of the faults an
            // integrity monitor is tested on.
            EventKind::CodeStep => Some(Allowed::closed(-100e3, 100e3, "m")),
            // assumed: 1 km/s, ten times the fastest ramp the RAIM tables inject (100 m/s,
            // validate::integrity::raim); an ionospheric gradient stays below 1 m/s.
            EventKind::IonoRamp => Some(Allowed::closed(-1000.0, 1000.0, "m/s")),
            // assumed: a million cycles (190 km), as the code step.
            EventKind::PhaseJump => Some(Allowed::closed(-1e6, 1e6, "cycles")),
        }
    }
}

/// `[[errors.events]]`: a fault on `antenna` (None: all) x `satellite` (None: all) over
/// `[start_s, end_s)` of receive time from the scenario start.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventConfig {
    pub kind: EventKind,
    /// Antenna name (`[[antennas]]` `name`); absent: every antenna.
    #[serde(default)]
    pub antenna: Option<String>,
    /// Satellite (`G05`, `C23`); absent: every satellite.
    #[serde(default)]
    pub satellite: Option<String>,
    /// Start of the fault (s from the scenario start, inclusive).
    pub start_s: f64,
    /// End of the fault (s from the scenario start, exclusive; may lie beyond the end).
    pub end_s: f64,
    /// Size of the fault in the unit of its kind ([`EventKind::value_range`]); required
    /// except for an outage. Absent is stored as NaN so `check` can tell.
    #[serde(default = "absent_value")]
    pub value: f64,
}

fn absent_value() -> f64 {
    f64::NAN
}

/// What the active events do to one link at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventEffect {
    /// Factor on the signal amplitude: 1 none, 0 outage, `10^(dB / 20)` for power steps.
    pub amplitude_factor: f64,
    /// Extra code delay (m, positive: longer pseudorange).
    pub code_m: f64,
    /// Carrier phase change expressed as range (m): negative shortens the carrier range
    /// (phase advance, as for the ionosphere).
    pub carrier_m: f64,
    /// Extra carrier phase (cycles) from phase jumps, added to the carrier range.
    pub carrier_cycles: f64,
}

impl EventEffect {
    /// No event active.
    pub const NONE: EventEffect = EventEffect {
        amplitude_factor: 1.0,
        code_m: 0.0,
        carrier_m: 0.0,
        carrier_cycles: 0.0,
    };

    /// The effect on another signal of the satellite, whose ionospheric delay is
    /// `iono_scale` times this one's: the ionospheric ramp (the only carrier range term,
    /// `-carrier_m`, also in the code) scales; code steps, phase jumps (the same cycles)
    /// and power steps act alike on every signal.
    pub fn with_iono_scale(self, iono_scale: f64) -> Self {
        let ramp_m = -self.carrier_m;
        Self {
            code_m: self.code_m + (iono_scale - 1.0) * ramp_m,
            carrier_m: iono_scale * self.carrier_m,
            ..self
        }
    }
}

impl EventConfig {
    /// Checks for a scenario of `duration_s` seconds: `start_s` finite in
    /// `[0, duration_s)`, `end_s > start_s` (not NaN; +inf allowed), `value` finite unless
    /// the kind is an outage, `satellite` a valid id. Antenna names are resolved by
    /// [`EventSchedule::new`]. Field paths are relative to the `[[errors.events]]` entry.
    pub fn check(&self, duration_s: f64) -> Result<(), Invalid> {
        if !(self.start_s.is_finite() && self.start_s >= 0.0 && self.start_s < duration_s) {
            return Err(Invalid::new(
                "start_s",
                self.start_s,
                format!("must be in [0, {duration_s}) s, inside the scenario"),
            ));
        }
        if self.end_s.is_nan() || self.end_s <= self.start_s {
            return Err(Invalid::new(
                "end_s",
                self.end_s,
                format!("must be greater than start_s ({})", self.start_s),
            ));
        }
        if let Some(range) = self.kind.value_range()
            && !range.contains(self.value)
        {
            let shown = if self.value.is_nan() {
                "absent".to_string()
            } else {
                shown(self.value)
            };
            return Err(Invalid::new(
                "value",
                shown,
                format!("a {} event needs a value in {range}", self.kind.name()),
            ));
        }
        if let Some(text) = &self.satellite {
            parse_sat(text)?;
        }
        if let Some(name) = &self.antenna
            && name.trim().is_empty()
        {
            return Err(Invalid::new(
                "antenna",
                format!("{name:?}"),
                "must name an antenna (omit it for every antenna)",
            ));
        }
        Ok(())
    }
}

fn parse_sat(text: &str) -> Result<SatId, Invalid> {
    text.parse::<SatId>().map_err(|e| {
        Invalid::new(
            "satellite",
            format!("{text:?}"),
            format!("{e}; omit it for every satellite"),
        )
    })
}

/// One event with its links resolved.
#[derive(Debug, Clone, PartialEq)]
struct ResolvedEvent {
    kind: EventKind,
    /// Antenna index; None: every antenna.
    antenna: Option<usize>,
    /// None: every satellite.
    sat: Option<SatId>,
    start_s: f64,
    end_s: f64,
    value: f64,
}

impl ResolvedEvent {
    fn applies(&self, t_s: f64, antenna: usize, sat: SatId) -> bool {
        t_s >= self.start_s
            && t_s < self.end_s
            && self.antenna.is_none_or(|a| a == antenna)
            && self.sat.is_none_or(|s| s == sat)
    }
}

/// Resolved events (antenna names -> indices, satellite strings -> [`SatId`]) for lookup
/// per link and instant.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EventSchedule {
    events: Vec<ResolvedEvent>,
}

impl EventSchedule {
    /// Resolves `events` against the scenario's antenna names (index = position in
    /// `antennas`) and satellites. An unknown antenna or a satellite that is not in `sats`
    /// is an error whose field path names the event: `events[2].antenna`. Call
    /// [`EventConfig::check`] first for the numeric fields.
    pub fn new(events: &[EventConfig], antennas: &[&str], sats: &[SatId]) -> Result<Self, Invalid> {
        let resolved = events
            .iter()
            .enumerate()
            .map(|(i, event)| {
                resolve(event, antennas, sats).map_err(|e| e.within(&format!("events[{i}]")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { events: resolved })
    }

    /// True when there are no events at all.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// Combined effect at receive time `t_s` (s from the scenario start) on the link
    /// (antenna index `antenna`, satellite `sat`).
    pub fn effect(&self, t_s: f64, antenna: usize, sat: SatId) -> EventEffect {
        let mut effect = EventEffect::NONE;
        let mut outage = false;
        let mut power_db = 0.0;
        for event in self.events.iter().filter(|e| e.applies(t_s, antenna, sat)) {
            match event.kind {
                EventKind::Outage => outage = true,
                EventKind::PowerStep => power_db += event.value,
                EventKind::CodeStep => effect.code_m += event.value,
                EventKind::IonoRamp => {
                    let delay_m = event.value * (t_s - event.start_s);
                    effect.code_m += delay_m;
                    effect.carrier_m -= delay_m;
                }
                EventKind::PhaseJump => effect.carrier_cycles += event.value,
            }
        }
        effect.amplitude_factor = if outage {
            0.0
        } else {
            10f64.powf(power_db / 20.0)
        };
        effect
    }
}

fn resolve(
    event: &EventConfig,
    antennas: &[&str],
    sats: &[SatId],
) -> Result<ResolvedEvent, Invalid> {
    let antenna = match &event.antenna {
        None => None,
        Some(name) => Some(antennas.iter().position(|a| a == name).ok_or_else(|| {
            Invalid::new(
                "antenna",
                format!("{name:?}"),
                format!("must be one of the scenario's antennas {antennas:?}"),
            )
        })?),
    };
    let sat = match &event.satellite {
        None => None,
        Some(text) => {
            let sat = parse_sat(text)?;
            if !sats.contains(&sat) {
                return Err(Invalid::new(
                    "satellite",
                    format!("{text:?}"),
                    "must be a satellite of the scenario's constellations",
                ));
            }
            Some(sat)
        }
    };
    Ok(ResolvedEvent {
        kind: event.kind,
        antenna,
        sat,
        start_s: event.start_s,
        end_s: event.end_s,
        value: if event.kind == EventKind::Outage {
            0.0
        } else {
            event.value
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(kind: EventKind, value: f64) -> EventConfig {
        EventConfig {
            kind,
            antenna: None,
            satellite: None,
            start_s: 10.0,
            end_s: 20.0,
            value,
        }
    }

    const ANTENNAS: [&str; 2] = ["top", "side"];

    fn sats() -> Vec<SatId> {
        vec![SatId::gps(5), SatId::gps(7), SatId::beidou(23)]
    }

    fn schedule(events: &[EventConfig]) -> EventSchedule {
        EventSchedule::new(events, &ANTENNAS, &sats()).expect("valid events")
    }

    #[test]
    fn each_kind_alone() {
        let g05 = SatId::gps(5);
        let outage = schedule(&[event(EventKind::Outage, f64::NAN)]);
        assert_eq!(outage.effect(15.0, 0, g05).amplitude_factor, 0.0);
        // -6.0206 dB is half the amplitude (20 log10 0.5).
        let power = schedule(&[event(EventKind::PowerStep, 20.0 * 0.5f64.log10())]);
        assert!((power.effect(15.0, 0, g05).amplitude_factor - 0.5).abs() < 1e-12);
        let code = schedule(&[event(EventKind::CodeStep, 3.5)]);
        assert_eq!(
            code.effect(15.0, 1, g05),
            EventEffect {
                code_m: 3.5,
                ..EventEffect::NONE
            }
        );
        // 0.1 m/s for 4 s: code +0.4 m, carrier -0.4 m (diverging by 0.8 m).
        let ramp = schedule(&[event(EventKind::IonoRamp, 0.1)]);
        let e = ramp.effect(14.0, 0, g05);
        assert!((e.code_m - 0.4).abs() < 1e-12 && (e.carrier_m + 0.4).abs() < 1e-12);
        assert_eq!((e.amplitude_factor, e.carrier_cycles), (1.0, 0.0));
        assert_eq!(ramp.effect(10.0, 0, g05), EventEffect::NONE);
        let jump = schedule(&[event(EventKind::PhaseJump, 100.0)]);
        assert_eq!(
            jump.effect(15.0, 0, g05),
            EventEffect {
                carrier_cycles: 100.0,
                ..EventEffect::NONE
            }
        );
    }

    #[test]
    fn window_is_start_inclusive_end_exclusive() {
        let s = schedule(&[event(EventKind::CodeStep, 1.0)]);
        let g07 = SatId::gps(7);
        assert_eq!(s.effect(9.999_999, 0, g07).code_m, 0.0);
        assert_eq!(s.effect(10.0, 0, g07).code_m, 1.0);
        assert_eq!(s.effect(19.999_999, 0, g07).code_m, 1.0);
        assert_eq!(s.effect(20.0, 0, g07).code_m, 0.0);
    }

    #[test]
    fn overlaps_combine() {
        let g05 = SatId::gps(5);
        let mut late = event(EventKind::PowerStep, -3.0);
        late.start_s = 15.0;
        let steps = schedule(&[event(EventKind::PowerStep, -3.0), late.clone()]);
        assert!(
            (steps.effect(12.0, 0, g05).amplitude_factor - 10f64.powf(-3.0 / 20.0)).abs() < 1e-15
        );
        // Both: -6 dB in power = 10^(-6/20) in amplitude.
        assert!((steps.effect(16.0, 0, g05).amplitude_factor - 10f64.powf(-0.3)).abs() < 1e-15);
        // An outage wins over a +10 dB step; code and carrier terms still add.
        let mixed = schedule(&[
            event(EventKind::PowerStep, 10.0),
            event(EventKind::Outage, f64::NAN),
            event(EventKind::CodeStep, 1.0),
            event(EventKind::CodeStep, 2.0),
            event(EventKind::PhaseJump, 0.5),
        ]);
        let e = mixed.effect(12.0, 1, g05);
        assert_eq!(e.amplitude_factor, 0.0);
        assert_eq!((e.code_m, e.carrier_cycles), (3.0, 0.5));
    }

    #[test]
    fn events_select_their_links() {
        let mut only = event(EventKind::CodeStep, 1.0);
        only.antenna = Some("side".into());
        only.satellite = Some("C23".into());
        let s = schedule(&[only]);
        assert_eq!(s.effect(12.0, 1, SatId::beidou(23)).code_m, 1.0);
        assert_eq!(s.effect(12.0, 0, SatId::beidou(23)).code_m, 0.0);
        assert_eq!(s.effect(12.0, 1, SatId::gps(5)).code_m, 0.0);
        assert!(!s.is_empty());
        assert!(schedule(&[]).is_empty());
    }

    #[test]
    fn unknown_links_name_the_event() {
        let mut bad_antenna = event(EventKind::Outage, f64::NAN);
        bad_antenna.antenna = Some("bottom".into());
        let err = EventSchedule::new(
            &[event(EventKind::Outage, 0.0), bad_antenna],
            &ANTENNAS,
            &sats(),
        )
        .expect_err("unknown antenna");
        assert_eq!(err.field, "events[1].antenna");
        assert!(err.allowed.contains("top"));
        let mut absent_sat = event(EventKind::Outage, f64::NAN);
        absent_sat.satellite = Some("G09".into());
        let err = EventSchedule::new(&[absent_sat], &ANTENNAS, &sats()).expect_err("G09");
        assert_eq!(err.field, "events[0].satellite");
        let mut garbled = event(EventKind::Outage, f64::NAN);
        garbled.satellite = Some("X05".into());
        let err = EventSchedule::new(&[garbled], &ANTENNAS, &sats()).expect_err("X05");
        assert_eq!(err.field, "events[0].satellite");
    }

    #[test]
    fn check_names_bad_fields() {
        let duration_s = 60.0;
        assert_eq!(event(EventKind::Outage, f64::NAN).check(duration_s), Ok(()));
        let forever = EventConfig {
            end_s: f64::INFINITY,
            ..event(EventKind::PhaseJump, 1.0)
        };
        assert_eq!(forever.check(duration_s), Ok(()));
        let cases = [
            (
                EventConfig {
                    start_s: -1.0,
                    ..event(EventKind::Outage, 0.0)
                },
                "start_s",
            ),
            (
                EventConfig {
                    start_s: 60.0,
                    end_s: 70.0,
                    ..event(EventKind::Outage, 0.0)
                },
                "start_s",
            ),
            (
                EventConfig {
                    end_s: 10.0,
                    ..event(EventKind::Outage, 0.0)
                },
                "end_s",
            ),
            (
                EventConfig {
                    end_s: f64::NAN,
                    ..event(EventKind::Outage, 0.0)
                },
                "end_s",
            ),
            (event(EventKind::PowerStep, f64::NAN), "value"),
            (event(EventKind::IonoRamp, f64::INFINITY), "value"),
            (
                EventConfig {
                    satellite: Some("G99".into()),
                    ..event(EventKind::Outage, 0.0)
                },
                "satellite",
            ),
            (
                EventConfig {
                    antenna: Some(" ".into()),
                    ..event(EventKind::Outage, 0.0)
                },
                "antenna",
            ),
        ];
        for (config, field) in cases {
            assert_eq!(config.check(duration_s).expect_err(field).field, field);
        }
        let err = event(EventKind::PowerStep, f64::NAN)
            .check(duration_s)
            .expect_err("value");
        assert_eq!(err.value, "absent");
        assert!(err.allowed.contains("dB"));
    }

    #[test]
    fn deserialises_kebab_case_kinds_and_optional_value() {
        let outage: EventConfig =
            serde_json::from_str(r#"{"kind": "outage", "start_s": 1, "end_s": 2}"#)
                .expect("outage");
        assert_eq!(outage.kind, EventKind::Outage);
        assert!(outage.value.is_nan());
        assert_eq!(outage.check(10.0), Ok(()));
        for kind in [
            EventKind::Outage,
            EventKind::PowerStep,
            EventKind::CodeStep,
            EventKind::IonoRamp,
            EventKind::PhaseJump,
        ] {
            let json = format!(
                r#"{{"kind": "{}", "start_s": 1, "end_s": 2, "value": 1}}"#,
                kind.name()
            );
            let parsed: EventConfig = serde_json::from_str(&json).expect("kind");
            assert_eq!(parsed.kind, kind);
        }
        assert!(
            serde_json::from_str::<EventConfig>(r#"{"kind": "ramp", "start_s": 1, "end_s": 2}"#)
                .is_err()
        );
    }
}
