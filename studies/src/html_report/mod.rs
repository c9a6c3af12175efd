//! `skyforge report`: one self-contained HTML page (inline SVG figures, no network) from
//! the outputs in a directory: the truth of a run (`truth.h5`), a thesis validation
//! (`results.json`, and `curves.json`: the thesis figures its tables compute) and a study
//! (`study.h5`), each as a section of the page when present, and the attitude chain's
//! errors when its output directory is named.

pub(crate) mod attitude;
pub(crate) mod chart;
pub(crate) mod curves;
pub(crate) mod geometry;
mod loop_errors;
pub(crate) mod page;
pub(crate) mod results;
pub(crate) mod study;
pub(crate) mod truth;

use chart::Chart;
use page::{Figure, Page};
use skyforge_formats::FormatError;
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

impl From<FormatError> for ReportError {
    fn from(e: FormatError) -> Self {
        match e {
            FormatError::File { path, message } => ReportError { path, message },
            FormatError::Row {
                path,
                line,
                message,
            } => ReportError {
                path,
                message: format!("line {line}: {message}"),
            },
        }
    }
}

/// What a report is made of: the outputs directory, and optionally `skyforge attitude`'s
/// output for that run with the observations it read (default: the run's own,
/// DIR/observations of an observation-level run).
#[derive(Debug, Clone, Copy)]
pub struct Inputs<'a> {
    pub dir: &'a Path,
    pub attitude: Option<&'a Path>,
    pub observations: Option<&'a Path>,
}

/// The report page of `inputs`: a section for each of `truth.h5`, `results.json`,
/// `curves.json` and the merged `study.h5` found in the directory, and the attitude
/// chain's when named. An error when there is none, or when one present cannot be read.
pub fn build(inputs: Inputs<'_>) -> Result<Page, ReportError> {
    let dir = inputs.dir;
    type Maker = fn(&Path) -> Result<page::Section, ReportError>;
    let makers: [(&str, Maker); 4] = [
        ("truth.h5", truth::section),
        ("results.json", results::section),
        (
            skyforge_validate::thesis::curves::CURVES_FILE,
            curves::section,
        ),
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
    if let Some(att) = inputs.attitude {
        // An observation-level run keeps its observations in DIR/observations.
        let own = dir.join("observations");
        let observations = inputs
            .observations
            .unwrap_or(if own.is_dir() { &own } else { dir });
        page.sections
            .push(attitude::section(dir, observations, att)?);
    }
    if page.sections.is_empty() {
        return Err(ReportError::new(
            dir,
            format!(
                "nothing to report: none of truth.h5 (skyforge synth or run), results.json \
                 or {} (validate thesis --out) or {} (study run or merge) is here",
                skyforge_validate::thesis::curves::CURVES_FILE,
                crate::study::MERGED_FILE
            ),
        ));
    }
    Ok(page)
}

/// `chart` drawn, with `caption`; an error names `path`, the file the chart comes from.
/// The text of `path`, refused (before reading) when larger than `max_bytes`.
fn read_text(path: &Path, max_bytes: u64) -> Result<String, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let size = std::fs::metadata(path)
        .map_err(|e| err(e.to_string()))?
        .len();
    if size > max_bytes {
        return Err(err(format!("{size} bytes; at most {max_bytes} are read")));
    }
    std::fs::read_to_string(path).map_err(|e| err(e.to_string()))
}

fn figure(chart: &Chart, caption: String, path: &Path) -> Result<Figure, ReportError> {
    let svg = chart
        .to_svg()
        .map_err(|e| ReportError::new(path, e.to_string()))?;
    Ok(Figure { caption, svg })
}
