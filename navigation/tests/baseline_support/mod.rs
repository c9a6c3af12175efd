//! Double-difference test epochs from a known plane-wave geometry: satellites at random
//! directions, antennas on known baselines, integer phase offsets, clocks and the noise of
//! eqs. 2.4-9/2.4-10. Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::baseline::{
    DdLayout, DdModel, ElevationNoise, FloatBaselines, LineOfSight, NoiseModel,
};
use skyforge_orbits::ephemeris::SatId;

/// A platform with antennas on known baselines and satellites spread over the sky.
pub struct Scene {
    pub views: Vec<LineOfSight>,
    /// Baselines from antenna 0 (m, ECEF).
    pub baselines: Vec<Vector3<f64>>,
    /// Integer phase offsets per satellite and antenna (cycles).
    pub offsets: Vec<Vec<i64>>,
    /// Geometric range from antenna 0 (m).
    pub ranges: Vec<f64>,
}

/// The two baselines of [`scene`] (about 1 m, nearly orthogonal).
pub fn two_baselines() -> Vec<Vector3<f64>> {
    vec![
        Vector3::new(0.98, 0.1, -0.17),
        Vector3::new(-0.05, 1.01, 0.03),
    ]
}

/// Three antennas (the two baselines of [`two_baselines`]), `gps` GPS and `bds` BeiDou
/// satellites at random directions above the horizon.
pub fn scene(rng: &mut ChaCha8Rng, gps: usize, bds: usize) -> Scene {
    scene_with(rng, gps, bds, two_baselines())
}

/// As [`scene`] with the given baselines (one antenna more than baselines).
pub fn scene_with(
    rng: &mut ChaCha8Rng,
    gps: usize,
    bds: usize,
    baselines: Vec<Vector3<f64>>,
) -> Scene {
    let mut views = Vec::new();
    let sats = (1..=gps as u8)
        .map(SatId::gps)
        .chain((1..=bds as u8).map(SatId::beidou));
    for sat in sats {
        let elevation: f64 = rng.random_range(0.15..1.5);
        let azimuth: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        // A local frame with z up is enough: the model only sees directions.
        let los = Vector3::new(
            elevation.cos() * azimuth.cos(),
            elevation.cos() * azimuth.sin(),
            elevation.sin(),
        );
        views.push(LineOfSight {
            sat,
            los_ecef: los,
            elevation_rad: elevation,
            delay_gradient: Vector3::zeros(),
        });
    }
    let n = views.len();
    let antennas = baselines.len() + 1;
    Scene {
        views,
        baselines,
        offsets: (0..n)
            .map(|_| {
                (0..antennas)
                    .map(|_| rng.random_range(-1_000_000..1_000_000))
                    .collect()
            })
            .collect(),
        ranges: (0..n).map(|_| rng.random_range(2.0e7..2.6e7)).collect(),
    }
}

pub fn signal_of(sat: SatId) -> Signal {
    Signal::of_system(sat.system)
}

/// Observations of antenna `a`: plane-wave range `rho - l . b_a`, its integer offset, a
/// receiver clock of the antenna and a satellite clock shared by all, plus noise from
/// `noise` when given.
pub fn observe(
    scene: &Scene,
    a: usize,
    clocks_m: (f64, &[f64]),
    noise: Option<(&NoiseModel, &mut ChaCha8Rng)>,
) -> Vec<ObsRecord> {
    let mut noise = noise;
    let position = if a == 0 {
        Vector3::zeros()
    } else {
        scene.baselines[a - 1]
    };
    scene
        .views
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let signal = signal_of(v.sat);
            let lambda = signal.wavelength_m();
            let range = scene.ranges[i] - v.los_ecef.dot(&position) + clocks_m.0 - clocks_m.1[i];
            let (dp, dc) = match noise.as_mut() {
                Some((model, rng)) => {
                    let e = v.elevation_rad;
                    let g1: f64 = StandardNormal.sample(*rng);
                    let g2: f64 = StandardNormal.sample(*rng);
                    (g1 * model.phase.sigma_m(e), g2 * model.code.sigma_m(e))
                }
                None => (0.0, 0.0),
            };
            let phase = (range + dp) / lambda + scene.offsets[i][a] as f64;
            ObsRecord::complete(v.sat, signal, range + dc, phase, 0.0, 45.0)
        })
        .collect()
}

pub fn noise_model() -> NoiseModel {
    // assumed: the thesis's elevation model with a0 = 10, elev0 = 10 deg (eq. 2.4-10 has
    // no printed values); zenith sigmas 3 mm / 0.3 m.
    let e = |s| ElevationNoise {
        sigma0_m: s,
        a0: 10.0,
        elev0_deg: 10.0,
    };
    NoiseModel::new(e(0.003), e(0.3))
}

pub fn solve(scene: &Scene, obs: &[Vec<ObsRecord>], noise: &NoiseModel) -> FloatBaselines {
    let refs: Vec<&[ObsRecord]> = obs.iter().map(Vec::as_slice).collect();
    let signals = [Signal::GpsL1Ca, Signal::BdsB1I];
    let layout = DdLayout::select(&refs, &scene.views, &signals).unwrap();
    let model = DdModel::new(layout, refs.len(), noise).unwrap();
    FloatBaselines::solve(model, &refs, None).unwrap()
}

/// The true double-difference integers, in the layout's order, baseline by baseline
/// (vec(N)).
pub fn true_integers(scene: &Scene, float: &FloatBaselines) -> Vec<i64> {
    let index = |sat: SatId| scene.views.iter().position(|v| v.sat == sat).unwrap();
    let mut out = Vec::new();
    for k in 1..=scene.baselines.len() {
        for (_, sat, reference) in float.model.layout.ambiguity_ids() {
            let (i, r) = (index(sat), index(reference));
            let sd = |j: usize| scene.offsets[j][k] - scene.offsets[j][0];
            out.push(sd(i) - sd(r));
        }
    }
    out
}

pub fn clocks(rng: &mut ChaCha8Rng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-3e5..3e5)).collect()
}

/// One single-epoch float solution of `gps` GPS satellites over `baselines` with `noise`,
/// no clocks (sky, integer offsets and noise from `seed`), and its true integers (vec(N)).
pub fn single_epoch(
    seed: u64,
    gps: usize,
    baselines: Vec<Vector3<f64>>,
    noise: &NoiseModel,
) -> (FloatBaselines, Vec<i64>) {
    use rand::SeedableRng;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = scene_with(&mut rng, gps, 0, baselines);
    let zero = vec![0.0; gps];
    let obs: Vec<_> = (0..=scene.baselines.len())
        .map(|a| observe(&scene, a, (0.0, &zero), Some((noise, &mut rng))))
        .collect();
    let float = solve(&scene, &obs, noise);
    let truth = true_integers(&scene, &float);
    (float, truth)
}
