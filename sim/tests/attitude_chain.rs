//! `skyforge attitude` end to end on the observation level: a LEO with three antennas on
//! two 1 m baselines -> observables -> double differences, LAMBDA, fixed baselines,
//! attitude -> compared with the truth SkyForge wrote (`truth.h5`).

mod support;

use nalgebra::{Quaternion, UnitQuaternion};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::euler::YawPitchRoll;
use skyforge_orbits::frames::geodetic::ecef_to_geodetic;
use skyforge_orbits::frames::ned::c_ecef_ned;
use skyforge_orbits::time::parse_epoch;
use skyforge_validate::observables::read_obs_file;
use std::collections::HashMap;
use std::path::Path;
use support::{dataset, skyforge, skyforge_ok, text};

/// The thesis LEO with three antennas (master at the body origin, baselines of 1 m along
/// body X and Y), GPS + BDS-3 at 45 dB-Hz, a slow pitch oscillation, `duration_s` long.
fn scenario(dir: &Path, duration_s: u32, gps_only: bool, observation_level: bool) -> String {
    let base = include_str!("../../scenarios/calibration/leo-gps-bds.toml");
    let mut text = base
        .replacen(
            "duration_s = 130.0",
            &format!("duration_s = {duration_s}.0"),
            1,
        )
        .replacen("seed = 20261125", "seed = 5", 1);
    if gps_only {
        text = text.replacen("[gnss.beidou]\n", "[gnss.beidou]\nenabled = false\n", 1);
    }
    text += r#"
[platform.attitude]
pitch = { amplitude_deg = 2.0, period_s = 600.0, phase_deg = 0.0 }
roll = { offset_deg = 0.5 }

[[antennas]]
name = "ant2"
position_body_m = [1.0, 0.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 80.0

[[antennas]]
name = "ant3"
position_body_m = [0.0, 1.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 80.0

"#;
    if observation_level {
        text += "\n[observation]\nlevel = \"observation\"\n";
    }
    let path = dir.join("leo.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// True attitude (NED at the master) and true NED baselines at truth row `i`.
fn truth_at(file: &hdf5::File, i: usize) -> (YawPitchRoll, [Vec3; 2]) {
    let r: Vec<f64> = dataset(file, "platform/r_ecef_m");
    let q: Vec<f64> = dataset(file, "platform/q_body_ecef");
    let c_body_ecef = UnitQuaternion::from_quaternion(Quaternion::new(
        q[4 * i],
        q[4 * i + 1],
        q[4 * i + 2],
        q[4 * i + 3],
    ))
    .to_rotation_matrix()
    .into_inner();
    let g = ecef_to_geodetic(&Vec3::new(r[3 * i], r[3 * i + 1], r[3 * i + 2]));
    let c_body_ned = c_ecef_ned(g.lat_rad, g.lon_rad) * c_body_ecef;
    let angles = YawPitchRoll::from_c_ref_body(&c_body_ned.transpose());
    (angles, [c_body_ned * Vec3::x(), c_body_ned * Vec3::y()])
}

/// `skyforge receive` over every recording in `sim` into `rx`; returns `rx`.
fn receive(sim: &Path, rx: &Path) -> std::path::PathBuf {
    let mut meta: Vec<String> = std::fs::read_dir(sim)
        .unwrap()
        .map(|e| e.unwrap().path().to_string_lossy().into_owned())
        .filter(|p| p.ends_with(".sigmf-meta"))
        .collect();
    meta.sort();
    let (nav, config) = (sim.join("nav.rnx"), sim.join("receiver.toml"));
    let mut args: Vec<&str> = vec!["receive"];
    args.extend(meta.iter().map(String::as_str));
    args.extend([
        "--assist",
        nav.to_str().unwrap(),
        "--config",
        config.to_str().unwrap(),
        "--out",
        rx.to_str().unwrap(),
    ]);
    println!("{}", skyforge_ok(&args, sim));
    rx.to_path_buf()
}

/// Carrier phase (cycles) of every (epoch, satellite) of an observation file, keyed by the
/// epoch's printed time.
fn phases(path: &Path) -> HashMap<(String, String), f64> {
    let file = read_obs_file(path).unwrap();
    let mut out = HashMap::new();
    for e in &file.epochs {
        for r in &e.sats {
            if let Some(p) = r.carrier_phase_cycles {
                out.insert((e.time.to_string(), r.sat.to_string()), p);
            }
        }
    }
    out
}

/// Every integer in `att/ambiguities.csv` against the true double-difference integer,
/// `round(DD(observed phase) - DD(truth phase))` of the same epoch (the truth's phase has
/// no ambiguity). Returns (integers checked, wrong ones, largest distance of an observed
/// minus truth DD from its integer).
fn check_integers(att: &Path, observations: &Path, sim: &Path) -> (usize, usize, f64) {
    let names = ["ant1", "ant2", "ant3"];
    let obs: Vec<_> = names
        .iter()
        .map(|a| phases(&observations.join(format!("{a}.obs.rnx"))))
        .collect();
    let truth: Vec<_> = names
        .iter()
        .map(|a| phases(&sim.join(format!("{a}.obs.rnx"))))
        .collect();
    let text = std::fs::read_to_string(att.join("ambiguities.csv")).unwrap();
    let (mut checked, mut wrong, mut worst) = (0, 0, 0.0f64);
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (t, k) = (f[0].to_string(), f[1].parse::<usize>().unwrap());
        let integer: i64 = f[5].parse().unwrap();
        let dd = |set: &[HashMap<(String, String), f64>]| -> Option<f64> {
            let p = |a: usize, sat: &str| set[a].get(&(t.clone(), sat.to_string())).copied();
            Some((p(k, f[3])? - p(0, f[3])?) - (p(k, f[4])? - p(0, f[4])?))
        };
        let (Some(o), Some(tr)) = (dd(&obs), dd(&truth)) else {
            continue;
        };
        let d = o - tr;
        worst = worst.max((d - d.round()).abs());
        checked += 1;
        wrong += usize::from(d.round() as i64 != integer);
    }
    (checked, wrong, worst)
}

fn std(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
}

/// Run the chain with `config` (observation level, 120 s; or signal level of the given
/// duration) and return the fraction of epochs fixed from the first fix on, and the
/// per-axis NED baseline errors (m) and attitude errors (deg) of the fixed epochs.
fn chain_errors(
    gps_only: bool,
    signal_level: Option<u32>,
    config: &str,
) -> (f64, Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let dir = tempfile::tempdir().unwrap();
    let duration = signal_level.unwrap_or(120);
    let path = scenario(dir.path(), duration, gps_only, signal_level.is_none());
    let sim = dir.path().join("sim");
    skyforge_ok(&["run", &path, "--out", sim.to_str().unwrap()], dir.path());
    std::fs::write(dir.path().join("rel.toml"), config).unwrap();
    let observations = if signal_level.is_some() {
        receive(&sim, &dir.path().join("rx"))
    } else {
        sim.join("observations")
    };
    let obs: Vec<String> = ["ant1", "ant2", "ant3"]
        .iter()
        .map(|a| {
            observations
                .join(format!("{a}.obs.rnx"))
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let out = dir.path().join("att");
    let mut args: Vec<&str> = vec!["attitude"];
    args.extend(obs.iter().map(String::as_str));
    let (nav, geometry) = (sim.join("nav.rnx"), sim.join("geometry.toml"));
    let rel = dir.path().join("rel.toml");
    args.extend([
        "--nav",
        nav.to_str().unwrap(),
        "--geometry",
        geometry.to_str().unwrap(),
        "--config",
        rel.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    println!("{}", skyforge_ok(&args, dir.path()));
    let (checked, wrong, worst) = check_integers(&out, &observations, &sim);
    println!(
        "INTEGERS checked {checked}, wrong {wrong}, largest distance from an integer {worst:.3} cycles"
    );
    assert!(checked > 0);
    assert_eq!(wrong, 0, "fixed integers differ from the truth's");
    assert!(
        worst < 0.25,
        "an observed DD is {worst} cycles from an integer"
    );
    let truth = hdf5::File::open(sim.join("truth.h5")).unwrap();
    let start = parse_epoch("2023-03-12T00:00:00 GPST").unwrap();
    let mut rdr = std::fs::read_to_string(out.join("attitude.csv")).unwrap();
    let text_csv = std::mem::take(&mut rdr);
    let mut lines = text_csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (mut fixed, mut rows) = (0usize, 0usize);
    let (mut baseline_err, mut attitude_err) = (Vec::new(), Vec::new());
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        // Epochs count from the first fix on.
        let is_fixed = f[col("status")] == "fixed";
        if fixed == 0 && !is_fixed {
            continue;
        }
        rows += 1;
        if !is_fixed {
            continue;
        }
        fixed += 1;
        let t = (parse_epoch(f[0]).unwrap() - start).to_seconds().round() as usize;
        let (angles, b) = truth_at(&truth, t);
        let v = |n: &str| f[col(n)].parse::<f64>().unwrap();
        for (k, bk) in b.iter().enumerate() {
            let p = format!("b{}_", k + 1);
            baseline_err.push([
                v(&format!("{p}n_m")) - bk.x,
                v(&format!("{p}e_m")) - bk.y,
                v(&format!("{p}d_m")) - bk.z,
            ]);
        }
        if f[col("yaw_deg")].is_empty() {
            continue;
        }
        let wrap = |d: f64| (d + 180.0).rem_euclid(360.0) - 180.0;
        attitude_err.push([
            wrap(v("yaw_deg") - angles.yaw_rad.to_degrees()),
            v("pitch_deg") - angles.pitch_rad.to_degrees(),
            wrap(v("roll_deg") - angles.roll_rad.to_degrees()),
        ]);
    }
    (fixed as f64 / rows as f64, baseline_err, attitude_err)
}

/// Issue #12's bars on the observation level (the signal-level run is the acceptance
/// tier's): every epoch fixed, every fixed integer the truth's; NED baseline error std below 3 mm per axis and no epoch
/// off by a centimetre (a wrong integer moves a 1 m baseline by centimetres); attitude
/// error std below 0.1 deg per axis with the KF.
#[test]
fn leo_three_antennas_fix_every_epoch_with_millimetre_baselines() {
    check_chain(None);
}

/// The same bars at the signal level, as issue #12 states them: 300 s of I/Q for three
/// antennas -> `skyforge receive` -> `skyforge attitude`, GPS + BDS and GPS alone.
#[test]
#[ignore = "acceptance tier: 300 s of I/Q for three antennas, synthesised and received (minutes)"]
fn signal_level_leo_three_antennas_fix_every_epoch_with_millimetre_baselines() {
    check_chain(Some(300));
}

fn check_chain(signal_level: Option<u32>) {
    for gps_only in [false, true] {
        let config = "[relative]\nattitude = { method = \"kf\" }\n";
        let (fixed, b, a) = chain_errors(gps_only, signal_level, config);
        let axis = |v: &[[f64; 3]], i: usize| v.iter().map(|e| e[i]).collect::<Vec<f64>>();
        let b_std: Vec<f64> = (0..3).map(|i| std(&axis(&b, i))).collect();
        let a_std: Vec<f64> = (0..3).map(|i| std(&axis(&a, i))).collect();
        let worst = b.iter().flatten().fold(0.0f64, |m, e| m.max(e.abs()));
        println!(
            "ATTITUDE_CHAIN signal_level={signal_level:?} gps_only={gps_only}: fixed {:.3}, baseline std N/E/D {:.2}/{:.2}/{:.2} mm (worst {:.1} mm), attitude std {:.4}/{:.4}/{:.4} deg over {} epochs",
            fixed,
            b_std[0] * 1e3,
            b_std[1] * 1e3,
            b_std[2] * 1e3,
            worst * 1e3,
            a_std[0],
            a_std[1],
            a_std[2],
            a.len()
        );
        assert_eq!(fixed, 1.0);
        // The first attitude within 30 s of the start: acquisition, pull-in and the first
        // ephemerides. (10 s at first; GPS alone at the signal level first fixed after 13 s.)
        let epochs = signal_level.unwrap_or(120) as usize;
        assert!(
            a.len() + 30 >= epochs,
            "{} epochs with an attitude",
            a.len()
        );
        assert!(b_std.iter().all(|s| *s < 3e-3), "{b_std:?}");
        assert!(worst < 0.01, "{worst}");
        assert!(a_std.iter().all(|s| *s < 0.1), "{a_std:?}");
    }
}

/// Bad inputs: one clear error, exit code 2, nothing written.
#[test]
fn attitude_input_errors_are_clear() {
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path(), 10, false, true);
    let sim = dir.path().join("sim");
    skyforge_ok(&["run", &path, "--out", sim.to_str().unwrap()], dir.path());
    let s = |p: &str| sim.join(p).to_string_lossy().into_owned();
    let out = dir.path().join("att");
    let o_ = out.to_string_lossy().into_owned();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                s("observations/ant1.obs.rnx"),
                s("observations/ant2.obs.rnx"),
            ],
            "2 observation files for the 3 antennas",
        ),
        (
            vec![
                s("observations/ant1.obs.rnx"),
                s("observations/ant2.obs.rnx"),
                s("nav.rnx"),
            ],
            "nav.rnx",
        ),
    ];
    for (files, expected) in cases {
        let mut args: Vec<String> = vec!["attitude".into()];
        args.extend(files);
        args.extend([
            "--nav".into(),
            s("nav.rnx"),
            "--geometry".into(),
            s("geometry.toml"),
            "--out".into(),
            o_.clone(),
        ]);
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = skyforge(&refs, dir.path());
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains(expected), "{}", text(&o));
        assert!(!out.exists());
    }
}
