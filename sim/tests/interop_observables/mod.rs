//! GNSS-SDR's RINEX observations against SkyForge's observation truth of the same
//! recording (`skyforge_validate::observables::compare`): the measured pseudorange and
//! carrier-phase noise of a third-party receiver on SkyForge's signals, at GNSS-SDR's loop
//! bandwidths (read from the generated .conf), checked against the thermal-noise formulas.

pub mod side_by_side;

use skyforge_gnss::observation::dll_thermal_chips;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_receiver::tracking::error_budget::thermal_jitter_deg;
use skyforge_validate::observables::compare::{CompareOptions, ObsComparison, compare_with};
use skyforge_validate::observables::table::cell;
use skyforge_validate::observables::{ObsFile, read_obs_file};
use std::path::{Path, PathBuf};

/// GNSS-SDR's tracking settings (the .conf's `Tracking_*` keys).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loops {
    pub pll_bw_hz: f64,
    pub dll_bw_hz: f64,
    /// Early-prompt (= prompt-late) spacing, chips.
    pub early_late_space_chips: f64,
}

/// GNSS-SDR's coherent integration: 1 ms (the .conf leaves `extend_correlation_symbols` at
/// its default of 1).
const T_COH_S: f64 = 1e-3;

/// GNSS-SDR's early-prompt spacing when the .conf leaves it out (its `Dll_Pll_Conf`
/// default, 0.5 chip, as in the GPS .conf SkyForge writes).
const DEFAULT_EARLY_LATE_SPACE_CHIPS: f64 = 0.5;

/// The tracking settings of a GNSS-SDR .conf text.
pub fn loops(conf: &str) -> Loops {
    let value = |key: &str| {
        conf.lines()
            .filter(|l| l.starts_with("Tracking_"))
            .find_map(|l| {
                l.split_once(&format!(".{key}="))?
                    .1
                    .trim()
                    .parse::<f64>()
                    .ok()
            })
    };
    let required = |key: &str| {
        value(key).unwrap_or_else(|| panic!("no Tracking_*.{key} in the .conf:\n{conf}"))
    };
    Loops {
        pll_bw_hz: required("pll_bw_hz"),
        dll_bw_hz: required("dll_bw_hz"),
        early_late_space_chips: value("early_late_space_chips")
            .unwrap_or(DEFAULT_EARLY_LATE_SPACE_CHIPS),
    }
}

/// Code-tracking thermal noise (m, 1 sigma) of GNSS-SDR's DLL: the non-coherent
/// early-minus-late power formula with `D` twice GNSS-SDR's early-prompt spacing. At 4 Msps B1I (2.046 Mchip/s) is in
/// the band-limited regime, where the jitter is lower than this.
pub fn dll_sigma_m(loops: &Loops, cn0_dbhz: f64, chip_rate_hz: f64) -> f64 {
    let d = 2.0 * loops.early_late_space_chips;
    dll_thermal_chips(loops.dll_bw_hz, d, cn0_dbhz, T_COH_S) * C_MPS / chip_rate_hz
}

/// Carrier-phase thermal noise (m, 1 sigma) of the PLL (thesis eq. 3.2-3).
pub fn pll_sigma_m(loops: &Loops, cn0_dbhz: f64, carrier_hz: f64) -> f64 {
    thermal_jitter_deg(loops.pll_bw_hz, cn0_dbhz, T_COH_S).to_radians() / std::f64::consts::TAU
        * C_MPS
        / carrier_hz
}

/// GNSS-SDR's RINEX observation file in `dir` (`GSDR*.yyO`), if it wrote one (it does
/// from its first fix on).
pub fn find_gnss_sdr_obs_file(dir: &Path) -> Option<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            name.starts_with("GSDR") && name.ends_with('O')
        })
}

/// [`find_gnss_sdr_obs_file`], which must have found one.
fn gnss_sdr_obs_file(dir: &Path) -> PathBuf {
    find_gnss_sdr_obs_file(dir).unwrap_or_else(|| {
        panic!(
            "no GNSS-SDR RINEX observation file (GSDR*O) in {}",
            dir.display()
        )
    })
}

/// Compare GNSS-SDR's observations in `out` (antenna 1, `band`) with the truth, print the
/// result (a JSON line `GNSS_SDR_OBSERVABLES {...}` and a markdown table), and assert what
/// must hold: every satellite GNSS-SDR reports is matched with the truth, with pseudorange
/// and carrier phase; the code and phase error stds stay below twice the thermal-noise
/// formulas at the scenario's C/N0 and GNSS-SDR's loop settings. Time-scale labels are
/// handled as in [`compare_gnss_sdr`].
pub fn check(out: &Path, band: &str, signal: Signal, chip_rate_hz: f64, cn0_dbhz: f64) {
    let conf = std::fs::read_to_string(out.join(format!("ant1.{band}.gnss-sdr.conf"))).unwrap();
    let loops = loops(&conf);
    let (estimate, c, tag_offset_s) = compare_gnss_sdr(out, band);
    let sigma_code = dll_sigma_m(&loops, cn0_dbhz, chip_rate_hz);
    let sigma_phase = pll_sigma_m(&loops, cn0_dbhz, signal.carrier_hz());
    report(band, &loops, &c, tag_offset_s, sigma_code, sigma_phase);

    assert!(
        c.satellites_without_truth.is_empty(),
        "{band}: GNSS-SDR satellites without truth: {:?}",
        c.satellites_without_truth
    );
    // Every epoch GNSS-SDR reports a satellite in is matched with the truth, but for the
    // estimate epochs outside the truth (its first, tagged before the truth starts). How
    // many epochs a satellite has is GNSS-SDR's affair: one CI run decoded C10 only two
    // epochs before the end (other runs: 32).
    let unmatched_epochs = c.estimate_epochs - c.matched_epochs;
    let mut reported: std::collections::BTreeMap<String, (usize, usize)> = Default::default();
    for e in &estimate.epochs {
        for s in &e.sats {
            let n = reported.entry(s.sat.to_string()).or_default();
            n.0 += usize::from(s.pseudorange_m.is_some());
            n.1 += usize::from(s.carrier_phase_cycles.is_some());
        }
    }
    let matched = |e: &skyforge_validate::observables::compare::ObservableErrors, sat: &str| {
        e.per_satellite
            .iter()
            .find(|s| s.sat.to_string() == sat)
            .map_or(0, |s| s.stats.count)
    };
    for (sat, (code, phase)) in &reported {
        for (what, n, m) in [
            ("pseudorange", *code, matched(&c.pseudorange_m, sat)),
            ("carrier phase", *phase, matched(&c.carrier_phase_m, sat)),
        ] {
            assert!(
                n > 0 && m + unmatched_epochs >= n,
                "{band}: {sat}: {n} epochs with a {what} from GNSS-SDR, {m} matched with the truth"
            );
        }
    }
    let code = c.pseudorange_m.overall.std.unwrap();
    let phase = c.carrier_phase_m.overall.std.unwrap();
    assert!(
        code < 2.0 * sigma_code,
        "{band}: code error std {code} m, DLL thermal noise {sigma_code} m"
    );
    assert!(
        phase < 2.0 * sigma_phase,
        "{band}: phase error std {phase} m, PLL thermal noise {sigma_phase} m"
    );
}

/// GNSS-SDR's observations in `out` against the truth there: (its observation file, the
/// comparison, the tag offset applied). A time-tag error the pseudoranges measure in whole
/// seconds is a time-scale label (GNSS-SDR 0.0.17 tags its BeiDou-only RINEX epochs in GPS
/// time under a `BDT` header, 14 s off): the tags are shifted back by it.
pub fn compare_gnss_sdr(out: &Path, band: &str) -> (ObsFile, ObsComparison, f64) {
    let estimate = read_obs_file(&gnss_sdr_obs_file(out)).unwrap();
    let truth = read_obs_file(&out.join("ant1.obs.rnx")).unwrap();
    let mut opts = CompareOptions::default();
    let mut c = compare_with(&estimate, &truth, &opts).unwrap();
    if let Some(tag) = c.tag_error
        && tag.delta_s.abs() > 0.5
        && (tag.delta_s - tag.delta_s.round()).abs() < 5.0 * tag.std_error_s.max(1e-3)
    {
        println!(
            "{band}: GNSS-SDR's time tags are {:.4} s (+/- {:.4} s) off the times its pseudoranges belong to: a time-scale label; shifting them by {} s",
            tag.delta_s,
            tag.std_error_s,
            -tag.delta_s.round()
        );
        opts.tag_offset_s = -tag.delta_s.round();
        c = compare_with(&estimate, &truth, &opts).unwrap();
    }
    (estimate, c, opts.tag_offset_s)
}

/// Print the JSON line and the markdown table.
fn report(
    band: &str,
    loops: &Loops,
    c: &ObsComparison,
    tag_offset_s: f64,
    sigma_code: f64,
    sigma_phase: f64,
) {
    let line = serde_json::json!({
        "band": band,
        "gnss_sdr": "0.0.17",
        "pll_bw_hz": loops.pll_bw_hz,
        "dll_bw_hz": loops.dll_bw_hz,
        "early_late_space_chips": loops.early_late_space_chips,
        "tag_offset_s": tag_offset_s,
        "dll_theory_m": sigma_code,
        "pll_theory_m": sigma_phase,
        "comparison": c,
    });
    println!("GNSS_SDR_OBSERVABLES {line}");
    println!(
        "\n| {band} | epochs | code bias (m) | code std (m) | phase std (mm) | Doppler std (Hz) | C/N0 bias (dB) |"
    );
    println!("|---|---|---|---|---|---|---|");
    let find = |e: &skyforge_validate::observables::compare::ObservableErrors, sat| {
        e.per_satellite
            .iter()
            .find(|s| s.sat == sat)
            .map(|s| s.stats)
    };
    let f = cell;
    for s in &c.pseudorange_m.per_satellite {
        let ph = find(&c.carrier_phase_m, s.sat);
        let dop = find(&c.doppler_hz, s.sat);
        let cn0 = find(&c.cn0_dbhz, s.sat);
        println!(
            "| {} | {} | {} | {} | {} | {} | {} |",
            s.sat,
            s.stats.count,
            f(s.stats.mean, 1.0, 2),
            f(s.stats.std, 1.0, 2),
            f(ph.and_then(|p| p.std), 1e3, 2),
            f(dop.and_then(|p| p.std), 1.0, 2),
            f(cn0.and_then(|p| p.mean), 1.0, 2),
        );
    }
    let [epochs, code, phase, doppler, cn0] = overall_cells(c, 2);
    println!("| **all** | {epochs} | - | **{code}** | **{phase}** | {doppler} | {cn0} |");
    println!(
        "| theory | | | {:.2} (DLL) | {:.2} (PLL) | | |\n",
        sigma_code,
        sigma_phase * 1e3
    );
}

/// Matched epochs and the overall code std (m), phase std (mm), Doppler std (Hz) and C/N0
/// bias (dB) of `c`, for a markdown table row.
pub fn overall_cells(c: &ObsComparison, decimals: usize) -> [String; 5] {
    [
        c.matched_epochs.to_string(),
        cell(c.pseudorange_m.overall.std, 1.0, decimals),
        cell(c.carrier_phase_m.overall.std, 1e3, decimals),
        cell(c.doppler_hz.overall.std, 1.0, decimals),
        cell(c.cn0_dbhz.overall.mean, 1.0, 2),
    ]
}
