//! `skyforge validate thesis` and `skyforge validate obs`.

use crate::BadInput;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_validate::observables::compare::{CompareOptions, compare_with};
use skyforge_validate::observables::read_obs_file;
use skyforge_validate::observables::table::print_comparison;
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

/// Compare a receiver's RINEX observations with the truth, print the table and optionally
/// write the comparison as JSON (via a temporary file, renamed when complete).
pub fn obs(
    truth: &Path,
    estimate: &Path,
    json: Option<&Path>,
    tag_offset_s: f64,
) -> anyhow::Result<()> {
    let bad = |e: skyforge_validate::observables::ObsError| BadInput(e.to_string());
    let truth = read_obs_file(truth).map_err(bad)?;
    let estimate = read_obs_file(estimate).map_err(bad)?;
    let opts = CompareOptions { tag_offset_s };
    let comparison = compare_with(&estimate, &truth, &opts).map_err(bad)?;
    print_comparison(&comparison, &mut std::io::stdout().lock())?;
    if let Some(path) = json {
        let text = serde_json::to_string_pretty(&comparison)?;
        let tmp = path.with_extension("json.partial");
        std::fs::write(&tmp, text + "\n")
            .and_then(|()| std::fs::rename(&tmp, path))
            .with_context(|| format!("cannot write {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
