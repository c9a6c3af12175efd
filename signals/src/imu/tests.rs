use super::*;
use crate::errors::{Stream, overlapping_adev, stream_rng};
use skyforge_orbits::frames::{Geodetic, c_ecef_ned, geodetic_to_ecef};
use skyforge_orbits::gravity::{earth_rate_ecef, normal_gravity_ned};
use skyforge_orbits::platform::Kinematics;
use skyforge_orbits::{Mat3, Vec3};

const LAT: f64 = 0.5; // rad
const LON: f64 = 2.0;

fn site() -> Geodetic {
    Geodetic {
        lat_rad: LAT,
        lon_rad: LON,
        h_m: 100.0,
    }
}

fn rot_z(a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// A vehicle at the site turning on the spot at a varying rate: heading
/// `psi(t) = 0.3 t + 0.2 sin(1.7 t)`, level, so its rate is `psi'` about body z.
fn turning(t: f64) -> Option<Kinematics> {
    let g = site();
    let psi = 0.3 * t + 0.2 * (1.7 * t).sin();
    let rate = 0.3 + 0.34 * (1.7 * t).cos();
    Some(Kinematics {
        r_ecef_m: geodetic_to_ecef(&g),
        v_ecef_mps: Vec3::zeros(),
        a_ecef_mps2: Vec3::zeros(),
        c_body_ecef: c_ecef_ned(g.lat_rad, g.lon_rad).transpose() * rot_z(psi),
        omega_eb_body_rps: Vec3::new(0.0, 0.0, rate),
    })
}

#[test]
fn a_level_static_imu_senses_earth_rate_and_minus_gravity() {
    let k = turning(0.0).map(|k| Kinematics {
        omega_eb_body_rps: Vec3::zeros(),
        c_body_ecef: c_ecef_ned(LAT, LON).transpose(),
        ..k
    });
    let s = sensed(&k.unwrap());
    let g = normal_gravity_ned(&site());
    assert!((s.f_body_mps2 + g).norm() < 1e-12, "{:?}", s.f_body_mps2);
    let w = earth_rate_ecef().norm();
    let expected = Vec3::new(w * LAT.cos(), 0.0, -w * LAT.sin());
    assert!((s.omega_ib_body_rps - expected).norm() < 1e-18);
}

#[test]
fn gauss_legendre_increments_agree_with_a_fine_simpson_oracle() {
    let (t0, dt) = (12.345, 0.01);
    let (dtheta, dv) = increments(&turning, t0, dt).unwrap();
    let n = 2000;
    let h = dt / n as f64;
    let (mut a, mut b) = (Vec3::zeros(), Vec3::zeros());
    for i in 0..=n {
        let w = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let s = sensed(&turning(t0 + i as f64 * h).unwrap());
        a += w * h / 3.0 * s.omega_ib_body_rps;
        b += w * h / 3.0 * s.f_body_mps2;
    }
    assert!((dtheta - a).norm() < 1e-15, "{}", (dtheta - a).norm());
    assert!((dv - b).norm() < 1e-12, "{}", (dv - b).norm());
}

#[test]
fn the_ideal_grade_outputs_the_truth_and_no_kinematics_is_an_error() {
    let mut imu = ImuSimulator::new(&ImuConfig::of_grade(ImuGrade::Ideal, 200.0), 7, 0);
    for _ in 0..10 {
        let s = imu.next_sample(&turning).unwrap();
        assert_eq!(
            (s.dtheta_rad, s.dv_mps),
            (s.ideal_dtheta_rad, s.ideal_dv_mps)
        );
    }
    assert_eq!(
        imu.next_sample(&|_| None),
        Err(ImuError::NoKinematics { t_s: 10.0 / 200.0 })
    );
}

fn only(errors: TriadErrors) -> Triad {
    Triad::new(errors, stream_rng(11, Stream::Named("imu test"), 0))
}

#[test]
fn angle_random_walk_has_its_allan_deviation() {
    // White rate noise of density N has the Allan deviation N / sqrt(tau).
    let density = 0.1 * DEG_PER_ROOT_H;
    let mut triad = only(TriadErrors {
        density,
        ..TriadErrors::NONE
    });
    let dt = 0.01;
    let mut angle = vec![0.0];
    for _ in 0..200_000 {
        let x = triad.measure(Vec3::zeros(), dt).x;
        angle.push(angle.last().unwrap() + x);
    }
    for m in [100, 1000] {
        let tau = m as f64 * dt;
        let adev = overlapping_adev(&angle, dt, m);
        let theory = density / tau.sqrt();
        assert!(
            (adev / theory - 1.0).abs() < 0.1,
            "tau {tau}: {adev} vs {theory}"
        );
    }
}

#[test]
fn bias_instability_is_stationary_with_its_correlation() {
    let (sigma, tau, dt) = (1e-5, 50.0, 0.5);
    let mut triad = only(TriadErrors {
        instability: sigma,
        instability_tau_s: tau,
        ..TriadErrors::NONE
    });
    let lag = 100; // 50 s = one correlation time
    let xs: Vec<f64> = (0..400_000)
        .map(|_| {
            let b = triad.bias().x;
            triad.measure(Vec3::zeros(), dt);
            b
        })
        .collect();
    let n = xs.len() as f64;
    let var = xs.iter().map(|x| x * x).sum::<f64>() / n;
    let cov = xs.iter().zip(&xs[lag..]).map(|(a, b)| a * b).sum::<f64>() / (n - lag as f64);
    // 400 000 samples span 4000 correlation times: the variance's standard error is
    // about sigma^2 sqrt(2 tau / T) ~ 2 %.
    assert!(
        (var.sqrt() / sigma - 1.0).abs() < 0.05,
        "{}",
        var.sqrt() / sigma
    );
    let rho = cov / var;
    assert!((rho - (-1.0_f64).exp()).abs() < 0.05, "{rho}");
}

#[test]
fn turn_on_bias_scale_factor_and_misalignment_are_drawn_at_their_sigmas() {
    let (b, s, m) = (1e-4, 3e-4, 5e-4);
    let errors = TriadErrors {
        bias: b,
        scale_factor: s,
        misalignment_rad: m,
        ..TriadErrors::NONE
    };
    let n = 1000;
    let (mut bb, mut ss, mut mm) = (0.0, 0.0, 0.0);
    for seed in 0..n {
        let mut t = Triad::new(errors, stream_rng(seed, Stream::ImuGyro, 0));
        let g = t.gain();
        bb += t.bias().norm_squared() / 3.0;
        ss += ((g - Mat3::identity()).diagonal()).norm_squared() / 3.0;
        mm += (g - Mat3::from_diagonal(&g.diagonal())).norm_squared() / 6.0;
        // the output is exactly gain * truth + bias * dt without noise
        let x = Vec3::new(0.1, -0.2, 0.3);
        let expected = g * x + t.bias() * 0.01;
        assert!((t.measure(x, 0.01) - expected).norm() < 1e-17);
    }
    let rms = |sum: f64| (sum / n as f64).sqrt();
    // standard errors of an RMS from 3000 or 6000 draws: about 1.3 % and 0.9 %
    assert!((rms(bb) / b - 1.0).abs() < 0.05, "{}", rms(bb) / b);
    assert!((rms(ss) / s - 1.0).abs() < 0.05, "{}", rms(ss) / s);
    assert!((rms(mm) / m - 1.0).abs() < 0.05, "{}", rms(mm) / m);
}

#[test]
fn quantisation_carries_its_remainder() {
    let q = 1e-6;
    let mut triad = only(TriadErrors {
        quantum: q,
        ..TriadErrors::NONE
    });
    let (mut sum_in, mut sum_out) = (Vec3::zeros(), Vec3::zeros());
    for k in 0..10_000 {
        let x = Vec3::new(3.3e-7, -7.7e-7, 1.2345e-6 * (k as f64).sin());
        let y = triad.measure(x, 0.01);
        for v in y.iter() {
            assert!(
                (v / q - (v / q).round()).abs() < 1e-6,
                "{v} not whole counts"
            );
        }
        sum_in += x;
        sum_out += y;
        // floating-point sums of 10 000 terms: rounding of order 1e-14
        assert!((sum_in - sum_out).amax() <= q / 2.0 + 1e-12);
    }
}

#[test]
fn vibration_adds_its_sinusoid_and_nothing_else_for_an_otherwise_ideal_sensor() {
    let config = ImuConfig {
        vibration: Some(VibrationConfig {
            frequency_hz: 10.0,
            accel_mps2: 0.5,
            gyro_dps: 0.0,
        }),
        ..ImuConfig::of_grade(ImuGrade::Custom, 100.0)
    };
    let config = ImuConfig {
        gyro: Some(GyroSpec {
            bias_deg_h: 0.0,
            instability_deg_h: 0.0,
            instability_tau_s: 1.0,
            arw_deg_rth: 0.0,
            scale_factor_ppm: 0.0,
            misalignment_mrad: 0.0,
            quantum_urad: 0.0,
        }),
        accel: Some(AccelSpec {
            bias_ug: 0.0,
            instability_ug: 0.0,
            instability_tau_s: 1.0,
            vrw_mps_rth: 0.0,
            scale_factor_ppm: 0.0,
            misalignment_mrad: 0.0,
            quantum_umps: 0.0,
        }),
        ..config
    };
    config.check().unwrap();
    let mut imu = ImuSimulator::new(&config, 3, 0);
    let (mut sum, mut peak) = (Vec3::zeros(), 0.0_f64);
    for _ in 0..100 {
        // one second: ten whole periods
        let s = imu.next_sample(&turning).unwrap();
        assert_eq!(s.dtheta_rad, s.ideal_dtheta_rad);
        let d = s.dv_mps - s.ideal_dv_mps;
        sum += d;
        peak = peak.max(d.amax());
    }
    assert!(sum.amax() < 1e-12, "{sum:?}");
    // the largest 10-ms increment of a 0.5 m/s^2 sinusoid at 10 Hz: A/w * 2 sin(w dt / 2)
    let w = std::f64::consts::TAU * 10.0;
    let bound = 0.5 / w * 2.0 * (w * 0.005).sin();
    assert!(
        peak <= bound + 1e-12 && peak > 0.8 * bound,
        "{peak} vs {bound}"
    );
}

#[test]
fn configs_read_and_their_errors_name_the_field() {
    let read = |text: &str| toml::from_str::<ImuConfig>(text);
    for grade in [
        "ideal",
        "navigation",
        "tactical",
        "consumer",
        "book-table-3-1",
    ] {
        let c = read(&format!("rate_hz = 100\ngrade = \"{grade}\"")).unwrap();
        c.check().unwrap();
    }
    let book = read("rate_hz = 100\ngrade = \"book-table-3-1\"").unwrap();
    let (gyro, accel) = book.errors();
    assert!((gyro.instability - 0.5 * DEG_PER_H).abs() < 1e-20);
    assert!((accel.instability - 5e-4 * 9.80665).abs() < 1e-15);
    assert_eq!(gyro.instability_tau_s, 3600.0);
    assert_eq!(accel.instability_tau_s, 1800.0);
    let e = read("rate_hz = 100\ngrade = \"custom\"").unwrap().check();
    assert!(e.unwrap_err().to_string().contains("gyro"));
    let e = read("rate_hz = 0.5\ngrade = \"ideal\"").unwrap().check();
    assert!(e.unwrap_err().to_string().contains("rate_hz"));
    let text = "rate_hz = 100\ngrade = \"tactical\"\n[vibration]\nfrequency_hz = 60\n\
                accel_mps2 = 1\ngyro_dps = 0";
    let e = read(text).unwrap().check().unwrap_err().to_string();
    assert!(
        e.contains("vibration.frequency_hz") && e.contains("50"),
        "{e}"
    );
    assert!(read("rate_hz = 100\ngrade = \"platinum\"").is_err());
}
