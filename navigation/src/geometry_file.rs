//! The body geometry file (`geometry.toml`): each antenna's name and nominal phase-centre
//! position in the body frame, master first. `skyforge synth` writes it for its scenario,
//! `skyforge attitude --estimate-geometry` writes the corrected one, and the attitude chain
//! reads it: the one definition of the format, reader and writer together.

use crate::attitude::{BodyGeometry, MAX_BASELINE_M, beyond_max_baseline};
use serde::{Deserialize, Serialize};
use skyforge_orbits::Vec3;
use skyforge_orbits::bounded_read::read_text;
use std::path::Path;

/// Largest geometry file read (bytes).
const MAX_GEOMETRY_BYTES: u64 = 1 << 20;

/// Why a geometry file could not be read.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {message}")]
pub struct GeometryFileError {
    pub path: String,
    pub message: String,
}

/// One antenna of the body geometry.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GeometryAntenna {
    pub name: String,
    /// Nominal phase-centre position in the body frame (m).
    pub position_body_m: [f64; 3],
}

/// The body geometry file (TOML, `[[antennas]]` with `name` and `position_body_m`, master
/// first), as `skyforge synth` writes it for its scenario.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodyGeometryFile {
    pub antennas: Vec<GeometryAntenna>,
}

impl BodyGeometryFile {
    /// This geometry with every antenna but the master moved to the master plus its
    /// `corrected` baseline (the estimate of `skyforge attitude --estimate-geometry`).
    pub fn corrected(&self, corrected: &BodyGeometry) -> Self {
        let master = self.positions().first().copied().unwrap_or_default();
        Self::from_positions(self.antennas.iter().enumerate().map(|(k, a)| {
            let p = match k.checked_sub(1).and_then(|i| corrected.baselines().get(i)) {
                Some(b) => master + b,
                None => master,
            };
            (a.name.clone(), p)
        }))
    }

    /// The antennas `(name, body-frame position)`, master first.
    pub fn from_positions(antennas: impl IntoIterator<Item = (String, Vec3)>) -> Self {
        Self {
            antennas: antennas
                .into_iter()
                .map(|(name, p)| GeometryAntenna {
                    name,
                    position_body_m: [p.x, p.y, p.z],
                })
                .collect(),
        }
    }

    /// Read and check the geometry file at `path`.
    pub fn read(path: &Path) -> Result<Self, GeometryFileError> {
        let error = |message: String| GeometryFileError {
            path: path.display().to_string(),
            message,
        };
        let text = read_text(path, MAX_GEOMETRY_BYTES, "geometry file")
            .map_err(|e| error(e.to_string()))?;
        let file: Self = toml::from_str(&text).map_err(|e| error(e.to_string()))?;
        if file.antennas.len() < 2 {
            return Err(error(format!(
                "{} antennas; at least two are needed for a baseline",
                file.antennas.len()
            )));
        }
        if let Some(a) = file
            .antennas
            .iter()
            .find(|a| a.position_body_m.iter().any(|v| !v.is_finite()))
        {
            return Err(error(format!(
                "antenna {}: position_body_m is not finite",
                a.name
            )));
        }
        let far = |a: &&GeometryAntenna| beyond_max_baseline(&Vec3::from(a.position_body_m));
        if let Some(a) = file.antennas.iter().find(far) {
            return Err(error(format!(
                "antenna {}: position_body_m {:?} lies beyond {MAX_BASELINE_M:e} m of the body origin",
                a.name, a.position_body_m,
            )));
        }
        Ok(file)
    }

    /// Body positions, master first.
    pub fn positions(&self) -> Vec<Vec3> {
        self.antennas
            .iter()
            .map(|a| Vec3::from(a.position_body_m))
            .collect()
    }

    /// The file's text: `header` as comment lines, then the antennas' tables.
    pub fn to_text(&self, header: &str) -> Result<String, toml::ser::Error> {
        let comments: String = header.lines().map(|l| format!("# {l}\n")).collect();
        Ok(comments + &toml::to_string(self)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_is_written_reads_back_the_same() {
        let file = BodyGeometryFile::from_positions([
            ("A".to_owned(), Vec3::new(0.0, 0.0, 0.0)),
            ("B".to_owned(), Vec3::new(1.0, -0.25, 1e-3 / 3.0)),
            ("C".to_owned(), Vec3::new(-0.5, 0.8660254037844386, 0.1)),
        ]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("geometry.toml");
        std::fs::write(&path, file.to_text("a header\nof two lines").unwrap()).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.starts_with("# a header\n# of two lines\n[[antennas]]"),
            "{text}"
        );
        assert_eq!(BodyGeometryFile::read(&path).unwrap(), file);
    }

    /// A 1e300 m antenna was reported as "collinear" by the attitude chain; it is refused
    /// where the file is read, naming the file and the antenna.
    #[test]
    fn an_antenna_beyond_the_body_is_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("geometry.toml");
        for far in [1e300, 1.000001e8] {
            let file = BodyGeometryFile::from_positions([
                ("A".to_owned(), Vec3::new(0.0, 0.0, 0.0)),
                ("B".to_owned(), Vec3::new(far, 0.0, 0.0)),
            ]);
            std::fs::write(&path, file.to_text("").unwrap()).unwrap();
            let e = BodyGeometryFile::read(&path).unwrap_err().to_string();
            assert!(
                e.contains("geometry.toml")
                    && e.contains("antenna B: position_body_m")
                    && e.contains("lies beyond 1e8 m of the body origin"),
                "{e}"
            );
        }
        let g = BodyGeometry::new(&[Vec3::new(1e300, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]);
        assert!(g.unwrap_err().to_string().contains("longer than 1e8 m"));
    }

    #[test]
    fn a_single_antenna_or_a_non_finite_position_is_refused_with_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("geometry.toml");
        std::fs::write(
            &path,
            "[[antennas]]\nname = \"A\"\nposition_body_m = [0.0, 0.0, 0.0]\n",
        )
        .unwrap();
        let e = BodyGeometryFile::read(&path).unwrap_err().to_string();
        assert!(
            e.contains("geometry.toml") && e.contains("at least two"),
            "{e}"
        );
        std::fs::write(
            &path,
            "[[antennas]]\nname = \"A\"\nposition_body_m = [0.0, 0.0, 0.0]\n\
             [[antennas]]\nname = \"B\"\nposition_body_m = [nan, 0.0, 0.0]\n",
        )
        .unwrap();
        let e = BodyGeometryFile::read(&path).unwrap_err().to_string();
        assert!(
            e.contains("antenna B: position_body_m is not finite"),
            "{e}"
        );
    }
}
