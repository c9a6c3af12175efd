//! Figures of the geometry-offset estimate (`skyforge attitude --estimate-geometry`'s
//! `geometry_offsets.h5`) against the truth: each baseline's three offset errors against
//! time (thesis figures 4.3-4 and 4.3-5). Baselines do not see the orientation of the
//! antennas in the body frame (`receiver::geometry_offset::shape`), so the truth at each
//! update is the true geometry turned to that estimate's orientation (docs/geometry.md).

use super::chart::{Chart, Series};
use super::page::Figure;
use super::{ReportError, figure};
use skyforge_formats::geometry_offsets::{GEOMETRY_OFFSETS_H5, read_h5};
use skyforge_navigation::geometry_offset::align;
use skyforge_orbits::Vec3;
use skyforge_validate::attitude::OutputsComparison;
use std::path::Path;

/// The two figures, when `attitude` holds `geometry_offsets.h5`; `c` gives the nominal and
/// true body positions (two baselines).
pub fn figures(c: &OutputsComparison, attitude: &Path) -> Result<Vec<Figure>, ReportError> {
    let path = attitude.join(GEOMETRY_OFFSETS_H5);
    if !path.is_file() {
        return Ok(Vec::new());
    }
    let h5 = read_h5(&path)?;
    let Some(last_cov) = h5.covariance_m2.last() else {
        // The estimator never had four consecutive fixed epochs: nothing to draw.
        return Ok(Vec::new());
    };
    if c.antennas.len() != 3 {
        return Err(ReportError::new(
            &path,
            format!(
                "{} antennas: the offsets are of two baselines",
                c.antennas.len()
            ),
        ));
    }
    let body = |f: fn(&skyforge_validate::attitude::AntennaPosition) -> [f64; 3]| {
        let p: Vec<Vec3> = c.antennas.iter().map(|a| Vec3::from(f(a))).collect();
        [p[1] - p[0], p[2] - p[0]]
    };
    let (b0, truth) = (body(|a| a.nominal_body_m), body(|a| a.true_body_m));
    let mut errors: [Vec<(f64, f64)>; 6] = Default::default();
    for (t_s, row) in h5.t_s.iter().zip(&h5.offsets_m) {
        let est = [0, 1].map(|b| b0[b] + Vec3::new(row[3 * b], row[3 * b + 1], row[3 * b + 2]));
        let turned = align(&truth, &est)
            .map_err(|e| ReportError::new(&path, e.to_string()))?
            .baselines;
        for (i, series) in errors.iter_mut().enumerate() {
            series.push((*t_s, 1e3 * (est[i / 3][i % 3] - turned[i / 3][i % 3])));
        }
    }
    let last_sigma_mm = |i: usize| 1e3 * last_cov[7 * i].sqrt();
    let mut out = Vec::new();
    for b in 0..2 {
        let mut chart = Chart::new(
            &format!("Baseline {} geometry-offset error", b + 1),
            "time (s)",
            "error (mm)",
        );
        let mut last = Vec::new();
        for (j, axis) in ["x", "y", "z"].iter().enumerate() {
            let i = 3 * b + j;
            last.push(format!(
                "d{axis}{} {:+.3} mm (sigma {:.3})",
                b + 1,
                errors[i].last().map_or(f64::NAN, |p| p.1),
                last_sigma_mm(i)
            ));
            chart
                .series
                .push(Series::line(format!("d{axis}{}", b + 1), errors[i].clone()));
        }
        let caption = format!(
            "Baseline {} offset estimate minus the true offset, the true geometry turned to the \
             estimate's orientation (which baselines do not see), over {} updates; last: {}. \
             Thesis figures 4.3-4/4.3-5 (table 4.3-4: std about 0.21 mm).",
            b + 1,
            h5.t_s.len(),
            last.join(", ")
        );
        out.push(figure(&chart, caption, &path)?);
    }
    Ok(out)
}
