//! The observation level (`[observation] level = "observation"`): observables drawn from
//! the link truth and a noise model, written where `skyforge receive` writes its own.
//!
//! The acceptance tier checks the bundled calibration against the signal level on
//! scenarios it was not measured on.

mod support;

use skyforge_orbits::ephemeris::System;
use skyforge_validate::observables::{ObsComparison, compare, read_obs_file};
use std::path::{Path, PathBuf};
use support::{receive_all_recordings, skyforge_ok};

/// The calibration scenario with `duration_s`, `seed`, `start` and extra TOML.
fn scenario(dir: &Path, name: &str, duration_s: u32, seed: u64, extra: &str) -> String {
    let base = include_str!("../../scenarios/calibration/leo-gps-bds.toml");
    let text = base
        .replacen(
            "duration_s = 130.0",
            &format!("duration_s = {duration_s}.0"),
            1,
        )
        .replacen("seed = 20261125", &format!("seed = {seed}"), 1)
        + extra;
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// Antenna `ant`'s observables in `estimate_dir` against the truth in `truth_dir`.
fn comparison(truth_dir: &Path, estimate_dir: &Path, ant: &str) -> ObsComparison {
    let file = format!("{ant}.obs.rnx");
    let truth = read_obs_file(&truth_dir.join(&file)).unwrap();
    let estimate = read_obs_file(&estimate_dir.join(&file)).unwrap();
    compare(&estimate, &truth).unwrap()
}

/// Code and phase error std (m) of `system`.
fn stds(c: &ObsComparison, system: System) -> (f64, f64) {
    let of = |e: &skyforge_validate::observables::compare::ObservableErrors| {
        e.per_system
            .iter()
            .find(|s| s.system == system)
            .and_then(|s| s.stats.std)
            .unwrap()
    };
    (of(&c.pseudorange_m), of(&c.carrier_phase_m))
}

const TWO_ANTENNAS: &str = r#"
[[antennas]]
name = "ant2"
position_body_m = [1.0, 0.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 80.0
"#;

/// `skyforge run` in `dir` of the calibration scenario ([`scenario`] `name`, `duration_s`,
/// `seed`) at the observation level on [`TWO_ANTENNAS`] with constant noise (code 0.4 m,
/// phase 2 mm), `observation` (whole lines) added to its `[observation]` table; returns
/// the output directory `dir/out`.
fn run_with_constant_noise(
    dir: &Path,
    name: &str,
    duration_s: u32,
    seed: u64,
    observation: &str,
) -> PathBuf {
    let extra = format!(
        "{TWO_ANTENNAS}\n[observation]\nlevel = \"observation\"\n{observation}[observation.noise]\nmodel = \"constant\"\nphase_m = 0.002\ncode_m = 0.4\n"
    );
    let path = scenario(dir, name, duration_s, seed, &extra);
    let out = dir.join("out");
    skyforge_ok(&["run", &path, "--out", out.to_str().unwrap()], dir);
    out
}

/// Constant noise: every antenna gets `observations/<antenna>.obs.rnx` and no recording;
/// against the truth, code and phase scatter as configured. The comparison removes a
/// clock offset per epoch fitted to about 20 pseudoranges (a few per cent less scatter)
/// and each arc's phase offset; with about 600 observations per system a std's standard
/// error is 3 %; 12 % covers both.
#[test]
fn observation_level_writes_receiver_style_files_with_the_configured_noise() {
    let dir = tempfile::tempdir().unwrap();
    let out = run_with_constant_noise(dir.path(), "obs", 40, 11, "");
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.contains("sigmf")), "{names:?}");
    for ant in ["ant1", "ant2"] {
        let c = comparison(&out, &out.join("observations"), ant);
        // The comparison evaluates the truth at each epoch's sample time, which may fall
        // just outside the truth's span at either end.
        assert!(c.matched_epochs >= 38, "{}", c.matched_epochs);
        for system in [System::Gps, System::Beidou] {
            let (code, phase) = stds(&c, system);
            assert!(
                (code / 0.4 - 1.0).abs() < 0.12,
                "{ant} {system:?} code {code}"
            );
            assert!(
                (phase / 0.002 - 1.0).abs() < 0.12,
                "{ant} {system:?} phase {phase}"
            );
        }
    }
}

/// `[observation] rate_hz = 10`: the truth's and the observables' files hold an epoch
/// every 0.1 s, and the noise is the configured one (as the 1 Hz test: about 800
/// observations per system, 12 %); a rate that does not divide 1000 and a rate at the
/// signal level are refused.
#[test]
fn observation_level_at_ten_hertz_writes_ten_epochs_a_second() {
    let dir = tempfile::tempdir().unwrap();
    let out = run_with_constant_noise(dir.path(), "obs10", 8, 11, "rate_hz = 10\n");
    for file in [
        out.join("ant1.obs.rnx"),
        out.join("observations/ant1.obs.rnx"),
    ] {
        let obs = read_obs_file(&file).unwrap();
        let steps: Vec<f64> = (obs.epochs.windows(2))
            .map(|w| (w[1].time - w[0].time).to_seconds())
            .collect();
        assert!(steps.len() >= 78, "{} epochs", obs.epochs.len());
        assert!(
            steps.iter().all(|s| (s - 0.1).abs() < 1e-6),
            "{}: {steps:?}",
            file.display()
        );
    }
    let c = comparison(&out, &out.join("observations"), "ant1");
    assert!(c.matched_epochs >= 78, "{}", c.matched_epochs);
    for system in [System::Gps, System::Beidou] {
        let (code, phase) = stds(&c, system);
        assert!((code / 0.4 - 1.0).abs() < 0.12, "{system:?} code {code}");
        assert!(
            (phase / 0.002 - 1.0).abs() < 0.12,
            "{system:?} phase {phase}"
        );
    }
    for (observation, named) in [
        ("level = \"observation\"\nrate_hz = 3\n", "divisor of 1000"),
        ("rate_hz = 10\n", "signal level"),
    ] {
        let text = format!("{TWO_ANTENNAS}\n[observation]\n{observation}");
        let path = scenario(dir.path(), "bad", 8, 11, &text);
        let o = support::skyforge(&["run", &path, "--out", "bad"], dir.path());
        assert!(
            !o.status.success() && support::text(&o).contains(named),
            "{}",
            support::text(&o)
        );
    }
}

/// A calibration file that is not one: one located error, nothing written.
#[test]
fn a_bad_calibration_file_is_one_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("cal.toml"), "scenario = 3\n").unwrap();
    let extra = "\n[observation]\nlevel = \"observation\"\n[observation.noise]\nmodel = \"calibrated\"\nfile = \"cal.toml\"\n";
    let path = scenario(dir.path(), "bad", 20, 1, extra);
    let out = dir.path().join("out");
    let o = support::skyforge(&["run", &path, "--out", out.to_str().unwrap()], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", support::text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("observation.noise.file") && err.contains("not a calibration file"),
        "{err}"
    );
    assert!(!out.exists());
}

/// The bundled calibration (measured on the calibration scenario, seed 20261125, starting
/// 2023-03-12T00:00) transfers to another seed and another hour of the orbit: per system,
/// the observation level's code and phase scatter against the truth is within 15 % of the
/// signal level's (tolerance chosen before the first run; each std has a standard error
/// of about 3-4 % at these sample sizes).
#[test]
#[ignore = "acceptance tier: a signal-level run (about a minute)"]
fn bundled_calibration_matches_the_signal_level_on_another_seed_and_hour() {
    let dir = tempfile::tempdir().unwrap();
    let moved = |extra: &str, name: &str| {
        let path = scenario(dir.path(), name, 70, 424242, extra);
        let text = std::fs::read_to_string(&path).unwrap().replacen(
            "2023-03-12T00:00:00 GPST",
            "2023-03-12T01:00:00 GPST",
            1,
        );
        std::fs::write(&path, text).unwrap();
        path
    };
    let signal = moved("", "signal");
    let observation = moved("\n[observation]\nlevel = \"observation\"\n", "observation");
    let sig_out = dir.path().join("sig");
    let rx_out = dir.path().join("rx");
    let obs_out = dir.path().join("obs");
    skyforge_ok(
        &["synth", &signal, "--out", sig_out.to_str().unwrap()],
        dir.path(),
    );
    receive_all_recordings(&sig_out, &rx_out, &[], dir.path());
    skyforge_ok(
        &["run", &observation, "--out", obs_out.to_str().unwrap()],
        dir.path(),
    );
    let at_signal = comparison(&sig_out, &rx_out, "ant1");
    let at_observation = comparison(&obs_out, &obs_out.join("observations"), "ant1");
    for system in [System::Gps, System::Beidou] {
        let (sc, sp) = stds(&at_signal, system);
        let (oc, op) = stds(&at_observation, system);
        println!(
            "OBS_LEVEL_TRANSFER {system:?}: code {oc:.3} vs {sc:.3} m ({:.3}), phase {:.2} vs {:.2} mm ({:.3})",
            oc / sc,
            op * 1e3,
            sp * 1e3,
            op / sp
        );
        assert!((oc / sc - 1.0).abs() < 0.15, "{system:?} code {oc} vs {sc}");
        assert!(
            (op / sp - 1.0).abs() < 0.15,
            "{system:?} phase {op} vs {sp}"
        );
    }
}

/// The bundled calibration is what `skyforge calibrate` measures on its scenario (code,
/// phase and Doppler factors). The run
/// is deterministic for a seed and a CPU, but the correlator's kernel depends on the CPU
/// (AVX-512 or portable, which round differently: f32 lanes, fused multiply-add), so the
/// factors are held to a part in a thousand (they moved by at most 1.2e-4 when session
/// 33's window kernel replaced the earlier correlator arithmetic), and everything else
/// (signals, counts, C/N0, loops) exactly.
#[test]
#[ignore = "acceptance tier: a 130 s signal-level run (about a minute)"]
fn bundled_calibration_is_reproduced_by_the_calibrate_command() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/calibration/leo-gps-bds.toml"
    );
    let out = dir.path().join("cal");
    skyforge_ok(
        &["calibrate", scenario, "--out", out.to_str().unwrap()],
        dir.path(),
    );
    let measured: toml::Table =
        toml::from_str(&std::fs::read_to_string(out.join("calibration.toml")).unwrap()).unwrap();
    let bundled: toml::Table = toml::from_str(skyforge_scenarios::BUNDLED_CALIBRATION).unwrap();
    let signals = |t: &toml::Table| t["signals"].as_array().unwrap().clone();
    let (measured, bundled) = (signals(&measured), signals(&bundled));
    assert_eq!(measured.len(), bundled.len());
    for (m, b) in measured.iter().zip(&bundled) {
        let (mut m, mut b) = (m.as_table().unwrap().clone(), b.as_table().unwrap().clone());
        for factor in ["code_factor", "phase_factor", "doppler_factor"] {
            let (fm, fb) = (
                m.remove(factor).unwrap().as_float().unwrap(),
                b.remove(factor).unwrap().as_float().unwrap(),
            );
            assert!((fm / fb - 1.0).abs() < 1e-3, "{factor}: {fm} vs {fb}");
        }
        assert_eq!(m, b);
    }
    assert!(!out.join("work").exists(), "the recordings are removed");
}

/// Observed-only signals (`observed_signals`): every antenna's observation file and truth
/// file carry L2, L5, B2I and B3I beside L1 C/A and B1I, on one line per satellite, and
/// they read back as their own signals on the same satellites.
#[test]
fn observed_only_signals_are_written_beside_the_synthesised_ones() {
    let dir = tempfile::tempdir().unwrap();
    let observed = "observed_signals = [\"gps-l2\", \"gps-l5\", \"bds-b2i\", \"bds-b3i\"]\n";
    let out = run_with_constant_noise(dir.path(), "multi", 10, 12, observed);
    for file in [
        out.join("ant2.obs.rnx"),
        out.join("observations/ant2.obs.rnx"),
    ] {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(
            text.contains("G   12 C1C L1C D1C S1C C2W L2W D2W S2W C5I L5I D5I S5I"),
            "{}",
            file.display()
        );
        assert!(text.contains("C   12 C2I L2I D2I S2I C7I L7I D7I S7I C6I L6I D6I S6I"));
        let obs = read_obs_file(&file).unwrap();
        let epoch = &obs.epochs[5];
        for (synthesised, observed) in [
            (
                skyforge_gnss::signal::Signal::GpsL1Ca,
                [
                    skyforge_gnss::signal::Signal::GpsL2,
                    skyforge_gnss::signal::Signal::GpsL5,
                ],
            ),
            (
                skyforge_gnss::signal::Signal::BdsB1I,
                [
                    skyforge_gnss::signal::Signal::BdsB2I,
                    skyforge_gnss::signal::Signal::BdsB3I,
                ],
            ),
        ] {
            let sats = |s| {
                epoch
                    .sats
                    .iter()
                    .filter(|r| r.signal == s && r.carrier_phase_cycles.is_some())
                    .map(|r| r.sat)
                    .collect::<Vec<_>>()
            };
            assert!(sats(synthesised).len() >= 4, "{synthesised}");
            for o in observed {
                assert_eq!(sats(o), sats(synthesised), "{o} in {}", file.display());
            }
        }
    }
}

/// Observed-only signals need the observation level, and a noise model that has them:
/// each mistake is one located error and nothing is written.
#[test]
fn observed_only_signals_outside_the_observation_level_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra, said) in [
        (
            "signal-level",
            "\n[observation]\nobserved_signals = [\"gps-l2\"]\n",
            "observed-only signals are drawn at the observation level alone",
        ),
        (
            "calibrated",
            "\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gps-l5\"]\n",
            "the calibrated noise model has no calibration for it",
        ),
        (
            "synthesised",
            "\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gps-l1ca\"]\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.002\ncode_m = 0.4\n",
            "is tracked by the bundled receiver or transmitted",
        ),
        (
            "unknown",
            "\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gal-e6\"]\n",
            "unknown signal",
        ),
        (
            "twice",
            "\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gps-l2\", \"gps-l2\"]\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.002\ncode_m = 0.4\n",
            "is listed twice",
        ),
    ] {
        let path = scenario(dir.path(), name, 10, 1, extra);
        let out = dir.path().join(format!("out-{name}"));
        let o = support::skyforge(&["run", &path, "--out", out.to_str().unwrap()], dir.path());
        assert_eq!(o.status.code(), Some(2), "{name}: {}", support::text(&o));
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("observed_signals") && err.contains(said),
            "{name}: {err}"
        );
        assert!(!out.exists(), "{name}");
    }
}
