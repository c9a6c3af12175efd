//! `skyforge report`: one self-contained HTML page (inline SVG figures, no network) from
//! the outputs in a directory: the truth of a run (`truth.h5`), a thesis validation
//! (`results.json`) and a study (`study.h5`), each as a section of the page when present.

pub mod chart;
pub mod page;
pub mod results;
pub mod study;
pub mod truth;

use hdf5::H5Type;
use page::Page;
use std::path::{Path, PathBuf};

/// Largest dataset read (elements): beyond this a file is not one SkyForge wrote for a
/// report to draw.
const MAX_ELEMENTS: usize = 50_000_000;

/// A file the report could not use: which file and why.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct ReportError {
    path: PathBuf,
    message: String,
}

impl ReportError {
    fn new(path: &Path, message: String) -> Self {
        ReportError {
            path: path.to_path_buf(),
            message,
        }
    }
}

/// The report page of `dir`: a section for each of `truth.h5`, `results.json` and the
/// merged `study.h5` found there. An error when there is none, or when one present
/// cannot be read.
pub fn build(dir: &Path) -> Result<Page, ReportError> {
    type Maker = fn(&Path) -> Result<page::Section, ReportError>;
    let makers: [(&str, Maker); 3] = [
        ("truth.h5", truth::section),
        ("results.json", results::section),
        (crate::study::MERGED_FILE, study::section),
    ];
    let mut page = Page {
        title: format!("SkyForge report: {}", dir.display()),
        sections: Vec::new(),
    };
    for (name, make) in makers {
        let path = dir.join(name);
        if path.is_file() {
            page.sections.push(make(&path)?);
        }
    }
    if page.sections.is_empty() {
        return Err(ReportError::new(
            dir,
            format!(
                "nothing to report: none of truth.h5 (skyforge synth or run), results.json \
                 (validate thesis --out) or {} (study run or merge) is here",
                crate::study::MERGED_FILE
            ),
        ));
    }
    Ok(page)
}

/// The whole dataset `name` of `file` (at most `MAX_ELEMENTS` values).
fn read_dataset<T: H5Type>(
    file: &hdf5::File,
    path: &Path,
    name: &str,
) -> Result<Vec<T>, ReportError> {
    let err = |m: String| ReportError::new(path, format!("dataset {name}: {m}"));
    let ds = file.dataset(name).map_err(|e| err(e.to_string()))?;
    if ds.size() > MAX_ELEMENTS {
        return Err(err(format!(
            "{} values; at most {MAX_ELEMENTS} are read",
            ds.size()
        )));
    }
    ds.read_raw().map_err(|e| err(e.to_string()))
}
