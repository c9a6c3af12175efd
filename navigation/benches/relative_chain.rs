//! The relative-positioning and attitude chain per epoch (issue #12 bars: the
//! observation-level chain at 1e4 epochs per second or more on one core; the multivariate
//! constrained search under 2 ms per epoch).
//!
//! Epochs: three antennas on two 1 m body baselines (B0 = [[1, 0], [0, 1], [0, 0]] m),
//! attitude yaw 30, pitch 5, roll -3 deg from the master's NED frame at 35 N 120 E, and
//! satellites at random directions (the double-difference tests' plane-wave scene),
//! 3 mm phase and 0.3 m code at the zenith with the elevation model of eqs. 2.4-9/10.
//! 200 epochs with fresh noise are drawn once and cycled.
//!
//! - `chain/steady`: `RelativeSolver::epoch` with the default configuration (integers held
//!   after the first epoch, the KF attitude), 10 GPS + 10 BDS satellites: the running
//!   chain's cost per epoch (float solution, the hold's chi-square check, fixed baselines,
//!   NED baselines, attitude update).
//! - `chain/single-epoch/*`: no hold, so every epoch runs the integer search: the
//!   multivariate search under the geometry (`geometry`), the length-constrained one
//!   (`length`) and plain LAMBDA (`none`), with 8 GPS satellites (a weak single-epoch
//!   model, many candidates) and 10 GPS + 10 BDS.

#[path = "../tests/baseline_support/mod.rs"]
mod baseline_support;

use baseline_support::{clocks, noise_model, observe, scene_with};
use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use skyforge_gnss::observation::ObsRecord;
use skyforge_navigation::attitude::AttitudeMethod;
use skyforge_navigation::relative::Constraint;
use skyforge_navigation::relative::{RelativeConfig, RelativeSolver};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use std::hint::black_box;

const EPOCHS: usize = 200;

struct Epochs {
    master_ecef_m: Vec3,
    views: Vec<skyforge_navigation::baseline::LineOfSight>,
    /// Per epoch, per antenna.
    records: Vec<Vec<Vec<ObsRecord>>>,
}

fn body_positions() -> [Vec3; 3] {
    [
        Vec3::zeros(),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ]
}

fn epochs(gps: usize, bds: usize, seed: u64) -> Epochs {
    let master_ecef_m = geodetic_to_ecef(&Geodetic {
        lat_rad: 35f64.to_radians(),
        lon_rad: 120f64.to_radians(),
        h_m: 100.0,
    });
    let c_ned_ecef = c_ecef_ned(35f64.to_radians(), 120f64.to_radians());
    let attitude = YawPitchRoll::new(30f64.to_radians(), 5f64.to_radians(), (-3f64).to_radians());
    let baselines: Vec<Vector3<f64>> = body_positions()[1..]
        .iter()
        .map(|b| c_ned_ecef.transpose() * (attitude.c_body_ref() * b))
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = scene_with(&mut rng, gps, bds, baselines);
    let noise = noise_model();
    let n = scene.views.len();
    let records = (0..EPOCHS)
        .map(|_| {
            let sat_clocks = clocks(&mut rng, n);
            (0..3)
                .map(|a| {
                    let receiver_clock = clocks(&mut rng, 1)[0];
                    observe(
                        &scene,
                        a,
                        (receiver_clock, &sat_clocks),
                        Some((&noise, &mut rng)),
                    )
                })
                .collect()
        })
        .collect();
    Epochs {
        master_ecef_m,
        views: scene.views,
        records,
    }
}

fn config(hold: bool, constraint: Constraint) -> RelativeConfig {
    let noise = noise_model();
    let mut c = RelativeConfig {
        phase: noise.phase,
        code: noise.code,
        hold,
        constraint,
        ..RelativeConfig::default()
    };
    c.attitude.method = AttitudeMethod::Kf;
    c
}

/// Time `config` over the cycled epochs of `e`.
fn bench_chain(c: &mut Criterion, name: &str, e: &Epochs, config: RelativeConfig) {
    let mut solver = RelativeSolver::new(config, &body_positions()).expect("solver");
    let mut k = 0usize;
    c.bench_function(name, |b| {
        b.iter(|| {
            let epoch = &e.records[k % EPOCHS];
            let antennas: Vec<&[ObsRecord]> = epoch.iter().map(Vec::as_slice).collect();
            let out = solver.epoch(k as f64, &antennas, &e.views, &e.master_ecef_m);
            k += 1;
            black_box(out.ok())
        })
    });
}

fn chain(c: &mut Criterion) {
    // assumed: seeds chosen before the first run.
    let both = epochs(10, 10, 11);
    let gps = epochs(8, 0, 12);
    bench_chain(
        c,
        "chain/steady/gps10+bds10",
        &both,
        config(true, Constraint::Geometry),
    );
    for (name, constraint) in [
        ("geometry", Constraint::Geometry),
        ("length", Constraint::Length),
        ("none", Constraint::None),
    ] {
        for (sky, e) in [("gps8", &gps), ("gps10+bds10", &both)] {
            bench_chain(
                c,
                &format!("chain/single-epoch/{name}/{sky}"),
                e,
                config(false, constraint),
            );
        }
    }
}

criterion_group!(benches, chain);
criterion_main!(benches);
