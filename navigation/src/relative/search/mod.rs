//! How an epoch's free ambiguities are searched besides plain LAMBDA, in the stage idiom:
//! `[relative] constraint` chooses one in [`build`]. Under the whole body geometry
//! ([`multivariate`], two or more baselines), under each baseline's length ([`length`]),
//! or not at all ([`NoConstraint`]). Where a search does not apply or fails, LAMBDA's
//! ratio test and success-rate floor decide ([`super::resolve`]).

pub mod length;
pub mod multivariate;

use super::config::Constraint;
use crate::attitude::BodyGeometry;
use crate::baseline::{Conditioned, FloatBaselines};
use length::LengthSearch;
use multivariate::{ConstrainedFix, GeometrySearch};
use skyforge_orbits::Vec3;

/// A search of the free ambiguities under what is known of the baselines.
pub trait ConstrainedSearch: std::fmt::Debug + Send {
    /// The best integers of the free ambiguities of `cond` (the `held` ones fixed) with the
    /// second-best score, or `None` where the search does not apply or fails. The master
    /// antenna's position `master_ecef_m` places the local frame; the search may stop
    /// once the ratio of its two best scores reaches `accept_ratio`.
    fn search(
        &self,
        float: &FloatBaselines,
        cond: &Conditioned,
        held: &[(usize, i64)],
        master_ecef_m: &Vec3,
        accept_ratio: f64,
    ) -> Option<ConstrainedFix>;
}

/// No constraint: plain LAMBDA decides.
#[derive(Debug, Clone, Copy)]
pub struct NoConstraint;

impl ConstrainedSearch for NoConstraint {
    fn search(
        &self,
        _: &FloatBaselines,
        _: &Conditioned,
        _: &[(usize, i64)],
        _: &Vec3,
        _: f64,
    ) -> Option<ConstrainedFix> {
        None
    }
}

/// The search `constraint` names, for the baselines `geometry` (body frame).
pub fn build(constraint: Constraint, geometry: &BodyGeometry) -> Box<dyn ConstrainedSearch> {
    match constraint {
        Constraint::None => Box::new(NoConstraint),
        Constraint::Geometry => Box::new(GeometrySearch::new(geometry.clone())),
        Constraint::Length => Box::new(LengthSearch::new(geometry.clone())),
    }
}
