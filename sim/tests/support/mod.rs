//! Helpers of the integration tests of the `skyforge` binary: running it, reading what it
//! printed or wrote, shortening a bundled scenario, and reading RTKLIB's `rnx2rtkp`
//! solutions.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use skyforge_orbits::Vec3;
use skyforge_validate::observables::{compare, read_obs_file};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Dataset `name` (a path inside `group`, which may be a whole file) read whole.
pub fn dataset<T: hdf5::H5Type>(group: &hdf5::Group, name: &str) -> Vec<T> {
    group
        .dataset(name)
        .and_then(|d| d.read_raw())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Run `skyforge args` in `cwd`.
pub fn skyforge(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run skyforge")
}

/// Run `skyforge args` in `cwd` with the environment variables `env` set (a value of
/// `None` removes the variable).
pub fn skyforge_with_env(args: &[&str], cwd: &Path, env: &[(&str, Option<&str>)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_skyforge"));
    command.args(args).current_dir(cwd);
    for (key, value) in env {
        match value {
            Some(v) => command.env(key, v),
            None => command.env_remove(key),
        };
    }
    command.output().expect("run skyforge")
}

/// Made-up Galileo E1 code tables (pseudo-random chips, not the ICD's) in `dir`, in the
/// format `SKYFORGE_GALILEO_E1_CODES` names (docs/signals.md).
pub fn made_up_e1_tables(dir: &Path) {
    let mut x: u32 = 12345;
    for name in ["galileo_e1b.txt", "galileo_e1c.txt"] {
        let mut text = String::from("# made-up codes for tests, not the ICD's\n");
        for n in 1..=50 {
            let digits: String = (0..1023)
                .map(|_| {
                    x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                    char::from_digit((x >> 16) & 15, 16).unwrap()
                })
                .collect();
            text.push_str(&format!("{n} {digits}\n"));
        }
        std::fs::write(dir.join(name), text).expect("write a made-up E1 table");
    }
}

/// `synth SCENARIO --receive --out DIR/out` in `dir` with made-up Galileo E1 code tables
/// ([`made_up_e1_tables`], the check off); returns the output folder after checking that
/// the run succeeded (its log printed).
pub fn synth_receive_with_made_up_e1(dir: &Path, scenario: &str) -> PathBuf {
    let tables = dir.join("e1");
    std::fs::create_dir(&tables).expect("tables dir");
    made_up_e1_tables(&tables);
    let out = dir.join("out");
    let made = skyforge_with_env(
        &[
            "synth",
            scenario,
            "--receive",
            "--out",
            out.to_str().unwrap(),
        ],
        dir,
        &[
            ("SKYFORGE_GALILEO_E1_CODES", Some(tables.to_str().unwrap())),
            ("SKYFORGE_GALILEO_E1_CODES_CHECK", Some("off")),
        ],
    );
    let log = text(&made);
    println!("{log}");
    assert!(made.status.success(), "{log}");
    out
}

/// What tells `receive` how to read a raw recording of 4 Msps ci8 GPS L1 C/A samples (the
/// options after its file name).
pub const RAW_CI8_4MSPS_GPS: [&str; 6] = ["--format", "ci8", "--fs", "4e6", "--signal", "gps-l1ca"];

/// The address-space limit (`ulimit -v`) issue #11's reproductions must hold under.
pub const MEMORY_LIMIT_BYTES: u64 = 4 << 30;

/// Run `skyforge args` in `cwd` under `ulimit -v` of `limit` bytes.
pub fn skyforge_limited(args: &[&str], cwd: &Path, limit: u64) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {}; exec \"$0\" \"$@\"", limit / 1024))
        .arg(env!("CARGO_BIN_EXE_skyforge"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run skyforge under sh")
}

/// Run `skyforge args` in `cwd`, which must succeed; returns its standard output.
pub fn skyforge_ok(args: &[&str], cwd: &Path) -> String {
    let o = skyforge(args, cwd);
    assert!(
        o.status.success(),
        "skyforge {args:?} failed:\n{}",
        text(&o)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// `skyforge receive` in `cwd` of every recording (`*.sigmf-meta`, in name order) in
/// `sim`, with the navigation file and receiver configuration `synth` wrote beside them,
/// into `rx`, `extra` appended; it must succeed. Returns its standard output.
pub fn receive_all_recordings(sim: &Path, rx: &Path, extra: &[&str], cwd: &Path) -> String {
    receive_all_recordings_with(sim, &sim.join("receiver.toml"), rx, extra, cwd)
}

/// [`receive_all_recordings`] with the receiver configuration `config`.
pub fn receive_all_recordings_with(
    sim: &Path,
    config: &Path,
    rx: &Path,
    extra: &[&str],
    cwd: &Path,
) -> String {
    let mut meta: Vec<String> = std::fs::read_dir(sim)
        .expect("read the recordings' directory")
        .map(|e| e.expect("dir entry").path().to_string_lossy().into_owned())
        .filter(|p| p.ends_with(".sigmf-meta"))
        .collect();
    meta.sort();
    let nav = sim.join("nav.rnx");
    let mut args: Vec<&str> = vec!["receive"];
    args.extend(meta.iter().map(String::as_str));
    args.extend([
        "--assist",
        nav.to_str().unwrap(),
        "--config",
        config.to_str().unwrap(),
        "--out",
        rx.to_str().unwrap(),
    ]);
    args.extend(extra);
    skyforge_ok(&args, cwd)
}

/// Standard output followed by standard error.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Bundled scenario `name` shortened to `duration_s`, written to `dir/short.toml`.
pub fn short_scenario(dir: &Path, name: &str, duration_s: u32) -> PathBuf {
    let o = skyforge(&["scenarios", "show", name], dir);
    assert!(o.status.success(), "{}", text(&o));
    let toml = String::from_utf8(o.stdout).expect("UTF-8 scenario");
    let line = toml
        .lines()
        .find(|l| l.trim_start().starts_with("duration_s"))
        .expect("duration_s in the bundled scenario");
    let short = toml.replacen(line, &format!("duration_s = {duration_s}"), 1);
    let path = dir.join("short.toml");
    std::fs::write(&path, short).expect("write scenario");
    path
}

/// The JSON file at `path`, parsed.
pub fn json_file(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `skyforge validate monitor --truth sim --monitor mon --json score.json` in `dir`, which
/// must succeed: what it printed and the score.
pub fn validate_monitor(dir: &Path) -> (String, serde_json::Value) {
    validate_monitor_of(dir, "mon", "score.json")
}

/// [`validate_monitor`] of the monitor output `mon`, the score written to `json`.
pub fn validate_monitor_of(dir: &Path, mon: &str, json: &str) -> (String, serde_json::Value) {
    let printed = skyforge_ok(
        &[
            "validate",
            "monitor",
            "--truth",
            "sim",
            "--monitor",
            mon,
            "--json",
            json,
        ],
        dir,
    );
    (printed, json_file(&dir.join(json)))
}

/// The `results.json` `skyforge validate thesis --out <out>` wrote.
pub fn results_file(out: &Path) -> serde_json::Value {
    let json = std::fs::read_to_string(out.join("results.json")).expect("results.json");
    serde_json::from_str(&json).expect("results.json: JSON")
}

/// The rows `skyforge validate thesis --out <out>` wrote to `out/results.json`.
pub fn results_json(out: &Path) -> Vec<serde_json::Value> {
    results_file(out)["rows"]
        .as_array()
        .expect("results.json: rows")
        .clone()
}

/// Fail loudly when RTKLIB's `rnx2rtkp` is not installed.
pub fn require_rnx2rtkp() {
    assert!(
        Command::new("rnx2rtkp").output().is_ok(),
        "\n*** rnx2rtkp is not installed: apt-get install rtklib (scripts/test.sh does) ***\n"
    );
}

/// Run RTKLIB's `rnx2rtkp` with `args` in `cwd`; it must succeed.
pub fn rnx2rtkp<S: AsRef<std::ffi::OsStr>>(args: &[S], cwd: &Path) {
    let o = Command::new("rnx2rtkp")
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("rnx2rtkp runs");
    assert!(o.status.success(), "rnx2rtkp failed: {}", text(&o));
}

/// The first `n` fields of each line of an `rnx2rtkp` solution file (header lines start
/// with `%`) whose first `n` fields are all numbers; other lines are passed over.
pub fn rtklib_numeric_rows(pos: &str, n: usize) -> Vec<Vec<f64>> {
    pos.lines()
        .filter(|l| !l.starts_with('%'))
        .filter_map(|l| {
            let f: Vec<f64> = l
                .split_whitespace()
                .take(n)
                .filter_map(|x| x.parse().ok())
                .collect();
            (f.len() == n).then_some(f)
        })
        .collect()
}

/// The ECEF positions (m) of an `rnx2rtkp` solution file written with
/// `out-solformat=xyz` and the default time format: header lines start with `%`, then one
/// line per epoch of GPS week, seconds of week, x, y, z, ...
pub fn rtklib_xyz_solutions(pos: &str) -> Vec<Vec3> {
    pos.lines()
        .filter(|l| !l.starts_with('%'))
        .filter_map(|l| {
            let f: Vec<f64> = l
                .split_whitespace()
                .skip(2)
                .take(3)
                .filter_map(|x| x.parse().ok())
                .collect();
            (f.len() == 3).then(|| Vec3::new(f[0], f[1], f[2]))
        })
        .collect()
}

/// Position and clock bias per row of the receiver's pvt.csv: (tow_s, r, bias_m).
pub fn fixes(rx: &Path) -> Vec<(f64, Vec3, f64)> {
    let text = std::fs::read_to_string(rx.join("pvt.csv")).expect("pvt.csv");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
    let (t, x, y, z, b) = (
        col("tow_s"),
        col("x_m"),
        col("y_m"),
        col("z_m"),
        col("clock_bias_m"),
    );
    lines
        .map(|l| {
            let f: Vec<f64> = l
                .split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect();
            (f[t], Vec3::new(f[x], f[y], f[z]), f[b])
        })
        .collect()
}

/// The site the truth RINEX header gives (the scenario's antenna position).
pub fn truth_site(sim: &Path) -> Vec3 {
    header_position(&sim.join("ant1.obs.rnx"))
}

/// The `APPROX POSITION XYZ` (three F14.4 fields) of the RINEX observation file `path`.
pub fn header_position(path: &Path) -> Vec3 {
    let text = std::fs::read_to_string(path).expect("RINEX observation file");
    let line = text
        .lines()
        .find(|l| l.contains("APPROX POSITION XYZ"))
        .expect("APPROX POSITION XYZ");
    let v: Vec<f64> = (0..3)
        .map(|k| line[14 * k..14 * k + 14].trim().parse().expect("number"))
        .collect();
    Vec3::new(v[0], v[1], v[2])
}

pub fn rms(v: &[f64]) -> f64 {
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

/// Pseudorange and carrier-phase error stds against the truth RINEX (m) and the epochs
/// matched, after printing the comparison table.
pub fn observable_errors(sim: &Path, rx: &Path) -> (f64, f64, usize) {
    let truth = read_obs_file(&sim.join("ant1.obs.rnx")).expect("truth RINEX reads");
    let estimate = read_obs_file(&rx.join("ant1.obs.rnx")).expect("receiver RINEX reads");
    let c = compare(&estimate, &truth).expect("comparison");
    let mut table = Vec::new();
    skyforge_validate::observables::table::print_comparison(&c, &mut table).expect("table");
    println!("{}", String::from_utf8_lossy(&table));
    (
        c.pseudorange_m.overall.std.expect("pseudorange std"),
        c.carrier_phase_m.overall.std.expect("phase std"),
        c.matched_epochs,
    )
}

/// The bars of the bundled receiver's acceptance on the static ground scenarios: 45 fixes
/// or more within 5 m 3D RMS (`fixes` of them, `rms_m`) and, against the truth, 70 epochs
/// matched or more, pseudorange error std below 0.5 m and carrier-phase error std below
/// 2 mm (as [`observable_errors`] returns them).
pub fn assert_static_ground_bars(
    fixes: usize,
    rms_m: f64,
    (pr_std, phase_std, matched): (f64, f64, usize),
) {
    assert!(fixes >= 45, "{fixes} fixes");
    assert!(rms_m < 5.0, "3D RMS {rms_m} m");
    assert!(matched >= 70, "{matched} epochs matched");
    assert!(pr_std < 0.5, "pseudorange error std {pr_std} m");
    assert!(phase_std < 2e-3, "carrier-phase error std {phase_std} m");
}

/// One epoch of an `rnx2rtkp` solution file written with `out-solformat=enu` and
/// `out-timeform=hms`: the GPST time as written (`yyyy/mm/dd hh:mm:ss.sss`), the
/// east/north/up baseline from the base (m) and the quality flag `Q` (1 fixed, 2 float,
/// 4 DGPS, 5 single).
#[derive(Debug, Clone, PartialEq)]
pub struct RtklibEnu {
    pub time: String,
    pub enu_m: [f64; 3],
    pub q: u8,
}

/// The epochs of an `rnx2rtkp` ENU solution file (header lines start with `%`).
pub fn rtklib_enu_solutions(pos: &str) -> Vec<RtklibEnu> {
    pos.lines()
        .filter(|l| !l.starts_with('%'))
        .filter_map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            let number = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok());
            Some(RtklibEnu {
                time: format!("{} {}", f.first()?, f.get(1)?),
                enu_m: [number(2)?, number(3)?, number(4)?],
                q: f.get(5)?.parse().ok()?,
            })
        })
        .collect()
}

/// Names in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| {
            e.expect("dir entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    names
}

/// Whether the tests run as root (mounting a tmpfs needs it; CI runs as root).
pub fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}

/// A small tmpfs mounted at `.0` for the life of the value (a disk that fills up).
pub struct Tmpfs(pub PathBuf);

impl Tmpfs {
    /// Mount it; a test that needs one fails (not passes) where the suite does not run as
    /// root (CI and `scripts/test.sh` in a container do).
    pub fn mount(dir: &Path, size: &str) -> Self {
        assert!(
            is_root(),
            "\n*** this test mounts a small tmpfs (a disk that fills up) and needs root: run it as root ***\n"
        );
        std::fs::create_dir(dir).expect("create mount point");
        let o = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(dir)
            .output()
            .expect("run mount");
        assert!(
            o.status.success(),
            "\n*** running as root but cannot mount a tmpfs for the full-disk test: {} ***\n",
            text(&o)
        );
        Self(dir.to_path_buf())
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let unmounted = Command::new("umount")
            .arg(&self.0)
            .status()
            .is_ok_and(|s| s.success());
        if !unmounted {
            let _ = Command::new("umount").arg("-l").arg(&self.0).status();
        }
    }
}

/// Output directories as a careless user or an attacker names them: a space, both quotes,
/// `$(...)`, backquotes, `#` and `%`.
pub const HOSTILE_DIRS: [&str; 4] = [
    "out dir",
    "it's \"q\" #z",
    "$(touch PWNED) `touch PWNED2`",
    "50% %a",
];

/// A small study of the T-5.4-3 set-up: 60 s runs, two signal levels, `seeds` seeds.
pub fn small_study(dir: &Path, seeds: u32) -> String {
    let scenario = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/thesis/t-5.4-3.toml");
    std::fs::copy(scenario, dir.join("t-5.4-3.toml")).unwrap();
    let study = format!(
        "name = \"small\"\nscenario = \"t-5.4-3.toml\"\nseed = 11\nseeds = {seeds}\n\
         metrics = [\"fix_rate\", \"yaw_rms_deg\", \"baseline_rms_m\", \"pseudorange_rms_m\", \
         \"phase_rms_m\"]\n\
         \n[[parameters]]\nkey = \"time.duration_s\"\nvalues = [60.0]\n\
         \n[[parameters]]\nkey = \"signal.cn0_dbhz\"\nvalues = [40.0, 45.0]\n"
    );
    std::fs::write(dir.join("small.toml"), &study).unwrap();
    study
}

/// `[[stations]]` tables of stations A-D at the positions in the `APPROX POSITION XYZ`
/// headers of `dir/{A,B,C,D}.obs.rnx` (surveyed positions, for a monitor configuration).
pub fn surveyed_stations(dir: &Path) -> String {
    let mut stations = String::new();
    for s in ["A", "B", "C", "D"] {
        let r = header_position(&dir.join(format!("{s}.obs.rnx")));
        stations += &format!(
            "[[stations]]\nname = \"{s}\"\nposition_ecef_m = [{:?}, {:?}, {:?}]\n",
            r.x, r.y, r.z
        );
    }
    stations
}

/// Monitor configuration text `config` with `stations` (`[[stations]]` tables) in place
/// of its empty station list, before its `[thresholds]` table.
pub fn with_stations(config: &str, stations: &str) -> String {
    let config = config.replace("stations = []\n", "");
    let at = config.find("[thresholds]").expect("a [thresholds] table");
    format!("{}{stations}\n{}", &config[..at], &config[at..])
}

/// Every dataset of an HDF5 file as (path, raw little-endian bytes), sorted by path.
pub fn h5_contents(path: &Path) -> Vec<(String, Vec<u8>)> {
    use hdf5::types::{FloatSize, IntSize, TypeDescriptor, VarLenUnicode};
    /// The dataset's values as `T`, each turned into bytes.
    fn bytes<T: hdf5::H5Type, B: AsRef<[u8]>>(ds: &hdf5::Dataset, of: fn(&T) -> B) -> Vec<u8> {
        let values = ds.read_raw::<T>().unwrap();
        values
            .iter()
            .flat_map(|x| of(x).as_ref().to_vec())
            .collect()
    }
    fn walk(g: &hdf5::Group, prefix: &str, out: &mut Vec<(String, Vec<u8>)>) {
        for name in g.member_names().unwrap() {
            let full = format!("{prefix}/{name}");
            if let Ok(sub) = g.group(&name) {
                walk(&sub, &full, out);
                continue;
            }
            let ds = g.dataset(&name).unwrap();
            let data: Vec<u8> = match ds.dtype().unwrap().to_descriptor().unwrap() {
                TypeDescriptor::Float(FloatSize::U8) => bytes(&ds, |x: &f64| x.to_le_bytes()),
                TypeDescriptor::Float(FloatSize::U4) => bytes(&ds, |x: &f32| x.to_le_bytes()),
                TypeDescriptor::Unsigned(IntSize::U1) => ds.read_raw::<u8>().unwrap(),
                TypeDescriptor::Unsigned(IntSize::U2) => bytes(&ds, |x: &u16| x.to_le_bytes()),
                TypeDescriptor::Unsigned(IntSize::U4) => bytes(&ds, |x: &u32| x.to_le_bytes()),
                TypeDescriptor::VarLenUnicode => {
                    bytes(&ds, |x: &VarLenUnicode| x.as_bytes().to_vec())
                }
                other => panic!("{full}: compare type {other:?} too"),
            };
            out.push((full, data));
        }
    }
    let file = hdf5::File::open(path).unwrap();
    let mut out = Vec::new();
    walk(&file, "", &mut out);
    out.sort();
    out
}

/// `skyforge run` of the observation-level scenario `path` into `dir/out`, then `validate
/// obs` of its observables against its truth: the `system` row's (count, pseudorange std,
/// carrier-phase std in m).
pub fn observation_level_noise(dir: &Path, path: &str, system: &str) -> (f64, f64, f64) {
    let out = dir.join("out");
    skyforge_ok(&["run", path, "--out", out.to_str().unwrap()], dir);
    let json = dir.join("obs.json");
    skyforge_ok(
        &[
            "validate",
            "obs",
            "--truth",
            out.join("ant1.obs.rnx").to_str().unwrap(),
            "--estimate",
            out.join("observations/ant1.obs.rnx").to_str().unwrap(),
            "--json",
            json.to_str().unwrap(),
        ],
        dir,
    );
    let v = json_file(&json);
    let row = |what: &str| {
        v[what]["per_system"]
            .as_array()
            .and_then(|a| a.iter().find(|s| s["system"] == system))
            .cloned()
            .unwrap_or_else(|| panic!("no {system} row in {what}"))
    };
    let (code, phase) = (row("pseudorange_m"), row("carrier_phase_m"));
    (
        code["count"].as_f64().unwrap_or(0.0),
        code["std"].as_f64().unwrap_or(f64::NAN),
        phase["std"].as_f64().unwrap_or(f64::NAN),
    )
}

/// The observation level of the scenario `scenario(extra)` writes (120 s, one antenna, a
/// transmitted signal tagged `tag` of `system` that the calibrated noise model has no
/// factors for): refused under the calibrated model, naming `tag`; with a constant 0.3 m
/// code and 3 mm phase noise, `system`'s observables scatter about the truth by those
/// within 15 % (over 7 standard errors of 1/sqrt(2 n) for n > 400).
pub fn assert_constant_observation_noise(
    dir: &Path,
    scenario: impl Fn(&str) -> String,
    system: &str,
    tag: &str,
) {
    let level = "\n[observation]\nlevel = \"observation\"\n";
    let out = dir.join("out");
    let o = skyforge(
        &["run", &scenario(level), "--out", out.to_str().unwrap()],
        dir,
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("no calibration for {tag}")), "{err}");
    // assumed: 0.3 m code and 3 mm phase, the thesis table 1.2-2 kind of constant setting.
    let constant = format!(
        "{level}\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.003\ncode_m = 0.3\n"
    );
    let (n, std_code, std_phase) = observation_level_noise(dir, &scenario(&constant), system);
    assert!(n > 400.0, "{n} {system} pseudoranges");
    assert!((std_code / 0.3 - 1.0).abs() < 0.15, "code std {std_code}");
    assert!(
        (std_phase / 0.003 - 1.0).abs() < 0.15,
        "phase std {std_phase}"
    );
}

/// `text` written to `dir/name`; its path as the CLI takes it.
/// The bundled scenario `name` (`scenarios/bundled/NAME.toml`) with each `(from, to)` of
/// `edits` applied once, in order; panics when a `from` is not in the text (an edit that
/// silently changed nothing would test another scenario than the one described).
pub fn bundled_edited(name: &str, edits: &[(&str, &str)]) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios/bundled")
        .join(format!("{name}.toml"));
    let mut text = std::fs::read_to_string(&path).expect("bundled scenario");
    for (from, to) in edits {
        assert!(text.contains(from), "{name}: no {from:?} to replace");
        text = text.replacen(from, to, 1);
    }
    text
}

pub fn write_scenario(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write scenario");
    path.to_string_lossy().into_owned()
}

/// A `[[vehicles]]` entry: a LEO `name` on the book's 500 km, e = 0.01 orbit (book 5.6) at
/// mean anomaly `anomaly_deg`, one antenna `ant1` at the centre of mass (zenith).
pub fn leo_vehicle(name: &str, anomaly_deg: f64) -> String {
    format!(
        r#"
[[vehicles]]
name = "{name}"
[vehicles.platform.leo.elements]
semi_major_axis_km = 6878.137
eccentricity = 0.01
inclination_deg = 98.0
raan_deg = 0.0
arg_perigee_deg = 0.0
mean_anomaly_deg = {anomaly_deg:?}
[[vehicles.antennas]]
name = "ant1"
position_body_m = [0.0, 0.0, 0.0]
"#
    )
}

/// A `[[jammers]]` entry of the interference tests: a noise jammer `name` 111 m north of
/// `interop-gps-static`'s site, 2 m above it, at J/S `js_db` from `start_s` to `stop_s`.
pub fn noise_jammer_toml(name: &str, js_db: f64, (start_s, stop_s): (f64, f64)) -> String {
    format!(
        "\n[[jammers]]\nname = \"{name}\"\nwaveform = \"noise\"\nlatitude_deg = 30.001\n\
         longitude_deg = 114.0\nheight_m = 52.0\njs_db = {js_db}\nstart_s = {start_s}\n\
         stop_s = {stop_s}\n"
    )
}
