//! The IMU of a scenario (`[imu]`): `synth` writes its increments as SkyForge's CSV,
//! KF-GINS's text file and `imu.h5` with the truth beside them; the strapdown INS of the
//! navigation crate, reading only the increment file, follows the truth of an error-free
//! IMU on generated legs to under a millimetre after ten minutes (issue #36's bar for the
//! mechanisation), and a biased IMU errs by the biases its truth records.

mod support;

use skyforge_formats::imu::{ImuH5, ImuRow, read_h5};
use skyforge_gnss::imu::{ImuIncrement, read_csv, read_kf_gins};
use skyforge_navigation::ins::InsState;
use skyforge_orbits::Mat3;
use skyforge_orbits::constants::GM_GPS;
use skyforge_orbits::gravity::GravityModel;
use std::path::Path;

/// A boat on a lake: out, a turn with heave and waves, faster, back (ten minutes).
const BOAT: &str = r#"
name = "boat"
seed = 11
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 600.0
[gnss.beidou]
enabled = false
[signal]
cn0_dbhz = 45.0
[observation]
level = "observation"
[platform.segments]
latitude_deg = 28.2
longitude_deg = 112.9
height_m = 30.0
heading_deg = 90.0
heave = { amplitude_m = 0.3, period_s = 6.0 }
[[platform.segments.legs]]
duration_s = 60.0
acceleration_mps2 = 0.1
[[platform.segments.legs]]
duration_s = 200.0
[[platform.segments.legs]]
duration_s = 60.0
turn_rate_deg_s = 3.0
[[platform.segments.legs]]
duration_s = 280.0
acceleration_mps2 = 0.01
[platform.attitude]
pitch = { amplitude_deg = 2.0, period_s = 7.0 }
roll = { amplitude_deg = 4.0, period_s = 5.0 }
[[antennas]]
name = "ant1"
position_body_m = [0.5, 0.0, -1.2]
"#;

fn synth(dir: &Path, imu: &str) -> std::path::PathBuf {
    std::fs::write(dir.join("boat.toml"), format!("{BOAT}{imu}")).unwrap();
    support::skyforge_ok(&["synth", "boat.toml", "--out", "sim"], dir);
    dir.join("sim")
}

/// The body -> ECEF rotation of a `[w, x, y, z]` quaternion.
fn rotation(q: [f64; 4]) -> Mat3 {
    let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        q[0], q[1], q[2], q[3],
    ));
    *q.to_rotation_matrix().matrix()
}

/// The INS started from the truth at the first sample's end, run over the increments
/// after it subtracting `gravity`: its position error (m) at the last sample.
fn ins_error_at_end(h5: &ImuH5, increments: &[ImuIncrement], gravity: GravityModel) -> f64 {
    let first: &ImuRow = &h5.rows[0];
    let mut ins = InsState {
        t: increments[0].t_end,
        r_ecef_m: first.r_ecef_m,
        v_ecef_mps: first.v_ecef_mps,
        c_body_ecef: rotation(first.q_body_ecef),
    };
    ins.propagate_all_in(gravity, &increments[1..]).unwrap();
    let last = h5.rows.last().unwrap();
    (ins.r_ecef_m - last.r_ecef_m).norm()
}

/// An ideal IMU: the three files hold the same increments at 100 Hz over the run (the
/// text files to their printed digits), the output is the truth's increments, the CSV
/// names the lever arm, and the INS run on the CSV alone stays within a millimetre of
/// the truth after ten minutes of accelerating, turning and heaving.
#[test]
fn an_ideal_imu_on_a_boat_carries_the_truths_motion_through_the_ins() {
    let dir = tempfile::tempdir().unwrap();
    let sim = synth(dir.path(), "[imu]\nrate_hz = 100.0\ngrade = \"ideal\"\n");
    let h5 = read_h5(&sim.join("imu.h5")).unwrap();
    let csv = read_csv(&sim.join("imu.csv")).unwrap();
    assert_eq!((h5.rows.len(), csv.len()), (60_000, 60_000));
    let week = csv[0].t_end.to_time_of_week().0;
    let kf = read_kf_gins(&sim.join("imu.txt"), week, 0.01).unwrap();
    assert_eq!(kf.len(), csv.len());
    for ((row, c), k) in h5.rows.iter().zip(&csv).zip(&kf) {
        assert_eq!(
            (row.dtheta_rad, row.dv_mps),
            (row.ideal_dtheta_rad, row.ideal_dv_mps)
        );
        assert!((c.t_end - h5.start).to_seconds() - row.t_s < 1e-6);
        assert!((c.dtheta_rad - row.dtheta_rad).norm() < 1e-12);
        assert!((c.dv_mps - row.dv_mps).norm() < 1e-9);
        assert!((k.t_end - c.t_end).abs().to_seconds() < 1e-6);
        assert!((k.dtheta_rad - c.dtheta_rad).norm() < 1e-12);
        assert!((k.dv_mps - c.dv_mps).norm() < 1e-9);
    }
    let text = std::fs::read_to_string(sim.join("imu.csv")).unwrap();
    assert!(text.contains("ant1: 0.5 0 -1.2"), "the lever arm is named");
    let error_m = ins_error_at_end(&h5, &csv, GravityModel::Normal);
    assert!(error_m < 1e-3, "INS error after 10 min {error_m} m");
}

/// A custom IMU with turn-on biases only: the output minus the truth's increments is the
/// bias `imu.h5` records, per sample, and the same seed draws the same IMU again.
#[test]
fn a_biased_imu_errs_by_the_biases_it_records_and_repeats_with_its_seed() {
    let custom = "[imu]\nrate_hz = 50.0\ngrade = \"custom\"\n\
        [imu.gyro]\nbias_deg_h = 10.0\ninstability_deg_h = 0.0\ninstability_tau_s = 100.0\n\
        arw_deg_rth = 0.0\nscale_factor_ppm = 0.0\nmisalignment_mrad = 0.0\nquantum_urad = 0.0\n\
        [imu.accel]\nbias_ug = 100.0\ninstability_ug = 0.0\ninstability_tau_s = 100.0\n\
        vrw_mps_rth = 0.0\nscale_factor_ppm = 0.0\nmisalignment_mrad = 0.0\nquantum_umps = 0.0\n";
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let (sim_a, sim_b) = (synth(a.path(), custom), synth(b.path(), custom));
    let h5 = read_h5(&sim_a.join("imu.h5")).unwrap();
    assert_eq!(h5.rows.len(), 30_000);
    let (gyro, accel) = (h5.rows[0].gyro_bias_rps, h5.rows[0].accel_bias_mps2);
    let (deg_h, ug) = (std::f64::consts::PI / 180.0 / 3600.0, 9.806_65e-6);
    for (bias, sigma) in [(gyro, 10.0 * deg_h), (accel, 100.0 * ug)] {
        assert!(
            bias.iter().all(|&x| x != 0.0 && x.abs() < 5.0 * sigma),
            "{bias}"
        );
    }
    for r in &h5.rows {
        assert_eq!((r.gyro_bias_rps, r.accel_bias_mps2), (gyro, accel));
        assert!(((r.dtheta_rad - r.ideal_dtheta_rad) / r.dt_s - gyro).norm() < 1e-12);
        assert!(((r.dv_mps - r.ideal_dv_mps) / r.dt_s - accel).norm() < 1e-9);
    }
    let text = |sim: &Path| std::fs::read(sim.join("imu.txt")).unwrap();
    assert_eq!(text(&sim_a), text(&sim_b), "the same seed, the same IMU");
}

/// The `imu.h5` of an ideal IMU at 100 Hz on the bundled `od-leo` over `seconds`.
fn leo_imu(seconds: u32) -> ImuH5 {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = support::short_scenario(d, "od-leo", seconds);
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(
        &path,
        format!("{text}\n[imu]\nrate_hz = 100.0\ngrade = \"ideal\"\n"),
    )
    .unwrap();
    support::skyforge_ok(&["synth", path.to_str().unwrap(), "--out", "sim"], d);
    read_h5(&d.join("sim/imu.h5")).unwrap()
}

/// An IMU on a LEO (the bundled `od-leo`, 10 s, an ideal IMU at 100 Hz): `synth` writes
/// its files, and the truth's increments are what a free-falling, Earth-pointing body
/// senses: a specific force of the drag alone (under 1e-5 m/s^2) and a turn at the orbit
/// rate about the pitch axis (1.1e-3 rad/s for its 7000-km orbit, within 1 %).
#[test]
fn an_imu_on_a_leo_senses_the_drag_and_the_orbit_rate() {
    let h5 = leo_imu(10);
    assert_eq!(h5.rows.len(), 1000);
    let a = h5.rows[0].r_ecef_m.norm();
    let n = (GM_GPS / a.powi(3)).sqrt();
    for r in &h5.rows {
        let f = r.ideal_dv_mps / r.dt_s;
        let w = r.ideal_dtheta_rad / r.dt_s;
        assert!(f.norm() < 1e-5, "specific force {f}");
        assert!(
            (w.y + n).abs() < 0.01 * n && w.x.abs() < 0.01 * n,
            "rate {w} vs {n}"
        );
    }
}

/// The mechanisation against an orbit (issue #36's acceptance: "a LEO orbit or a circle"):
/// an ideal IMU on the bundled `od-leo` (J2..J6 and drag, Earth-pointing) for 10 minutes,
/// its full-precision increments from `imu.h5` through the INS subtracting the same zonal
/// field (`GravityModel::Zonal { degree: 6 }`): the position within 1 mm of the truth.
#[test]
fn an_ideal_imu_on_a_leo_carries_the_orbit_through_the_ins() {
    let h5 = leo_imu(600);
    assert_eq!(h5.rows.len(), 60_000);
    let increments: Vec<ImuIncrement> = (h5.rows.iter())
        .map(|r| ImuIncrement {
            t_end: h5.start + hifitime::Duration::from_seconds(r.t_s),
            dt_s: r.dt_s,
            dtheta_rad: r.ideal_dtheta_rad,
            dv_mps: r.ideal_dv_mps,
        })
        .collect();
    let error_m = ins_error_at_end(&h5, &increments, GravityModel::Zonal { degree: 6 });
    println!("LEO INS error after 10 min: {error_m} m");
    assert!(error_m < 1e-3, "INS error after 10 min {error_m} m");
}
