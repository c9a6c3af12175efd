//! `skyforge validate thesis`.

use crate::BadInput;
use crate::output::staged_dir::StagedDir;
use skyforge_validate::report::{print_table, write_json};
use skyforge_validate::thesis::{self, Options, ValidateError};
use std::path::{Path, PathBuf};

/// Default real-data folder, relative to the working directory.
const DEFAULT_DATA_DIR: &str = "../shared/data";

/// Run the thesis tables, print them and optionally write `results.json`.
pub fn thesis(
    only: Vec<String>,
    out: Option<&Path>,
    force: bool,
    data: Option<PathBuf>,
) -> anyhow::Result<()> {
    let data_dir = data
        .or_else(|| std::env::var_os("SKYFORGE_DATA").map(PathBuf::from))
        .unwrap_or_else(|| PathBuf::from(DEFAULT_DATA_DIR));
    let staged = out.map(|dir| StagedDir::create(dir, force)).transpose()?;
    let opts = Options {
        only,
        data_dir: Some(data_dir),
    };
    let rows = match thesis::run(&opts, |table| eprintln!("validate: running {table}")) {
        Err(ValidateError::UnknownTable { id, known }) => {
            return Err(BadInput(format!("unknown table {id:?}; known tables: {known}")).into());
        }
        other => other?,
    };
    print_table(&rows, &mut std::io::stdout().lock())?;
    if let Some(staged) = staged {
        write_json(&rows, &staged.file("results.json"))?;
        let dir = staged.commit()?;
        println!("wrote {}", dir.join("results.json").display());
    }
    Ok(())
}
