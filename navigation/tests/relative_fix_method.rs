//! Each epoch's resolution says what fixed its integers and, where the configured
//! constrained search could not decide, why LAMBDA decided instead (`Resolution::method`,
//! `Resolution::fallback`): nothing falls back silently.

mod baseline_support;

use baseline_support::{single_epoch, two_baselines};
use nalgebra::Vector3;
use skyforge_navigation::attitude::BodyGeometry;
use skyforge_navigation::baseline::{AmbiguityHold, ElevationNoise, FloatBaselines, NoiseModel};
use skyforge_navigation::relative::search::{self, ConstrainedSearch};
use skyforge_navigation::relative::{
    AmbiguityStatus, Constraint, FixMethod, RelativeConfig, Resolution, resolve,
};

/// A single epoch of eight GPS satellites over `baselines` (2 mm phase, 0.3 m code): its
/// float solution and true integers.
fn epoch(seed: u64, baselines: Vec<Vector3<f64>>) -> (FloatBaselines, Vec<i64>) {
    let e = ElevationNoise::constant;
    single_epoch(seed, 8, baselines, &NoiseModel::new(e(0.002), e(0.3)))
}

/// LAMBDA (or partial fixing, or nothing) decided, not a constrained search.
fn lambda_decided(r: &Resolution) -> bool {
    matches!(
        r.method,
        FixMethod::Lambda | FixMethod::Partial | FixMethod::None
    )
}

/// A master on the Earth's surface (the geometry search's local frame).
fn master() -> Vector3<f64> {
    Vector3::new(4.0e6, 3.0e6, 3.5e6)
}

fn resolve_with(
    float: &FloatBaselines,
    hold: &mut AmbiguityHold,
    search: &dyn ConstrainedSearch,
    master: &Vector3<f64>,
) -> Resolution {
    resolve(float, hold, &RelativeConfig::default(), search, master).unwrap()
}

#[test]
fn the_geometry_search_fixes_and_then_the_hold_does() {
    let baselines = two_baselines();
    let geometry = BodyGeometry::new(&baselines).unwrap();
    let by_geometry = search::build(Constraint::Geometry, &geometry);
    let (float, truth) = epoch(1, baselines);
    let mut hold = AmbiguityHold::new();
    let r = resolve_with(&float, &mut hold, by_geometry.as_ref(), &master());
    assert_eq!(r.status, AmbiguityStatus::Fixed);
    assert_eq!(
        (r.method, r.fallback.as_deref()),
        (FixMethod::Geometry, None)
    );
    let fixed: Vec<i64> = r.integers.iter().map(|v| v.unwrap()).collect();
    assert_eq!(fixed, truth);
    // The same epoch again: every integer comes from the hold.
    let again = resolve_with(&float, &mut hold, by_geometry.as_ref(), &master());
    assert_eq!((again.method, again.held), (FixMethod::Held, truth.len()));
}

#[test]
fn without_a_constraint_lambda_decides_and_nothing_is_a_fallback() {
    let baselines = two_baselines();
    let geometry = BodyGeometry::new(&baselines).unwrap();
    let none = search::build(Constraint::None, &geometry);
    let (float, _) = epoch(2, baselines);
    let r = resolve_with(&float, &mut AmbiguityHold::new(), none.as_ref(), &master());
    assert!(lambda_decided(&r), "{:?}", r.method);
    assert_eq!(r.fallback, None);
}

/// The geometry search with one baseline, and with a master at the Earth's centre (no
/// local frame): LAMBDA decides and the resolution says why.
#[test]
fn a_search_that_cannot_decide_is_a_recorded_fallback() {
    let one = vec![two_baselines()[0]];
    let geometry = BodyGeometry::new(&one).unwrap();
    let by_geometry = search::build(Constraint::Geometry, &geometry);
    let (float, _) = epoch(3, one);
    let r = resolve_with(
        &float,
        &mut AmbiguityHold::new(),
        by_geometry.as_ref(),
        &master(),
    );
    assert_ne!(r.method, FixMethod::Geometry);
    let why = r.fallback.expect("a fallback");
    assert!(why.contains("two or more baselines"), "{why}");

    let baselines = two_baselines();
    let geometry = BodyGeometry::new(&baselines).unwrap();
    let by_geometry = search::build(Constraint::Geometry, &geometry);
    let (float, _) = epoch(4, baselines);
    let centre = Vector3::zeros();
    let r = resolve_with(
        &float,
        &mut AmbiguityHold::new(),
        by_geometry.as_ref(),
        &centre,
    );
    assert!(lambda_decided(&r), "{:?}", r.method);
    let why = r.fallback.expect("a fallback");
    assert!(why.starts_with("geometry search failed: "), "{why}");
}
