//! The filter on a synthetic geometry: two receivers 200 km apart on one LEO orbit
//! (integrated with the filter's own gravity field), eight satellites, perfect single
//! differences of range (code) and of range plus integer ambiguities (phase) on two
//! signals, no ionosphere, no clocks. After 600 s the filter must have the baseline to a
//! micrometre and the double-difference integers exactly, all 14 fixed.

use super::config::DoubleDifferenceConfig;
use super::dynamics::{gravity_field, propagate_pair};
use super::filter::{Anchor, DdEpoch, DdFilter, Key, SatPair, SignalSd};
use super::fixing::resolve;
use rand::{Rng, SeedableRng};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::{Mat3, Vec3};

#[test]
fn perfect_ranges_give_the_baseline_and_the_integers() {
    let start = hifitime::Epoch::from_gregorian_utc_at_midnight(2023, 3, 12);
    let forces = gravity_field(&Default::default(), start);
    let mu = forces.gm();
    let (r, inc) = (6.878e6_f64, 89f64.to_radians());
    let v = (mu / r).sqrt();
    let orbit = |u: f64| {
        let (s, c) = u.sin_cos();
        (
            Vec3::new(r * c, r * s * inc.cos(), r * s * inc.sin()),
            Vec3::new(-v * s, v * c * inc.cos(), v * c * inc.sin()),
        )
    };
    let mut states = [orbit(0.3), orbit(0.3 - 200e3 / r)];
    let signals = [Signal::GpsL1Ca, Signal::GpsL2];
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    // Satellites fixed in space at GPS radius, spread over the sky of the pair.
    let sats: Vec<(SatId, Vec3, [i64; 2])> = (0..8)
        .map(|k| {
            let az = f64::from(k) * 0.8;
            let tilt = 0.3 + 0.1 * f64::from(k % 3);
            let up = states[0].0.normalize();
            let east = Vec3::z().cross(&up).normalize();
            let north = up.cross(&east);
            let dir =
                (up * tilt.cos() + (east * az.cos() + north * az.sin()) * tilt.sin()).normalize();
            let id = SatId {
                system: System::Gps,
                prn: k as u8 + 1,
            };
            let n = [
                rng.random_range(-100_000..100_000),
                rng.random_range(-100_000..100_000),
            ];
            (id, states[0].0 + dir * 2.0e7, n)
        })
        .collect();
    // A loose dynamics model: the float epochs' error is forgotten within the run.
    let config = DoubleDifferenceConfig {
        acceleration_sigma_mps2: 1e-4,
        ..Default::default()
    };
    let mut filter = DdFilter::new(config, forces.clone());
    let mut count = Default::default();
    for step in 0..600 {
        let t = f64::from(step);
        if step > 0 {
            states = propagate_pair(&forces, states, 1.0);
        }
        let anchor = Anchor {
            t_s: t,
            r_eci_m: states[0].0,
            v_eci_mps: states[0].1,
        };
        let truth = (states[1].0 - states[0].0, states[1].1 - states[0].1);
        if filter.started() {
            filter.predict(anchor);
        } else {
            let off = Vec3::new(3.0, -2.0, 4.0);
            filter.start(anchor, (truth.0 + off, truth.1), (10.0, 1.0), 2.0);
        }
        let pairs = sats
            .iter()
            .map(|(sat, at, n)| {
                let sd = (at - states[1].0).norm() - (at - states[0].0).norm();
                SatPair {
                    sat: *sat,
                    at_target_m: *at,
                    at_chaser_m: *at,
                    clock_sd_m: 0.0,
                    elevation_rad: [1.0, 1.0],
                    signals: signals
                        .iter()
                        .zip(n)
                        .map(|(&signal, &n)| SignalSd {
                            signal,
                            code_m: sd,
                            phase_cycles: sd / signal.wavelength_m() + n as f64,
                            slip: false,
                        })
                        .collect(),
                }
            })
            .collect();
        let epoch = DdEpoch {
            r_target_ecef_m: states[0].0,
            c_eci_ecef: Mat3::identity(),
            v_chaser_ecef_mps: states[1].1,
            tag_difference_s: 0.0,
            sats: pairs,
        };
        let pairings = filter.update(t, &epoch);
        count = resolve(&mut filter, &pairings);
        if step == 599 {
            for p in &pairings {
                let n = |sat: SatId| {
                    let i = filter.index(Key::Ambiguity(sat, p.signal)).unwrap();
                    filter.x[i]
                };
                let f = signals.iter().position(|s| *s == p.signal).unwrap();
                let truth_n = |sat: SatId| sats.iter().find(|s| s.0 == sat).unwrap().2[f];
                let dd = n(p.sat) - n(p.reference);
                let want = (truth_n(p.sat) - truth_n(p.reference)) as f64;
                assert!((dd - want).abs() < 1e-6, "{p:?}: {dd} against {want}");
            }
        }
    }
    let (b, _) = filter.baseline();
    let truth = states[1].0 - states[0].0;
    assert!((b - truth).norm() < 1e-6, "{} m", (b - truth).norm());
    assert_eq!((count.fixed, count.float), (14, 0));
}
