//! `validate thesis --only B-3.2` (the book's GPS/INS simulations, section 3.2): the
//! Table 3-1 SINS on an aircraft's 550-s flight with a 180-deg turn, started with Table
//! 3-2's errors, alone and in the 18-state tightly coupled filter with Table 3-4's GPS
//! receiver (90-m pseudoranges, 0.1-m/s range rates, clock) and a barometer, 20 seeds.
//! The cascaded simulations (3.2.1: the receiver's position fixes every 25 s, or its
//! velocity every second, into the 15-state loosely coupled filter) add 8 rows. Checked:
//! the selection runs this table alone, its 18 rows are there with finite positive
//! values, and the rows reproduced at the first run (2026-12-02, registered before it)
//! stay so. Cascades: 7 of 8 reproduced (horizontal 52 m and altitude 63 m against about
//! 40 and 75, velocity 0.85 m/s straight and 2.29 m/s in the turn against 0.5 and 1.8,
//! level 1.48' and azimuth 6.0' at 500 s against 1.5' and 5'; velocity-only 0.105 m/s
//! against 0.1); the velocity-only azimuth at 150 s, 26.9' against about 3', deviates:
//! with velocities alone the heading is unobservable until a horizontal manoeuvre, and
//! the assumed profile's first is the turn at 200 s. 18-state and pure INS: the pure INS
//! north 2589 m and up 751 m against 2150 and 840, the filter's north and up velocity
//! 0.020 and 0.024 m/s against 0.035 and 0.045 reproduced; the other seven deviated:
//! the pure INS west 1711 m against 2500 (0.68, the band is 0.7-1.3), and the filter is 2-5 times better than the book (west velocity 0.013 m/s,
//! position 3.1 / 1.6 / 5.3 m, azimuth 0.62' against 3'): today's full GPS
//! constellation against the book's era, most likely (docs/ins.md). The table is printed
//! (`cargo test -p skyforge-validate --test thesis_book_gps_ins -- --nocapture`).

mod thesis_support;

use skyforge_validate::report::Verdict;
use thesis_support::table_and_figures;

/// The rows reproduced at the first run.
const REPRODUCED: [&str; 10] = [
    "pure INS north position at 550 s",
    "pure INS up position at 550 s",
    "18-state filter north velocity at 550 s",
    "position-only cascade (T = 25 s) mean horizontal error",
    "position-only cascade mean altitude error",
    "position-only cascade velocity error, straight flight",
    "position-only cascade largest velocity error in the turn",
    "position-only cascade level error at 500 s",
    "position-only cascade azimuth error at 500 s",
    "velocity-only cascade (T = 1 s) velocity error, straight flight",
];

#[test]
fn b_3_2_pure_ins_and_the_18_state_filter() {
    let (rows, _) = table_and_figures("B-3.2");
    for r in &rows {
        println!(
            "{:55} book {:8.4} ours {:8.4} {:?}",
            r.row,
            r.thesis.unwrap_or(f64::NAN),
            r.ours.unwrap_or(f64::NAN),
            r.verdict,
        );
    }
    assert_eq!(rows.len(), 18, "{rows:#?}");
    for r in &rows {
        assert_eq!(r.table, "B-3.2");
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
        if REPRODUCED.contains(&r.row.as_str()) {
            assert_eq!(
                r.verdict,
                Verdict::Reproduced,
                "no longer reproduced: {r:?}"
            );
        }
    }
}
