//! A scenario's IMU outputs (`[imu]`), written beside the truth by `synth`: `imu.csv`
//! (SkyForge's IMU CSV), `imu.txt` (KF-GINS's increment file) and `imu.h5` (the output
//! with its truth: error-free increments, position, velocity, attitude, biases).

use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use hifitime::{Duration, Epoch};
use skyforge_formats::imu::{IMU_H5, ImuH5Writer, ImuRow};
use skyforge_gnss::imu::{CsvWriter, ImuIncrement, KfGinsWriter};
use skyforge_orbits::Mat3;
use skyforge_orbits::platform::PlatformWindow;
use skyforge_scenarios::Scenario;
use skyforge_signals::imu::{ImuConfig, ImuSample, ImuSimulator};
use std::fs::File;
use std::io::BufWriter;

/// SkyForge's IMU CSV.
pub const IMU_CSV: &str = "imu.csv";
/// KF-GINS's increment file.
pub const IMU_KF_GINS: &str = "imu.txt";

/// The `[w, x, y, z]` unit quaternion of the rotation `c`.
fn quaternion(c: &Mat3) -> [f64; 4] {
    let rotation = nalgebra::Rotation3::from_matrix(c);
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&rotation);
    [q.w, q.i, q.j, q.k]
}

/// The increment record of `sample` for a run that started at `start`.
fn increment(start: Epoch, sample: &ImuSample) -> ImuIncrement {
    ImuIncrement {
        t_end: start + Duration::from_seconds(sample.t_s),
        dt_s: sample.dt_s,
        dtheta_rad: sample.dtheta_rad,
        dv_mps: sample.dv_mps,
    }
}

/// The truth file's row of `sample`.
fn row(sample: &ImuSample) -> ImuRow {
    ImuRow {
        t_s: sample.t_s,
        dt_s: sample.dt_s,
        dtheta_rad: sample.dtheta_rad,
        dv_mps: sample.dv_mps,
        ideal_dtheta_rad: sample.ideal_dtheta_rad,
        ideal_dv_mps: sample.ideal_dv_mps,
        r_ecef_m: sample.truth.r_ecef_m,
        v_ecef_mps: sample.truth.v_ecef_mps,
        q_body_ecef: quaternion(&sample.truth.c_body_ecef),
        gyro_bias_rps: sample.gyro_bias_rps,
        accel_bias_mps2: sample.accel_bias_mps2,
    }
}

/// The comment lines of `imu.csv`: what made it, the axes, the lever arms.
fn comments(scenario: &Scenario, imu: &ImuConfig) -> String {
    let mut text = format!(
        "SkyForge IMU output of scenario {} ({}), grade {:?}, {} Hz.\n\
         Body axes front-right-down; the IMU sits at the body origin.\n\
         Lever arms from the IMU to the antennas' reference points (body, m):",
        scenario.name, scenario.source, imu.grade, imu.rate_hz
    );
    for a in &scenario.antennas {
        let p = a.position_body_m;
        text.push_str(&format!("\n  {}: {} {} {}", a.name, p[0], p[1], p[2]));
    }
    text
}

/// Writes the IMU outputs of `scenario` into `staged` (nothing without `[imu]`).
pub fn write_imu(scenario: &Scenario, staged: &StagedDir) -> anyhow::Result<()> {
    let (Some(imu), Some(motion)) = (&scenario.imu, scenario.imu_motion()?) else {
        return Ok(());
    };
    let start = scenario.time.start;
    let create = |name: &str| -> anyhow::Result<BufWriter<File>> {
        let path = staged.file(name);
        let file =
            File::create(&path).with_context(|| format!("cannot create {}", path.display()))?;
        Ok(BufWriter::new(file))
    };
    let mut csv = CsvWriter::new(create(IMU_CSV)?, &comments(scenario, imu))?;
    let mut kf_gins = KfGinsWriter::new(create(IMU_KF_GINS)?);
    let h5_path = staged.file(IMU_H5);
    let mut h5 = ImuH5Writer::create(&h5_path, start)
        .with_context(|| format!("cannot create {}", h5_path.display()))?;
    let mut simulator = ImuSimulator::new(imu, scenario.receiver_seed(), 0);
    let n = (scenario.time.duration_s * imu.rate_hz + 1e-9).floor() as u64;
    let kinematics = |t_s| PlatformWindow::kinematics(&motion, t_s);
    for _ in 0..n {
        let sample = simulator.next_sample(&kinematics)?;
        let record = increment(start, &sample);
        csv.push(&record)?;
        kf_gins.push(&record)?;
        h5.push(row(&sample))
            .with_context(|| format!("cannot write {}", h5_path.display()))?;
    }
    csv.finish()?;
    kf_gins.finish()?;
    h5.finish()
        .with_context(|| format!("cannot write {}", h5_path.display()))?;
    Ok(())
}
