//! What the thesis-table tests share: run one table alone and print it.

use skyforge_validate::report::{Row, print_table};
use skyforge_validate::thesis::{Options, run};

/// `validate thesis --only id`: its rows, printed; checks that this table alone ran.
pub fn table_alone(id: &str) -> Vec<Row> {
    let opts = Options {
        only: vec![id.into()],
        data_dir: None,
        plan: None,
    };
    let mut started = Vec::new();
    let rows = run(&opts, |t| started.push(t.to_string()))
        .unwrap()
        .results
        .rows;
    print_table(&rows, &mut std::io::stdout()).unwrap();
    assert_eq!(started, [id]);
    rows
}
