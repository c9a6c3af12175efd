//! Single-epoch ambiguity resolution on two frequencies at the signal level (issue #34's
//! acceptance): the bundled `attitude-leo-l1-l5` (thesis LEO, three antennas on two 1 m
//! baselines, 60 s of GPS L1 C/A and L5 I/Q at 45 dB-Hz, 20.46 Msps) synthesised and
//! received on each of four seeds, its observations through the chain resolving every
//! epoch on its own (plain LAMBDA, the best candidate taken whatever its ratio) with L1
//! C/A alone and with L1 C/A + L5; beside it the same scenario at the observation level
//! with the noise calibrated on the same receiver, signals, sample rate and C/N0
//! (`scenarios/calibration/gps-l1-l5.toml`, measured on another seed and part of the
//! orbit), on eight seeds.
//!
//! Long (four signal-level runs of three antennas on two carriers): `scripts/acceptance.sh`.

use skyforge_gnss::signal::Signal;
use skyforge_navigation::relative::Constraint;
use skyforge_scenarios::Scenario;
use skyforge_signals::obs_model::{Level, ObsNoiseConfig};
use skyforge_validate::attitude::{SuccessRate, single_epoch_each};
use skyforge_validate::draw::Draw;

const L1: &[Signal] = &[Signal::GpsL1Ca];
const L1_L5: &[Signal] = &[Signal::GpsL1Ca, Signal::GpsL5];

/// The bundled scenario at `level`; at the observation level with the L1 C/A + L5
/// calibration.
fn scenario(level: Level) -> Scenario {
    let mut s = skyforge_scenarios::resolve("attitude-leo-l1-l5").unwrap();
    s.observation.level = level;
    if level == Level::Observation {
        let file = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../scenarios/calibration/gps-l1-l5.toml"
        );
        s.observation.noise = ObsNoiseConfig::Calibrated {
            file: Some(file.into()),
        };
    }
    s
}

/// Two standard errors of the difference of `a` and `b` (runs independent).
fn two_se(a: &SuccessRate, b: &SuccessRate) -> f64 {
    let se = |r: &SuccessRate| r.success.standard_error.unwrap_or(0.0);
    2.0 * (se(a).powi(2) + se(b).powi(2)).sqrt()
}

/// Runs at the signal level: # assumed: four, the most that fit in about an hour on the
/// project's two cores (some 12 minutes each); the observation level keeps its registered
/// eight.
const SIGNAL_RUNS: u64 = 4;

#[test]
#[ignore = "long: four signal-level runs of three antennas on L1 C/A and L5 (tens of minutes)"]
fn two_frequencies_fix_single_epochs_at_least_as_often_and_as_the_observation_level_says() {
    let rates = |level, draw| {
        single_epoch_each(&scenario(level), &[L1, L1_L5], Constraint::None, draw).unwrap()
    };
    let observation = rates(Level::Observation, Draw::REGISTERED);
    for r in &observation {
        println!(
            "SINGLE_EPOCH {:?} observation level: {}",
            r.signals,
            r.summary()
        );
    }
    let signal = rates(
        Level::Signal,
        Draw {
            offset: 0,
            runs: Some(SIGNAL_RUNS),
        },
    );
    for (name, s, o) in [
        ("GPS L1 C/A", &signal[0], &observation[0]),
        ("GPS L1 C/A + L5", &signal[1], &observation[1]),
    ] {
        println!("SINGLE_EPOCH {name:16} signal level:      {}", s.summary());
        println!("SINGLE_EPOCH {name:16} observation level: {}", o.summary());
    }
    let (l1, l15) = (&signal[0], &signal[1]);
    assert!(
        l15.success.mean >= l1.success.mean - two_se(l15, l1),
        "L1 + L5 {:?} below L1 {:?}",
        l15.success,
        l1.success
    );
    for (s, o) in signal.iter().zip(&observation) {
        assert!(
            (s.success.mean - o.success.mean).abs() <= two_se(s, o),
            "{:?}: signal level {:?}, observation level {:?}",
            s.signals,
            s.success,
            o.success
        );
    }
}
