//! `skyforge report DIR`: one self-contained HTML page of a run's truth, a validation's
//! results and a study, checked as text here and in a real browser (headless Chromium,
//! Debian's `chromium`) in the interoperability tier.

mod support;

use std::path::Path;
use support::{skyforge, skyforge_ok, small_study, text};

/// A `results.json` of three rows, one per verdict, with text a page must escape.
const RESULTS: &str = r#"[
  {"table": "T-5.4-4", "row": "yaw", "quantity": "std", "unit": "deg", "thesis": 0.05,
   "ours": 0.048, "tolerance": "+-20 %", "verdict": "reproduced", "note": ""},
  {"table": "T-5.4-4", "row": "pitch", "quantity": "std", "unit": "deg", "thesis": 0.1,
   "ours": 0.2, "tolerance": "+-20 %", "verdict": "deviates", "note": "<script>x</script>"},
  {"table": "P2-4.2", "row": "ramp", "quantity": "alarm", "unit": "", "thesis": null,
   "ours": 1.0, "tolerance": "none", "verdict": "explained", "note": "a & b"}
]
"#;

/// A run's directory (`skyforge run`: truth.h5, geometry, observations) with a study's
/// `study.h5`, a `results.json` and the `curves.json` of `validate thesis --only T-3.3-R
/// --only T-3.3-S` added (with `attitude_tables`, also the figures of `--only T-4.3
/// --only T-5.5`: minutes of runs), and `skyforge attitude`'s output for the run: every
/// source the report draws from. Returns the two directory names.
fn outputs(d: &Path, attitude_tables: bool) -> (&'static str, &'static str) {
    skyforge_ok(
        &[
            "validate", "thesis", "--only", "T-3.3-R", "--only", "T-3.3-S", "--out", "val",
        ],
        d,
    );
    if attitude_tables {
        skyforge_ok(
            &[
                "validate", "thesis", "--only", "T-4.3", "--only", "T-5.5", "--out", "val45",
            ],
            d,
        );
        let read = |dir: &str| -> serde_json::Value {
            serde_json::from_str(&std::fs::read_to_string(d.join(dir).join("curves.json")).unwrap())
                .unwrap()
        };
        let (mut all, more) = (read("val"), read("val45"));
        let extra = more["curves"].as_array().unwrap().clone();
        assert_eq!(extra.len(), ATTITUDE_FIGURES);
        all["curves"].as_array_mut().unwrap().extend(extra);
        std::fs::write(d.join("val/curves.json"), all.to_string()).unwrap();
    }
    small_study(d, 2);
    skyforge_ok(&["study", "run", "small.toml", "--out", "study"], d);
    let scenario = std::fs::read_to_string(d.join("t-5.4-3.toml")).unwrap();
    // assumed: 60 s of the T-5.4-3 set-up, enough for curves, quick in the suite.
    let short = scenario.replacen("duration_s = 600.0", "duration_s = 60.0", 1);
    assert_ne!(short, scenario);
    std::fs::write(d.join("short.toml"), short).unwrap();
    skyforge_ok(&["run", "short.toml", "--out", "run"], d);
    std::fs::copy(d.join("study/study.h5"), d.join("run/study.h5")).unwrap();
    std::fs::write(d.join("run/results.json"), RESULTS).unwrap();
    std::fs::copy(d.join("val/curves.json"), d.join("run/curves.json")).unwrap();
    let mut args = vec!["attitude".to_string()];
    for a in ["ant1", "ant2", "ant3"] {
        args.push(format!("run/observations/{a}.obs.rnx"));
    }
    args.extend(
        [
            "--nav",
            "run/nav.rnx",
            "--geometry",
            "run/geometry.toml",
            "--out",
            "att",
        ]
        .map(String::from),
    );
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    skyforge_ok(&args, d);
    ("run", "att")
}

/// Figures of the page of [`outputs`]: GPS in view, the three Doppler figures and the 20
/// loop-error figures, the validation's ratios, the thesis figures 3.3-7, 3.3-8 (a)..(d),
/// 3.3-9 and the phase and Doppler halves of 3.3-10 and 3.3-11, five study metrics, two
/// baselines and the attitude.
const FIGURES: usize = 4 + 20 + 1 + 10 + 5 + 3;

/// Thesis figures of T-4.3 (4.3-2, 4.3-3, 4.3-6..4.3-10) and T-5.5 (5.5-2 and 5.5-3 per
/// baseline, 5.5-4 and 5.5-5 angles and rates).
const ATTITUDE_FIGURES: usize = 7 + 8;

#[test]
fn the_page_holds_every_source_inline_and_escapes_what_it_quotes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (dir, att) = outputs(d, false);
    let printed = skyforge_ok(&["report", dir, "--attitude", att], d);
    assert!(
        printed.contains(&format!("5 sections, {FIGURES} figures")),
        "{printed}"
    );
    let html = std::fs::read_to_string(d.join("run/report.html")).unwrap();
    assert_eq!(html.matches("<figure><svg").count(), FIGURES);
    for needle in [
        "Truth: scenario",
        "GPS satellites in view",
        "figure 1.2-1, 3 to 16, mean 9",
        "thesis figure 3.2-3",
        "Study small",
        "fix_rate against signal.cn0_dbhz",
        "3 rows: 1 reproduced, 1 explained, 1 deviate.",
        "SkyForge against the thesis, row by row",
        "<td class=\"deviates\">deviates</td>",
        "&lt;script&gt;x&lt;/script&gt;",
        "a &amp; b",
        "Baseline 2 (ant3 - ant1) error",
        "Thesis table 5.4-5 (real-time KF): std 0.041 / 0.074 / 0.081 deg",
        "fixed integers wrong",
    ] {
        assert!(html.contains(needle), "{needle}");
    }
    for n in 4..=23 {
        assert!(html.contains(&format!("Thesis figure 3.2-{n}:")), "3.2-{n}");
    }
    // Thesis figures 3.3-7..3.3-11 with the thesis's printed numbers beside SkyForge's.
    for caption in [
        "Thesis figure 3.3-7: E[fd_hat Tc] against delta",
        "Thesis figure 3.3-8 (a): R_f against delta, L = 64",
        "Thesis figure 3.3-8 (d): R_f against delta, L = 512",
        "Thesis figure 3.3-9: NMSE of fd_hat Tc against fd Tc",
        "Thesis figure 3.3-10 (a), (c): phase error against time, same Q and R",
        "Thesis figure 3.3-10 (b), (d): Doppler error against time, same Q and R",
        "Thesis figure 3.3-11 (a), (c): phase error against time, different Q",
        "Thesis figure 3.3-11 (b), (d): Doppler error against time, different Q",
    ] {
        assert!(html.contains(caption), "{caption}");
    }
    for printed in [
        "thesis 1.0902.",
        "thesis 1.4444.",
        "thesis 1e-9.",
        "thesis 233.1055 Hz.",
        "thesis -2.936 Hz.",
        "thesis 0.0254 rad.",
        "thesis 1.9401 Hz.",
    ] {
        assert!(html.contains(printed), "{printed}");
    }
    // Self-contained: nothing fetched from anywhere.
    for outside in [" src=", " href=", "url(", "@import"] {
        assert!(!html.contains(outside), "{outside}");
    }
    // In a directory skyforge wrote, the page joins the manifest, so `run --force` can
    // still replace the directory.
    std::fs::remove_file(d.join("run/results.json")).unwrap();
    std::fs::remove_file(d.join("run/curves.json")).unwrap();
    std::fs::remove_file(d.join("run/study.h5")).unwrap();
    let manifest = std::fs::read_to_string(d.join("run/.skyforge-manifest")).unwrap();
    assert!(manifest.lines().any(|l| l == "report.html"), "{manifest}");
    skyforge_ok(&["run", "short.toml", "--out", "run", "--force"], d);
}

#[test]
fn bad_directories_and_pages_it_did_not_write_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::create_dir(d.join("empty")).unwrap();
    let o = skyforge(&["report", "empty"], d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("nothing to report"), "{}", text(&o));
    assert!(!d.join("empty/report.html").exists());

    let o = skyforge(&["report", "missing"], d);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("not a directory"), "{}", text(&o));

    // A broken results.json: the file, line and column.
    std::fs::create_dir(d.join("bad")).unwrap();
    std::fs::write(d.join("bad/results.json"), "[\n  {\"table\": 1}\n]\n").unwrap();
    let o = skyforge(&["report", "bad"], d);
    assert_eq!(o.status.code(), Some(2));
    let t = text(&o);
    assert!(t.contains("results.json") && t.contains("line 2"), "{t}");
    assert!(!d.join("bad/report.html").exists());

    // So is a broken curves.json.
    std::fs::create_dir(d.join("bad-curves")).unwrap();
    std::fs::write(
        d.join("bad-curves/curves.json"),
        "{\"curves\": [\n  {}\n]}\n",
    )
    .unwrap();
    let o = skyforge(&["report", "bad-curves"], d);
    assert_eq!(o.status.code(), Some(2));
    let t = text(&o);
    assert!(t.contains("curves.json") && t.contains("line 2"), "{t}");
    assert!(!d.join("bad-curves/report.html").exists());

    // A user's page of the same name stays, --force or not; ours is replaced with --force.
    std::fs::write(d.join("bad/results.json"), RESULTS).unwrap();
    std::fs::write(d.join("bad/report.html"), "my notes").unwrap();
    for args in [&["report", "bad"][..], &["report", "bad", "--force"]] {
        let o = skyforge(args, d);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains("exists"), "{}", text(&o));
    }
    assert_eq!(
        std::fs::read_to_string(d.join("bad/report.html")).unwrap(),
        "my notes"
    );
    std::fs::remove_file(d.join("bad/report.html")).unwrap();
    skyforge_ok(&["report", "bad"], d);
    let o = skyforge(&["report", "bad"], d);
    assert!(text(&o).contains("give --force"), "{}", text(&o));
    skyforge_ok(&["report", "bad", "--force"], d);
    // Written through a file of its own, renamed: nothing is left beside the page.
    let names: Vec<String> = std::fs::read_dir(d.join("bad"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.contains("partial")), "{names:?}");
}

/// `chromium --headless` with `args` on `page`: (stdout, stderr).
fn chromium(page: &Path, args: &[&str]) -> (String, String) {
    let o = std::process::Command::new("chromium")
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            // Containers often have a small /dev/shm.
            "--disable-dev-shm-usage",
            "--no-first-run",
        ])
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium (Debian package chromium; scripts/test.sh installs it)");
    assert!(o.status.success(), "{}", text(&o));
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
#[ignore = "interoperability tier: needs Debian's chromium"]
fn chromium_renders_every_figure_without_a_console_error() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let (dir, att) = outputs(d, true);
    skyforge_ok(&["report", dir, "--attitude", att], d);
    let page = d.join("run/report.html");
    let html = std::fs::read_to_string(&page).unwrap();
    for caption in [
        "Thesis figure 4.3-2: xi_t error, 22-state UKF, seed 1, every",
        "Thesis figure 4.3-3: rate error, 22-state UKF, seed 1",
        "Thesis figure 4.3-6: estimated Delta&#39;, 22-state UKF, seed 1",
        "Thesis figure 4.3-7: attitude error, 6-state UKF, B0 uncorrected, seed 1",
        "Thesis figure 4.3-10: rate error, 6-state UKF, B0&#39; corrected, seed 1",
        "Thesis figure 5.5-2 baseline 1: ECEF error, LS, seed 1, all 600 fixed epochs",
        "Thesis figure 5.5-3 baseline 2: ECEF error, proposed (reverse UKF), seed 1",
        "Thesis figure 5.5-4 angles: attitude error, KF on LS baselines, seed 1",
        "Thesis figure 5.5-5 rates: rate error, KF on reverse-UKF baselines, seed 1",
    ] {
        assert!(html.contains(caption), "{caption}");
    }
    // Thesis tables 4.3-2 and 5.5-4 beside SkyForge's.
    for printed in ["thesis 0.0614 deg.", "thesis 0.3286 deg."] {
        assert!(html.contains(printed), "{printed}");
    }
    let figures = FIGURES + ATTITUDE_FIGURES;

    // The page's own script counts the figures the browser laid out with a drawing.
    let (dom, _) = chromium(&page, &["--dump-dom"]);
    assert!(
        dom.contains(&format!(
            "data-figures=\"{figures}\" data-figures-rendered=\"{figures}\""
        )),
        "{}",
        dom.lines()
            .find(|l| l.contains("<body"))
            .unwrap_or("no <body>")
    );

    // Console: the script's own message shows the log is captured; nothing else is said
    // at warning level or above from the page.
    let shot = d.join("report.png");
    let (_, log) = chromium(
        &page,
        &[
            "--enable-logging=stderr",
            "--v=0",
            "--window-size=1000,6000",
            &format!("--screenshot={}", shot.display()),
        ],
    );
    let console: Vec<&str> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
    assert!(
        console
            .iter()
            .any(|l| l.contains(&format!("skyforge-report: {figures} of {figures} figures"))),
        "{log}"
    );
    let bad: Vec<&&str> = console
        .iter()
        .filter(|l| !l.contains("skyforge-report:"))
        .collect();
    assert!(bad.is_empty(), "console: {bad:?}");
    // A PNG of the whole page.
    let png = std::fs::read(&shot).unwrap();
    assert!(
        png.starts_with(b"\x89PNG") && png.len() > 50_000,
        "{} bytes",
        png.len()
    );
}
