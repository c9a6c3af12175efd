//! The static start every run on files aligns on: the IMU at rest for the first
//! `span_s`, its attitude from the means of the increments (coarse alignment,
//! `ins::coarse_alignment`) and, if asked, refined by a fine alignment through the same
//! increments (zero-velocity updates, `ins::fine_alignment`), which leaves a filter's
//! estimate of the heading's and the tilts' standard deviations beside the state.

use super::from_files::InsRunError;
use crate::ins::{
    FineAlignment, FineAlignmentConfig, InsState, coarse_alignment, fine_alignment, static_means,
};
use hifitime::{Duration, Epoch};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::ecef_to_geodetic;

/// How a run aligns on its static start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticAlignment {
    /// The static start's length from the first IMU record (s).
    pub span_s: f64,
    /// `Some`: after the coarse alignment, a fine alignment through the same increments
    /// from the coarse attitude at the start's beginning; `None`: coarse only.
    pub fine: Option<FineAlignmentConfig>,
}

impl StaticAlignment {
    /// Coarse alignment over `span_s`.
    pub fn coarse(span_s: f64) -> Self {
        Self { span_s, fine: None }
    }
}

/// The INS aligned: its state at the end of the static start, how many increments that
/// took, and the fine alignment's diagnostics where one ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aligned {
    pub state: InsState,
    pub records: usize,
    pub fine: Option<FineAlignment>,
}

/// How many of `increments` fall in the static start of `span_s`, and its end.
pub(crate) fn alignment_span(
    increments: &[ImuIncrement],
    span_s: f64,
) -> Result<(usize, Epoch), InsRunError> {
    let start = first_instant(increments)
        .ok_or_else(|| InsRunError::Input("the IMU file holds no record".into()))?;
    let end = start + Duration::from_seconds(span_s);
    match increments.iter().take_while(|i| i.t_end <= end).count() {
        0 => Err(InsRunError::Input(format!(
            "no IMU record in the {span_s} s alignment from {start}"
        ))),
        n => Ok((n, end)),
    }
}

/// The instant the first increment begins.
fn first_instant(increments: &[ImuIncrement]) -> Option<Epoch> {
    (increments.first()).map(|i| i.t_end - Duration::from_seconds(i.dt_s))
}

/// The INS aligned on the static start, its antenna at `antenna` or, without, at the mean
/// of the fixes (time, antenna position) meanwhile.
pub(crate) fn align(
    increments: &[ImuIncrement],
    alignment: &StaticAlignment,
    lever: &Vec3,
    antenna: Option<Vec3>,
    fixes: &[(Epoch, Vec3)],
) -> Result<Aligned, InsRunError> {
    let span_s = alignment.span_s;
    let (n, end) = alignment_span(increments, span_s)?;
    let during: Vec<Vec3> = (fixes.iter()).filter(|f| f.0 <= end).map(|f| f.1).collect();
    let antenna = match antenna {
        Some(a) => a,
        None if during.is_empty() => {
            return Err(InsRunError::Input(format!(
                "no GNSS fix in the {span_s} s alignment to {end}"
            )));
        }
        None => during.iter().sum::<Vec3>() / during.len() as f64,
    };
    let still = &increments[..n];
    let means = static_means(still)?;
    let c = coarse_alignment(
        &means.f_body_mps2,
        &means.w_body_rps,
        &ecef_to_geodetic(&antenna),
    )?;
    let at = |t| InsState::at_rest(t, antenna - c * lever, c);
    let (state, fine) = match &alignment.fine {
        None => (at(still[n - 1].t_end), None),
        Some(cfg) => {
            let begin = first_instant(still).unwrap_or(still[0].t_end);
            let out = fine_alignment(&at(begin), still, cfg)?;
            (out.state, Some(out))
        }
    };
    Ok(Aligned {
        state,
        records: n,
        fine,
    })
}
