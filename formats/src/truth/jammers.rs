//! `truth.h5`'s `jammers` group (docs/truth-h5.md): what each antenna received of each
//! jammer at every geometry epoch, written beside the samples and read by validation.
//! Matrices are `[epoch, antenna * n_jammers + jammer]`, antennas in the order of the
//! group's `antennas` dataset (the scenario's), jammers in that of its `names` dataset
//! (strings: a name may hold any printable character).

use crate::FormatError;
use crate::h5::{append_rows, create_group, create_rows, read_column};
use hdf5::Dataset;
use hdf5::types::VarLenUnicode;
use skyforge_signals::interference::{Jammer, JammerLink};
use std::path::Path;

/// The group.
pub const JAMMERS_GROUP: &str = "jammers";
/// Rows per chunk.
const CHUNK_ROWS: usize = 64;
/// The most jammer or antenna names read.
const MAX_NAMES: usize = 4096;

/// A column: name, unit, description, the value of a link.
type Column = (
    &'static str,
    &'static str,
    &'static str,
    fn(&JammerLink) -> f64,
);

/// The columns.
const COLUMNS: [Column; 4] = [
    (
        "range_m",
        "m",
        "range from the jammer to the antenna",
        |l| l.range_m,
    ),
    (
        "jn0_dbhz",
        "dB-Hz",
        "jammer power over the thermal noise density, with the antenna's gain",
        |l| l.jn0_dbhz,
    ),
    (
        "azimuth_deg",
        "deg",
        "its azimuth in the antenna frame",
        |l| l.azimuth_rad.to_degrees(),
    ),
    (
        "elevation_deg",
        "deg",
        "its elevation above the antenna's XY plane",
        |l| l.elevation_rad.to_degrees(),
    ),
];

/// A 1-D dataset `name` of `values` in `group`.
fn strings(group: &hdf5::Group, name: &str, values: &[impl AsRef<str>]) -> hdf5::Result<()> {
    let texts = (values.iter())
        .map(|v| v.as_ref().parse::<VarLenUnicode>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| hdf5::Error::from(e.to_string()))?;
    group
        .new_dataset_builder()
        .obj_track_times(false)
        .with_data(&texts)
        .create(name)?;
    Ok(())
}

/// The group's datasets while a run writes them.
#[derive(Debug)]
pub(crate) struct JammerSets {
    t_s: Dataset,
    /// `[epoch, jammer]`: 1 while it transmits.
    on: Dataset,
    columns: Vec<Dataset>,
    width: usize,
    rows: usize,
}

impl JammerSets {
    /// The group in `file` for `jammers` received by `antennas` antennas.
    pub fn create(
        file: &hdf5::File,
        jammers: &[Jammer],
        antennas: &[String],
    ) -> hdf5::Result<Self> {
        let group = create_group(file, JAMMERS_GROUP)?;
        let names: Vec<&str> = jammers.iter().map(|j| j.config.name.as_str()).collect();
        strings(&group, "names", &names)?;
        strings(&group, "antennas", antennas)?;
        let width = antennas.len() * jammers.len();
        let t_s = create_rows::<f64>(
            &group,
            "t_s",
            0,
            CHUNK_ROWS,
            "s",
            "seconds since start_epoch",
        )?;
        let on = create_rows::<u8>(
            &group,
            "on",
            jammers.len(),
            CHUNK_ROWS,
            "1",
            "1 while the jammer transmits",
        )?;
        let columns = (COLUMNS.iter())
            .map(|(name, unit, what, _)| {
                create_rows::<f64>(&group, name, width, CHUNK_ROWS, unit, what)
            })
            .collect::<hdf5::Result<_>>()?;
        Ok(Self {
            t_s,
            on,
            columns,
            width,
            rows: 0,
        })
    }

    /// One epoch's links (`links[a * n_jammers + j]`) and whether each jammer transmits.
    pub fn append(&mut self, t_s: f64, on: &[bool], links: &[JammerLink]) -> hdf5::Result<()> {
        if links.len() != self.width {
            return Err(hdf5::Error::from(format!(
                "{} jammer links for {} columns",
                links.len(),
                self.width
            )));
        }
        append_rows(&self.t_s, self.rows, &[t_s], 0)?;
        let on: Vec<u8> = on.iter().map(|o| u8::from(*o)).collect();
        append_rows(&self.on, self.rows, &on, on.len())?;
        for ((_, _, _, get), ds) in COLUMNS.iter().zip(&self.columns) {
            let values: Vec<f64> = links.iter().map(get).collect();
            append_rows(ds, self.rows, &values, self.width)?;
        }
        self.rows += 1;
        Ok(())
    }
}

/// The `jammers` group as read: names, times, and per epoch one value per antenna and
/// jammer (`[k][a * names.len() + j]`).
#[derive(Debug, Clone, PartialEq)]
pub struct JammerTruth {
    pub names: Vec<String>,
    pub antennas: Vec<String>,
    pub t_s: Vec<f64>,
    /// `[k][j]`: whether jammer `j` transmits at epoch `k`.
    pub on: Vec<Vec<bool>>,
    pub range_m: Vec<Vec<f64>>,
    pub jn0_dbhz: Vec<Vec<f64>>,
    pub azimuth_deg: Vec<Vec<f64>>,
    pub elevation_deg: Vec<Vec<f64>>,
}

/// Reads the `jammers` group of `file` (at `path`), at most `max_rows` epochs; `None`
/// when the run had no jammer.
pub fn read_jammers(
    file: &hdf5::File,
    path: &Path,
    max_rows: usize,
) -> Result<Option<JammerTruth>, FormatError> {
    if file.group(JAMMERS_GROUP).is_err() {
        return Ok(None);
    }
    let err = |m: String| FormatError::file(path, format!("group {JAMMERS_GROUP}: {m}"));
    let list = |name: &str| -> Result<Vec<String>, FormatError> {
        let dataset = format!("{JAMMERS_GROUP}/{name}");
        let texts: Vec<VarLenUnicode> = read_column(file, path, &dataset, MAX_NAMES)?;
        Ok(texts.iter().map(|t| t.as_str().to_string()).collect())
    };
    let (names, antennas) = (list("names")?, list("antennas")?);
    let t_s: Vec<f64> = read_column(file, path, &format!("{JAMMERS_GROUP}/t_s"), max_rows)?;
    let on: Vec<u8> = read_column(
        file,
        path,
        &format!("{JAMMERS_GROUP}/on"),
        max_rows.saturating_mul(names.len()),
    )?;
    if on.len() != t_s.len() * names.len() {
        return Err(err(format!(
            "on: {} values for {} epochs",
            on.len(),
            t_s.len()
        )));
    }
    let on = on
        .chunks(names.len())
        .map(|r| r.iter().map(|v| *v != 0).collect())
        .collect();
    let mut matrices = Vec::new();
    for (name, ..) in COLUMNS {
        let dataset = format!("{JAMMERS_GROUP}/{name}");
        let width = file
            .dataset(&dataset)
            .map(|d| d.shape().get(1).copied().unwrap_or(0))
            .map_err(|e| err(format!("{name}: {e}")))?;
        let values: Vec<f64> = read_column(file, path, &dataset, max_rows.saturating_mul(width))?;
        if width != names.len() * antennas.len() || values.len() != t_s.len() * width {
            return Err(err(format!(
                "{name}: {} values for {} epochs of width {width}, {} jammers, {} antennas",
                values.len(),
                t_s.len(),
                names.len(),
                antennas.len()
            )));
        }
        matrices.push(
            values
                .chunks(width)
                .map(<[f64]>::to_vec)
                .collect::<Vec<_>>(),
        );
    }
    let Ok([range_m, jn0_dbhz, azimuth_deg, elevation_deg]) = <[_; 4]>::try_from(matrices) else {
        return Err(err("not four columns".into()));
    };
    Ok(Some(JammerTruth {
        names,
        antennas,
        t_s,
        on,
        range_m,
        jn0_dbhz,
        azimuth_deg,
        elevation_deg,
    }))
}
