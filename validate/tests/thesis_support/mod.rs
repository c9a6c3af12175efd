//! What the thesis-table tests share: run one table alone and print it; check the figures
//! it computes against its rows.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use skyforge_validate::report::{Row, print_table};
use skyforge_validate::thesis::curves::{Curve, MAX_POINTS};
use skyforge_validate::thesis::{Options, run};

/// `validate thesis --only id`: its rows, printed, and its figures' data; checks that this
/// table alone ran.
pub fn table_and_figures(id: &str) -> (Vec<Row>, Vec<Curve>) {
    let opts = Options {
        only: vec![id.into()],
        data_dir: None,
        plan: None,
    };
    let mut started = Vec::new();
    let outcome = run(&opts, |t| started.push(t.to_string())).unwrap();
    let rows = outcome.results.rows;
    print_table(&rows, &mut std::io::stdout()).unwrap();
    assert_eq!(started, [id]);
    (rows, outcome.curves)
}

/// The figures are `expected` (number and panels), each with `series` series of finite
/// points (at most [`MAX_POINTS`], at least `min_points`), and every caption value quoting
/// a row (`(row "name")`) carries that row's value exactly; returns how many do.
pub fn check_figures(
    rows: &[Row],
    curves: &[Curve],
    expected: &[&str],
    series: impl Fn(&Curve) -> usize,
    min_points: usize,
) -> usize {
    let ids: Vec<String> = curves.iter().map(Curve::number).collect();
    assert_eq!(ids, expected);
    let mut quoted = 0;
    for c in curves {
        assert_eq!(c.series.len(), series(c), "{}", c.figure);
        for s in &c.series {
            let n = s.points.len();
            assert!(
                (min_points..=MAX_POINTS).contains(&n),
                "{} {}: {n}",
                c.figure,
                s.name
            );
            assert!(s.points.iter().all(|p| p.0.is_finite() && p.1.is_finite()));
        }
        for v in &c.values {
            assert!(v.ours.is_some_and(f64::is_finite), "{} {v:?}", c.figure);
            let Some((_, name)) = v.what.split_once("(row \"") else {
                continue;
            };
            let name = name.trim_end_matches("\")");
            let row = rows
                .iter()
                .find(|r| r.row == name)
                .unwrap_or_else(|| panic!("{name}"));
            assert_eq!(v.ours, row.ours, "{} {name}", c.figure);
            assert_eq!(v.thesis, row.thesis, "{} {name}", c.figure);
            quoted += 1;
        }
    }
    quoted
}
