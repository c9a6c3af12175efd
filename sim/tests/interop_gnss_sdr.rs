//! Interoperability tier: the real GNSS-SDR (Debian package `gnss-sdr`) decodes SkyForge's
//! I/Q to a position fix; on the static GPS and BeiDou runs its RINEX observations are
//! compared with SkyForge's observation truth (`interop_observables`). Run with `cargo test -p skyforge-sim --test interop_gnss_sdr --
//! --ignored` (scripts/test.sh --ci installs gnss-sdr and runs it).

mod interop_observables;
mod support;

use skyforge_gnss::codes::BDS_B1I_CHIP_RATE_HZ;
use skyforge_gnss::codes::GPS_CA_CHIP_RATE_HZ;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use std::path::Path;
use std::process::Command;
use support::dataset;

/// The site of the bundled `interop-gps-static` and `interop-bds-static` scenarios.
const SITE: (f64, f64, f64) = (30.0, 114.0, 50.0);
/// The scenario's C/N0 (dB-Hz).
const CN0_DBHZ: f64 = 45.0;

fn ecef(lat_deg: f64, lon_deg: f64, h_m: f64) -> Vec3 {
    geodetic_to_ecef(&Geodetic {
        lat_rad: lat_deg.to_radians(),
        lon_rad: lon_deg.to_radians(),
        h_m,
    })
}

/// `ddmm.mmmm` + hemisphere to degrees.
fn nmea_angle(value: &str, hemi: &str) -> Option<f64> {
    let v: f64 = value.parse().ok()?;
    let deg = (v / 100.0).trunc() + (v % 100.0) / 60.0;
    Some(if hemi == "S" || hemi == "W" {
        -deg
    } else {
        deg
    })
}

/// (lat, lon, height) of every GGA fix.
fn fixes(nmea: &str) -> Vec<(f64, f64, f64)> {
    timed_fixes(nmea)
        .into_iter()
        .map(|(_, lat, lon, h)| (lat, lon, h))
        .collect()
}

/// (UTC seconds of day, lat, lon, height) of every GGA fix.
fn timed_fixes(nmea: &str) -> Vec<(f64, f64, f64, f64)> {
    nmea.lines()
        .filter(|l| l.starts_with("$GPGGA") || l.starts_with("$GNGGA"))
        .filter_map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let hms = f.get(1)?;
            let sod = hms.get(0..2)?.parse::<f64>().ok()? * 3600.0
                + hms.get(2..4)?.parse::<f64>().ok()? * 60.0
                + hms.get(4..)?.parse::<f64>().ok()?;
            let lat = nmea_angle(f.get(2)?, f.get(3)?)?;
            let lon = nmea_angle(f.get(4)?, f.get(5)?)?;
            let alt: f64 = f.get(9)?.parse().ok()?;
            let sep: f64 = f.get(11)?.parse().unwrap_or(0.0);
            Some((sod, lat, lon, alt + sep))
        })
        .collect()
}

/// PRN -> SNR (dB-Hz) from the last complete group of GSV sentences of `talker` (`GP`
/// for GPS, `BD` for BeiDou). A trailing NMEA 4.1 signal-ID field forms a chunk of one
/// and is skipped.
fn last_gsv(nmea: &str, talker: &str) -> Vec<(u8, f64)> {
    let tag = format!("${talker}GSV");
    let gsv: Vec<&str> = nmea.lines().filter(|l| l.starts_with(&tag)).collect();
    let Some(last_first) = gsv.iter().rposition(|l| l.split(',').nth(2) == Some("1")) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for line in &gsv[last_first..] {
        let body = line.split('*').next().unwrap_or("");
        let f: Vec<&str> = body.split(',').collect();
        for sat in f[4..].chunks(4) {
            if let (Some(prn), Some(snr)) = (sat.first(), sat.get(3))
                && let (Ok(prn), Ok(snr)) = (prn.parse::<u8>(), snr.parse::<f64>())
            {
                out.push((prn, snr));
            }
        }
    }
    out
}

/// PRNs of `system` (`'G'`, `'C'`) whose elevation stays above `mask_deg` for the whole
/// run, from truth.h5.
fn satellites_above(truth: &Path, system: char, mask_deg: f64) -> Vec<u8> {
    let file = hdf5::File::open(truth).unwrap();
    let ids: Vec<hdf5::types::VarLenUnicode> = dataset(&file, "satellites/id");
    let g = file.group("antennas/ant1").unwrap();
    let sat_index: Vec<u16> = dataset(&g, "sat_index");
    let elevation: Vec<f64> = dataset(&g, "elevation_rad");
    let mut min_el = vec![f64::INFINITY; ids.len()];
    for (&s, &e) in sat_index.iter().zip(&elevation) {
        min_el[s as usize] = min_el[s as usize].min(e.to_degrees());
    }
    ids.iter()
        .zip(&min_el)
        .filter(|(_, el)| el.is_finite() && **el > mask_deg)
        .filter_map(|(id, _)| id.as_str().strip_prefix(system)?.parse().ok())
        .collect()
}

/// Satellites (`C01`, `G05`, `E11`) with an ephemeris record in the RINEX 3 navigation files
/// GNSS-SDR wrote into `dir` (`GSDR*.yyN`; Galileo's alone `GSDR*.yyL`).
fn rinex_nav_satellites(dir: &Path) -> std::collections::BTreeSet<String> {
    let mut sats = std::collections::BTreeSet::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !(name.starts_with("GSDR") && (name.ends_with('N') || name.ends_with('L'))) {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let body = text.split("END OF HEADER").nth(1).unwrap_or("");
        for line in body.lines() {
            // A record starts with the satellite and the epoch's year: "C06 2023 ...".
            let b = line.as_bytes();
            if b.len() > 8
                && (b[0] == b'C' || b[0] == b'G' || b[0] == b'E')
                && b[1..3].iter().all(u8::is_ascii_digit)
                && b[3] == b' '
                && b[4..8].iter().all(u8::is_ascii_digit)
            {
                sats.insert(line[..3].to_string());
            }
        }
    }
    sats
}

/// One of these tests at a time, from synthesis to the last check: GNSS-SDR is
/// multi-threaded and the machine has two cores. In one CI run where the tests' analyses
/// overlapped another test's GNSS-SDR run, GNSS-SDR's BeiDou fixes came out at 13.5 m RMS
/// (worst 43.6 m) against 3.5-3.9 m in three runs alone; that the overlap caused it is a
/// guess, not established.
fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

/// Remove what GNSS-SDR wrote into `out` (its RINEX files and NMEA), before it runs
/// once more on the same recording.
fn remove_gnss_sdr_outputs(out: &Path) {
    for entry in std::fs::read_dir(out).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.starts_with("GSDR") || name.ends_with(".nmea") {
            std::fs::remove_file(&path).unwrap();
        }
    }
}

/// Synthesise bundled `scenario` into `dir/out`; returns the output folder.
fn synth(dir: &Path, scenario: &str) -> std::path::PathBuf {
    assert!(
        Command::new("gnss-sdr").arg("--version").output().is_ok(),
        "\n*** gnss-sdr is not installed: apt-get install gnss-sdr (scripts/test.sh does) ***\n"
    );
    let out = dir.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(["synth", scenario, "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

/// Run GNSS-SDR in `out` with configuration file `conf` (a name in `out`); returns its
/// console log.
fn run_gnss_sdr(out: &Path, conf: &str) -> String {
    let o = Command::new("gnss-sdr")
        .arg(format!("--config_file={conf}"))
        .current_dir(out)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "gnss-sdr failed:\n{log}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    log
}

/// Run GNSS-SDR in `out` on antenna 1's recording of `band` (`gps-l1ca`, `bds-b1i`) with
/// the .conf SkyForge wrote; returns (its console log, its NMEA output).
fn receive_band(out: &Path, band: &str) -> (String, String) {
    let log = run_gnss_sdr(out, &format!("ant1.{band}.gnss-sdr.conf"));
    let nmea = std::fs::read_to_string(out.join(format!("ant1.{band}.nmea"))).unwrap();
    (log, nmea)
}

/// Synthesise bundled `scenario` into `dir/out` and run [`receive_band`] there; returns
/// (output folder, GNSS-SDR's console log, its NMEA output).
fn synth_and_receive(
    dir: &Path,
    scenario: &str,
    band: &str,
) -> (std::path::PathBuf, String, String) {
    let out = synth(dir, scenario);
    let (log, nmea) = receive_band(&out, band);
    (out, log, nmea)
}

/// Both receivers on `scenario`'s antenna-1 recording of `band` at the equal loops of
/// `interop_observables::side_by_side` (GNSS-SDR's tracking block `role`), compared with
/// the truth over the same epochs.
fn side_by_side(scenario: &str, band: &str, role: &str) {
    use interop_observables::side_by_side::{EQUAL_LOOPS, check};
    let _turn = one_at_a_time();
    let tmp = tempfile::tempdir().unwrap();
    let out = synth(tmp.path(), scenario);
    let conf = std::fs::read_to_string(out.join(format!("ant1.{band}.gnss-sdr.conf"))).unwrap();
    std::fs::write(
        out.join("equal.gnss-sdr.conf"),
        EQUAL_LOOPS.gnss_sdr_conf(&conf, role),
    )
    .unwrap();
    let log = run_gnss_sdr(&out, "equal.gnss-sdr.conf");
    if interop_observables::find_gnss_sdr_obs_file(&out).is_none() {
        // GNSS-SDR is nondeterministic on a shared CPU (see the BeiDou fix test): once in
        // CI (stop 26) it wrote no observation file on the B1I recording, which it had
        // fixed on in every run before. The samples being identical, one more run tells
        // its nondeterminism from the signal; both runs are reported.
        let tail: Vec<&str> = log.lines().rev().take(40).collect();
        println!(
            "GNSS-SDR, first run: no fix (no GSDR*O); its log ended:\n{}\nrunning GNSS-SDR \
             once more on the same recording",
            tail.into_iter().rev().collect::<Vec<_>>().join("\n")
        );
        remove_gnss_sdr_outputs(&out);
        run_gnss_sdr(&out, "equal.gnss-sdr.conf");
    }
    std::fs::write(out.join("equal.toml"), EQUAL_LOOPS.receiver_toml()).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .arg("receive")
        .arg(out.join(format!("ant1.{band}.sigmf-meta")))
        .arg("--config")
        .arg(out.join("equal.toml"))
        .arg("--out")
        .arg(out.join("rx"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    check(&out, band, &out.join("rx/ant1.obs.rnx"));
}

/// GNSS-SDR's fixes of a static run against `SITE`.
struct StaticFixes {
    count: usize,
    rms_m: f64,
    worst_m: f64,
    /// Error of the averaged position.
    mean_error_m: f64,
}

impl StaticFixes {
    fn of(nmea: &str) -> Self {
        Self::at(nmea, SITE)
    }

    /// The fixes of `nmea` against the site `(lat deg, lon deg, h m)`.
    fn at(nmea: &str, site: (f64, f64, f64)) -> Self {
        let truth = ecef(site.0, site.1, site.2);
        let points: Vec<Vec3> = fixes(nmea)
            .iter()
            .map(|&(lat, lon, h)| ecef(lat, lon, h))
            .collect();
        let errors: Vec<f64> = points.iter().map(|p| (p - truth).norm()).collect();
        let n = errors.len().max(1) as f64;
        let mean_point = points.iter().fold(Vec3::zeros(), |acc, p| acc + p) / n;
        Self {
            count: errors.len(),
            rms_m: (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt(),
            worst_m: errors.iter().cloned().fold(0.0, f64::max),
            mean_error_m: (mean_point - truth).norm(),
        }
    }

    /// At least 30 fixes in 90 s; RMS 3D error and averaged position within 10 m.
    fn within_bars(&self) -> bool {
        self.count >= 30 && self.rms_m < 10.0 && self.mean_error_m < 10.0
    }
}

impl std::fmt::Display for StaticFixes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} fixes, 3D error RMS {:.2} m, worst epoch {:.2} m, averaged position {:.2} m",
            self.count, self.rms_m, self.worst_m, self.mean_error_m
        )
    }
}

/// Position check of a static run: GNSS-SDR's single-epoch fixes scatter by a few metres
/// (code noise at 45 dB-Hz through its 2 Hz DLL, times the DOP); the RMS 3D error and the
/// error of the averaged position must both stay within 10 m of `SITE`. The worst single
/// epoch is reported.
fn assert_static_fixes(nmea: &str, log: &str, label: &str) {
    let stats = StaticFixes::of(nmea);
    println!("GNSS-SDR {label}: {stats}");
    assert!(stats.within_bars(), "{label}: {stats}\n{log}");
}

/// Every PRN of `prns` is in GNSS-SDR's last GSV group at the scenario's C/N0 +/- 2 dB.
fn assert_in_solution_at_scenario_cn0(gsv: &[(u8, f64)], system: char, prns: &[u8]) {
    for &prn in prns {
        let snr = gsv.iter().find(|(p, _)| *p == prn).map(|(_, s)| *s);
        println!("{system}{prn:02}: GNSS-SDR C/N0 {snr:?} dB-Hz");
        let snr = snr.unwrap_or_else(|| {
            panic!("{system}{prn:02} is above 10 deg but not in GNSS-SDR's solution: {gsv:?}")
        });
        assert!(
            (snr - CN0_DBHZ).abs() <= 2.0,
            "{system}{prn:02}: C/N0 {snr} dB-Hz, scenario {CN0_DBHZ}"
        );
    }
}

#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_tracks_and_fixes_on_interop_gps_static() {
    let _turn = one_at_a_time();
    let tmp = tempfile::tempdir().unwrap();
    let (out, log, nmea) = synth_and_receive(tmp.path(), "interop-gps-static", "gps-l1ca");
    assert_static_fixes(&nmea, &log, "GPS");
    let above = satellites_above(&out.join("truth.h5"), 'G', 10.0);
    assert_in_solution_at_scenario_cn0(&last_gsv(&nmea, "GP"), 'G', &above);
    interop_observables::check(
        &out,
        "gps-l1ca",
        Signal::GpsL1Ca,
        GPS_CA_CHIP_RATE_HZ,
        CN0_DBHZ,
    );
}

/// BeiDou B1I (the BDS-2 set, GEO + IGSO + MEO; see the scenario file for why): every
/// satellite above 10 deg that GNSS-SDR 0.0.17 can acquire (PRN 1-33) is tracked, has its
/// ephemeris decoded -- from D2 for the GEOs C01-C05, from D1 for the others -- and is in
/// the solution at 45 +/- 2 dB-Hz; the fixes are within 10 m of the site.
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_tracks_decodes_d1_d2_and_fixes_on_interop_bds_static() {
    let _turn = one_at_a_time();
    use skyforge_signals::synth::gnss_sdr::GNSS_SDR_0017_BDS_PRN_MAX;
    let tmp = tempfile::tempdir().unwrap();
    let (out, mut log, mut nmea) = synth_and_receive(tmp.path(), "interop-bds-static", "bds-b1i");
    // GNSS-SDR 0.0.17's BeiDou solution is now and then off on the very same samples: 13.5 m
    // and 50.6 m RMS (worst epochs 44 m and 220 m) in two of some thirty runs, 3.3-5.6 m in
    // the others (validation/gnss_sdr_observables.md); once (session 9, CPU shared with a
    // fuzzer) it lost lock on C06 early and decoded no D1 ephemeris for it in 90 s. The
    // samples being identical, one more GNSS-SDR run tells its nondeterminism from the
    // signal; both runs are reported.
    let (supported, unsupported): (Vec<u8>, Vec<u8>) =
        satellites_above(&out.join("truth.h5"), 'C', 10.0)
            .into_iter()
            .partition(|&prn| prn <= GNSS_SDR_0017_BDS_PRN_MAX);
    let undecoded = |out: &Path| {
        let decoded = rinex_nav_satellites(out);
        supported
            .iter()
            .filter(|&&prn| !decoded.contains(&format!("C{prn:02}")))
            .map(|prn| format!("C{prn:02}"))
            .collect::<Vec<_>>()
    };
    let first = StaticFixes::of(&nmea);
    let missing = undecoded(&out);
    if !first.within_bars() || !missing.is_empty() {
        println!(
            "GNSS-SDR BeiDou, first run: {first}, no ephemeris for {missing:?}; running \
             GNSS-SDR once more on the same recording"
        );
        remove_gnss_sdr_outputs(&out);
        (log, nmea) = receive_band(&out, "bds-b1i");
    }
    assert_static_fixes(&nmea, &log, "BeiDou");

    for prn in &unsupported {
        println!("C{prn:02}: above 10 deg, no B1I replica in GNSS-SDR 0.0.17 (not checked)");
    }
    // D2 (GEO, C01-C05 in GNSS-SDR) and D1 ephemerides as GNSS-SDR records them in its
    // RINEX navigation output (its console lines come from several threads and can
    // interleave mid-line, so they are not parsed for this).
    let decoded = rinex_nav_satellites(&out);
    let is_geo = |prn: u8| (1..=5).contains(&prn);
    for &prn in &supported {
        let message = if is_geo(prn) { "D2" } else { "D1" };
        assert!(
            decoded.contains(&format!("C{prn:02}")),
            "C{prn:02}: no {message} ephemeris in GNSS-SDR's RINEX navigation output {decoded:?}:\n{log}"
        );
        println!("C{prn:02}: {message} ephemeris decoded");
    }
    assert!(
        supported.iter().any(|&p| is_geo(p)) && supported.iter().any(|&p| !is_geo(p)),
        "the scenario must put a GEO (D2) and a MEO/IGSO (D1) above 10 deg: {supported:?}"
    );
    assert_in_solution_at_scenario_cn0(&last_gsv(&nmea, "BD"), 'C', &supported);
    interop_observables::check(
        &out,
        "bds-b1i",
        Signal::BdsB1I,
        BDS_B1I_CHIP_RATE_HZ,
        CN0_DBHZ,
    );
}

/// Acceptance (issue #34): GNSS-SDR 0.0.17 acquires and tracks SkyForge's Galileo E5a on
/// its pilot, decodes F/NAV from E5a-I and fixes; the median 3D error of its fixes is
/// under 5 m at the site of `interop-gal-static`, from at least 20 fixes (F/NAV needs a
/// subframe of 50 s before the first ephemeris, so the fixes come in the last minute).
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_decodes_fnav_and_fixes_on_interop_gal_static() {
    pilot_signal_fixes("interop-gal-static", "gal-e5a", "F/NAV");
}

/// Acceptance (issue #34): GNSS-SDR 0.0.17 acquires SkyForge's GPS L5 on I5, tracks the
/// Q5 pilot, decodes CNAV from I5 and fixes; the median 3D error of its fixes is under
/// 5 m at the site of `interop-l5-static`, from at least 20 fixes.
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_decodes_cnav_and_fixes_on_interop_l5_static() {
    pilot_signal_fixes("interop-l5-static", "gps-l5", "CNAV");
}

/// Acceptance (issue #34): GNSS-SDR 0.0.17 acquires SkyForge's Galileo E1 (CBOC) on the
/// E1-C pilot with a BOC(1,1) replica, tracks it with its very-early-minus-late loop,
/// decodes I/NAV from E1-B and fixes; the median 3D error of its fixes is under 5 m at the
/// site of `interop-e1-static`, from at least 20 fixes.
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_decodes_inav_and_fixes_on_interop_e1_static() {
    pilot_signal_fixes("interop-e1-static", "gal-e1", "I/NAV");
}

/// Acceptance (issue #34): GNSS-SDR 0.0.17 fixes on GPS L1 C/A and Galileo E1 recorded
/// together (`interop-l1-e1-static`, one recording of the 1575.42 MHz band) with the one
/// configuration SkyForge writes for it: at least 20 fixes, median 3D error under 5 m, and
/// satellites of both systems in its solution (its last GSV sentences of each).
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_fixes_on_gps_l1ca_and_galileo_e1_in_one_recording() {
    let (log, nmea) =
        pilot_signal_fixes("interop-l1-e1-static", "gps-l1ca+gal-e1", "LNAV and I/NAV");
    let (gps, galileo) = (last_gsv(&nmea, "GP"), last_gsv(&nmea, "GA"));
    println!(
        "GNSS-SDR's last GSV: {} GPS, {} Galileo satellites",
        gps.len(),
        galileo.len()
    );
    assert!(gps.len() >= 4 && galileo.len() >= 4, "{log}");
}

/// GNSS-SDR on the bundled static `scenario` (at 52 N 13 E, 100 m) recorded on `band`:
/// at least 20 fixes, their median 3D error under 5 m; prints the satellites whose
/// `message` ephemeris GNSS-SDR decoded; returns GNSS-SDR's console log and NMEA output.
fn pilot_signal_fixes(scenario: &str, band: &str, message: &str) -> (String, String) {
    let _turn = one_at_a_time();
    let tmp = tempfile::tempdir().unwrap();
    let (out, log, nmea) = synth_and_receive(tmp.path(), scenario, band);
    let site = (52.0, 13.0, 100.0);
    let truth = ecef(site.0, site.1, site.2);
    let mut errors: Vec<f64> = fixes(&nmea)
        .iter()
        .map(|&(lat, lon, h)| (ecef(lat, lon, h) - truth).norm())
        .collect();
    errors.sort_by(f64::total_cmp);
    let median = errors
        .get(errors.len() / 2)
        .copied()
        .unwrap_or(f64::INFINITY);
    println!(
        "GNSS-SDR {band}: {}; median 3D error {median:.2} m",
        StaticFixes::at(&nmea, site)
    );
    let decoded = rinex_nav_satellites(&out);
    println!("{message} ephemerides GNSS-SDR decoded: {decoded:?}");
    assert!(errors.len() >= 20, "{} fixes\n{log}", errors.len());
    assert!(median < 5.0, "median 3D error {median} m\n{log}");
    (log, nmea)
}

/// Issue #4's side-by-side bar on GPS L1 C/A (`interop_observables::side_by_side`).
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn side_by_side_with_gnss_sdr_at_equal_loops_on_gps_l1ca() {
    side_by_side("interop-gps-static", "gps-l1ca", "Tracking_1C");
}

/// Issue #4's side-by-side bar on BeiDou B1I, GEOs (D2) and MEO/IGSO (D1).
#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn side_by_side_with_gnss_sdr_at_equal_loops_on_bds_b1i() {
    side_by_side("interop-bds-static", "bds-b1i", "Tracking_B1");
}

#[test]
#[ignore = "interop tier: needs gnss-sdr (scripts/test.sh installs it)"]
fn gnss_sdr_fixes_on_the_thesis_leo() {
    let _turn = one_at_a_time();
    let tmp = tempfile::tempdir().unwrap();
    let (out, log, nmea) = synth_and_receive(tmp.path(), "interop-leo-gps", "gps-l1ca");
    // Truth: the platform's ECEF position at 1 Hz (the antenna sits at the centre of mass).
    let file = hdf5::File::open(out.join("truth.h5")).unwrap();
    let t: Vec<f64> = dataset(&file, "time/t_s");
    let r: Vec<f64> = dataset(&file, "platform/r_ecef_m");
    // NMEA times are UTC; the scenario starts at 2023-03-12T00:00:00 GPST.
    let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
    let midnight_utc = hifitime::Epoch::from_gregorian_utc_at_midnight(2023, 3, 12);
    let offset_s = (midnight_utc - start).to_seconds();
    let mut errors = Vec::new();
    for (sod, lat, lon, h) in timed_fixes(&nmea) {
        let ts = sod + offset_s;
        let Some(i) = t.iter().position(|&x| x > ts).filter(|&i| i > 0) else {
            continue;
        };
        let w = (ts - t[i - 1]) / (t[i] - t[i - 1]);
        let at = |k: usize| Vec3::new(r[3 * k], r[3 * k + 1], r[3 * k + 2]);
        let truth = at(i - 1) * (1.0 - w) + at(i) * w;
        errors.push((ecef(lat, lon, h) - truth).norm());
    }
    assert!(
        errors.len() >= 20,
        "only {} LEO fixes in 90 s:\n{log}",
        errors.len()
    );
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    let worst = errors.iter().cloned().fold(0.0, f64::max);
    println!(
        "GNSS-SDR on the LEO: {} fixes, 3D error RMS {rms:.2} m, worst {worst:.2} m",
        errors.len()
    );
    assert!(worst < 50.0, "a LEO fix {worst} m from truth");
}
