//! `validate thesis --only T-5.5` (thesis section 5.5, reverse filtering of the baseline
//! vectors): the bundled `thesis/t-5.5` on eight seeds, the chain with epoch-by-epoch LS
//! baselines and with the reverse baseline UKF, the KF attitude from each. Checked: the
//! selection runs this table alone, every row is there with a finite positive value and
//! a verdict, and every fixed integer was the truth's (the notes' counts); its figures
//! 5.5-2..5.5-5 draw every epoch of the first run and quote every row. The table is
//! printed (`cargo test -p skyforge-validate --test thesis_reverse_filter -- --nocapture`).

mod thesis_support;

use thesis_support::{check_figures, table_and_figures};

#[test]
fn t_5_5_writes_every_row_with_finite_values() {
    let (rows, curves) = table_and_figures("T-5.5");
    for r in &rows {
        println!("{}: {}", r.row, r.note);
    }
    // Two baselines x three ECEF components x (LS, proposed), three axes x (LS, proposed).
    assert_eq!(rows.len(), 18, "{rows:#?}");
    for r in &rows {
        assert_eq!(r.table, "T-5.5");
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
        assert!(r.thesis.is_some_and(f64::is_finite), "{r:?}");
        assert!(
            r.note.contains("8 runs") && r.note.contains(", 0 wrong"),
            "{r:?}"
        );
    }
    let proposed = rows
        .iter()
        .filter(|r| r.row.contains("proposed") || r.row.contains("filtered"));
    assert_eq!(proposed.count(), 9);

    // Figures 5.5-2 and 5.5-3 per baseline, 5.5-4 and 5.5-5 angles and rates: X, Y, Z or
    // yaw, pitch, roll of most of the 600 epochs; the captions quote all 18 rows.
    let expected = [
        "5.5-2 baseline 1",
        "5.5-2 baseline 2",
        "5.5-3 baseline 1",
        "5.5-3 baseline 2",
        "5.5-4 angles",
        "5.5-4 rates",
        "5.5-5 angles",
        "5.5-5 rates",
    ];
    assert_eq!(check_figures(&rows, &curves, &expected, |_| 3, 500), 18);
    // The rates against the central difference of the true attitude: errors well below
    // the profile's rates (0.47..0.52 deg/s at most), which a wrong sign or frame would
    // not give.
    for c in curves.iter().filter(|c| c.panels == "rates") {
        for v in c.values.iter().filter(|v| v.what.contains("std")) {
            let std = v.ours.unwrap();
            assert!(std > 0.0 && std < 0.4, "{} {v:?}", c.figure);
        }
    }
}
