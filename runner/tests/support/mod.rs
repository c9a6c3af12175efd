//! The static site the runner's observation-level tests share.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

/// GPS alone at a static ground site (52 N 13 E, 100 m) with one antenna looking up over
/// the whole sky, 45 dB-Hz: the scenario between its `[time]`/`[gnss.gps]` sections and its
/// error and observation sections.
pub const STATIC_SITE: &str = r#"
[gnss.beidou]
enabled = false

[platform.ground]
latitude_deg = 52.0
longitude_deg = 13.0
height_m = 100.0

[[antennas]]
name = "ant1"
position_body_m = [0.0, 0.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 90.0

[signal]
cn0_dbhz = 45.0
"#;

/// `[observation]` at the observation level with `extra` lines (observed signals), and
/// constant noise of `code_m` on the code and `phase_m` on the carrier.
pub fn observation_level(extra: &str, code_m: f64, phase_m: f64) -> String {
    format!(
        "\n[observation]\nlevel = \"observation\"\n{extra}\n[observation.noise]\nmodel = \"constant\"\nphase_m = {phase_m:?}\ncode_m = {code_m:?}\n"
    )
}

/// The static site `name` with `seed`, run at the observation level in `dir`: `head` holds
/// the `[time]` table and what comes before the site (a constellation's source), `tail`
/// the tables after it (errors, `[observation]`).
pub fn run_static_site(
    name: &str,
    seed: u64,
    head: &str,
    tail: &str,
    dir: &std::path::Path,
) -> skyforge_runner::ObservationRun {
    let text = format!("name = {name:?}\nseed = {seed}\n\n{head}\n{STATIC_SITE}\n{tail}");
    let scenario =
        skyforge_scenarios::parse(&text, &format!("{name}.toml"), dir).expect("scenario");
    skyforge_runner::observation_run(&scenario).expect("run")
}

/// RMS of the 3-D position error (m) of the first antenna's fixes with `pvt` on `signals`
/// from `from_s` seconds on, over at least `at_least` fixes (fixes outside the simulated
/// span, where the receiver clock put them, are left out).
pub fn fix_rms_m(
    run: &skyforge_runner::ObservationRun,
    pvt: &skyforge_navigation::pvt::PvtConfig,
    signals: &[skyforge_gnss::signal::Signal],
    from_s: f64,
    at_least: usize,
) -> f64 {
    let squares: Vec<f64> = run
        .first_antenna_fixes_with(pvt, signals)
        .iter()
        .filter_map(|f| {
            let t = (f.at - run.start).to_seconds();
            let truth = run.true_position(0, t)?;
            (t >= from_s).then(|| (f.r_ecef_m - truth).norm_squared())
        })
        .collect();
    assert!(squares.len() >= at_least, "{} fixes", squares.len());
    (squares.iter().sum::<f64>() / squares.len() as f64).sqrt()
}
