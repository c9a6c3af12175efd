//! Single-point positioning against pseudoranges built here from the ephemerides: the
//! light-time solved in the rotating Earth frame by fixed-point iteration, satellite clock
//! with group delay, broadcast ionosphere, standard troposphere and a receiver clock.

mod pvt_support;

use pvt_support::{World, world};

use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::{Measurement, PvtConfig, PvtError, solve, solve_velocity};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, F_BDS_B1I_HZ, F_GPS_L1_HZ, OMEGA_E_BDS, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{KlobucharCoeffs, bds_klobuchar_b1i_s, gps_klobuchar_l1_s};
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::frames::{az_el, c_ecef_ned};
use skyforge_orbits::time::{bdt_week_sow, gpst_week_sow};
use skyforge_orbits::troposphere::standard_slant_delay_m;

const GPS_IONO: KlobucharCoeffs = KlobucharCoeffs {
    alpha: [1.2e-8, -7.5e-9, -6.0e-8, 1.2e-7],
    beta: [1.2e5, -2.5e5, -6.6e4, 1.1e6],
};
const BDS_IONO: KlobucharCoeffs = KlobucharCoeffs {
    alpha: [4.2e-8, 4.4e-7, -2.9e-6, 3.6e-6],
    beta: [8.4e4, 1.0e6, -7.8e6, 8.3e6],
};

/// The pseudorange (m) and Doppler (Hz) of `sat` for a receiver at `r` moving at `v`,
/// received at true time `t_s` with clock offset `clock_m` and drift `drift_mps`, and the
/// satellite's elevation (rad).
#[allow(clippy::too_many_arguments)]
fn observe(
    w: &World,
    sat: SatId,
    t_s: f64,
    r: &Vec3,
    v: &Vec3,
    clock_m: f64,
    drift_mps: f64,
    ground: bool,
) -> (f64, f64, f64) {
    let eph = w.store.select(sat, t_s).unwrap();
    let omega = if sat.system == System::Gps {
        OMEGA_E_GPS
    } else {
        OMEGA_E_BDS
    };
    // Fixed point: tau = |R3(omega tau) r_sat(t - tau) - r| / c.
    let at = |tau: f64| {
        let (p, vs) = eph.state_ecef(t_s - tau);
        let (s, c) = (omega * tau).sin_cos();
        let rot = |x: Vec3| Vec3::new(c * x.x + s * x.y, -s * x.x + c * x.y, x.z);
        (rot(p), rot(vs))
    };
    let mut tau = 0.07;
    for _ in 0..10 {
        tau = (at(tau).0 - r).norm() / C_MPS;
    }
    let (p, vs) = at(tau);
    let los = (p - r) / (p - r).norm();
    let g = ecef_to_geodetic(r);
    let (az, el) = az_el(&(c_ecef_ned(g.lat_rad, g.lon_rad) * los));
    let t_tx = t_s - tau;
    let sat_clock_m = C_MPS * (eph.clock_offset_s(t_tx) - eph.eph.clock.tgd_s);
    let mut media = 0.0;
    if ground {
        let at = w.origin.epoch_at(t_s);
        media += C_MPS
            * match sat.system {
                System::Gps | System::Galileo => {
                    gps_klobuchar_l1_s(&GPS_IONO, g.lat_rad, g.lon_rad, az, el, gpst_week_sow(at).1)
                }
                System::Beidou => {
                    bds_klobuchar_b1i_s(&BDS_IONO, g.lat_rad, g.lon_rad, az, el, bdt_week_sow(at).1)
                }
            };
        media += standard_slant_delay_m(g.lat_rad, g.h_m, el, 0.5);
    }
    let pr = C_MPS * tau + clock_m - sat_clock_m + media;
    let f = if sat.system == System::Gps {
        F_GPS_L1_HZ
    } else {
        F_BDS_B1I_HZ
    };
    let range_rate = los.dot(&(vs - v)) + drift_mps - C_MPS * eph.clock_drift(t_tx);
    (pr, -range_rate * f / C_MPS, el)
}

fn measurements(
    w: &World,
    systems: &[System],
    t_s: f64,
    r: &Vec3,
    v: &Vec3,
    clocks_m: (f64, f64),
    ground: bool,
) -> Vec<Measurement> {
    w.store
        .satellites()
        .into_iter()
        .filter(|s| systems.contains(&s.system))
        .filter_map(|sat| {
            let clock = if sat.system == System::Gps {
                clocks_m.0
            } else {
                clocks_m.1
            };
            let (pr, doppler, el) = observe(w, sat, t_s, r, v, clock, 55.0, ground);
            (el > 12f64.to_radians()).then(|| Measurement {
                sat,
                pseudorange_m: pr,
                doppler_hz: Some(doppler),
                signal: Signal::of_system(sat.system),
            })
        })
        .collect()
}

fn ground_config() -> PvtConfig {
    PvtConfig {
        iono_gps: Some(GPS_IONO),
        iono_bds: Some(BDS_IONO),
        ..PvtConfig::default()
    }
}

fn site() -> Vec3 {
    geodetic_to_ecef(&Geodetic {
        lat_rad: 30f64.to_radians(),
        lon_rad: 114f64.to_radians(),
        h_m: 50.0,
    })
}

#[test]
fn gps_ground_fix_recovers_position_clock_and_velocity() {
    let w = world(true);
    let (t_true, clock_m) = (3600.0, 3e-4 * C_MPS);
    let r = site();
    let meas = measurements(
        &w,
        &[System::Gps],
        t_true,
        &r,
        &Vec3::zeros(),
        (clock_m, 0.0),
        true,
    );
    assert!(meas.len() >= 6, "{} satellites", meas.len());
    let t_tag = t_true + clock_m / C_MPS;
    let fix = solve(&meas, t_tag, &w.store, &w.origin, &ground_config(), None).unwrap();
    let err = (fix.r_ecef_m - r).norm();
    assert!(err < 0.01, "position error {err} m");
    assert!(
        (fix.clock_bias_m - clock_m).abs() < 0.01,
        "clock {}",
        fix.clock_bias_m
    );
    assert!((fix.t_s - t_true).abs() < 1e-10);
    assert!(fix.excluded.is_empty() && fix.inter_system_bias_m.is_none());
    assert!(fix.dop.pdop > 1.0 && fix.dop.pdop < 6.0 && fix.dop.hdop < fix.dop.pdop);
    let vel = solve_velocity(&meas, t_tag, &w.store, &fix).unwrap();
    assert!(vel.v_ecef_mps.norm() < 1e-3, "velocity {}", vel.v_ecef_mps);
    assert!((vel.clock_drift_mps - 55.0).abs() < 1e-3);
}

#[test]
fn gps_and_beidou_share_a_fix_with_an_inter_system_bias() {
    let w = world(true);
    let (t_true, gps_clock, bds_clock) = (7200.0, 150.0, 162.5);
    let r = site();
    let meas = measurements(
        &w,
        &[System::Gps, System::Beidou],
        t_true,
        &r,
        &Vec3::zeros(),
        (gps_clock, bds_clock),
        true,
    );
    let t_tag = t_true + gps_clock / C_MPS;
    let fix = solve(&meas, t_tag, &w.store, &w.origin, &ground_config(), None).unwrap();
    assert!(
        (fix.r_ecef_m - r).norm() < 0.01,
        "{}",
        (fix.r_ecef_m - r).norm()
    );
    let isb = fix.inter_system_bias_m.expect("two systems");
    assert!((isb - 12.5).abs() < 0.01, "ISB {isb}");
    // BeiDou alone: its own clock.
    let bds: Vec<Measurement> = meas
        .iter()
        .copied()
        .filter(|m| m.sat.system == System::Beidou)
        .collect();
    let fix = solve(&bds, t_tag, &w.store, &w.origin, &ground_config(), None).unwrap();
    assert!((fix.r_ecef_m - r).norm() < 0.01);
    assert!((fix.clock_bias_m - bds_clock).abs() < 0.01);
}

#[test]
fn leo_fix_without_atmosphere() {
    let w = world(true);
    let r = geodetic_to_ecef(&Geodetic {
        lat_rad: 0.3,
        lon_rad: -1.2,
        h_m: 600e3,
    });
    let v = Vec3::new(1200.0, -5300.0, 4900.0);
    let meas = measurements(
        &w,
        &[System::Gps, System::Beidou],
        500.0,
        &r,
        &v,
        (-20.0, -20.0),
        false,
    );
    // Troposphere and ionosphere stay switched on: above their ceilings they do nothing.
    let t_tag = 500.0 - 20.0 / C_MPS;
    let fix = solve(&meas, t_tag, &w.store, &w.origin, &ground_config(), None).unwrap();
    assert!(
        (fix.r_ecef_m - r).norm() < 0.01,
        "{}",
        (fix.r_ecef_m - r).norm()
    );
    let vel = solve_velocity(&meas, t_tag, &w.store, &fix).unwrap();
    assert!((vel.v_ecef_mps - v).norm() < 1e-3, "{}", vel.v_ecef_mps - v);
}

#[test]
fn residual_test_excludes_a_faulty_satellite() {
    let w = world(true);
    let r = site();
    let mut meas = measurements(
        &w,
        &[System::Gps, System::Beidou],
        1000.0,
        &r,
        &Vec3::zeros(),
        (0.0, 0.0),
        true,
    );
    assert!(meas.len() >= 10);
    // Code noise of the assumed size (Box-Muller on a fixed LCG), then a 60 m fault.
    let mut state = 12345u64;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    for m in &mut meas {
        let (u1, u2) = (uniform(), uniform());
        m.pseudorange_m += 0.3 * (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
    }
    let faulty = meas[3].sat;
    meas[3].pseudorange_m += 60.0;
    let fix = solve(&meas, 1000.0, &w.store, &w.origin, &ground_config(), None).unwrap();
    assert_eq!(fix.excluded, vec![faulty]);
    assert!(
        (fix.r_ecef_m - r).norm() < 3.0,
        "{}",
        (fix.r_ecef_m - r).norm()
    );
    // Without the test the fault pulls the fix away.
    let off = PvtConfig {
        raim_pfa: 0.0,
        ..ground_config()
    };
    let biased = solve(&meas, 1000.0, &w.store, &w.origin, &off, None).unwrap();
    assert!(biased.excluded.is_empty());
    assert!((biased.r_ecef_m - r).norm() > (fix.r_ecef_m - r).norm());
}

#[test]
fn too_few_satellites_is_an_error() {
    let w = world(true);
    let meas = measurements(
        &w,
        &[System::Gps],
        0.0,
        &site(),
        &Vec3::zeros(),
        (0.0, 0.0),
        true,
    );
    let err = solve(&meas[..3], 0.0, &w.store, &w.origin, &ground_config(), None).unwrap_err();
    assert!(
        matches!(
            err,
            PvtError::TooFewSatellites {
                have: 3,
                need: 4,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn gga_and_rmc_carry_the_fix() {
    use skyforge_navigation::pvt::{gga, gsa, rmc};
    let w = world(true);
    let r = site();
    let v = Vec3::new(3.0, 4.0, 0.0);
    let meas = measurements(&w, &[System::Gps], 100.0, &r, &v, (0.0, 0.0), true);
    let fix = solve(&meas, 100.0, &w.store, &w.origin, &ground_config(), None).unwrap();
    let vel = solve_velocity(&meas, 100.0, &w.store, &fix).unwrap();
    let line = gga(&fix, 3723.5);
    let f: Vec<&str> = line.split(',').collect();
    assert_eq!(f[0], "$GPGGA");
    assert_eq!(f[1], "010203.50");
    let lat = f[2][..2].parse::<f64>().unwrap() + f[2][2..].parse::<f64>().unwrap() / 60.0;
    let lon = f[4][..3].parse::<f64>().unwrap() + f[4][3..].parse::<f64>().unwrap() / 60.0;
    assert!((lat - 30.0).abs() < 1e-6 && f[3] == "N", "{line}");
    assert!((lon - 114.0).abs() < 1e-6 && f[5] == "E", "{line}");
    assert!((f[9].parse::<f64>().unwrap() - 50.0).abs() < 0.01, "{line}");
    assert_eq!(f[7].parse::<usize>().unwrap(), meas.len());
    assert!(gsa(&fix).starts_with("$GPGSA,A,3,"));
    // 5 m/s over ground; the course of an ECEF (3, 4, 0) m/s velocity at 114 E.
    let line = rmc(&fix, &vel, 3723.5, "120323");
    let f: Vec<&str> = line.split(',').collect();
    let speed_mps = f[7].parse::<f64>().unwrap() * 1852.0 / 3600.0;
    let g = skyforge_orbits::frames::ecef_to_geodetic(&r);
    let v_ned = c_ecef_ned(g.lat_rad, g.lon_rad) * v;
    assert!((speed_mps - v_ned.x.hypot(v_ned.y)).abs() < 0.01, "{line}");
    assert_eq!(f[9], "120323");
}
