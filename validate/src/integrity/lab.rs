//! Paper 002's laboratory set-up (the bundled `integrity-lab` scenario) with its fault
//! cases, run at the observation level and monitored.

use skyforge_navigation::integrity::{MonitorConfig, MonitorEpoch, Unmonitored};
use skyforge_navigation::integrity::{run_files, stations};
use skyforge_runner::{ObservationRun, observation_run};
use skyforge_scenarios::Scenario;
use std::path::Path;

/// The bundled scenario of the set-up.
pub const SCENARIO: &str = "integrity-lab";
/// The faulted station and satellite of the paper's cases (digest 2.3: station C,
/// "satellite 3", read as BeiDou C03).
pub const FAULT_STATION: &str = "C";
pub const FAULT_SATELLITE: &str = "C03";

/// Paper 002 section 4.2: the cases, each as the `[[errors.events]]` it adds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Case {
    FaultFree,
    /// 100 cycles at 500 s on C03 at station C, kept to the end (4.2.2).
    CycleSlip,
    /// 30 m on the pseudorange of C03 at station C, 600-605 s (4.2.3).
    Multipath,
    /// 0.1 m/s ionospheric ramp on C03, 500-673 s, at station C only (4.2.4 as printed).
    IonoRampAtC,
    /// The same ramp at every station (the reading the paper's results fit; digest 2.3).
    IonoRampCommon,
}

impl Case {
    /// Every case, in table order.
    pub const ALL: [Case; 5] = [
        Case::FaultFree,
        Case::CycleSlip,
        Case::Multipath,
        Case::IonoRampAtC,
        Case::IonoRampCommon,
    ];

    /// Short name in rows and errors.
    pub fn name(self) -> &'static str {
        match self {
            Case::FaultFree => "fault-free",
            Case::CycleSlip => "cycle slip",
            Case::Multipath => "multipath",
            Case::IonoRampAtC => "iono ramp at C",
            Case::IonoRampCommon => "common iono ramp",
        }
    }

    /// The fault as events: (kind, station or every one, start, end, value).
    pub fn events(self) -> Vec<Fault> {
        let at_c = Some(FAULT_STATION);
        match self {
            Case::FaultFree => vec![],
            Case::CycleSlip => vec![Fault::new("phase-jump", at_c, 500.0, 1800.0, 100.0)],
            Case::Multipath => vec![Fault::new("code-step", at_c, 600.0, 605.0, 30.0)],
            Case::IonoRampAtC => vec![Fault::new("iono-ramp", at_c, 500.0, 673.0, 0.1)],
            Case::IonoRampCommon => vec![Fault::new("iono-ramp", None, 500.0, 673.0, 0.1)],
        }
    }
}

/// One injected fault on [`FAULT_SATELLITE`] (or another satellite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fault {
    pub kind: &'static str,
    pub station: Option<&'static str>,
    pub satellite: &'static str,
    pub start_s: f64,
    pub end_s: f64,
    pub value: f64,
}

impl Fault {
    /// A fault on [`FAULT_SATELLITE`].
    pub fn new(
        kind: &'static str,
        station: Option<&'static str>,
        start_s: f64,
        end_s: f64,
        value: f64,
    ) -> Self {
        Self {
            kind,
            station,
            satellite: FAULT_SATELLITE,
            start_s,
            end_s,
            value,
        }
    }

    /// The fault as a `[[errors.events]]` table.
    pub fn toml(&self) -> String {
        let station = self
            .station
            .map(|s| format!("antenna = \"{s}\"\n"))
            .unwrap_or_default();
        format!(
            "\n[[errors.events]]\nkind = \"{}\"\n{station}satellite = \"{}\"\nstart_s = {:?}\nend_s = {:?}\nvalue = {:?}\n",
            self.kind, self.satellite, self.start_s, self.end_s, self.value
        )
    }
}

/// The lab scenario with `faults`, on `seed`, lasting `duration_s` (the bundled 1800 s
/// when `None`).
pub fn scenario(faults: &[Fault], seed: u64, duration_s: Option<f64>) -> Result<Scenario, String> {
    let bundled = skyforge_scenarios::bundled()
        .iter()
        .find(|b| b.name == SCENARIO)
        .ok_or_else(|| format!("no bundled scenario {SCENARIO}"))?;
    let mut text = bundled.text.to_string();
    if let Some(d) = duration_s {
        text = text.replace("duration_s = 1800.0", &format!("duration_s = {d:?}"));
    }
    for f in faults {
        text.push_str(&f.toml());
    }
    let mut s = skyforge_scenarios::parse(&text, &format!("bundled:{SCENARIO}"), Path::new("."))
        .map_err(|e| e.to_string())?;
    s.seed = seed;
    Ok(s)
}

/// A monitored run: the observation-level run and the monitor's epochs.
#[derive(Debug)]
pub struct MonitoredRun {
    pub run: ObservationRun,
    pub epochs: Vec<MonitorEpoch>,
    /// The satellite-epochs the monitor could not monitor, by reason.
    pub unmonitored: Unmonitored,
}

/// Run `scenario` at the observation level and monitor its four receivers.
pub fn monitored(scenario: &Scenario, config: &MonitorConfig) -> Result<MonitoredRun, String> {
    let fail = |e: &dyn std::fmt::Display| format!("{} seed {}: {e}", scenario.name, scenario.seed);
    let run = observation_run(scenario).map_err(|e| fail(&e))?;
    let mut epochs = Vec::with_capacity(run.platform.len());
    let stations = stations(&run.measured, &run.antennas, config).map_err(|e| fail(&e))?;
    let monitored = run_files(
        &run.measured,
        stations,
        run.ephemerides.clone(),
        config.clone(),
        |e| epochs.push(e.clone()),
    )
    .map_err(|e| fail(&e))?;
    Ok(MonitoredRun {
        run,
        epochs,
        unmonitored: monitored.unmonitored,
    })
}
