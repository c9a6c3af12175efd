//! One recording per band (`[signal] recordings = "per-band"`): the signals on one carrier
//! summed in one recording per antenna, as a front end takes them; the bundled receiver
//! reads such a recording once per signal it receives.

mod support;

use skyforge_signals::synth::ThermalNoise;

/// The bundled L5 site (52 N 13 E, 20.46 Msps) with GPS L5 and Galileo E5a, both on
/// 1176.45 MHz, recorded as `recordings` says, `duration_s` long (in `cf32` rather than
/// ci8 when `cf32`).
fn scenario(
    dir: &std::path::Path,
    name: &str,
    recordings: &str,
    duration_s: u32,
    cf32: bool,
) -> String {
    let format = if cf32 {
        "format = \"cf32\""
    } else {
        "format = \"ci8\"\nbits = 8"
    };
    let text = support::bundled_edited(
        "interop-l5-static",
        &[
            (
                "name = \"interop-l5-static\"",
                &format!("name = \"{name}\""),
            ),
            (
                "duration_s = 120.0",
                &format!("duration_s = {duration_s}.0"),
            ),
            (
                "signals = [\"gps-l5\"]",
                &format!("signals = [\"gps-l5\", \"gal-e5a\"]\nrecordings = \"{recordings}\""),
            ),
            ("format = \"ci8\"\nbits = 8", format),
            (
                "[platform.ground]",
                "[gnss.galileo]\nsource = \"embedded\"\n\n[platform.ground]",
            ),
        ],
    );
    support::write_scenario(dir, &format!("{name}.toml"), &text)
}

/// The satellites of `system` a RINEX observation body has lines of (a line starts with
/// the satellite: `G05`, `E11`).
fn observed(body: &str, system: char) -> usize {
    let mut sats: Vec<&str> = (body.lines())
        .filter(|l| l.starts_with(system) && l.len() > 3)
        .map(|l| &l[..3])
        .collect();
    sats.sort_unstable();
    sats.dedup();
    sats.len()
}

/// The median of the 3D errors (m) of the fixes in `rx` against the site of `out`, and
/// their number.
fn median_error(out: &std::path::Path, rx: &std::path::Path) -> (f64, usize) {
    let site = support::truth_site(out);
    let mut errors: Vec<f64> = (support::fixes(rx).iter())
        .map(|(_, r, _)| (r - site).norm())
        .collect();
    errors.sort_by(f64::total_cmp);
    let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
    (median, errors.len())
}

/// The first `n` complex samples of a cf32 recording.
fn cf32(path: &std::path::Path, n: usize) -> Vec<(f32, f32)> {
    let bytes = std::fs::read(path).expect("recording");
    bytes
        .chunks_exact(8)
        .take(n)
        .map(|c| {
            let f = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            (f(&c[..4]), f(&c[4..]))
        })
        .collect()
}

/// A band's recording holds what the two signals' own recordings hold, their thermal noise
/// once: every antenna's noise is one stream whatever the layout (keyed by seed, antenna
/// and sample), so band = L5 + E5a - noise, sample by sample, to float rounding.
#[test]
fn a_band_recording_is_the_sum_of_its_signals_recordings() {
    let dir = tempfile::tempdir().expect("tempdir");
    let each = scenario(dir.path(), "each", "per-signal", 1, true);
    let band = scenario(dir.path(), "band", "per-band", 1, true);
    for (path, out) in [(&each, "each"), (&band, "band")] {
        support::skyforge_ok(&["synth", path, "--out", out], dir.path());
    }
    let listing = support::listing(&dir.path().join("band"));
    for file in [
        "ant1.gps-l5+gal-e5a.sigmf-data",
        "ant1.gps-l5+gal-e5a.sigmf-meta",
        "ant1.gps-l5+gal-e5a.gnss-sdr.conf",
    ] {
        assert!(listing.iter().any(|f| f == file), "{file} in {listing:?}");
    }
    let meta = support::json_file(&dir.path().join("band/ant1.gps-l5+gal-e5a.sigmf-meta"));
    assert_eq!(
        meta["global"]["skyforge:signals"],
        serde_json::json!(["gps-l5", "gal-e5a"])
    );
    assert_eq!(meta["captures"][0]["core:frequency"], 1176.45e6);
    let conf =
        std::fs::read_to_string(dir.path().join("band/ant1.gps-l5+gal-e5a.gnss-sdr.conf")).unwrap();
    assert!(conf.contains("Channels_L5.count=") && conf.contains("Channels_5X.count="));
    assert_eq!(conf.matches("SignalSource.filename=").count(), 1);
    // 0.1 s: a hundred blocks.
    let n = 2_046_000;
    let l5 = cf32(&dir.path().join("each/ant1.gps-l5.sigmf-data"), n);
    let e5a = cf32(&dir.path().join("each/ant1.gal-e5a.sigmf-data"), n);
    let sum = cf32(&dir.path().join("band/ant1.gps-l5+gal-e5a.sigmf-data"), n);
    assert_eq!((l5.len(), e5a.len(), sum.len()), (n, n, n));
    // seed = 1 and antenna 0, as the scenario; sigma 1 per component, as the synthesiser.
    let (mut ni, mut nq) = (vec![0f32; n], vec![0f32; n]);
    ThermalNoise::new(1, 0, 1.0).add(0, &mut ni, &mut nq);
    let mut worst = 0f32;
    let mut signal_power = 0f64;
    for k in 0..n {
        let di = sum[k].0 - (l5[k].0 + e5a[k].0 - ni[k]);
        let dq = sum[k].1 - (l5[k].1 + e5a[k].1 - nq[k]);
        worst = worst.max(di.abs()).max(dq.abs());
        signal_power += f64::from((l5[k].0 - ni[k]).powi(2) + (l5[k].1 - nq[k]).powi(2));
    }
    // The L5 signal alone: 20 or so satellites at 48.6 dB-Hz over 20.46 MHz of unit noise.
    let per_sample = signal_power / n as f64;
    println!("largest difference {worst:e}; L5 signal power {per_sample:e} per sample");
    assert!(per_sample > 1e-3, "the L5 recording holds no signal");
    assert!(worst < 1e-5, "band != L5 + E5a - noise: {worst}");
}

/// `synth --receive` of a band recording: the receiver takes it once per signal (GPS L5 and
/// Galileo E5a from one stream of samples) and fixes on both constellations together.
#[test]
#[ignore = "acceptance tier: 30 s of 20.46 Msps received on 20 channels (minutes); the L1 C/A + E1 test below covers the same path in CI"]
fn the_bundled_receiver_fixes_on_both_signals_of_a_band_recording() {
    let dir = tempfile::tempdir().expect("tempdir");
    // assumed: 30 s, as the dual-frequency test (the ephemerides come from nav.rnx).
    let path = scenario(dir.path(), "l5-e5a", "per-band", 30, false);
    let log = support::skyforge_ok(&["synth", &path, "--receive", "--out", "out"], dir.path());
    println!("{log}");
    let out = dir.path().join("out");
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    let (gps, galileo) = (observed(body, 'G'), observed(body, 'E'));
    println!("observed: {gps} GPS satellites on L5, {galileo} Galileo satellites on E5a");
    assert!(
        gps >= 4 && galileo >= 4,
        "{gps} GPS, {galileo} Galileo satellites"
    );
    let (median, fixes) = median_error(&out, &rx);
    println!("{fixes} fixes, median 3D error {median:.2} m");
    // As the dual-frequency test: 10 fixes in 30 s at least.
    assert!(fixes >= 10, "{fixes} fixes");
    assert!(median < 5.0, "median {median} m");
}

/// GPS L1 C/A and Galileo E1 in one recording (the bundled `interop-l1-e1-static` cut to
/// 25 s, made-up E1 code tables, as `pilot_signals`' E1 test): `synth --receive` reads it
/// for both signals and fixes on both constellations together; the bars of that test.
#[test]
fn gps_l1ca_and_galileo_e1_from_one_recording_are_fixed_together() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenarios/bundled/interop-l1-e1-static.toml"),
    )
    .expect("bundled scenario")
    .replacen("duration_s = 120.0", "duration_s = 25.0", 1);
    let path = support::write_scenario(dir.path(), "l1-e1.toml", &text);
    let out = support::synth_receive_with_made_up_e1(dir.path(), &path);
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    let (gps, galileo) = (observed(body, 'G'), observed(body, 'E'));
    println!("observed: {gps} GPS satellites on L1 C/A, {galileo} Galileo satellites on E1");
    assert!(
        gps >= 4 && galileo >= 4,
        "{gps} GPS, {galileo} Galileo satellites"
    );
    let (median, fixes) = median_error(&out, &rx);
    println!("{fixes} fixes, median 3D error {median:.2} m");
    assert!(fixes >= 5, "{fixes} fixes");
    assert!(median < 5.0, "median {median} m");
}
