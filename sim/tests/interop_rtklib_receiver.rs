//! Interoperability tier: RTKLIB (Debian package `rtklib`) reads the receiver's RINEX 3.04
//! observation files (`skyforge_receiver::session::RinexObsFiles`): receiver time tags with a fractional second, loss-of-lock
//! indicators, signal strength indicators.
//!
//! - `convbin` re-reads our file and writes it again in its own RINEX writer: the epochs,
//!   satellites, values and loss-of-lock flags it writes back are the ones we wrote.
//! - `rnx2rtkp` solves single-point positions from receiver-style observations made of
//!   the synthesiser's truth (`skyforge synth`, interop-gps-static, troposphere off, its
//!   navigation file): each epoch tagged at a fractional second with a receiver clock
//!   offset of the same size in the pseudoranges. RTKLIB's solution time (tag minus its
//!   clock estimate) must land back on the true whole second, and its position on the site.

mod support;

use hifitime::{Duration, Epoch, TimeScale};
use rinex::prelude::{Constellation, Observable};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::PvtError;
use skyforge_orbits::constants::{C_MPS, F_GPS_L1_HZ};
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_receiver::observables::Observation;
use skyforge_receiver::pipeline::fixtures::{fix, report};
use skyforge_receiver::pipeline::{AntennaFix, EpochReport};
use skyforge_receiver::session::RinexObsFiles;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use support::{rtklib_numeric_rows, skyforge_ok};

fn require(program: &str) {
    assert!(
        Command::new(program).arg("-?").output().is_ok(),
        "\n*** {program} is not installed: apt-get install rtklib (scripts/test.sh does) ***\n"
    );
}

/// Run `program` in `dir` and insist on success.
fn run(dir: &Path, program: &str, args: &[&str]) {
    let o = Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{program} {args:?} failed: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The data records of a RINEX 3 observation file: per epoch line, its satellite lines.
fn records(text: &str) -> Vec<(String, Vec<String>)> {
    let body = text.split("END OF HEADER").nth(1).unwrap_or("");
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    for line in body.lines() {
        if line.starts_with('>') {
            out.push((line[..35].to_string(), Vec::new()));
        } else if let Some(last) = out.last_mut() {
            last.1.push(line.trim_end().to_string());
        }
    }
    out
}

/// Numbers of the F14.3 fields of a satellite line, and the phase's loss-of-lock digit.
fn values(line: &str) -> (String, Vec<f64>, char) {
    let field = |i: usize| line.get(3 + 16 * i..3 + 16 * i + 14).unwrap_or("").trim();
    let v = (0..4)
        .map(|i| field(i).parse().unwrap_or(f64::NAN))
        .collect();
    let lli = line.as_bytes().get(33).map_or(' ', |&b| char::from(b));
    (line[..3].to_string(), v, lli)
}

#[test]
#[ignore = "interop tier: needs rtklib (scripts/test.sh installs it)"]
fn rtklib_convbin_reads_back_epochs_flags_and_values() {
    require("convbin");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let names = vec!["ant1".to_string()];
    let mut out = RinexObsFiles::new(dir, &names, &[Signal::GpsL1Ca, Signal::BdsB1I], None, 0.1);
    for k in 0..5 {
        let mut r = report(k);
        r.observations.retain(|o| o.antenna == 0);
        r.fixes.truncate(1);
        out.write_epoch(&r).unwrap();
    }
    out.finish().unwrap();
    // -od -os: keep Doppler and signal strength.
    run(
        dir,
        "convbin",
        &[
            "-r",
            "rinex",
            "-v",
            "3.04",
            "-od",
            "-os",
            "-o",
            "rtklib.obs",
            "ant1.obs.rnx",
        ],
    );
    let ours = records(&std::fs::read_to_string(dir.join("ant1.obs.rnx")).unwrap());
    let theirs = records(&std::fs::read_to_string(dir.join("rtklib.obs")).unwrap());
    println!("RTKLIB convbin read back {} epochs", theirs.len());
    assert_eq!(ours.len(), 5);
    assert_eq!(theirs.len(), ours.len());
    let mut flags = Vec::new();
    for (k, ((our_epoch, our_sats), (their_epoch, their_sats))) in
        ours.iter().zip(&theirs).enumerate()
    {
        assert_eq!(their_epoch, our_epoch);
        assert_eq!(their_sats.len(), our_sats.len(), "{our_epoch}");
        for (o, t) in our_sats.iter().zip(their_sats) {
            let (sat, ov, olli) = values(o);
            let (their_sat, tv, tlli) = values(t);
            assert_eq!(their_sat, sat);
            for (a, b) in ov.iter().zip(&tv) {
                assert!((a - b).abs() < 1e-3, "{sat} at {our_epoch}: {o} vs {t}");
            }
            assert_eq!(tlli, olli, "{sat} at {our_epoch}");
            if tlli == '1' {
                flags.push((k, sat));
            }
        }
    }
    // Every satellite starts with lock lost; G12 loses it again at epoch 2.
    let expected: Vec<(usize, String)> = ["G07", "G12", "G19", "C19"]
        .iter()
        .map(|s| (0, s.to_string()))
        .chain([(2, "G12".to_string())])
        .collect();
    assert_eq!(flags, expected);
    assert!(theirs[1].0.ends_with("30.1000001  0  4"), "{}", theirs[1].0);
}

/// The truth observations of `ant1.obs.rnx`: per whole-second GPST epoch, per satellite,
/// C1C, L1C, D1C, S1C.
fn truth_observations(path: &Path) -> BTreeMap<Epoch, BTreeMap<SatId, [f64; 4]>> {
    let rnx = rinex::Rinex::from_file(path).unwrap();
    let mut out: BTreeMap<Epoch, BTreeMap<SatId, [f64; 4]>> = BTreeMap::new();
    for (key, o) in rnx.signal_observations_iter() {
        assert_eq!(o.sv.constellation, Constellation::GPS);
        let i = match &o.observable {
            Observable::PseudoRange(_) => 0,
            Observable::PhaseRange(_) => 1,
            Observable::Doppler(_) => 2,
            Observable::SSI(_) => 3,
            other => panic!("{other:?}"),
        };
        let sat = SatId {
            system: System::Gps,
            prn: o.sv.prn,
        };
        out.entry(key.epoch.to_time_scale(TimeScale::GPST))
            .or_default()
            .entry(sat)
            .or_insert([f64::NAN; 4])[i] = o.value;
    }
    out
}

#[test]
#[ignore = "interop tier: needs rtklib (scripts/test.sh installs it)"]
fn rtklib_single_point_from_fractional_second_epochs_recovers_time_and_site() {
    require("rnx2rtkp");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let toml = skyforge_ok(&["scenarios", "show", "interop-gps-static"], dir).replacen(
        "duration_s = 90.0",
        "duration_s = 10.0",
        1,
    ) + "\n[errors.troposphere]\nmodel = \"off\"\n";
    std::fs::write(dir.join("short.toml"), toml).unwrap();
    skyforge_ok(&["synth", "short.toml", "--out", "synth"], dir);
    let synth_dir = dir.join("synth");
    let truth = truth_observations(&synth_dir.join("ant1.obs.rnx"));
    assert!(truth.len() >= 10, "{} truth epochs", truth.len());

    let site = geodetic_to_ecef(&Geodetic {
        lat_rad: 30f64.to_radians(),
        lon_rad: 114f64.to_radians(),
        h_m: 50.0,
    });
    let recv_dir = dir.join("receive");
    std::fs::create_dir(&recv_dir).unwrap();
    let mut out = RinexObsFiles::new(
        &recv_dir,
        &["ant1".to_string()],
        &[Signal::GpsL1Ca],
        None,
        1.0,
    );
    // Receiver clock ahead by 0.1234567 s + k x 1.0001 ms (whole 100 ns, so the tags
    // keep it exactly): tags and pseudoranges both carry it.
    let offset_s = |k: usize| 0.123_456_7 + 0.001_000_1 * k as f64;
    let first_sat = *truth.values().next().unwrap().keys().next().unwrap();
    for (k, (t, sats)) in truth.iter().enumerate() {
        let dt_s = offset_s(k);
        let observations: Vec<Observation> = sats
            .iter()
            .map(|(&sat, v)| Observation {
                antenna: 0,
                sat,
                signal: Signal::GpsL1Ca,
                pseudorange_m: v[0] + C_MPS * dt_s,
                carrier_phase_cycles: v[1] + F_GPS_L1_HZ * dt_s,
                doppler_hz: v[2],
                cn0_dbhz: v[3],
                lock_time_s: k as f64,
                loss_of_lock: k == 0 || (k == 5 && sat == first_sat),
            })
            .collect();
        // The first epoch has no fix; later ones put the header position 40 m off.
        let fix = if k == 0 {
            Err(PvtError::Singular)
        } else {
            let sats: Vec<SatId> = sats.keys().copied().collect();
            Ok(fix(
                site + skyforge_orbits::Vec3::new(30.0, -20.0, 20.0),
                &sats,
            ))
        };
        out.write_epoch(&EpochReport {
            sample_index: 0.0,
            t_rx: *t + Duration::from_seconds(dt_s),
            observations,
            fixes: vec![AntennaFix {
                antenna: 0,
                fix,
                velocity: None,
            }],
        })
        .unwrap();
    }
    out.finish().unwrap();

    std::fs::write(
        recv_dir.join("spp.conf"),
        "pos1-posmode=single\npos1-elmask=5\npos1-ionoopt=brdc\npos1-tropopt=off\npos1-sateph=brdc\npos1-navsys=1\nout-solformat=xyz\nout-timesys=gpst\nout-timeform=tow\nout-timendec=9\n",
    )
    .unwrap();
    let nav = synth_dir.join("nav.rnx");
    run(
        &recv_dir,
        "rnx2rtkp",
        &[
            "-k",
            "spp.conf",
            "-o",
            "spp.pos",
            "ant1.obs.rnx",
            nav.to_str().unwrap(),
        ],
    );
    let pos = std::fs::read_to_string(recv_dir.join("spp.pos")).unwrap();
    // Columns: GPS week, seconds of week, x, y, z, quality, satellites, ...
    let solutions: Vec<(f64, f64, usize)> = rtklib_numeric_rows(&pos, 7)
        .iter()
        .map(|f| {
            let r = skyforge_orbits::Vec3::new(f[2], f[3], f[4]);
            (f[1], (r - site).norm(), f[6] as usize)
        })
        .collect();
    let worst_time = solutions
        .iter()
        .map(|s| (s.0 - s.0.round()).abs())
        .fold(0.0, f64::max);
    let worst_m = solutions.iter().map(|s| s.1).fold(0.0, f64::max);
    println!(
        "RTKLIB single point on receiver-style RINEX: {} of {} epochs, worst time {worst_time:.2e} s off the whole second, worst 3D error {worst_m:.4} m",
        solutions.len(),
        truth.len()
    );
    assert_eq!(solutions.len(), truth.len(), "{pos}");
    for ((tow, err_m, ns), (t, sats)) in solutions.iter().zip(&truth) {
        let sow = skyforge_orbits::time::gpst_week_sow(*t).1;
        assert!(
            (tow - sow).abs() < 1e-6,
            "solution at {tow}, truth epoch {sow}"
        );
        assert!(*err_m < 0.01, "{err_m} m from the site");
        assert!(
            *ns >= 4 && *ns <= sats.len(),
            "{ns} satellites of {}",
            sats.len()
        );
    }
}
