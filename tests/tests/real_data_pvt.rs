//! The receiver's single-point solution on real observations: station ESBC00DNK
//! (Esbjerg), 2020-06-25, its own broadcast navigation file (ephemerides and Klobuchar
//! coefficients), GPS C1C and BeiDou C2I (B1I) pseudoranges every 30 min, against the
//! station position in the observation file's header.

use hifitime::TimeScale;
use rinex::prelude::{Constellation, Observable};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::{Measurement, PvtConfig, solve};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_orbits::ephemeris::rinex_nav_iono::read_iono_file;
use skyforge_orbits::ephemeris::{EphemerisStore, SatId, System};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeMap;

/// One epoch every this many seconds.
const EVERY_S: f64 = 1800.0;

#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn single_point_fixes_on_real_observations_are_within_metres_of_the_station() {
    let data = skyforge_orbits::real_data::require_dir();
    let nav = data.join("nav/ESBC00DNK_R_20201770000_01D_MN.rnx.gz");
    let obs =
        rinex::Rinex::from_gzip_file(data.join("obs/ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz"))
            .expect("observation file");
    let (x, y, z) = obs.header.rx_position.expect("APPROX POSITION XYZ");
    let station = Vec3::new(x, y, z);
    let start = hifitime::Epoch::from_gregorian_str("2020-06-25T00:00:00 GPST").unwrap();
    let origin = TimeOrigin::new(start);
    let store = EphemerisStore::new(read_nav_file(&nav).unwrap(), &origin);
    let iono = read_iono_file(&nav).unwrap();
    let cfg = PvtConfig {
        iono_gps: iono.gps,
        iono_bds: iono.bds,
        ..PvtConfig::default()
    };
    // Pseudoranges per epoch (GPST seconds since the start).
    let mut epochs: BTreeMap<i64, Vec<Measurement>> = BTreeMap::new();
    for (key, o) in obs.signal_observations_iter() {
        let t = (key.epoch.to_time_scale(TimeScale::GPST) - start).to_seconds();
        if t.rem_euclid(EVERY_S) != 0.0 {
            continue;
        }
        let (system, signal) = match (o.sv.constellation, &o.observable) {
            (Constellation::GPS, Observable::PseudoRange(c)) if c == "C1C" => {
                (System::Gps, Signal::GpsL1Ca)
            }
            (Constellation::BeiDou, Observable::PseudoRange(c)) if c == "C2I" => {
                (System::Beidou, Signal::BdsB1I)
            }
            _ => continue,
        };
        epochs.entry(t as i64).or_default().push(Measurement {
            sat: SatId {
                system,
                prn: o.sv.prn,
            },
            pseudorange_m: o.value,
            doppler_hz: None,
            signal,
        });
    }
    assert!(epochs.len() >= 40, "{} epochs", epochs.len());
    let mut errors = Vec::new();
    let mut excluded = 0;
    for (label, systems) in [
        ("GPS", vec![System::Gps]),
        ("BeiDou", vec![System::Beidou]),
        ("GPS + BeiDou", vec![System::Gps, System::Beidou]),
    ] {
        let mut e = Vec::new();
        for (&t, meas) in &epochs {
            let meas: Vec<Measurement> = meas
                .iter()
                .copied()
                .filter(|m| systems.contains(&m.sat.system))
                .collect();
            let Ok(fix) = solve(&meas, t as f64, &store, &origin, &cfg, None) else {
                continue;
            };
            excluded += fix.excluded.len();
            e.push((fix.r_ecef_m - station).norm());
        }
        let rms = (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt();
        let worst = e.iter().cloned().fold(0.0, f64::max);
        println!(
            "{label}: {} fixes of {} epochs, 3D error RMS {rms:.2} m, worst {worst:.2} m",
            e.len(),
            epochs.len()
        );
        errors.push((label, e.len(), rms, worst));
    }
    println!("satellites excluded by the residual test: {excluded}");
    for (label, n, rms, worst) in errors {
        assert!(n >= 40, "{label}: {n} fixes");
        // Broadcast orbits and clocks (~1-2 m), Klobuchar (~50 % of the ionosphere) and a
        // standard troposphere: single-frequency SPP is good to a few metres.
        assert!(
            rms < 5.0 && worst < 15.0,
            "{label}: RMS {rms} m, worst {worst} m"
        );
    }
}
