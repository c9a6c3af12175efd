//! The book's position filter (orbit determination, section 5.5.4): one fix through
//! `PositionFilter::update` (prediction over 60 s with the Clohessy-Wiltshire matrices
//! and J2 + drag at both ends of the step, the Kalman update), on a circular 893 km
//! polar orbit's fixes.

use criterion::{Criterion, criterion_group, criterion_main};
use hifitime::{Epoch, TimeScale};
use skyforge_navigation::orbit_determination::{FixInput, PositionFilter, PositionFilterConfig};
use skyforge_orbits::Vec3;
use std::hint::black_box;

/// A circular polar orbit's ECEF-like positions and velocities (accuracy is not the
/// point: the filter does the same work on any fix).
fn fixes(n: usize) -> Vec<FixInput> {
    let (r, w) = (7_271e3, 1.0e-3);
    (0..n)
        .map(|k| {
            let t = k as f64 * 60.0;
            let (s, c) = (w * t).sin_cos();
            FixInput {
                t_s: t,
                r_ecef_m: Vec3::new(r * c, 0.0, r * s),
                v_ecef_mps: Some(Vec3::new(-r * w * s, 0.0, r * w * c)),
                gdop: 2.0,
            }
        })
        .collect()
}

fn update(c: &mut Criterion) {
    let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
    let config = PositionFilterConfig {
        forces: Default::default(),
        position_sigma_m: 18.6,
        velocity_sigma_mps: 0.1,
        acceleration_sigma_mps2: 1e-5,
    };
    let fixes = fixes(120);
    c.bench_function("position_filter_120_fixes", |b| {
        b.iter(|| {
            let mut filter = PositionFilter::new(config.clone(), start);
            for fix in &fixes {
                black_box(filter.update(black_box(fix)));
            }
        })
    });
}

criterion_group!(benches, update);
criterion_main!(benches);
