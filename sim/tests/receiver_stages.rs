//! The receiver's configurable stages on SkyForge's own recordings: `[stages]
//! acquisition = "pmf-fft"` (PCPS detection, PMF-FFT fine Doppler) with `carrier = "ukf"`
//! (the UKF of thesis 3.3.4) must track and fix on the bundled static interop scenarios;
//! each test also runs the default stages (PCPS, FLL/PLL) on the same recording and prints
//! both receivers' observable errors against the truth side by side.
//!
//! Bars for the UKF configuration: those of the default loops' acceptance
//! (`receiver_acceptance.rs`): 45 or more fixes within 5 m 3D RMS, no loss of lock,
//! pseudorange error std below 0.5 m and carrier-phase error std below 2 mm.

mod support;

use std::path::Path;
use std::sync::Mutex;
use support::{assert_static_ground_bars, fixes, observable_errors, rms, skyforge_ok, truth_site};

/// One end-to-end run at a time: each holds gigabytes of samples and both cores.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// `[stages]` of the configuration under test.
const STAGES: &str = "\n[stages]\nacquisition = \"pmf-fft\"\ncarrier = \"ukf\"\n";

/// Receive `dir/sim/ant1.<band>` into `dir/<out>` with the assistance synth wrote and
/// `extra` appended to its receiver.toml; returns the receive log.
fn receive(dir: &Path, band: &str, out: &str, extra: &str) -> String {
    let base = std::fs::read_to_string(dir.join("sim/receiver.toml")).expect("receiver.toml");
    let config = format!("{out}.toml");
    std::fs::write(dir.join(&config), base + extra).expect("write config");
    let meta = format!("sim/ant1.{band}.sigmf-meta");
    let args = [
        "receive",
        meta.as_str(),
        "--assist",
        "sim/nav.rnx",
        "--config",
        config.as_str(),
        "--out",
        out,
    ];
    skyforge_ok(&args, dir)
}

fn pmf_fft_and_ukf_track_and_fix(scenario: &str, band: &str) {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    skyforge_ok(&["synth", scenario, "--out", "sim"], dir);
    let sim = dir.join("sim");
    let default_log = receive(dir, band, "rx-default", "");
    let stages_log = receive(dir, band, "rx-stages", STAGES);
    std::fs::remove_file(sim.join(format!("ant1.{band}.sigmf-data"))).expect("samples removed");
    println!("default stages:\n{default_log}\npmf-fft + ukf:\n{stages_log}");
    let site = truth_site(&sim);
    let mut report = Vec::new();
    for (name, rx) in [
        ("pcps + fll-pll", "rx-default"),
        ("pmf-fft + ukf", "rx-stages"),
    ] {
        let rx = dir.join(rx);
        let errors: Vec<f64> = fixes(&rx).iter().map(|f| (f.1 - site).norm()).collect();
        let (pr_std, phase_std, matched) = observable_errors(&sim, &rx);
        report.push((name, errors.len(), rms(&errors), pr_std, phase_std, matched));
    }
    println!("{scenario}: stages, fixes, 3D RMS (m), pseudorange std (m), phase std (mm), epochs");
    for (name, n, pos, pr, phase, matched) in &report {
        println!(
            "  {name:<15} {n:4} {pos:8.2} {pr:8.3} {:8.3} {matched:4}",
            phase * 1e3
        );
    }
    let (_, n, pos, pr, phase, matched) = report[1];
    assert!(stages_log.contains("0 losses of lock"), "{stages_log}");
    assert_static_ground_bars(n, pos, (pr, phase, matched));
}

#[test]
#[ignore = "acceptance tier (minutes): cargo test -p skyforge-sim --test receiver_stages -- --ignored"]
fn pmf_fft_and_ukf_track_and_fix_on_interop_gps_static() {
    pmf_fft_and_ukf_track_and_fix("interop-gps-static", "gps-l1ca");
}

#[test]
#[ignore = "acceptance tier (minutes): cargo test -p skyforge-sim --test receiver_stages -- --ignored"]
fn pmf_fft_and_ukf_track_and_fix_on_interop_bds_static() {
    pmf_fft_and_ukf_track_and_fix("interop-bds-static", "bds-b1i");
}
