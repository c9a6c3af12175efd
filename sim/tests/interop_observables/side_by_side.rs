//! SkyForge's receiver and GNSS-SDR side by side on the same recording at equal loops, both
//! compared with SkyForge's truth over the same epochs (issue #4: "pseudorange and
//! carrier-phase error std at equal loop bandwidths no worse than GNSS-SDR's").
//!
//! Equal loops means equal designs, not only equal numbers in two configuration files
//! (validation/gnss_sdr_observables.md has the measurements behind each choice):
//! - PLL of 2nd order in both. GNSS-SDR's 3rd-order carrier filter (its default) advances
//!   its two integrators with half and a quarter of the textbook gains, which realises
//!   0.85 of the configured noise bandwidth; its 2nd-order filter is the textbook bilinear
//!   one, as SkyForge's.
//! - DLL of 1st order in both (SkyForge's carrier-aided DLL; GNSS-SDR's default is 2nd).
//! - After bit sync, 20 ms coherent integration with the narrow bandwidths (GNSS-SDR's
//!   `extend_correlation_symbols`; BeiDou D2 GEOs stay at their 2 ms bits in both). At 1 ms
//!   GNSS-SDR hands its observables block one tracking output per data bit and interpolates
//!   linearly between these 20 ms-spaced points, which averages loop noise that SkyForge's
//!   1 ms records keep; with 20 ms integrations both receivers interpolate between the
//!   integration boundaries 20 ms apart, i.e. form their observables the same way.

use super::{compare_gnss_sdr, overall_cells};
use skyforge_validate::observables::compare::{
    CompareOptions, ObsComparison, ObservableErrors, compare_with,
};
use skyforge_validate::observables::read_obs_file;
use std::path::Path;

/// The loop settings both receivers run with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EqualLoops {
    /// Pull-in PLL and DLL noise bandwidths (Hz), 1 ms integrations.
    pub pll_bw_hz: f64,
    pub dll_bw_hz: f64,
    /// Early-to-late spacing during pull-in (chips; GNSS-SDR's early-prompt spacing is half).
    pub early_late_chips: f64,
    /// After bit sync: PLL and DLL noise bandwidths (Hz), spacing (chips), integration (ms).
    pub narrow_pll_bw_hz: f64,
    pub narrow_dll_bw_hz: f64,
    pub narrow_early_late_chips: f64,
    pub coherent_ms: u32,
}

/// GNSS-SDR's own pull-in values (the .conf SkyForge writes for it), then 5 Hz / 0.5 Hz /
/// half a chip over 20 ms: `Bn T` = 0.1, where both loops realise their design bandwidth.
pub const EQUAL_LOOPS: EqualLoops = EqualLoops {
    pll_bw_hz: 25.0,
    dll_bw_hz: 2.0,
    early_late_chips: 1.0,
    narrow_pll_bw_hz: 5.0,
    narrow_dll_bw_hz: 0.5,
    narrow_early_late_chips: 0.5,
    coherent_ms: 20,
};

impl EqualLoops {
    /// `conf` (a GNSS-SDR configuration) with the `role` (`Tracking_1C`, `Tracking_B1`)
    /// loop keys replaced by these settings.
    pub fn gnss_sdr_conf(&self, conf: &str, role: &str) -> String {
        let keys = [
            ("pll_filter_order", "2".to_string()),
            ("dll_filter_order", "1".to_string()),
            ("pll_bw_hz", self.pll_bw_hz.to_string()),
            ("dll_bw_hz", self.dll_bw_hz.to_string()),
            (
                "early_late_space_chips",
                (self.early_late_chips / 2.0).to_string(),
            ),
            ("extend_correlation_symbols", self.coherent_ms.to_string()),
            ("pll_bw_narrow_hz", self.narrow_pll_bw_hz.to_string()),
            ("dll_bw_narrow_hz", self.narrow_dll_bw_hz.to_string()),
            (
                "early_late_space_narrow_chips",
                (self.narrow_early_late_chips / 2.0).to_string(),
            ),
        ];
        let ours = |line: &str| {
            keys.iter()
                .any(|(k, _)| line.starts_with(&format!("{role}.{k}=")))
        };
        let mut out: String = conf
            .lines()
            .filter(|l| !ours(l))
            .map(|l| format!("{l}\n"))
            .collect();
        for (k, v) in keys {
            out.push_str(&format!("{role}.{k}={v}\n"));
        }
        out
    }

    /// The same settings as a `skyforge receive --config` file.
    pub fn receiver_toml(&self) -> String {
        format!(
            "[tracking]\npll_order = \"second\"\npll_bandwidth_hz = {:?}\n\
             pll_narrow_bandwidth_hz = {:?}\ncoherent_ms = {}\ndll_bandwidth_hz = {:?}\n\
             early_late_spacing_chips = {:?}\ndll_narrow_bandwidth_hz = {:?}\n\
             narrow_early_late_spacing_chips = {:?}\n",
            self.pll_bw_hz,
            self.narrow_pll_bw_hz,
            self.coherent_ms,
            self.dll_bw_hz,
            self.early_late_chips,
            self.narrow_dll_bw_hz,
            self.narrow_early_late_chips,
        )
    }
}

/// Standard error of the ratio of two independent std estimates from `n1` and `n2`
/// samples (relative; each std carries `1 / sqrt(2 n)`).
fn ratio_standard_error(n1: usize, n2: usize) -> f64 {
    (1.0 / (2.0 * n1 as f64) + 1.0 / (2.0 * n2 as f64)).sqrt()
}

fn overall(e: &ObservableErrors) -> (f64, usize) {
    (e.overall.std.expect("a std"), e.overall.count)
}

/// Compare GNSS-SDR's observations in `out` and SkyForge's receiver's `ours` with the
/// truth there, over the sample-time span of GNSS-SDR's matched epochs; print both and
/// assert SkyForge's code and phase error stds are no worse than GNSS-SDR's. "No worse":
/// not above GNSS-SDR's by more than twice the standard error of the ratio of the two
/// std estimates (about 4.5 % each at 90 s), the resolution of a 90 s comparison.
pub fn check(out: &Path, band: &str, ours: &Path) {
    let (_, theirs, tag_offset_s) = compare_gnss_sdr(out, band);
    let truth = read_obs_file(&out.join("ant1.obs.rnx")).unwrap();
    let opts = CompareOptions {
        window: Some(theirs.sample_span),
        ..CompareOptions::default()
    };
    let ours = compare_with(&read_obs_file(ours).unwrap(), &truth, &opts).unwrap();
    report(band, &theirs, &ours, tag_offset_s);
    for (what, unit, scale, g, s) in [
        (
            "pseudorange",
            "m",
            1.0,
            overall(&theirs.pseudorange_m),
            overall(&ours.pseudorange_m),
        ),
        (
            "carrier phase",
            "mm",
            1e3,
            overall(&theirs.carrier_phase_m),
            overall(&ours.carrier_phase_m),
        ),
    ] {
        let se = ratio_standard_error(g.1, s.1);
        let ratio = s.0 / g.0;
        println!(
            "{band} {what}: SkyForge {:.3} {unit} ({} samples), GNSS-SDR {:.3} {unit} ({} samples): ratio {ratio:.3} +/- {se:.3}",
            s.0 * scale,
            s.1,
            g.0 * scale,
            g.1
        );
        assert!(
            ratio <= 1.0 + 2.0 * se,
            "{band}: SkyForge's {what} error std {} {unit} is above GNSS-SDR's {} {unit} by more than 2 standard errors ({se})",
            s.0 * scale,
            g.0 * scale
        );
    }
}

/// One JSON line (`SIDE_BY_SIDE {...}`) and a markdown table.
fn report(band: &str, theirs: &ObsComparison, ours: &ObsComparison, tag_offset_s: f64) {
    let line = serde_json::json!({
        "band": band,
        "gnss_sdr_version": "0.0.17",
        "loops": format!("{EQUAL_LOOPS:?}"),
        "gnss_sdr_tag_offset_s": tag_offset_s,
        "gnss_sdr": theirs,
        "skyforge": ours,
    });
    println!("SIDE_BY_SIDE {line}");
    println!(
        "\n| {band} | epochs | code std (m) | phase std (mm) | Doppler std (Hz) | C/N0 bias (dB) |"
    );
    println!("|---|---|---|---|---|---|");
    for (who, c) in [("GNSS-SDR 0.0.17", theirs), ("SkyForge", ours)] {
        println!("| {who} | {} |", overall_cells(c, 3).join(" | "));
    }
    println!();
}

/// `|H(j 2 pi f)|^2` of the closed loop `H = P(s) / (s^n + P(s))` with loop-filter-times-NCO
/// polynomial `P(s) = sum c[k] s^k` (`c` lowest power first, `n = c.len()`).
fn closed_loop_power(c: &[f64], f_hz: f64) -> f64 {
    let s = nalgebra::Complex::<f64>::new(0.0, std::f64::consts::TAU * f_hz);
    let p = c
        .iter()
        .rev()
        .fold(nalgebra::Complex::<f64>::new(0.0, 0.0), |acc, &ck| {
            acc * s + ck
        });
    (p / (s.powu(c.len() as u32) + p)).norm_sqr()
}

/// `integral_0^inf |H|^2 w(f) df` by the trapezoid rule to 10 kHz, plus the `1/f^2` tail of
/// `|H|^2 -> c[n-1]^2 / (2 pi f)^2` when `w` is 1.
fn loop_integral(c: &[f64], w: impl Fn(f64) -> f64, with_tail: bool) -> f64 {
    let (df, f_max) = (0.01, 1e4);
    let n = (f_max / df) as usize;
    let sum: f64 = (0..=n)
        .map(|i| {
            let f = i as f64 * df;
            let edge = if i == 0 || i == n { 0.5 } else { 1.0 };
            edge * closed_loop_power(c, f) * w(f)
        })
        .sum();
    let lead = c[c.len() - 1];
    let tail = if with_tail {
        lead * lead / (std::f64::consts::TAU.powi(2) * f_max)
    } else {
        0.0
    };
    sum * df + tail
}

/// The numbers behind "equal loops" in validation/gnss_sdr_observables.md, from the
/// continuous closed loops: Kaplan's 3rd-order PLL at 25 Hz has 25 Hz of noise bandwidth;
/// GNSS-SDR's 3rd-order filter form (its integrators fed half the input:
/// `b3 w0 + 0.55 w0^2/s + 0.25 w0^3/s^2`) has 21.4 Hz, so 1.08x more phase noise with its
/// textbook 2nd-order filter; a 25 Hz 2nd-order loop's phase noise keeps a correlation of
/// 0.30 over one 20 ms data bit, the spacing GNSS-SDR interpolates its observables over.
#[test]
fn loop_bandwidths_and_correlation_behind_the_equal_loop_choice() {
    let w3: f64 = 25.0 / 0.7845;
    let kaplan = [w3.powi(3), 1.1 * w3 * w3, 2.4 * w3];
    let gnss_sdr = [0.25 * w3.powi(3), 0.55 * w3 * w3, 2.4 * w3];
    let bn_kaplan = loop_integral(&kaplan, |_| 1.0, true);
    let bn_gnss_sdr = loop_integral(&gnss_sdr, |_| 1.0, true);
    println!(
        "3rd order, 25 Hz: Kaplan {bn_kaplan:.2} Hz, GNSS-SDR's form {bn_gnss_sdr:.2} Hz, phase noise ratio {:.3}",
        (bn_kaplan / bn_gnss_sdr).sqrt()
    );
    assert!((bn_kaplan - 25.0).abs() < 0.1, "{bn_kaplan}");
    assert!((bn_gnss_sdr - 21.4).abs() < 0.1, "{bn_gnss_sdr}");

    let w2: f64 = 25.0 / 0.53;
    let second = [w2 * w2, 1.414 * w2];
    let lag = 0.02;
    let rho = loop_integral(&second, |f| (std::f64::consts::TAU * f * lag).cos(), false)
        / loop_integral(&second, |_| 1.0, true);
    println!("2nd order, 25 Hz: phase-noise correlation over 20 ms {rho:.3}");
    assert!((rho - 0.30).abs() < 0.01, "{rho}");
}
