//! `validate thesis --only P1-S` (paper 001's static test): a navigation-grade IMU on a
//! static site near Changsha, ten minutes of static alignment, then 2050 s of the INS
//! alone (20 seeds) and integrated with the three BeiDou GEOs' time-differenced carrier
//! phase, their code differences and the site's height (8 seeds, the observation level at
//! the paper's 10 Hz). Checked: the selection runs this table alone, its 15 rows are there
//! with finite positive values, and the 13 reproduced at the 10 Hz run (2026-12-02, the
//! verdict rules registered before the first run) stay so: pure INS medians north 126 m,
//! east 283 m, 0.120 and 0.367 m/s against the paper's 70, 310, 0.05, 0.33; integrated
//! sigmas north 0.52 m and 0.0072 / 0.0015 m/s against 1 m and 0.006 / 0.001 m/s, maxima
//! 0.17 m east and 0.023 / 0.0044 m/s, north/east ratios 9.4 and 4.5 (paper about 5 and
//! 6, bar 2), the pure INS 960 times the integrated error at 2050 s (bar 20). Two deviate,
//! better than the paper: the east position sigma 0.056 m (paper 0.2; on every other seed
//! set too) and the north position maximum 1.29 m (paper 3.5; on 2 of 3 other sets). At
//! the earlier 1 Hz (the observation level's only rate then) all 15 were reproduced. The
//! east pure-INS error is the Schuler loop's answer to the gyro drift (246 m, 0.28 m/s by
//! formula, `BOOK_PAPER001_TARGETS.md` 2.3). The table is printed
//! (`cargo test -p skyforge-validate --test thesis_paper001_static -- --nocapture`).

mod thesis_support;

use skyforge_validate::report::Verdict;
use thesis_support::table_and_figures;

/// The rows that deviated at the 10 Hz run (better than the paper).
const DEVIATED: [&str; 2] = [
    "integrated east position sigma",
    "integrated north position maximum",
];

#[test]
fn p1_s_pure_and_integrated_errors_are_the_papers() {
    let (rows, _) = table_and_figures("P1-S");
    for r in &rows {
        println!(
            "{:50} paper {:8.4} ours {:8.4} {:?}  {}",
            r.row,
            r.thesis.unwrap_or(f64::NAN),
            r.ours.unwrap_or(f64::NAN),
            r.verdict,
            r.note
        );
    }
    assert_eq!(rows.len(), 15, "{rows:#?}");
    for r in &rows {
        assert_eq!(r.table, "P1-S");
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
        if !DEVIATED.contains(&r.row.as_str()) {
            assert_eq!(
                r.verdict,
                Verdict::Reproduced,
                "no longer the recorded pass: {r:?}"
            );
        }
    }
}
