//! `validate thesis --only T-5.5` (thesis section 5.5, reverse filtering of the baseline
//! vectors): the bundled `thesis/t-5.5` on eight seeds, the chain with epoch-by-epoch LS
//! baselines and with the reverse baseline UKF, the KF attitude from each. Checked: the
//! selection runs this table alone, every row is there with a finite positive value and
//! a verdict, and every fixed integer was the truth's (the notes' counts). The table is
//! printed (`cargo test -p skyforge-validate --test thesis_reverse_filter -- --nocapture`).

mod thesis_support;

use thesis_support::table_alone;

#[test]
fn t_5_5_writes_every_row_with_finite_values() {
    let rows = table_alone("T-5.5");
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
}
