//! `skyforge report DIR`: the HTML page of a directory's outputs
//! (`skyforge_studies::html_report`), written whole or not at all.

use crate::bad_input::BadInput;
use crate::output::{manifest, whole_file};
use anyhow::Context;
use skyforge_studies::html_report::{Inputs, build};
use std::path::Path;

/// How every page `report` writes begins: the mark of a page `--force` may replace.
const PAGE_START: &str =
    "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>SkyForge report:";

/// Build the report of `inputs` and write it to `out` (default `DIR/report.html`).
pub fn report(inputs: Inputs<'_>, out: Option<&Path>, force: bool) -> anyhow::Result<()> {
    let dir = inputs.dir;
    if !dir.is_dir() {
        return Err(BadInput(format!("{}: not a directory", dir.display())).into());
    }
    let default = dir.join("report.html");
    let target = out.unwrap_or(&default);
    whole_file::check_target(target, force, "a report", |p| {
        whole_file::starts_with(p, PAGE_START.as_bytes())
    })?;
    let page = build(inputs).map_err(|e| BadInput(e.to_string()))?;
    let html = page.to_html();
    debug_assert!(html.starts_with(PAGE_START));
    whole_file::write(target, html.as_bytes())
        .with_context(|| format!("cannot write {}", target.display()))?;
    if let Some(name) = target.file_name().filter(|_| target.parent() == Some(dir)) {
        manifest::add(dir, Path::new(name))
            .with_context(|| format!("cannot update the manifest of {}", dir.display()))?;
    }
    println!(
        "wrote {} ({} sections, {} figures)",
        target.display(),
        page.sections.len(),
        page.figures()
    );
    Ok(())
}
