//! The `truth.h5` reader: what `skyforge validate` and the report read of a run's truth,
//! each read bounded and checked for shape, every error naming the file and the dataset
//! or attribute.

use super::jammers::{JammerTruth, read_jammers};
use super::{
    ANTENNAS_GROUP, EPOCH_INDEX, PLATFORM_GROUP, POSITION, ROTATION, SAT_INDEX, SATELLITE_ID,
    SATELLITES_GROUP, SCENARIO_ATTR, SCENARIO_TOML_ATTR, START_EPOCH_ATTR, T_S, TIME_GROUP,
    VELOCITY, VISIBLE, antenna_dataset, dataset,
};
use crate::FormatError;
use crate::h5::{read_column, read_text_attr};
use hdf5::H5Type;
use hdf5::types::VarLenUnicode;
use hifitime::Epoch;
use nalgebra::{Quaternion, UnitQuaternion};
use skyforge_orbits::Vec3;
use skyforge_orbits::time::parse_epoch;
use std::path::{Path, PathBuf};

/// An open `truth.h5`.
#[derive(Debug)]
pub struct TruthFile {
    file: hdf5::File,
    path: PathBuf,
}

/// The platform's state at every geometry epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct PlatformSeries {
    /// Seconds since the start epoch, increasing.
    pub t_s: Vec<f64>,
    /// Centre-of-mass position, ECEF (m).
    pub r_ecef_m: Vec<Vec3>,
    /// Centre-of-mass velocity, ECEF (m/s).
    pub v_ecef_mps: Vec<Vec3>,
    /// Body-to-ECEF rotation.
    pub q_body_ecef: Vec<UnitQuaternion<f64>>,
}

/// The visible links of one antenna: the epoch row and satellite column of each, in the
/// order of its per-link datasets.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VisibleLinks {
    pub epoch: Vec<u32>,
    pub sat: Vec<u16>,
}

impl TruthFile {
    /// Open `path` (it must exist and be HDF5).
    pub fn open(path: &Path) -> Result<Self, FormatError> {
        let err = |m: String| FormatError::file(path, m);
        std::fs::metadata(path).map_err(|e| err(e.to_string()))?;
        let file = hdf5::File::open(path).map_err(|e| err(format!("not readable as HDF5: {e}")))?;
        Ok(Self {
            file,
            path: path.to_path_buf(),
        })
    }

    fn error(&self, message: String) -> FormatError {
        FormatError::file(&self.path, message)
    }

    fn text_attr(&self, name: &str) -> Result<String, FormatError> {
        read_text_attr(&self.file, &self.path, name)
    }

    /// The scenario file's text the run was made from.
    pub fn scenario_toml(&self) -> Result<String, FormatError> {
        self.text_attr(SCENARIO_TOML_ATTR)
    }

    /// The `jammers` group (`None`: the run had no jammer), at most `max_rows` epochs.
    pub fn jammers(&self, max_rows: usize) -> Result<Option<JammerTruth>, FormatError> {
        read_jammers(&self.file, &self.path, max_rows)
    }

    /// The scenario's name.
    pub fn scenario_name(&self) -> Result<String, FormatError> {
        self.text_attr(SCENARIO_ATTR)
    }

    /// The GPST epoch that the times count from.
    pub fn start_epoch(&self) -> Result<Epoch, FormatError> {
        let text = self.text_attr(START_EPOCH_ATTR)?;
        parse_epoch(&text).map_err(|e| self.error(format!("attribute {START_EPOCH_ATTR}: {e}")))
    }

    /// The whole dataset `name`, at most `max_elements` values.
    fn column<T: H5Type>(&self, name: &str, max_elements: usize) -> Result<Vec<T>, FormatError> {
        read_column(&self.file, &self.path, name, max_elements)
    }

    /// The geometry epochs' times (s since the start), at most `max_elements`.
    pub fn times(&self, max_elements: usize) -> Result<Vec<f64>, FormatError> {
        self.column(&dataset(TIME_GROUP, T_S), max_elements)
    }

    /// The satellites' identifiers (`G05`, `C19`), the columns of the visibility masks.
    pub fn satellite_ids(&self, max_elements: usize) -> Result<Vec<String>, FormatError> {
        let ids: Vec<VarLenUnicode> =
            self.column(&dataset(SATELLITES_GROUP, SATELLITE_ID), max_elements)?;
        Ok(ids.iter().map(|s| s.as_str().to_string()).collect())
    }

    /// The antennas' names, in the file's (alphabetical) order.
    pub fn antenna_names(&self) -> Result<Vec<String>, FormatError> {
        self.file
            .group(ANTENNAS_GROUP)
            .and_then(|g| g.member_names())
            .map_err(|e| self.error(format!("group {ANTENNAS_GROUP}: {e}")))
    }

    /// The platform series, each of at most `max_rows` rows, finite, of one length, with
    /// increasing times.
    pub fn platform(&self, max_rows: usize) -> Result<PlatformSeries, FormatError> {
        let t_s = self.series(&dataset(TIME_GROUP, T_S), 1, max_rows)?;
        let position = dataset(PLATFORM_GROUP, POSITION);
        let velocity = dataset(PLATFORM_GROUP, VELOCITY);
        let rotation = dataset(PLATFORM_GROUP, ROTATION);
        let r = self.series(&position, 3, max_rows)?;
        let v = self.series(&velocity, 3, max_rows)?;
        let q = self.series(&rotation, 4, max_rows)?;
        if r.len() != 3 * t_s.len() || v.len() != r.len() || q.len() != 4 * t_s.len() {
            return Err(self.error(format!(
                "{TIME_GROUP}/{T_S}, {position}, {velocity} and {rotation} have {}, {}, {} and {} rows",
                t_s.len(),
                r.len() / 3,
                v.len() / 3,
                q.len() / 4
            )));
        }
        if t_s.is_empty() || t_s.windows(2).any(|w| w[1] <= w[0]) {
            return Err(self.error(format!("{TIME_GROUP}/{T_S} is empty or not increasing")));
        }
        Ok(PlatformSeries {
            t_s,
            r_ecef_m: r.chunks_exact(3).map(Vec3::from_column_slice).collect(),
            v_ecef_mps: v.chunks_exact(3).map(Vec3::from_column_slice).collect(),
            q_body_ecef: q
                .chunks_exact(4)
                .map(|c| UnitQuaternion::from_quaternion(Quaternion::new(c[0], c[1], c[2], c[3])))
                .collect(),
        })
    }

    /// A per-epoch series of `width` columns (1: one dimension), at most `max_rows` rows,
    /// every value finite.
    fn series(&self, name: &str, width: usize, max_rows: usize) -> Result<Vec<f64>, FormatError> {
        let err = |m: String| self.error(format!("dataset {name}: {m}"));
        let ds = self.file.dataset(name).map_err(|e| err(e.to_string()))?;
        let shape = ds.shape();
        let rows = shape.first().copied().unwrap_or(0);
        let expected = if width == 1 { 1 } else { 2 };
        if shape.len() != expected || (width > 1 && shape[1] != width) {
            return Err(err(format!("shape {shape:?}")));
        }
        if rows > max_rows {
            return Err(err(format!("{rows} rows; at most {max_rows} are read")));
        }
        let v: Vec<f64> = ds.read_raw().map_err(|e| err(e.to_string()))?;
        if v.iter().any(|x| !x.is_finite()) {
            return Err(err("a value is not finite".into()));
        }
        Ok(v)
    }

    /// An antenna's 3-vector attribute ([`super::NOMINAL_BODY_ATTR`],
    /// [`super::TRUE_BODY_ATTR`]), finite.
    pub fn antenna_vector(&self, antenna: &str, name: &str) -> Result<[f64; 3], FormatError> {
        let v: Vec<f64> = self
            .file
            .group(&format!("{ANTENNAS_GROUP}/{antenna}"))
            .and_then(|g| g.attr(name))
            .and_then(|x| x.read_raw())
            .map_err(|e| self.error(format!("antenna {antenna} attribute {name}: {e}")))?;
        match v.as_slice() {
            [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok([*x, *y, *z]),
            _ => Err(self.error(format!(
                "antenna {antenna} attribute {name}: {v:?} is not a finite 3-vector"
            ))),
        }
    }

    /// An antenna's `[epoch, satellite]` visibility mask, row-major: `epochs x sats`
    /// values, checked.
    pub fn visible(
        &self,
        antenna: &str,
        epochs: usize,
        sats: usize,
        max_elements: usize,
    ) -> Result<Vec<u8>, FormatError> {
        let name = antenna_dataset(antenna, VISIBLE);
        let v: Vec<u8> = self.column(&name, max_elements)?;
        if v.len() != epochs * sats {
            return Err(self.error(format!(
                "{name} has {} values, not epochs x satellites = {}",
                v.len(),
                epochs * sats
            )));
        }
        Ok(v)
    }

    /// An antenna's visible links, each indexing one of `epochs` epochs and `sats`
    /// satellites.
    pub fn links(
        &self,
        antenna: &str,
        epochs: usize,
        sats: usize,
        max_elements: usize,
    ) -> Result<VisibleLinks, FormatError> {
        let epoch: Vec<u32> = self.column(&antenna_dataset(antenna, EPOCH_INDEX), max_elements)?;
        let sat: Vec<u16> = self.column(&antenna_dataset(antenna, SAT_INDEX), max_elements)?;
        let bad = epoch.len() != sat.len()
            || epoch.iter().any(|&e| e as usize >= epochs)
            || sat.iter().any(|&s| s as usize >= sats);
        if bad {
            return Err(self.error(format!(
                "{ANTENNAS_GROUP}/{antenna}: {EPOCH_INDEX} and {SAT_INDEX} do not index the epochs and satellites"
            )));
        }
        Ok(VisibleLinks { epoch, sat })
    }

    /// A per-link geometry dataset of an antenna ([`super::DOPPLER_HZ`] and the like): one
    /// value per link of `links`.
    pub fn link_values(
        &self,
        antenna: &str,
        name: &str,
        links: &VisibleLinks,
    ) -> Result<Vec<f64>, FormatError> {
        let path = antenna_dataset(antenna, name);
        let values: Vec<f64> = self.column(&path, links.epoch.len())?;
        if values.len() != links.epoch.len() {
            return Err(self.error(format!(
                "{path} has {} values for {} links",
                values.len(),
                links.epoch.len()
            )));
        }
        Ok(values)
    }
}
