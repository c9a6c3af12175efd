//! The tightly coupled filter against closed-form truth: the aiding tests' car circling
//! at Changsha with an error-free IMU, its antenna's pseudoranges from the TDCP tests'
//! world (nominal GPS, a drifting receiver clock, no atmosphere), the Doppler from the
//! pseudoranges' rate.

use super::*;
use crate::ins::tests::truth::{Bias, Circle, Trajectory, increments, t0, true_state};
use crate::pvt::PvtConfig;
use crate::tdcp::tests::world::World;
use skyforge_gnss::observation::ObsEpoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic};

const LEVER: [f64; 3] = [0.8, -0.3, -1.2];
/// The world's receiver clock drift (s/s).
const DRIFT: f64 = 1e-7;

/// The aiding tests' filter, started 5 m off.
fn filter_config() -> LooselyCoupledConfig {
    LooselyCoupledConfig {
        initial_position_m: 5.0,
        ..super::aiding_tests::config()
    }
}

fn receiver(barometer: Option<BarometerNoise>) -> ReceiverNoise {
    ReceiverNoise {
        clock_bias_m: 30.0,
        clock_drift_mps: 0.3,
        clock_drift_tau_s: Some(3600.0),
        clock_phase_psd_m2_s: 0.01,
        code_sigma_m: 0.5,
        range_rate_sigma_mps: 0.02,
        barometer,
    }
}

/// The world's noise-free epoch at `t` for the antenna along `antenna`, each record's
/// Doppler from the pseudorange's central difference over 2 ms.
fn epoch_with_doppler(world: &World, t: f64, antenna: &dyn Fn(f64) -> Vec3) -> ObsEpoch {
    let h = 1e-3;
    let at = |s: f64| world.epoch(s, antenna(s), &mut |_| 0.0);
    let (before, after) = (at(t - h), at(t + h));
    let mut epoch = at(t);
    for rec in &mut epoch.sats {
        let p = |e: &ObsEpoch| e.sats.iter().find(|r| r.sat == rec.sat)?.pseudorange_m;
        if let (Some(p0), Some(p1)) = (p(&before), p(&after)) {
            let rate = (p1 - p0) / (2.0 * h);
            rec.doppler_hz = Some(-rate / rec.signal.wavelength_m());
        }
    }
    epoch
}

/// Runs `seconds` of the circle with range updates every second (and barometric heights
/// `baro_offset_m` above the truth when `barometer`), after checking that the first
/// epoch's noise-free ranges give the clock at the true antenna ([`clock_from_epoch`]: to
/// a centimetre and a centimetre per second); started with the INS 5 m and
/// 0.14 m/s off and the clock 20 m and 0.2 m/s off. Returns the filter and the truth's
/// IMU position and velocity at the end.
fn run(seconds: usize, barometer: Option<(BarometerNoise, f64)>) -> (TightlyCoupled, Vec3, Vec3) {
    let world = World::new(DRIFT);
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let shift = |e: hifitime::Epoch| world.start + (e - t0());
    let mut incs = increments(&traj, 0.01, seconds * 100, &Bias::default());
    for inc in &mut incs {
        inc.t_end = shift(inc.t_end);
    }
    let lever = Vec3::from(LEVER);
    let antenna = |t: f64| traj.r(t) + traj.c_body_ecef(t) * lever;
    let mut start = true_state(&traj, 0.0);
    start.t = shift(start.t);
    start.r_ecef_m += world.ned(3.0, -4.0, 0.0);
    start.v_ecef_mps += world.ned(0.1, -0.1, 0.0);
    let pvt = PvtConfig {
        troposphere: false,
        ..Default::default()
    };
    let first = epoch_with_doppler(&world, 0.0, &antenna);
    let v0 = (antenna(1e-3) - antenna(-1e-3)) / 2e-3;
    let r0 = antenna(0.0);
    let found = clock_from_epoch(&first, (&r0, &v0), &world.store, &world.origin, &pvt).unwrap();
    assert!(
        (found.0 - C_MPS * world.clock_s(0.0)).abs() < 0.01,
        "{found:?}"
    );
    assert!((found.1 - C_MPS * DRIFT).abs() < 0.01, "{found:?}");
    let clock = (C_MPS * world.clock_s(0.0) + 20.0, C_MPS * DRIFT - 0.2);
    let noise = receiver(barometer.map(|b| b.0));
    let mut filter = TightlyCoupled::new(start, filter_config(), noise, clock).unwrap();
    for (k, inc) in incs.iter().enumerate() {
        filter.propagate(inc).unwrap();
        if (k + 1) % 100 == 0 {
            let t = ((k + 1) / 100) as f64;
            let epoch = epoch_with_doppler(&world, t, &antenna);
            let u = filter.update_ranges(&epoch, &world.store, &world.origin, &pvt);
            assert!(u.unwrap().is_some(), "satellites in view at {t} s");
            if let Some((_, offset)) = barometer {
                let h = ecef_to_geodetic(&traj.r(t)).h_m;
                filter.update_barometer(h + offset).unwrap();
            }
        }
    }
    let end = seconds as f64;
    (filter, traj.r(end), traj.v(end))
}

/// Noise-free ranges and range rates over 20 s: the errors of the INS (5 m and 0.14 m/s
/// at the start) and of the clock (20 m, 0.2 m/s) fall within three of the filter's own
/// sigmas, which fall at least tenfold from their initial values.
#[test]
fn ranges_and_rates_find_position_velocity_and_clock() {
    let (filter, r, v) = run(20, None);
    let world = World::new(DRIFT);
    let p = filter.covariance();
    let sigma = |k: usize, n: usize| (k..k + n).map(|i| p[(i, i)]).sum::<f64>().sqrt();
    let (bias, drift) = filter.clock();
    let checks = [
        (
            "position (m)",
            (filter.state().r_ecef_m - r).norm(),
            sigma(0, 3),
            5.0 * 3f64.sqrt(),
        ),
        (
            "velocity (m/s)",
            (filter.state().v_ecef_mps - v).norm(),
            sigma(3, 3),
            0.2 * 3f64.sqrt(),
        ),
        (
            "clock bias (m)",
            (bias - C_MPS * world.clock_s(20.0)).abs(),
            sigma(15, 1),
            30.0,
        ),
        (
            "clock drift (m/s)",
            (drift - C_MPS * DRIFT).abs(),
            sigma(16, 1),
            0.3,
        ),
    ];
    for (what, error, sigma, initial) in checks {
        assert!(error < 3.0 * sigma, "{what}: error {error}, sigma {sigma}");
        assert!(
            sigma < initial / 10.0,
            "{what}: sigma {sigma} from {initial}"
        );
    }
}

/// A barometer reading 20 m high: the filter puts the 20 m into the barometer's bias
/// (the ranges hold the height), and refuses heights without a barometer.
#[test]
fn the_barometer_bias_is_estimated_and_a_missing_barometer_refused() {
    let baro = BarometerNoise {
        bias_m: 50.0,
        correlation_distance_m: 450e3,
        white_m: 1.0,
    };
    let (filter, r, _) = run(30, Some((baro, 20.0)));
    let bias = filter.barometer_bias();
    assert!((bias - 20.0).abs() < 1.0, "barometer bias {bias} m");
    let dr = (filter.state().r_ecef_m - r).norm();
    assert!(dr < 0.1, "position error {dr} m");
    let (mut without, ..) = run(1, None);
    assert!(without.update_barometer(50.0).is_err());
}

/// Bad receiver settings are refused, naming the field.
#[test]
fn bad_receiver_settings_are_refused() {
    let traj = Circle::new(&Geodetic::from_degrees(28.2, 113.0, 50.0), 200.0, 10.0);
    let mut noise = receiver(None);
    noise.code_sigma_m = 0.0;
    let e = TightlyCoupled::new(true_state(&traj, 0.0), filter_config(), noise, (0.0, 0.0))
        .unwrap_err();
    assert!(e.to_string().contains("receiver.code_sigma_m"), "{e}");
}
