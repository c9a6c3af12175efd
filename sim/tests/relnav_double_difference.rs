//! `skyforge relnav` in mode `double-difference` on the bundled GRACE-like pair
//! (`grace-relnav`: two LEOs 200 km apart on one orbit at 500 km, GPS L1 C/A + L2 at the
//! observation level, exact satellite orbits and clocks), compared with the truth by
//! `skyforge validate relnav`.
//!
//! The bar (issue #35 item 5, set before the first run): after 600 s of convergence, the
//! relative position error under 2 mm RMS per axis and at least 90 % of the
//! double-difference ambiguities fixed, on seeds 1-4. The position error is the
//! Earth-fixed baseline's (chaser minus target), expressed in the target's true orbit
//! frame (`validate relnav`'s `baseline`): the estimates' own frame comes from the
//! target's estimated orbit, and across 200 km its orientation error is that orbit's,
//! centimetres, not the relative navigation's (docs/orbit-determination.md, where both
//! are reported).

mod support;

use std::path::Path;

/// The settings: the scenario's noise model as the receivers' weights, and the target
/// orbit filter's force model that of the scenario's world (J2 and drag; the relative
/// dynamics take its gravity field).
const CONFIG: &str = "mode = \"double-difference\"
[double_difference]
phase = { sigma0_m = 0.002, a0 = 1.0, elev0_deg = 10.0 }
code = { sigma0_m = 0.3, a0 = 1.0, elev0_deg = 10.0 }
[target_orbit.forces]
higher_zonals = false
";

/// Synthesise `grace-relnav` with `seed` into `d/pair{seed}`, run relnav and validate
/// from 600 s on; the comparison.
fn run_seed(d: &Path, seed: u32) -> serde_json::Value {
    let pair = format!("pair{seed}");
    let out = format!("dd{seed}");
    let seed_text = seed.to_string();
    support::skyforge_ok(
        &[
            "synth",
            "grace-relnav",
            "--out",
            &pair,
            "--seed",
            &seed_text,
        ],
        d,
    );
    let obs = |v: &str| format!("{pair}/{v}/observations/ant1.obs.rnx");
    let nav = format!("{pair}/target/nav.rnx");
    support::skyforge_ok(
        &[
            "relnav",
            &obs("target"),
            &obs("chaser"),
            "--nav",
            &nav,
            "--config",
            "dd.toml",
            "--out",
            &out,
        ],
        d,
    );
    let json = format!("{out}.json");
    support::skyforge_ok(
        &[
            "validate",
            "relnav",
            "--truth",
            &pair,
            "--relnav",
            &out,
            "--settle-s",
            "600",
            "--json",
            &json,
        ],
        d,
    );
    support::json_file(&d.join(json))
}

#[test]
fn grace_pair_baseline_within_2_mm_with_90_percent_fixed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("dd.toml"), CONFIG).unwrap();
    let mut failures = Vec::new();
    for seed in 1..=4 {
        let c = run_seed(d, seed);
        let b = &c["baseline"];
        let rms: Vec<f64> = (0..3)
            .map(|i| b["position_m"]["rms"][i].as_f64().unwrap())
            .collect();
        let fraction = b["ambiguities"]["fraction"].as_f64().unwrap();
        let frame: Vec<f64> = (0..3)
            .map(|i| c["position_m"]["rms"][i].as_f64().unwrap())
            .collect();
        eprintln!(
            "seed {seed}: baseline RMS x {:.2} y {:.2} z {:.2} mm, {:.1} % fixed, {} compared; \
             in the estimated frame x {:.1} y {:.1} z {:.1} mm",
            rms[0] * 1e3,
            rms[1] * 1e3,
            rms[2] * 1e3,
            fraction * 100.0,
            b["compared"],
            frame[0] * 1e3,
            frame[1] * 1e3,
            frame[2] * 1e3
        );
        assert!(b["compared"].as_u64().unwrap() >= 590, "seed {seed}: {c}");
        if rms.iter().any(|&r| r >= 0.002) || fraction < 0.9 {
            failures.push(format!("seed {seed}: {rms:?} m, {fraction} fixed"));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}
