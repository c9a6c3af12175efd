//! One constellation on two signals at the signal level: GPS L1 C/A and L5 recorded side
//! by side (two recordings of one antenna, one receiver clock), received by the bundled
//! receiver and fixed with the ionosphere-free combination (`[pvt] ionosphere =
//! "dual-frequency"`).

mod support;

/// The bundled L5 site (52 N 13 E, 20.46 Msps ci8) with GPS on L1 C/A and L5, 45 dB-Hz on
/// each (# assumed: the L1 C/A interop scenarios' C/N0), `duration_s` long, the ionosphere
/// as `ionosphere` sets it.
fn scenario(dir: &std::path::Path, name: &str, duration_s: u32, ionosphere: &str) -> String {
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
                "signals = [\"gps-l1ca\", \"gps-l5\"]",
            ),
            ("cn0_dbhz = 48.6", "cn0_dbhz = 45.0"),
        ],
    ) + &format!("\n[errors.ionosphere]\n{ionosphere}\n");
    support::write_scenario(dir, &format!("{name}.toml"), &text)
}

/// `synth --receive` of `scenario` with the dual-frequency receiver; the 3D errors (m) of
/// its fixes against the site, in time order, and the receiver's RINEX text.
fn receive_dual_frequency(dir: &std::path::Path, scenario: &str, out: &str) -> (Vec<f64>, String) {
    let config = dir.join("receiver.toml");
    std::fs::write(&config, "[pvt]\nionosphere = \"dual-frequency\"\n").expect("config");
    let out = dir.join(out);
    let log = support::skyforge_ok(
        &[
            "synth",
            scenario,
            "--receive",
            "--receiver-config",
            config.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        dir,
    );
    println!("{log}");
    let rx = out.join("receive");
    let site = support::truth_site(&out);
    let errors = support::fixes(&rx)
        .iter()
        .map(|(_, r, _)| (r - site).norm())
        .collect();
    let obs = std::fs::read_to_string(rx.join("ant1.obs.rnx")).expect("receiver RINEX");
    (errors, obs)
}

fn median(errors: &[f64]) -> f64 {
    let mut e = errors.to_vec();
    e.sort_by(f64::total_cmp);
    e.get(e.len() / 2).copied().unwrap_or(f64::NAN)
}

/// With a threefold ionosphere (the broadcast coefficients unchanged) the dual-frequency
/// fix meets the interoperability bar, median 3D error under 5 m, on both signals
/// of every satellite.
#[test]
fn l1_and_l5_are_received_together_and_fixed_free_of_the_ionosphere() {
    let dir = tempfile::tempdir().expect("tempdir");
    // assumed: 30 s, the first CNAV ephemeris decoded after about 14 s.
    let path = scenario(
        dir.path(),
        "l1-l5",
        30,
        "model = \"klobuchar\"\nscale = 3.0",
    );
    let (errors, obs) = receive_dual_frequency(dir.path(), &path, "out");
    assert!(
        obs.contains("G    8 C1C L1C D1C S1C C5I L5I D5I S5I"),
        "{obs}"
    );
    // Satellite (3 characters) and four 16-character observations of L1 C/A before L5's.
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    let both = body
        .lines()
        .filter(|l| l.starts_with('G') && l.len() > 67 && !l[67..].trim().is_empty())
        .count();
    assert!(both >= 4 * 10, "{both} lines with L5 beside L1 C/A");
    assert_l5_is_timed_with_l1(body);
    assert_signal_truth_names_each_rows_signal(&dir.path().join("out").join("truth.h5"));
    println!("{} fixes, 3D errors {errors:.2?} m", errors.len());
    assert!(errors.len() >= 10, "{} fixes", errors.len());
    assert!(median(&errors) < 5.0, "median {} m", median(&errors));
}

/// Every satellite's L5 observations begin with its L1 C/A ones in the RINEX `body`: the
/// receiver times L5 from L1 C/A's decoded time (the hand-over) once Q5's secondary code
/// is found, where CNAV's own first message would come up to 13 s after acquisition
/// (without the hand-over, 2026-11-30: 9 of 12 satellites' L5 a second after their L1 C/A).
fn assert_l5_is_timed_with_l1(body: &str) {
    let mut t = 0.0;
    let mut first: std::collections::BTreeMap<String, [Option<f64>; 2]> = Default::default();
    for line in body.lines() {
        if let Some(epoch) = line.strip_prefix('>') {
            let f: Vec<f64> = epoch
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            t = f[3] * 3600.0 + f[4] * 60.0 + f[5];
        } else if line.starts_with('G') {
            let entry = first.entry(line[..3].to_string()).or_default();
            for (i, field) in [(0, 3..17), (1, 67..81)] {
                let has = line.get(field).is_some_and(|x| !x.trim().is_empty());
                if has && entry[i].is_none() {
                    entry[i] = Some(t);
                }
            }
        }
    }
    println!("first L1 C/A and L5 epochs (s of day): {first:?}");
    assert!(first.len() >= 4, "{first:?}");
    for (sat, [l1, l5]) in &first {
        let (Some(l1), Some(l5)) = (l1, l5) else {
            panic!("{sat}: L1 C/A first at {l1:?}, L5 at {l5:?}");
        };
        assert!(
            l5 - l1 <= 1.0,
            "{sat}: L1 C/A first at {l1} s, L5 at {l5} s"
        );
    }
}

/// truth.h5 lists each satellite once and says which signal a signal-truth row is: each
/// (time, satellite, signal) once, both signals present.
fn assert_signal_truth_names_each_rows_signal(path: &std::path::Path) {
    let file = hdf5::File::open(path).expect("truth.h5");
    let ids: Vec<hdf5::types::VarLenUnicode> = support::dataset(&file, "satellites/id");
    let mut unique: Vec<String> = ids.iter().map(|s| s.to_string()).collect();
    unique.sort();
    unique.dedup();
    assert_eq!(
        unique.len(),
        ids.len(),
        "satellites/id lists a satellite twice"
    );
    let g = file.group("antennas/ant1/signal").expect("signal truth");
    let tags: hdf5::types::VarLenUnicode = g.attr("signals").unwrap().read_scalar().unwrap();
    assert_eq!(tags.as_str(), "gps-l1ca gps-l5");
    let t: Vec<f64> = support::dataset(&g, "t_s");
    let sat: Vec<u16> = support::dataset(&g, "sat_index");
    let signal: Vec<u8> = support::dataset(&g, "signal_index");
    assert!(t.len() == signal.len() && sat.len() == signal.len());
    let mut keys: Vec<(u64, u16, u8)> = (0..t.len())
        .map(|k| ((t[k] * 1e3).round() as u64, sat[k], signal[k]))
        .collect();
    keys.sort_unstable();
    let rows = keys.len();
    keys.dedup();
    assert_eq!(keys.len(), rows, "a (time, satellite, signal) row twice");
    assert!(signal.contains(&0) && signal.contains(&1));
}

/// Issue #34's acceptance at the signal level: with the ionosphere scaled up threefold the
/// ionosphere-free fix stays within 1.5 times the RMS error of the same run without
/// ionosphere (same seed), over the fixes of a minute.
#[test]
#[ignore = "long tier (scripts/long-tests.txt): two 60 s runs of two bands at 20.46 Msps"]
fn the_ionosphere_free_fix_removes_a_threefold_ionosphere_from_samples() {
    let dir = tempfile::tempdir().expect("tempdir");
    let calm = scenario(dir.path(), "calm", 60, "model = \"off\"");
    let storm = scenario(
        dir.path(),
        "storm",
        60,
        "model = \"klobuchar\"\nscale = 3.0",
    );
    // The first fix of each run is left out: four satellites and a PDOP in the hundreds.
    let (calm, _) = receive_dual_frequency(dir.path(), &calm, "calm");
    let (storm, _) = receive_dual_frequency(dir.path(), &storm, "storm");
    let (calm_rms, storm_rms) = (support::rms(&calm[1..]), support::rms(&storm[1..]));
    println!(
        "RMS 3D error: {calm_rms:.2} m without ionosphere ({} fixes), {storm_rms:.2} m with a threefold one ({} fixes)",
        calm.len(),
        storm.len()
    );
    assert!(calm.len() >= 40 && storm.len() >= 40);
    assert!(
        storm_rms <= 1.5 * calm_rms,
        "{storm_rms} m against {calm_rms} m"
    );
}
