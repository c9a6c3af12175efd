//! Hand-built epoch reports for the tests of the receiver's writers (here and in the
//! crates that write its outputs), compiled for tests and with the `test-support`
//! feature only.
use crate::observables::Observation;
use crate::pipeline::{AntennaFix, EpochReport};
use hifitime::{Epoch, TimeScale};
use skyforge_navigation::pvt::{Dop, Fix, PvtError, VelocityFix};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{SatId, System};

pub fn gps(prn: u8) -> SatId {
    SatId {
        system: System::Gps,
        prn,
    }
}

pub fn bds(prn: u8) -> SatId {
    SatId {
        system: System::Beidou,
        prn,
    }
}

pub fn observation(antenna: usize, sat: SatId, k: usize, loss_of_lock: bool) -> Observation {
    Observation {
        antenna,
        sat,
        signal: skyforge_gnss::signal::Signal::of_system(sat.system),
        pseudorange_m: 2.0e7 + 1000.0 * f64::from(sat.prn) + 100.0 * k as f64,
        carrier_phase_cycles: 1.05e8 + 1.25 * k as f64,
        doppler_hz: -1500.0 + f64::from(sat.prn),
        cn0_dbhz: 40.0 + f64::from(sat.prn) / 10.0,
        lock_time_s: 0.1 * k as f64,
        loss_of_lock,
    }
}

/// A fix at `r_ecef_m` with `sats` used.
pub fn fix(r_ecef_m: Vec3, sats: &[SatId]) -> Fix {
    Fix {
        t_s: 0.0,
        r_ecef_m,
        clock_bias_m: 1500.0,
        inter_system_bias_m: None,
        dop: Dop {
            gdop: 2.5,
            pdop: 2.1,
            hdop: 1.2,
            vdop: 1.7,
            tdop: 1.3,
        },
        used: sats.iter().map(|&s| (s, 0.5, 0.7)).collect(),
        excluded: vec![],
        chi2: 1.0,
        dof: sats.len().saturating_sub(4),
        protection: None,
    }
}

/// Epoch `k` of a two-antenna run at 10 Hz starting 2022-01-01 00:00:30.0000001 GPST:
/// antenna 0 sees G07, G12, G19, C19 (G12 loses lock at epoch 2) and fixes from epoch 1
/// on (with velocity from epoch 2); antenna 1 sees G07 only and never fixes.
pub fn report(k: usize) -> EpochReport {
    let t0 = Epoch::from_gregorian(2022, 1, 1, 0, 0, 30, 100, TimeScale::GPST);
    let sats = [gps(7), gps(12), gps(19), bds(19)];
    let mut observations: Vec<Observation> = sats
        .iter()
        .map(|&s| observation(0, s, k, k == 0 || (k == 2 && s == gps(12))))
        .collect();
    observations.push(observation(1, gps(7), k, k == 0));
    let r = Vec3::new(-2_267_749.0, 5_009_154.0, 3_221_290.0);
    let fix0 = if k >= 1 {
        Ok(fix(r, &sats))
    } else {
        Err(PvtError::TooFewSatellites {
            have: 3,
            need: 5,
            clocks: 2,
        })
    };
    EpochReport {
        sample_index: k as f64 * 409_200.0,
        t_rx: t0 + hifitime::Duration::from_milliseconds(100.0 * k as f64),
        observations,
        fixes: vec![
            AntennaFix {
                antenna: 0,
                fix: fix0,
                velocity: (k >= 2).then_some(VelocityFix {
                    v_ecef_mps: Vec3::new(1.0, -2.0, 0.5),
                    clock_drift_mps: 0.25,
                }),
            },
            AntennaFix {
                antenna: 1,
                fix: Err(PvtError::Singular),
                velocity: None,
            },
        ],
    }
}
