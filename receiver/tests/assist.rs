//! Assisted search windows: the predicted Doppler of every satellite in view of a LEO
//! receiver matches the Doppler of the light-time range computed here, and a window built
//! from deliberately wrong assistance still contains the true Doppler.

use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, F_GPS_L1_HZ, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{System, nominal};
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_receiver::assist::{Assistance, search_hints};

fn leo_state(t: f64) -> (Vec3, Vec3) {
    // A circular 600 km orbit in an inclined plane, expressed in ECEF with the Earth's
    // rotation removed from the inertial velocity (good enough for a moving receiver).
    let r0: f64 = 6_978_137.0;
    let n = (3.986_004_418e14 / r0.powi(3)).sqrt();
    let inc: f64 = 0.6;
    let u = n * t;
    let r_eci = Vec3::new(
        r0 * u.cos(),
        r0 * u.sin() * inc.cos(),
        r0 * u.sin() * inc.sin(),
    );
    let v_eci = Vec3::new(
        -r0 * n * u.sin(),
        r0 * n * u.cos() * inc.cos(),
        r0 * n * u.cos() * inc.sin(),
    );
    let th = OMEGA_E_GPS * t;
    let (s, c) = th.sin_cos();
    let rot = |x: Vec3| Vec3::new(c * x.x + s * x.y, -s * x.x + c * x.y, x.z);
    let r = rot(r_eci);
    let w = Vec3::new(0.0, 0.0, OMEGA_E_GPS);
    (r, rot(v_eci) - w.cross(&r))
}

/// Doppler (Hz) of `eph` for the LEO at true time `t` by a central difference of the
/// light-time range (with the satellite clock drift).
fn true_doppler(eph: &skyforge_orbits::ephemeris::BoundEphemeris, t: f64) -> f64 {
    let range = |t: f64| {
        let r = leo_state(t).0;
        let mut tau = 0.07;
        for _ in 0..8 {
            let p = eph.position_ecef(t - tau);
            let (s, c) = (OMEGA_E_GPS * tau).sin_cos();
            let p = Vec3::new(c * p.x + s * p.y, -s * p.x + c * p.y, p.z);
            tau = (p - r).norm() / C_MPS;
        }
        C_MPS * tau - C_MPS * eph.clock_offset_s(t - tau)
    };
    let h = 0.01;
    -(range(t + h) - range(t - h)) / (2.0 * h) * F_GPS_L1_HZ / C_MPS
}

#[test]
fn predicted_doppler_and_windows_for_a_leo() {
    let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
    let store = nominal::gps_store(start);
    let t = 1234.0;
    let (r, v) = leo_state(t);
    let exact = Assistance {
        t_s: t,
        time_uncertainty_s: 0.0,
        r_ecef_m: r,
        v_ecef_mps: v,
        position_uncertainty_m: 0.0,
        velocity_uncertainty_mps: 0.0,
        oscillator_uncertainty: 0.0,
        elevation_mask_rad: 0.0,
    };
    let hints = search_hints(&store, &exact, Signal::GpsL1Ca);
    assert!(hints.len() >= 8, "{} satellites in view", hints.len());
    let mut largest: f64 = 0.0;
    for h in &hints {
        assert_eq!(h.sat.system, System::Gps);
        let eph = store.select(h.sat, t).unwrap();
        let truth = true_doppler(eph, t);
        assert!(
            (h.doppler_hz - truth).abs() < 0.05,
            "{}: {} vs {truth}",
            h.sat,
            h.doppler_hz
        );
        largest = largest.max(truth.abs());
        let rate = (true_doppler(eph, t + 0.5) - true_doppler(eph, t - 0.5)) / 1.0;
        assert!(
            (h.doppler_rate_hzps - rate).abs() < 0.5,
            "{}: rate {} vs {rate}",
            h.sat,
            h.doppler_rate_hzps
        );
    }
    assert!(largest > 20_000.0, "LEO Doppler up to {largest} Hz");
    // Wrong by 2 s, 20 km, 10 m/s and 0.5 ppm: the windows still hold the truth.
    let (r_wrong, v_wrong) = (
        r + Vec3::new(12e3, -12e3, 10e3),
        v + Vec3::new(6.0, -6.0, 5.0),
    );
    let rough = Assistance {
        t_s: t + 2.0,
        time_uncertainty_s: 2.0,
        r_ecef_m: r_wrong,
        v_ecef_mps: v_wrong,
        position_uncertainty_m: 20e3,
        velocity_uncertainty_mps: 10.0,
        oscillator_uncertainty: 0.5e-6,
        elevation_mask_rad: 0.0,
    };
    for h in search_hints(&store, &rough, Signal::GpsL1Ca) {
        let truth = true_doppler(store.select(h.sat, t).unwrap(), t);
        assert!(
            (h.doppler_hz - truth).abs() <= h.doppler_window_hz,
            "{}: off {} Hz, window {}",
            h.sat,
            h.doppler_hz - truth,
            h.doppler_window_hz
        );
        assert!(
            h.doppler_window_hz < 3000.0,
            "{}: window {}",
            h.sat,
            h.doppler_window_hz
        );
    }
}

#[test]
fn ground_receiver_sees_what_is_above_its_mask() {
    let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
    let store = nominal::gps_store(start);
    let site = geodetic_to_ecef(&Geodetic {
        lat_rad: 0.5,
        lon_rad: 2.0,
        h_m: 10.0,
    });
    let a = Assistance {
        t_s: 600.0,
        time_uncertainty_s: 1.0,
        r_ecef_m: site,
        v_ecef_mps: Vec3::zeros(),
        position_uncertainty_m: 1e3,
        velocity_uncertainty_mps: 0.0,
        oscillator_uncertainty: 1e-6,
        elevation_mask_rad: 10f64.to_radians(),
    };
    let hints = search_hints(&store, &a, Signal::GpsL1Ca);
    assert!((5..=14).contains(&hints.len()), "{}", hints.len());
    assert!(
        hints
            .iter()
            .all(|h| h.elevation_rad >= 10f64.to_radians() && h.doppler_hz.abs() < 5000.0)
    );
    assert!(
        hints
            .windows(2)
            .all(|w| w[0].elevation_rad >= w[1].elevation_rad)
    );
}
