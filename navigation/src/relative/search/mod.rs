//! How an epoch's free ambiguities are searched besides plain LAMBDA, in the stage idiom:
//! `[relative] constraint` chooses one in [`build`]. Under the whole body geometry
//! ([`multivariate`], two or more baselines), under each baseline's length ([`length`]),
//! or not at all ([`NoConstraint`]). Where a search does not apply or fails, LAMBDA's
//! ratio test and success-rate floor decide ([`super::resolve`]), and the epoch's
//! resolution says why ([`Searched::Fallback`]).

pub mod length;
pub mod multivariate;

use super::config::Constraint;
use super::resolve::FixMethod;
use crate::attitude::BodyGeometry;
use crate::baseline::{Conditioned, FloatBaselines};
use length::LengthSearch;
use multivariate::{ConstrainedFix, GeometrySearch};
use skyforge_orbits::Vec3;

/// What a constrained search gave.
#[derive(Debug, Clone, PartialEq)]
pub enum Searched {
    /// The best integers and the second-best score.
    Found(ConstrainedFix),
    /// No constrained search is configured: plain LAMBDA decides.
    NotConfigured,
    /// The configured search could not run or failed (why): plain LAMBDA decides instead.
    Fallback(String),
}

/// A search of the free ambiguities under what is known of the baselines.
pub trait ConstrainedSearch: std::fmt::Debug + Send {
    /// The best integers of the free ambiguities of `cond` (the `held` ones fixed) with the
    /// second-best score. The master antenna's position `master_ecef_m` places the local
    /// frame; the search may stop once the ratio of its two best scores reaches
    /// `accept_ratio`.
    fn search(
        &self,
        float: &FloatBaselines,
        cond: &Conditioned,
        held: &[(usize, i64)],
        master_ecef_m: &Vec3,
        accept_ratio: f64,
    ) -> Searched;

    /// The method an epoch's integers are credited to when this search fixes them.
    fn method(&self) -> FixMethod;
}

impl Searched {
    /// A search's result: found, or the fallback for its error.
    fn of<E: std::fmt::Display>(what: &str, result: Result<ConstrainedFix, E>) -> Self {
        match result {
            Ok(fix) => Searched::Found(fix),
            Err(e) => Searched::Fallback(format!("{what} search failed: {e}")),
        }
    }
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
    ) -> Searched {
        Searched::NotConfigured
    }

    fn method(&self) -> FixMethod {
        FixMethod::Lambda
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
