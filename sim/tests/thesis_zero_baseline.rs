//! `skyforge validate thesis` T-5.4-2: the zero-baseline table runs the whole chain
//! (synthesis, receiver, double differences). The full run is in the ignored tier (60 s of
//! four 4 Msps recordings); the default tier checks the table is known.

mod support;

use std::process::Command;
use support::{results_json, skyforge, text};

#[test]
fn an_unknown_table_is_refused_with_a_list_that_names_t_5_4_2() {
    let tmp = tempfile::tempdir().unwrap();
    let o = skyforge(
        &["validate", "thesis", "--only", "T-5.4-2", "--only", "T-9.9"],
        tmp.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("\"T-9.9\"") && err.contains("T-5.4-2"),
        "{err}"
    );
    // Refused before anything ran.
    assert!(!err.contains("running"), "{err}");
}

/// Physical bounds of a zero-baseline double difference at 45 dB-Hz, whatever the loops: a
/// (DD of four) carrier-phase tracking error of 0.1..10 mm (a PLL between 1 and 50 Hz
/// gives 0.35..2.4 mm; a half-cycle slip would add 95 mm), code 0.02..5 m (C/A chip 293 m,
/// B1I 147 m, DLL spacing and bandwidth anywhere in their usual ranges), and means that
/// are small against those: a zero baseline has no geometric or atmospheric term left.
fn sane(row: &serde_json::Value) -> Result<(), String> {
    let name = row["row"].as_str().unwrap_or_default();
    let ours = row["ours"]
        .as_f64()
        .ok_or_else(|| format!("{name}: no value"))?;
    let phase = name.contains("carrier phase");
    let (lo, hi) = match (phase, row["quantity"].as_str()) {
        (true, Some("std")) => (1e-4, 1e-2),
        (false, Some("std")) => (0.02, 5.0),
        (true, Some("mean")) => (0.0, 2e-3),
        (false, Some("mean")) => (0.0, 1.0),
        (_, q) => return Err(format!("{name}: unexpected quantity {q:?}")),
    };
    if (lo..=hi).contains(&ours.abs()) {
        Ok(())
    } else {
        Err(format!("{name}: {ours} m outside [{lo}, {hi}] m"))
    }
}

#[test]
#[ignore = "validation tier: 60 s synthesis of four recordings (about 2 GB) and the receiver; cargo test -- --ignored"]
fn t_5_4_2_writes_every_row_with_a_verdict_and_physically_sane_values() {
    let tmp = tempfile::tempdir().unwrap();
    // The recordings go to the system's temporary directory: make it one of the test's.
    let scratch = tmp.path().join("scratch");
    std::fs::create_dir(&scratch).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(["validate", "thesis", "--only", "T-5.4-2", "--out", "v"])
        .current_dir(tmp.path())
        .env("TMPDIR", &scratch)
        .output()
        .expect("run skyforge");
    assert!(o.status.success(), "{}", text(&o));
    let rows = results_json(&tmp.path().join("v"));
    // GPS L1 and BD2 B1 x pseudorange and carrier phase x mean and std; nothing else.
    assert_eq!(rows.len(), 8, "{rows:?}");
    for r in &rows {
        assert_eq!(r["table"], "T-5.4-2", "{r}");
        assert_eq!(r["unit"], "m", "{r}");
        assert!(
            ["reproduced", "deviates", "explained"].contains(&r["verdict"].as_str().unwrap()),
            "{r}"
        );
        assert!(r["thesis"].is_f64(), "{r}");
        let note = r["note"].as_str().unwrap();
        assert!(note.contains("default configuration"), "{r}");
        if let Err(e) = sane(r) {
            panic!("{e}\n{r}");
        }
    }
    // The scratch directory of the recordings is removed.
    let left: Vec<_> = std::fs::read_dir(&scratch)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}
