//! `skyforge ins`: an IMU file and one antenna's observations with the navigation data
//! into a GNSS/INS filter (`navigation::gnss_ins`: loosely coupled, tightly coupled, or
//! paper 001's TDCP-aided), written to `DIR/ins.csv` (`formats::ins`).

use crate::bad_input::BadInput;
use crate::cli::InsArgs;
use crate::output::staged_dir::StagedDir;
use anyhow::Context;
use skyforge_formats::ins::{INS_CSV, write_ins_csv};
use skyforge_gnss::imu::{ImuIncrement, read_csv, read_kf_gins};
use skyforge_navigation::gnss_ins::{
    Alignment, FromFilesConfig, ImuNoise, InsRun, LooselyCoupledConfig, Outages, ReceiverNoise,
    StaticAlignment, TdcpAidedConfig, TdcpFilesConfig, TightFilesConfig, TrackAlignment,
    loosely_coupled_from_files, tdcp_aided_from_files, tightly_coupled_from_files,
};
use skyforge_navigation::ins::FineAlignmentConfig;
use skyforge_navigation::tdcp::TdcpConfig;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_orbits::gravity::GravityModel;
use skyforge_signals::imu::{AccelSpec, BOOK_TABLE_3_1, CONSUMER, GyroSpec, NAVIGATION, TACTICAL};
use skyforge_validate::ins::filter_noise;

/// A range's error for the fixes' covariance (m). # assumed: single-frequency
/// single-point ranging with the broadcast ionosphere, a few metres.
const UERE_M: f64 = 2.0;
/// A Doppler range rate's error (m/s). # assumed: a few centimetres per second.
const RANGE_RATE_SIGMA_MPS: f64 = 0.05;
/// Elevation mask (deg). # assumed: the usual 10 degrees.
const ELEVATION_MASK_DEG: f64 = 10.0;
/// Standard gravity (m/s^2).
const G0: f64 = 9.806_65;
/// The fine alignment's zero-velocity updates: their rate (Hz) and sigma (m/s).
/// # assumed: 10 Hz and 1 mm/s, a vehicle parked with its engine running
/// (`FineAlignmentConfig::default`'s).
const ZUPT_RATE_HZ: f64 = 10.0;
const ZUPT_SIGMA_MPS: f64 = 1e-3;
/// Alignment on the track: the horizontal speed from which a fix's velocity gives the
/// heading (m/s), and the initial attitude and velocity sigmas (rad, m/s).
/// # assumed: 5 m/s (a Doppler velocity's 0.05 m/s is then 0.6 deg of heading); 2 deg of
/// tilt and heading (a road's camber and grade against the body, a car's sideslip);
/// 0.1 m/s, twice the range rate's error.
const TRACK_SPEED_MPS: f64 = 5.0;
const TRACK_ATTITUDE_RAD: f64 = 2.0 * std::f64::consts::PI / 180.0;
const TRACK_VELOCITY_MPS: f64 = 0.1;

/// The grade's data-sheet errors.
fn grade(name: &str) -> Result<(GyroSpec, AccelSpec), BadInput> {
    Ok(match name {
        "navigation" => NAVIGATION,
        "tactical" => TACTICAL,
        "consumer" => CONSUMER,
        "book-table-3-1" => BOOK_TABLE_3_1,
        other => {
            return Err(BadInput(format!(
                "--grade {other:?}: one of navigation, tactical, consumer, book-table-3-1"
            )));
        }
    })
}

/// The run's settings from the arguments: the grade's noise, and initial errors a static
/// alignment of that grade leaves (three times the tilt an accelerometer bias makes and
/// the heading a gyro bias makes at 45 degrees latitude, with floors).
/// `interval_s`: the IMU's interval, which sets how many increments lie between two
/// zero-velocity updates of a fine alignment.
fn config(args: &InsArgs, interval_s: f64) -> Result<FromFilesConfig, BadInput> {
    let imu = filter_noise(grade(&args.grade)?);
    let outages = match args.outages.as_deref() {
        None => None,
        Some(&[first_s, every_s, length_s]) => {
            if !(first_s >= 0.0 && every_s > 0.0 && length_s > 0.0 && length_s < every_s) {
                return Err(BadInput(format!(
                    "--outages {first_s},{every_s},{length_s}: FIRST >= 0 and 0 < LENGTH < EVERY (s)"
                )));
            }
            Some(Outages {
                first_s,
                every_s,
                length_s,
            })
        }
        Some(other) => return Err(BadInput(format!("--outages {other:?}: three numbers"))),
    };
    if !(args.alignment_s > 0.0 && args.alignment_s <= 3600.0) {
        return Err(BadInput(format!(
            "--alignment-s {}: in (0, 3600] s",
            args.alignment_s
        )));
    }
    if args.lever_arm.len() != 3 {
        return Err(BadInput(format!(
            "--lever-arm {:?}: three numbers X,Y,Z (m)",
            args.lever_arm
        )));
    }
    let gyrocompass = OMEGA_E_GPS * std::f64::consts::FRAC_1_SQRT_2;
    let at_rest = LooselyCoupledConfig {
        imu,
        lever_arm_body_m: Vec3::from_column_slice(&args.lever_arm),
        initial_position_m: UERE_M,
        initial_velocity_mps: 0.01,
        initial_tilt_rad: (3.0 * imu.accel_bias / G0).max(1e-4),
        initial_heading_rad: (3.0 * imu.gyro_bias / gyrocompass).clamp(1e-3, 0.5),
    };
    let still = |fine| {
        Alignment::Static(StaticAlignment {
            span_s: args.alignment_s,
            fine,
        })
    };
    let (filter, alignment) = match args.align.as_str() {
        "coarse" => (at_rest, still(None)),
        "fine" => (
            at_rest,
            still(Some(fine_alignment(&imu, &at_rest, interval_s))),
        ),
        "track" => (
            LooselyCoupledConfig {
                initial_velocity_mps: TRACK_VELOCITY_MPS,
                initial_tilt_rad: TRACK_ATTITUDE_RAD,
                initial_heading_rad: TRACK_ATTITUDE_RAD,
                ..at_rest
            },
            Alignment::Track(TrackAlignment {
                min_speed_mps: TRACK_SPEED_MPS,
            }),
        ),
        other => {
            return Err(BadInput(format!(
                "--align {other:?}: coarse, fine or track"
            )));
        }
    };
    let gravity = match args.gravity.as_str() {
        "auto" => None,
        "normal" => Some(GravityModel::Normal),
        "zonal" => Some(GravityModel::Zonal { degree: 6 }),
        other => {
            return Err(BadInput(format!(
                "--gravity {other:?}: auto, normal or zonal"
            )));
        }
    };
    Ok(FromFilesConfig {
        filter,
        alignment,
        gravity,
        uere_m: UERE_M,
        range_rate_sigma_mps: RANGE_RATE_SIGMA_MPS,
        elevation_mask_deg: ELEVATION_MASK_DEG,
        outages,
    })
}

/// The fine alignment's settings: the grade's white noise, the coarse alignment's
/// errors as the filter's (`filter`'s initial tilt and heading), and the updates at
/// [`ZUPT_RATE_HZ`] for an IMU of `interval_s`.
fn fine_alignment(
    imu: &ImuNoise,
    filter: &LooselyCoupledConfig,
    interval_s: f64,
) -> FineAlignmentConfig {
    FineAlignmentConfig {
        gyro_arw_rad_per_sqrt_s: imu.gyro_arw,
        accel_vrw_mps_per_sqrt_s: imu.accel_vrw,
        zupt_sigma_mps: ZUPT_SIGMA_MPS,
        level_sigma_rad: filter.initial_tilt_rad,
        heading_sigma_rad: filter.initial_heading_rad,
        update_every: ((1.0 / (ZUPT_RATE_HZ * interval_s)).round() as usize).max(1),
    }
}

/// The IMU file's increments.
fn read_imu(args: &InsArgs) -> anyhow::Result<Vec<ImuIncrement>> {
    let path = &args.imu;
    let bad = |e: skyforge_gnss::imu::ImuTextError| BadInput(e.to_string());
    if path.extension().is_some_and(|e| e == "csv") {
        return Ok(read_csv(path).map_err(bad)?);
    }
    let (Some(week), Some(rate)) = (args.gps_week, args.imu_rate_hz) else {
        return Err(BadInput(format!(
            "{}: a KF-GINS file needs --gps-week and --imu-rate-hz (it holds neither)",
            path.display()
        ))
        .into());
    };
    if !(rate.is_finite() && (1.0..=10_000.0).contains(&rate)) {
        return Err(BadInput(format!("--imu-rate-hz {rate}: in [1, 10000] Hz")).into());
    }
    Ok(read_kf_gins(path, week, 1.0 / rate).map_err(bad)?)
}

/// Mode tdcp's settings: the loose mode's filter, the surveyed start, the height
/// constraint, and the TDCP and code errors (assumed: 3 mm and 2 m, as P1-S).
fn tdcp_config(args: &InsArgs, loose: &FromFilesConfig) -> Result<TdcpFilesConfig, BadInput> {
    let Some(&[lat, lon, h]) = args.start.as_deref() else {
        return Err(BadInput(
            "--mode tdcp needs --start LAT,LON,H: three satellites cannot fix the start".into(),
        ));
    };
    if !(lat.abs() <= 90.0 && lon.abs() <= 360.0 && h.abs() <= 1e5) {
        return Err(BadInput(format!(
            "--start {lat},{lon},{h}: latitude in [-90, 90] deg, longitude in [-360, 360] deg, height within 100 km"
        )));
    }
    if loose.gravity.is_some_and(|g| g != GravityModel::Normal) {
        return Err(BadInput(
            "--mode tdcp runs near the Earth: --gravity auto or normal".into(),
        ));
    }
    let Alignment::Static(still) = loose.alignment else {
        return Err(BadInput(
            "--mode tdcp aligns at the surveyed start: --align coarse or fine".into(),
        ));
    };
    if let Some(sigma) = args.height_sigma.filter(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(BadInput(format!("--height-sigma {sigma}: positive (m)")));
    }
    Ok(TdcpFilesConfig {
        aided: TdcpAidedConfig {
            filter: LooselyCoupledConfig {
                initial_position_m: 0.1, // assumed: a survey good to 10 cm
                ..loose.filter
            },
            tdcp: TdcpConfig::default(),
            code_sigma_m: Some(UERE_M),
            height_m: args.height_sigma.map(|s| (h, s)),
        },
        alignment: still,
        start_antenna_m: geodetic_to_ecef(&Geodetic::from_degrees(lat, lon, h)),
    })
}

/// Mode tight's settings: the loose mode's filter, alignment, mask and outages, and the
/// receiver as the filter assumes it (assumed: the clock known to 5 m and 1 m/s after its
/// start from the first epoch, the drift wandering by 1 m/s over 10 minutes and the phase
/// by 0.01 m^2/s, a TCXO's; the loose mode's range and range-rate errors).
fn tight_config(loose: &FromFilesConfig) -> TightFilesConfig {
    TightFilesConfig {
        filter: loose.filter,
        receiver: ReceiverNoise {
            clock_bias_m: 5.0,
            clock_drift_mps: 1.0,
            clock_drift_tau_s: Some(600.0),
            clock_phase_psd_m2_s: 0.01,
            code_sigma_m: UERE_M,
            range_rate_sigma_mps: RANGE_RATE_SIGMA_MPS,
            barometer: None,
        },
        alignment: loose.alignment,
        gravity: loose.gravity,
        elevation_mask_deg: loose.elevation_mask_deg,
        outages: loose.outages,
    }
}

/// The integration `--mode` chose.
enum Mode {
    Loose,
    Tight(TightFilesConfig),
    Tdcp(TdcpFilesConfig),
}

/// Run `skyforge ins`.
pub fn ins(args: &InsArgs) -> anyhow::Result<()> {
    let increments = read_imu(args)?;
    let interval_s = increments.first().map_or(0.01, |i| i.dt_s);
    let config = config(args, interval_s)?;
    let mode = match args.mode.as_str() {
        "loose" => Mode::Loose,
        "tight" => Mode::Tight(tight_config(&config)),
        "tdcp" => Mode::Tdcp(tdcp_config(args, &config)?),
        other => return Err(BadInput(format!("--mode {other:?}: loose, tight or tdcp")).into()),
    };
    let file = super::read_observations(&args.file)?;
    let (ephemerides, iono) = super::attitude::read_nav_with_iono(&args.nav)?;
    let run = match &mode {
        Mode::Loose => loosely_coupled_from_files(&increments, &file, ephemerides, &iono, &config),
        Mode::Tight(t) => tightly_coupled_from_files(&increments, &file, ephemerides, &iono, t),
        Mode::Tdcp(t) => tdcp_aided_from_files(&increments, &file, ephemerides, &iono, t),
    }
    .map_err(|e| BadInput(e.to_string()))?;
    let staged = StagedDir::create(&args.out, args.force)?;
    let path = staged.file(INS_CSV);
    write_ins_csv(&path, &run.solutions).with_context(|| format!("writing {}", path.display()))?;
    let dir = staged.commit()?;
    print_summary(&run, increments.len());
    println!("wrote      {}", dir.join(INS_CSV).display());
    Ok(())
}

fn print_summary(run: &InsRun, records: usize) {
    let updated = run.solutions.iter().filter(|s| s.gnss).count();
    let hidden = run.solutions.iter().filter(|s| s.in_outage).count();
    let attitude = run.aligned.attitude_ned();
    println!(
        "aligned    at {}: yaw {:.3} pitch {:.3} roll {:.3} deg",
        run.aligned.t,
        attitude.yaw_rad.to_degrees(),
        attitude.pitch_rad.to_degrees(),
        attitude.roll_rad.to_degrees()
    );
    if let GravityModel::Zonal { degree } = run.gravity {
        println!("gravity    the orbit's: the point mass, J2..J{degree}, the centrifugal term");
    }
    if let Some(fine) = &run.fine {
        println!(
            "fine       {} zero-velocity updates (innovation RMS {:.2e} m/s): heading corrected by {:.4} deg, sigma heading {:.4} deg, tilt {:.4} deg (an east gyro bias's heading error not included)",
            fine.updates,
            fine.innovation_rms_mps,
            fine.heading_correction_rad.to_degrees(),
            fine.heading_sigma_rad.to_degrees(),
            fine.level_sigma_rad.to_degrees()
        );
    }
    println!(
        "solutions  {} from {records} IMU records: {updated} updated by GNSS, {hidden} in outages, {} epochs without a fix or a usable satellite",
        run.solutions.len(),
        run.no_fix
    );
}
