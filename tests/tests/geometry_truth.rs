//! Geometry truth of the bundled thesis LEO scenario checked against independent
//! computations: the light time in an explicitly inertial frame, and the sub-millimetre
//! interpolation the synthesiser will rely on.

use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::platform::PlatformWindow;
use skyforge_signals::truth::QuinticHermite;
use skyforge_signals::truth::light_time;
use skyforge_signals::truth::{GeometryChunk, GeometryTruth, TrueSatellite};

/// Ten minutes of 1 Hz geometry of the thesis LEO (all antennas, GPS + BeiDou).
fn thesis_chunk() -> (
    skyforge_scenarios::World,
    PlatformWindow,
    GeometryChunk,
    Vec<SatId>,
) {
    let scenario = skyforge_scenarios::resolve("thesis-leo").unwrap();
    let mut world = scenario.build().unwrap();
    let sats = world.satellites.clone();
    let truth = GeometryTruth::new(&world.ephemerides, &sats, &world.antennas, 1.0);
    let margin = truth.window_margin_s();
    let window = world.platform.window(-margin, 600.0 + margin).unwrap();
    let chunk = truth.chunk(&window, 0.0, 601);
    drop(truth);
    (world, window, chunk, sats)
}

#[test]
fn light_time_closes_in_an_inertial_frame_and_interpolation_is_sub_millimetre() {
    let (world, window, chunk, sats) = thesis_chunk();
    let mut links = 0;
    let mut worst_interp_m: f64 = 0.0;
    let mut worst_rate_mps: f64 = 0.0;
    let mut worst_inertial_m: f64 = 0.0;
    for (a, ant) in world.antennas.iter().enumerate() {
        for (s, sat) in sats.iter().enumerate() {
            for k in (0..600).step_by(7) {
                let (l0, l1) = (chunk.link(k, a, s), chunk.link(k + 1, a, s));
                if !(l0.visible && l1.visible) {
                    continue;
                }
                links += 1;
                let t_mid = k as f64 + 0.5;
                let st = window.state(t_mid);
                let r_ant = st.r_ecef_m + st.c_body_ecef * ant.true_body_m;
                let eph = world.ephemerides.select(*sat, chunk.t_s[k]).unwrap();
                let eph = TrueSatellite::broadcast(eph);
                let direct = light_time::solve(&eph, &r_ant, t_mid, l0.light_time_s);

                // Interpolation between the 1 Hz epochs against the direct solution.
                let q = QuinticHermite::new(
                    chunk.t_s[k],
                    chunk.t_s[k + 1],
                    [l0.range_m, l0.range_rate_mps, l0.range_accel_mps2],
                    [l1.range_m, l1.range_rate_mps, l1.range_accel_mps2],
                );
                worst_interp_m = worst_interp_m.max((q.value(t_mid) - direct.range_m()).abs());
                // Reference rate: five-point central difference of direct solutions with a
                // 50 ms spacing (rounding ~1e-6 m/s, truncation ~1e-10 m/s).
                let range_at = |t: f64| {
                    let st = window.state(t);
                    light_time::solve(
                        &eph,
                        &(st.r_ecef_m + st.c_body_ecef * ant.true_body_m),
                        t,
                        direct.tau_s,
                    )
                    .range_m()
                };
                let h = 0.05;
                let rate = (range_at(t_mid - 2.0 * h) - 8.0 * range_at(t_mid - h)
                    + 8.0 * range_at(t_mid + h)
                    - range_at(t_mid + 2.0 * h))
                    / (12.0 * h);
                worst_rate_mps = worst_rate_mps.max((q.rate(t_mid) - rate).abs());

                // The same path in the ECI frame: satellite at transmit time, antenna at
                // receive time, each rotated with its own epoch's Earth angle.
                let t_tx = t_mid - direct.tau_s;
                let (r_sat_eci, _) =
                    world
                        .earth
                        .ecef_to_eci(t_tx, &eph.position_ecef(t_tx), &Default::default());
                let (r_ant_eci, _) = world.earth.ecef_to_eci(t_mid, &r_ant, &Default::default());
                worst_inertial_m = worst_inertial_m
                    .max(((r_sat_eci - r_ant_eci).norm() - C_MPS * direct.tau_s).abs());
            }
        }
    }
    assert!(links > 500, "too few visible links checked: {links}");
    println!(
        "links {links}: interpolation {worst_interp_m:.3e} m, rate {worst_rate_mps:.3e} m/s, inertial closure {worst_inertial_m:.3e} m"
    );
    assert!(
        worst_interp_m < 1e-4,
        "quintic interpolation error {worst_interp_m} m at 1 Hz"
    );
    assert!(
        worst_rate_mps < 1e-5,
        "interpolated range rate error {worst_rate_mps} m/s"
    );
    assert!(
        worst_inertial_m < 1e-3,
        "light time does not close in ECI: {worst_inertial_m} m"
    );
}

#[test]
fn doppler_is_minus_range_rate_over_wavelength_and_angles_are_consistent() {
    let (world, _, chunk, sats) = thesis_chunk();
    let mut seen = 0;
    for a in 0..world.antennas.len() {
        for (s, sat) in sats.iter().enumerate() {
            let f = skyforge_gnss::signal::Signal::of_system(sat.system).carrier_hz();
            for k in 0..chunk.t_s.len() {
                let l = chunk.link(k, a, s);
                if !l.visible {
                    assert!(l.range_m.is_nan());
                    continue;
                }
                seen += 1;
                assert!((l.doppler_hz + l.range_rate_mps * f / C_MPS).abs() < 1e-9 * f);
                assert!((l.range_m - C_MPS * l.light_time_s).abs() < 1e-6);
                // +/-80 deg field of view about zenith: antenna elevation at least 10 deg.
                assert!(l.antenna_elevation_rad >= 10f64.to_radians() - 1e-9);
                // A LEO-to-MEO/GEO range lies between 19,000 and 48,000 km.
                assert!((1.9e7..4.8e7).contains(&l.range_m), "{sat}: {}", l.range_m);
                assert!(l.doppler_hz.abs() < 6.0e4);
            }
        }
    }
    assert!(seen > 1000);
}

/// With `[errors.satellite]` (the book's SA-era processes) every link's range and clock
/// move by exactly the truth's per-link errors: against the same geometry without errors,
/// the range differs by `sat_orbit_error_m` (within 5 mm: the second-order term
/// |d|^2 / 2 rho and the light time's change, both under 1e-4 m here, and the satellite's
/// motion during the changed light time, v d/c, under 1 mm for |d| < 80 m), the
/// satellite clock by `sat_clock_error_m` / c, and the range rate by the orbit error's
/// rate (finite difference of the truth's own values, within 1 mm/s). Two antennas see
/// the same satellite clock error (within 1 um), and orbit errors that agree along their (almost
/// parallel) lines of sight within 1 mm.
#[test]
fn satellite_errors_move_each_link_by_its_recorded_error() {
    use skyforge_signals::errors::{SatelliteErrors, SatelliteModel};
    let (world, window, plain, sats) = thesis_chunk();
    let errors = SatelliteErrors::draw(&SatelliteModel::BookSa.into(), 11, &sats, 600.0);
    let truth = GeometryTruth::new(&world.ephemerides, &sats, &world.antennas, 1.0)
        .with_satellite_errors(&errors);
    let chunk = truth.chunk(&window, 0.0, 601);
    let mut checked = 0;
    let (mut largest_orbit, mut largest_clock) = (0.0_f64, 0.0_f64);
    for (s, sat) in sats.iter().enumerate() {
        for k in 1..600 {
            for a in 0..world.antennas.len() {
                let (p, e) = (plain.link(k, a, s), chunk.link(k, a, s));
                if !(p.visible && e.visible) {
                    continue;
                }
                checked += 1;
                let d_range = e.range_m - p.range_m;
                assert!(
                    (d_range - e.sat_orbit_error_m).abs() < 5e-3,
                    "{sat} k={k}: range moved {d_range} m, recorded {} m",
                    e.sat_orbit_error_m
                );
                let d_clock = (e.sat_clock_s - p.sat_clock_s) * C_MPS;
                assert!((d_clock - e.sat_clock_error_m).abs() < 1e-6);
                let (before, after) = (chunk.link(k - 1, a, s), chunk.link(k + 1, a, s));
                if before.visible && after.visible {
                    let rate = (after.sat_orbit_error_m - before.sat_orbit_error_m) / 2.0;
                    let d_rate = e.range_rate_mps - p.range_rate_mps;
                    assert!((d_rate - rate).abs() < 1e-3, "rate {d_rate} vs {rate}");
                }
                let first = chunk.link(k, 0, s);
                if a > 0 && first.visible {
                    // The same path, at transmit times nanoseconds apart.
                    assert!((first.sat_clock_error_m - e.sat_clock_error_m).abs() < 1e-6);
                    assert!((first.sat_orbit_error_m - e.sat_orbit_error_m).abs() < 1e-3);
                }
                largest_orbit = largest_orbit.max(e.sat_orbit_error_m.abs());
                largest_clock = largest_clock.max(e.sat_clock_error_m.abs());
            }
        }
    }
    assert!(checked > 10_000, "{checked} links");
    // SA-sized errors, not zero: 1-sigma 11.5 m per orbit axis, 30 m clock.
    assert!(largest_orbit > 5.0 && largest_clock > 20.0);
    for l in &plain.links {
        assert!(!l.visible || (l.sat_orbit_error_m == 0.0 && l.sat_clock_error_m == 0.0));
    }
}
