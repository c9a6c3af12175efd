//! The pilot signals through the bundled receiver: `synth --receive` of GPS L5 and Galileo
//! E5a recorded side by side (two bands on one carrier), tracked on their pilots, CNAV and
//! F/NAV decoded for the time, fixed together (GPS and Galileo clocks) and compared with
//! the truth; BeiDou B2a alone likewise (B-CNAV2, BDT), and BeiDou B1C (B-CNAV1).

mod support;

/// The bundled E5a site (52 N 13 E, 20.46 Msps ci8, 45 dB-Hz) with GPS enabled on L5
/// beside Galileo E5a, 30 s (# assumed: the first CNAV message decoded after about 14 s
/// leaves about 15 fixes).
fn scenario(dir: &std::path::Path) -> String {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenarios/bundled/interop-gal-static.toml"),
    )
    .expect("bundled scenario")
    .replacen(
        "[gnss.gps]\nenabled = false",
        "[gnss.gps]\nsource = \"embedded\"",
        1,
    )
    .replacen("duration_s = 120.0", "duration_s = 30.0", 1)
    .replacen(
        "[signal]\n",
        "[signal]\nsignals = [\"gps-l5\", \"gal-e5a\"]\n",
        1,
    );
    support::write_scenario(dir, "l5-e5a.toml", &text)
}

#[test]
fn l5_and_e5a_are_received_and_fixed_together() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(dir.path());
    let out = dir.path().join("out");
    let log = support::skyforge_ok(
        &["synth", &path, "--receive", "--out", out.to_str().unwrap()],
        dir.path(),
    );
    println!("{log}");
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    assert!(obs.contains("G    4 C5I L5I D5I S5I"), "{obs}");
    assert!(obs.contains("E    4 C5Q L5Q D5Q S5Q"), "{obs}");
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    for system in ['G', 'E'] {
        let lines = body.lines().filter(|l| l.starts_with(system)).count();
        assert!(lines >= 4 * 10, "{lines} {system} observation lines");
    }
    // Fixes against the surveyed site: the interoperability bar (median under
    // 5 m), and the observables against the truth with the bundled receiver's bars.
    let errors = sorted_errors(&out, &rx);
    println!("{} fixes, 3D errors {errors:.2?} m", errors.len());
    assert!(errors.len() >= 10, "{} fixes", errors.len());
    assert!(
        errors[errors.len() / 2] < 5.0,
        "median {} m",
        errors[errors.len() / 2]
    );
    let (pr_std, phase_std, matched) = support::observable_errors(&out, &rx);
    assert!(matched >= 10, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}

/// The 3D errors (m) of the receiver's fixes in `rx` against the site of the synthesis in
/// `out`, smallest first.
fn sorted_errors(out: &std::path::Path, rx: &std::path::Path) -> Vec<f64> {
    let site = support::truth_site(out);
    let mut errors: Vec<f64> = support::fixes(rx)
        .iter()
        .map(|(_, r, _)| (r - site).norm())
        .collect();
    errors.sort_by(f64::total_cmp);
    errors
}

/// `synth --receive` of the bundled `name` scenario (120 s, one signal with a pilot):
/// the bar for each new signal alone (median 3D error under 5 m), from at least 60
/// fixes (# assumed: the first fix after at most a minute), with the bundled receiver's
/// observable bars.
fn bundled_receiver_fixes_alone(name: &str) {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("out");
    let log = support::skyforge_ok(
        &["synth", name, "--receive", "--out", out.to_str().unwrap()],
        dir.path(),
    );
    println!("{log}");
    let rx = out.join("receive");
    let errors = sorted_errors(&out, &rx);
    let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
    println!(
        "{name}: {} fixes, median 3D error {median:.2} m, RMS {:.2} m",
        errors.len(),
        support::rms(&errors)
    );
    assert!(errors.len() >= 60, "{} fixes", errors.len());
    assert!(median < 5.0, "median {median} m");
    let (pr_std, phase_std, matched) = support::observable_errors(&out, &rx);
    assert!(matched >= 60, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}

#[test]
#[ignore = "long tier (scripts/long-tests.txt): 120 s at 20.46 Msps"]
fn bundled_receiver_fixes_on_interop_l5_static() {
    bundled_receiver_fixes_alone("interop-l5-static");
}

#[test]
#[ignore = "long tier (scripts/long-tests.txt): 120 s at 20.46 Msps"]
fn bundled_receiver_fixes_on_interop_gal_static() {
    bundled_receiver_fixes_alone("interop-gal-static");
}

/// Galileo E1 through the bundled receiver with made-up code tables (SkyForge does not
/// ship the ICD's; the synthesis and the receiver read the same ones): `synth --receive`
/// of the bundled E1 site (15 Msps ci8, 46.5 dB-Hz) cut to 25 s, tracked on BOC(1,1)
/// replicas of the E1-C pilot, I/NAV decoded for the time (the ephemerides from the
/// assistance file), fixed on Galileo alone: the bar (median 3D error under 5 m)
/// and the bundled receiver's observable bars against the truth.
#[test]
fn e1_is_received_decoded_and_fixed_with_made_up_tables() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenarios/bundled/interop-e1-static.toml"),
    )
    .expect("bundled scenario")
    .replacen("duration_s = 120.0", "duration_s = 25.0", 1);
    let path = support::write_scenario(dir.path(), "e1.toml", &text);
    let out = support::synth_receive_with_made_up_e1(dir.path(), &path);
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    assert!(obs.contains("E    4 C1C L1C D1C S1C"), "{obs}");
    let errors = sorted_errors(&out, &rx);
    let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
    println!(
        "E1: {} fixes, median 3D error {median:.2} m, errors {errors:.2?} m",
        errors.len()
    );
    assert!(errors.len() >= 5, "{} fixes", errors.len());
    assert!(median < 5.0, "median {median} m");
    let (pr_std, phase_std, matched) = support::observable_errors(&out, &rx);
    assert!(matched >= 5, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}

/// The bundled BeiDou site (30 N 114 E, 50 m) on B2a: the embedded BDS-3 set (B2a is
/// broadcast by the BDS-3 MEO and IGSO satellites only; its GEOs are left out), 20.46 Msps
/// ci8 for B2a's +-10.23 MHz main lobe, 45 dB-Hz, seed 1, 40 s (# assumed: B-CNAV2 types
/// 10, 11 and 30 arrive within one 12 s cycle after frame sync, so a satellite's
/// ephemeris is decoded about 15-20 s in, leaving some 20 fixes).
fn b2a_scenario(dir: &std::path::Path) -> String {
    let text = support::bundled_edited(
        "interop-bds-static",
        &[
            ("name = \"interop-bds-static\"", "name = \"b2a-static\""),
            (
                "duration_s = 90.0",
                "duration_s = 40.0  # assumed: about 20 fixes after the first B-CNAV2 ephemerides",
            ),
            (
                "embedded_set = \"bds2\"",
                "embedded_set = \"bds3\"  # assumed: B2a is a BDS-3 MEO/IGSO signal",
            ),
            (
                "sample_rate_hz = 4.0e6",
                "signals = [\"bds-b2a\"]\nsample_rate_hz = 20.46e6  # assumed: B2a's +-10.23 MHz main lobe, as E5a's\n#",
            ),
        ],
    );
    support::write_scenario(dir, "b2a.toml", &text)
}

/// The channels the receiver's summary in `log` says were timed by their message.
fn timed_channels(log: &str) -> usize {
    log.split("timed ")
        .nth(1)
        .and_then(|t| t.split(',').next())
        .and_then(|n| n.trim().parse().ok())
        .expect("receiver summary")
}

/// BeiDou B2a alone through the bundled receiver: tracked on the B2a_p pilot, B-CNAV2
/// decoded (the ephemerides come from the message: the receiver's navigation file lists
/// the BDS-3 satellites it decoded), BDT fixes with median 3D error under 5 m, and the
/// observables against the truth with the bundled receiver's bars.
#[test]
fn bds_b2a_is_received_decoded_and_fixed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = b2a_scenario(dir.path());
    let out = dir.path().join("out");
    let log = support::skyforge_ok(
        &["synth", &path, "--receive", "--out", out.to_str().unwrap()],
        dir.path(),
    );
    println!("{log}");
    // Timed channels: a B-CNAV2 frame decoded (preamble, LDPC, CRC, PRN and SOW) ties the
    // channel's code epochs to BDT.
    let timed = timed_channels(&log);
    assert!(timed >= 4, "{timed} channels timed by B-CNAV2");
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    assert!(obs.contains("C    4 C5P L5P D5P S5P"), "{obs}");
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    let lines = body.lines().filter(|l| l.starts_with('C')).count();
    assert!(lines >= 4 * 10, "{lines} BeiDou observation lines");
    let errors = sorted_errors(&out, &rx);
    let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
    println!(
        "B2a: {} fixes, median 3D error {median:.2} m, RMS {:.2} m, errors {errors:.2?}",
        errors.len(),
        support::rms(&errors)
    );
    assert!(errors.len() >= 10, "{} fixes", errors.len());
    assert!(median < 5.0, "median {median} m");
    let (pr_std, phase_std, matched) = support::observable_errors(&out, &rx);
    println!("B2a: pseudorange std {pr_std:.3} m, phase std {phase_std:.5} m, {matched} epochs");
    assert!(matched >= 10, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}

/// The bundled BeiDou site (30 N 114 E, 50 m) on B1C: the embedded BDS-3 set (B1C is
/// broadcast by the BDS-3 MEO and IGSO satellites only), 15 Msps ci8 (# assumed: E1's
/// rate, for the QMBOC's +-7.161 MHz BOC(6,1) lobes), 45 dB-Hz for the whole signal (#
/// assumed: the B1I site's), seed 1, 50 s (# assumed: the start is 23:59:46 BDT, so the
/// first 18 s B-CNAV1 frame after the secondary-code sync starts 14 s in and is decoded
/// 32 s in, leaving some 17 fixes).
fn b1c_scenario(dir: &std::path::Path) -> String {
    let text = support::bundled_edited(
        "interop-bds-static",
        &[
            ("name = \"interop-bds-static\"", "name = \"b1c-static\""),
            ("duration_s = 90.0", "duration_s = 50.0"),
            (
                "embedded_set = \"bds2\"",
                "embedded_set = \"bds3\"  # B1C is a BDS-3 MEO/IGSO signal",
            ),
            (
                "sample_rate_hz = 4.0e6",
                "signals = [\"bds-b1c\"]\nsample_rate_hz = 15e6\n#",
            ),
        ],
    );
    support::write_scenario(dir, "b1c.toml", &text)
}

/// BeiDou B1C alone through the bundled receiver: tracked on the pilot's BOC(1,1) part,
/// frames aligned by the 1800-chip secondary code, B-CNAV1 decoded (a decoded frame's SOW
/// times a channel), BDT fixes with median 3D error under 5 m (the bar), and the
/// observables against the truth with the bundled receiver's bars.
#[test]
fn bds_b1c_is_received_decoded_and_fixed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = b1c_scenario(dir.path());
    let out = dir.path().join("out");
    let log = support::skyforge_ok(
        &["synth", &path, "--receive", "--out", out.to_str().unwrap()],
        dir.path(),
    );
    println!("{log}");
    let timed = timed_channels(&log);
    let rx = out.join("receive");
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    assert!(obs.contains("C    4 C1P L1P D1P S1P"), "{obs}");
    let errors = sorted_errors(&out, &rx);
    let median = errors.get(errors.len() / 2).copied().unwrap_or(f64::NAN);
    let (pr_std, phase_std, matched) = support::observable_errors(&out, &rx);
    println!(
        "B1C: {timed} channels timed by B-CNAV1, {} fixes, median 3D error {median:.2} m, RMS \
         {:.2} m, errors {errors:.2?}; pseudorange std {pr_std:.3} m, phase std \
         {phase_std:.5} m, {matched} epochs",
        errors.len(),
        support::rms(&errors)
    );
    assert!(timed >= 4, "{timed} channels timed by B-CNAV1");
    assert!(errors.len() >= 10, "{} fixes", errors.len());
    assert!(median < 5.0, "median {median} m");
    assert!(matched >= 10, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}
