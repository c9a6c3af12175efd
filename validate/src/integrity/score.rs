//! `skyforge monitor run`'s alarms against the fault events of the run's scenario
//! (`skyforge validate monitor`): detection and its delay per event, the statistic and
//! station that flagged it first, and alarms no event explains (false alarms).

use serde::Serialize;
use skyforge_formats::monitor::{Alarm, MonitorRecord};
use skyforge_formats::truth::{TRUTH_H5, TruthFile};
use skyforge_signals::errors::EventConfig;
use std::path::Path;

/// How long after an event's end its satellite's alarms are still its own (s).
/// # assumed: the smoothed code keeps 1 % of a step 460 s later, the divergence is tested
/// 300 s after it starts; 600 s covers both. Chosen before any run.
pub const HOLD_S: f64 = 600.0;

/// The scenario a run was made from: the `scenario_toml` attribute of `run_dir/truth.h5`.
pub fn run_scenario(run_dir: &Path) -> Result<skyforge_scenarios::Scenario, String> {
    let path = run_dir.join(TRUTH_H5);
    let text = TruthFile::open(&path)
        .and_then(|f| f.scenario_toml())
        .map_err(|e| e.to_string())?;
    skyforge_scenarios::parse(&text, &path.display().to_string(), run_dir)
        .map_err(|e| format!("{}: attribute scenario_toml: {e}", path.display()))
}

/// How far (s) a monitor's epochs may lie outside its run's span: the receive times of
/// the observation files, a few tens of milliseconds from the scenario's grid.
const SPAN_MARGIN_S: f64 = 1.0;

/// `record` (from `monitor_csv`) is of the run of `scenario` (from `truth`): its epochs lie
/// within the run's span and its stations are the run's antennas. Scoring another run's
/// alarms against these events would report detections and false alarms of nothing.
pub fn check_same_run(
    scenario: &skyforge_scenarios::Scenario,
    record: &MonitorRecord,
    monitor_csv: &Path,
    truth: &Path,
) -> Result<(), String> {
    let csv = monitor_csv.display();
    let Some((first_s, last_s)) = record.span_s else {
        return Err(format!("{csv}: no rows; the monitor monitored nothing"));
    };
    let duration = scenario.time.duration_s;
    if first_s < -SPAN_MARGIN_S || last_s > duration + SPAN_MARGIN_S {
        return Err(format!(
            "{csv}: epochs from {first_s:.1} s to {last_s:.1} s after the start of the run in {} \
             ({}, {duration} s from {}): the monitor watched another run",
            truth.display(),
            scenario.name,
            scenario.time.start
        ));
    }
    let antennas: Vec<&str> = scenario.antennas.iter().map(|a| a.name.as_str()).collect();
    let strangers: Vec<&str> = record
        .stations
        .iter()
        .map(String::as_str)
        .filter(|s| !antennas.contains(s))
        .collect();
    if !strangers.is_empty() {
        return Err(format!(
            "{csv}: stations {} are not antennas of the run in {} ({}: {}): the monitor \
             watched another run",
            strangers.join(", "),
            truth.display(),
            scenario.name,
            antennas.join(", ")
        ));
    }
    Ok(())
}

/// How one fault event was seen.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventOutcome {
    pub kind: String,
    pub antenna: Option<String>,
    pub satellite: Option<String>,
    pub start_s: f64,
    pub end_s: f64,
    pub detected: bool,
    /// First alarm on the event's satellite(s) from its start, minus the start (s).
    pub delay_s: Option<f64>,
    pub first_statistic: Option<String>,
    /// The station with the largest |B| / threshold at the first alarm.
    pub first_station: Option<String>,
    /// Whether that station is the event's antenna (an event at every antenna: `None`).
    pub isolated: Option<bool>,
    /// First loss of lock the receivers flagged on the event's satellite(s) from its
    /// start, minus the start (s), and the station: the receiver's own detection.
    pub lock_lost_s: Option<f64>,
    pub lock_lost_station: Option<String>,
}

/// The comparison.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MonitorScore {
    pub events: Vec<EventOutcome>,
    pub alarms: usize,
    /// Alarms on satellites no event touches, or outside every event's span plus
    /// [`HOLD_S`].
    pub false_alarms: usize,
    /// The first few of them: (t_s, station, satellite, statistic).
    pub false_alarm_examples: Vec<(f64, String, String, String)>,
}

/// Whether `event` explains an alarm on `sat` at `t_s`.
fn explains(event: &EventConfig, sat: &str, t_s: f64) -> bool {
    event.satellite.as_deref().is_none_or(|s| s == sat)
        && t_s >= event.start_s
        && t_s < event.end_s + HOLD_S
}

/// Score the monitor's `record` against `events`.
pub fn score(events: &[EventConfig], record: &MonitorRecord) -> MonitorScore {
    let alarms = &record.alarms;
    let outcomes = events
        .iter()
        .map(|e| {
            let flag = record
                .flags
                .iter()
                .filter(|f| explains(e, &f.sat, f.t_s))
                .min_by(|a, b| a.t_s.total_cmp(&b.t_s));
            let first_t = alarms
                .iter()
                .filter(|a| explains(e, &a.sat, a.t_s))
                .map(|a| a.t_s)
                .min_by(f64::total_cmp);
            let at_first: Vec<&Alarm> = alarms
                .iter()
                .filter(|a| Some(a.t_s) == first_t && explains(e, &a.sat, a.t_s))
                .collect();
            let strongest = at_first.iter().max_by(|a, b| a.ratio.total_cmp(&b.ratio));
            EventOutcome {
                kind: e.kind.name().to_string(),
                antenna: e.antenna.clone(),
                satellite: e.satellite.clone(),
                start_s: e.start_s,
                end_s: e.end_s,
                detected: first_t.is_some(),
                delay_s: first_t.map(|t| t - e.start_s),
                first_statistic: strongest.map(|a| a.statistic.clone()),
                first_station: strongest.map(|a| a.station.clone()),
                isolated: e
                    .antenna
                    .as_ref()
                    .and_then(|ant| strongest.map(|a| &a.station == ant)),
                lock_lost_s: flag.map(|f| f.t_s - e.start_s),
                lock_lost_station: flag.map(|f| f.station.clone()),
            }
        })
        .collect();
    let false_alarms: Vec<&Alarm> = alarms
        .iter()
        .filter(|a| !events.iter().any(|e| explains(e, &a.sat, a.t_s)))
        .collect();
    MonitorScore {
        events: outcomes,
        alarms: alarms.len(),
        false_alarms: false_alarms.len(),
        false_alarm_examples: false_alarms
            .iter()
            .take(10)
            .map(|a| (a.t_s, a.station.clone(), a.sat.clone(), a.statistic.clone()))
            .collect(),
    }
}

/// Print `score` as a table.
pub fn print_score(score: &MonitorScore, out: &mut impl std::io::Write) -> std::io::Result<()> {
    writeln!(
        out,
        "{:<11} {:<7} {:<5} {:>8} {:>8}  {:<9} {:>8}  {:<14} {:<7} {:<8}  lock lost (s, station)",
        "event",
        "antenna",
        "sat",
        "start_s",
        "end_s",
        "detected",
        "delay_s",
        "first by",
        "station",
        "isolated"
    )?;
    let opt = |v: &Option<String>| v.clone().unwrap_or_else(|| "all".into());
    for e in &score.events {
        writeln!(
            out,
            "{:<11} {:<7} {:<5} {:>8.1} {:>8.1}  {:<9} {:>8}  {:<14} {:<7} {:<8}  {}",
            e.kind,
            opt(&e.antenna),
            opt(&e.satellite),
            e.start_s,
            e.end_s,
            if e.detected { "yes" } else { "MISSED" },
            e.delay_s.map_or("-".into(), |d| format!("{d:.1}")),
            e.first_statistic.clone().unwrap_or_else(|| "-".into()),
            e.first_station.clone().unwrap_or_else(|| "-".into()),
            e.isolated.map_or("-", |i| if i { "yes" } else { "no" }),
            match (&e.lock_lost_s, &e.lock_lost_station) {
                (Some(t), Some(s)) => format!("{t:.1} {s}"),
                _ => "-".into(),
            },
        )?;
    }
    writeln!(
        out,
        "alarms {} ({} false: on no event's satellite and span + {HOLD_S} s)",
        score.alarms, score.false_alarms
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_formats::monitor::Flag;
    use skyforge_signals::errors::EventKind;

    fn alarm(t_s: f64, station: &str, sat: &str, ratio: f64) -> Alarm {
        Alarm {
            t_s,
            station: station.into(),
            sat: sat.into(),
            statistic: "carrier".into(),
            ratio,
        }
    }

    #[test]
    fn events_are_detected_isolated_and_other_alarms_are_false() {
        let slip = EventConfig {
            kind: EventKind::PhaseJump,
            antenna: Some("C".into()),
            satellite: Some("C03".into()),
            start_s: 500.0,
            end_s: 1800.0,
            value: 100.0,
        };
        let missed = EventConfig {
            satellite: Some("G07".into()),
            start_s: 100.0,
            end_s: 110.0,
            ..slip.clone()
        };
        let alarms = vec![
            alarm(501.0, "A", "C03", 7.0),
            alarm(501.0, "C", "C03", 20.0),
            alarm(1000.0, "C", "C03", 20.0),
            alarm(300.0, "C", "C03", 2.0), // before the slip: false
            alarm(900.0, "B", "G01", 2.0), // no event on G01: false
        ];
        let record = MonitorRecord {
            alarms,
            flags: vec![Flag {
                t_s: 105.0,
                station: "C".into(),
                sat: "G07".into(),
            }],
            ..MonitorRecord::default()
        };
        let s = score(&[slip, missed], &record);
        assert!(s.events[0].detected);
        assert_eq!(s.events[0].delay_s, Some(1.0));
        assert_eq!(s.events[0].first_station.as_deref(), Some("C"));
        assert_eq!(s.events[0].isolated, Some(true));
        assert!(!s.events[1].detected);
        assert_eq!(s.events[1].lock_lost_s, Some(5.0));
        assert_eq!(s.events[1].lock_lost_station.as_deref(), Some("C"));
        assert_eq!(s.events[0].lock_lost_s, None);
        assert_eq!((s.alarms, s.false_alarms), (5, 2));
    }
}
