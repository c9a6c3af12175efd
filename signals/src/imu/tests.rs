use super::*;
use crate::errors::{Stream, overlapping_adev, overlapping_avar, stream_rng};
use skyforge_orbits::frames::{Geodetic, c_ecef_ned, geodetic_to_ecef};
use skyforge_orbits::gravity::{earth_rate_ecef, normal_gravity_ecef, normal_gravity_ned};
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
        gravity_ecef_mps2: normal_gravity_ecef(&g),
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

/// Allan variance at averaging time `t` of a first-order Gauss-Markov rate of variance
/// `sigma^2` and correlation time `tau`: with `q = 2 sigma^2 / tau` its driving density,
/// `(q tau^2 / t) [1 - (tau / (2 t)) (3 - 4 e^(-t/tau) + e^(-2t/tau))]` (El-Sheimy, Hou &
/// Niu 2008, "Analysis and modeling of inertial sensors using Allan variance", IEEE Trans.
/// Instrum. Meas. 57(1), exponentially correlated noise; IEEE Std 952-1997 annex C).
/// Checked against the autocorrelation's integral in
/// `gauss_markov_allan_variance_is_its_autocorrelation_integral`.
fn gauss_markov_avar(sigma: f64, tau: f64, t: f64) -> f64 {
    let q = 2.0 * sigma * sigma / tau;
    let x = t / tau;
    q * tau * tau / t * (1.0 - (3.0 - 4.0 * (-x).exp() + (-2.0 * x).exp()) / (2.0 * x))
}

/// The Allan variance at `T` of a stationary rate whose integral over a length `T` has
/// variance `a(T)`: the two adjacent integrals `Y1`, `Y2` have `Var(Y1 + Y2) = a(2T) =
/// 2 a(T) + 2 Cov(Y1, Y2)`, so `Var(Y2 - Y1) = 4 a(T) - a(2T)` and the Allan variance,
/// `Var(Y2 - Y1) / (2 T^2)`, is `(4 a(T) - a(2T)) / (2 T^2)`.
fn avar_from_integral_variance(a: impl Fn(f64) -> f64, t: f64) -> f64 {
    (4.0 * a(t) - a(2.0 * t)) / (2.0 * t * t)
}

#[test]
fn gauss_markov_allan_variance_is_its_autocorrelation_integral() {
    // The integral of a rate of autocorrelation R(u) = sigma^2 e^(-|u|/tau) over a length T
    // has variance a(T) = 2 int_0^T (T - u) R(u) du: here by Simpson's rule, 20 000 panels.
    let (sigma, tau) = (3e-5, 10.0);
    let a = |t: f64| {
        let n = 20_000;
        let h = t / n as f64;
        let f = |u: f64| (t - u) * sigma * sigma * (-u / tau).exp();
        let inner: f64 = (1..n)
            .map(|i| if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h))
            .sum();
        2.0 * h / 3.0 * (f(0.0) + inner + f(t))
    };
    for x in [0.05, 0.5, 1.0, 1.89, 5.0, 50.0] {
        let t = x * tau;
        let closed = gauss_markov_avar(sigma, tau, t);
        let integral = avar_from_integral_variance(a, t);
        assert!(
            (closed / integral - 1.0).abs() < 1e-9,
            "T/tau {x}: {closed} vs {integral}"
        );
    }
    // Its limits: q T / 3 well inside the correlation time (a rate random walk), q tau^2 / T
    // well past it (white noise of density sqrt(q) tau); the peak, 0.6174 sigma at 1.89 tau.
    let q = 2.0 * sigma * sigma / tau;
    let short = gauss_markov_avar(sigma, tau, 1e-3 * tau) / (q * 1e-3 * tau / 3.0);
    let long = gauss_markov_avar(sigma, tau, 1e4 * tau) / (q * tau / 1e4);
    assert!(
        (short - 1.0).abs() < 1e-3 && (long - 1.0).abs() < 1e-3,
        "{short} {long}"
    );
    let peak = gauss_markov_avar(sigma, tau, 1.89 * tau).sqrt() / sigma;
    assert!((peak - 0.6174).abs() < 1e-4, "{peak}");
}

/// A level IMU at rest at the site: it senses Earth rate and minus gravity, both constant.
fn at_rest(_t: f64) -> Option<Kinematics> {
    let g = site();
    Some(Kinematics {
        r_ecef_m: geodetic_to_ecef(&g),
        v_ecef_mps: Vec3::zeros(),
        a_ecef_mps2: Vec3::zeros(),
        c_body_ecef: c_ecef_ned(g.lat_rad, g.lon_rad).transpose(),
        omega_eb_body_rps: Vec3::zeros(),
        gravity_ecef_mps2: normal_gravity_ecef(&g),
    })
}

#[test]
fn allan_deviation_of_a_static_imu_recovers_random_walk_and_bias_instability() {
    // assumed (chosen before the first run and not changed after it): a custom IMU at 10 Hz
    // with only the random walks and the Gauss-Markov instabilities: gyro ARW 0.1 deg/sqrt(h)
    // and 10 deg/h over tau = 10 s, accelerometer VRW 0.01 m/s/sqrt(h) and 30 micro-g over
    // tau = 20 s (two correlation times, so that mixing them up would show). The Allan
    // variance at each peak (0.63 sigma near 1.8 tau) is then 20 to 30 times the white
    // term's, and at T = 0.2 s and 0.5 s the white term is over 95 % of it.
    // assumed: runs of 20 000 s (2000 and 1000 correlation times), seeds 1 to 4, the three
    // axes of each pooled (their Allan variances averaged). Expected scatter: a
    // non-overlapping Allan deviation from n blocks errs by about 1 / sqrt(2 (n - 1)); at
    // T = 2 tau, n = 1000 (gyro) and 500 (accelerometer) blocks per axis: 2.2 % and 3.2 %,
    // one seed's three axes 1.3 % and 1.8 %, all twelve series 0.7 % and 0.9 % (the
    // overlapping estimator does better). At 3 tau, the grid's end: 1.1 % pooled.
    // assumed: the grid: T = 0.2 s and 0.5 s for the white region, T / tau = 0.5 to 3 for
    // the instability's peak; every point within 10 % of theory, and the largest Allan
    // deviation on the peak grid within 10 % of theory's largest there.
    let dt = 0.1;
    let samples = 200_000;
    let seeds = [1, 2, 3, 4];
    let short_m = [2, 5];
    let peak_x = [0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5, 3.0];
    let config = ImuConfig {
        gyro: Some(GyroSpec {
            bias_deg_h: 0.0,
            instability_deg_h: 10.0,
            instability_tau_s: 10.0,
            arw_deg_rth: 0.1,
            scale_factor_ppm: 0.0,
            misalignment_mrad: 0.0,
            quantum_urad: 0.0,
        }),
        accel: Some(AccelSpec {
            bias_ug: 0.0,
            instability_ug: 30.0,
            instability_tau_s: 20.0,
            vrw_mps_rth: 0.01,
            scale_factor_ppm: 0.0,
            misalignment_mrad: 0.0,
            quantum_umps: 0.0,
        }),
        ..ImuConfig::of_grade(ImuGrade::Custom, 1.0 / dt)
    };
    config.check().unwrap();
    let (gyro, accel) = config.errors();
    // Per sensor: the averaging factors m (T = m dt) and, per seed, the three axes'
    // integrated outputs (angle, velocity): the "phase" of the rate's Allan deviation.
    let grid = |e: &TriadErrors| -> Vec<usize> {
        let peak = peak_x.map(|x| (x * e.instability_tau_s / dt).round() as usize);
        short_m.iter().copied().chain(peak).collect()
    };
    let grids = [grid(&gyro), grid(&accel)];
    // pooled[sensor][seed][k]: the seed's Allan variance at grids[sensor][k], axes averaged
    let mut pooled = [vec![], vec![]];
    for seed in seeds {
        let mut imu = ImuSimulator::new(&config, seed, 0);
        let mut phase = [
            [vec![0.0], vec![0.0], vec![0.0]],
            [vec![0.0], vec![0.0], vec![0.0]],
        ];
        for _ in 0..samples {
            let s = imu.next_sample(&at_rest).unwrap();
            for (sensor, out) in [s.dtheta_rad, s.dv_mps].iter().enumerate() {
                for (axis, x) in phase[sensor].iter_mut().enumerate() {
                    x.push(x.last().unwrap() + out[axis]);
                }
            }
        }
        for sensor in 0..2 {
            let avar: Vec<f64> = (grids[sensor].iter())
                .map(|&m| {
                    (phase[sensor].iter())
                        .map(|x| overlapping_avar(x, dt, m))
                        .sum::<f64>()
                        / 3.0
                })
                .collect();
            pooled[sensor].push(avar);
        }
    }
    for (sensor, e) in [gyro, accel].iter().enumerate() {
        let name = ["gyro", "accelerometer"][sensor];
        let theory = |m: usize| {
            let t = m as f64 * dt;
            e.density * e.density / t + gauss_markov_avar(e.instability, e.instability_tau_s, t)
        };
        // The simulator holds each interval's bias, an exactly sampled AR(1) of
        // phi = e^(-dt/tau): its Allan variance (autocovariance summed instead of
        // integrated) differs from the continuous process's by under 0.5 % on this grid.
        let held = |m: usize| {
            let phi = (-dt / e.instability_tau_s).exp();
            let a = |t: f64| {
                let n = (t / dt).round() as usize;
                let sum: f64 = (1..n).map(|k| (n - k) as f64 * phi.powi(k as i32)).sum();
                (dt * e.instability).powi(2) * (n as f64 + 2.0 * sum)
            };
            let t = m as f64 * dt;
            e.density * e.density / t + avar_from_integral_variance(a, t)
        };
        let mean = |k: usize| pooled[sensor].iter().map(|v| v[k]).sum::<f64>() / seeds.len() as f64;
        let grid = &grids[sensor];
        let ratio = |k: usize| (mean(k) / theory(grid[k])).sqrt();
        for (k, &m) in grid.iter().enumerate() {
            let per_seed: Vec<String> = (pooled[sensor].iter())
                .map(|v| format!("{:.3}", (v[k] / theory(m)).sqrt()))
                .collect();
            eprintln!(
                "{name} T {:5.1} s: adev {:.4e}, theory {:.4e}, ratio {:.4} (seeds {})",
                m as f64 * dt,
                mean(k).sqrt(),
                theory(m).sqrt(),
                ratio(k),
                per_seed.join(" ")
            );
            assert!((held(m) / theory(m) - 1.0).abs() < 0.005, "{name} m {m}");
            assert!(
                (ratio(k) - 1.0).abs() < 0.1,
                "{name} T {} s: Allan deviation / theory {}",
                m as f64 * dt,
                ratio(k)
            );
        }
        let peak = |f: &dyn Fn(usize) -> f64| {
            (short_m.len()..grid.len())
                .map(|k| (f(k).sqrt(), grid[k] as f64 * dt))
                .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a })
        };
        let (measured, at) = peak(&mean);
        let (expected, theory_at) = peak(&|k| theory(grid[k]));
        eprintln!(
            "{name} peak: {measured:.4e} at {at} s, theory {expected:.4e} at {theory_at} s, \
             ratio {:.4}",
            measured / expected
        );
        assert!(
            (measured / expected - 1.0).abs() < 0.1,
            "{name} peak {measured} at {at} s vs {expected} at {theory_at} s"
        );
    }
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
