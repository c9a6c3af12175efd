//! Test support: simulated observations with known errors, written as RINEX 3.04 text
//! by hand (in any time system, with any loss-of-lock digit, as other receivers write
//! them) and read back through the project's RINEX reader.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use skyforge_gnss::observation::{ObsFile, parse_obs_text};
use skyforge_orbits::constants::{C_MPS, F_BDS_B1I_HZ, F_GPS_L1_HZ};

/// Standard normal by Box-Muller.
pub fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.random::<f64>().max(1e-300);
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// One satellite's record.
#[derive(Debug, Clone, Copy)]
pub struct Rec {
    /// `G05`, `C07`.
    pub sat: &'static str,
    pub pr: f64,
    pub phase: f64,
    pub dop: f64,
    pub cn0: f64,
    pub lli: u8,
}

/// Carrier wavelength (m) of a satellite name's signal (GPS L1, BDS B1I).
pub fn wavelength(sat: &str) -> f64 {
    if sat.starts_with('G') {
        C_MPS / F_GPS_L1_HZ
    } else {
        C_MPS / F_BDS_B1I_HZ
    }
}

/// RINEX 3.04 text; epoch tags in seconds after 2023-03-12 00:00:00 of `time_system`
/// (rounded to the format's 100 ns).
pub fn rinex(epochs: &[(f64, Vec<Rec>)], time_system: &str) -> String {
    let mut t = String::new();
    let mut line = |body: String, label: &str| t.push_str(&format!("{body:<60}{label}\n"));
    line(
        format!(
            "{:>9}{:11}{:<20}{:<20}",
            "3.04", "", "OBSERVATION DATA", "M"
        ),
        "RINEX VERSION / TYPE",
    );
    line("G    4 C1C L1C D1C S1C".into(), "SYS / # / OBS TYPES");
    line("C    4 C2I L2I D2I S2I".into(), "SYS / # / OBS TYPES");
    line(
        format!("  2023    03    12    00    00    0.0000000     {time_system}"),
        "TIME OF FIRST OBS",
    );
    line(String::new(), "END OF HEADER");
    for (tag_s, recs) in epochs {
        let ticks = (tag_s * 1e7).round() as i64;
        let (h, rem) = (ticks / 36_000_000_000, ticks % 36_000_000_000);
        let (m, s) = (rem / 600_000_000, rem % 600_000_000);
        t.push_str(&format!(
            "> 2023 03 12 {h:02} {m:02} {:2}.{:07}  0{:3}\n",
            s / 10_000_000,
            s % 10_000_000,
            recs.len()
        ));
        for r in recs {
            let lli = if r.lli == 0 {
                ' '
            } else {
                char::from(b'0' + r.lli)
            };
            t.push_str(&format!(
                "{}{:14.3}  {:14.3}{lli} {:14.3}  {:14.3}  \n",
                r.sat, r.pr, r.phase, r.dop, r.cn0
            ));
        }
    }
    t
}

/// [`rinex`] read back.
pub fn obs_file(epochs: &[(f64, Vec<Rec>)], time_system: &str) -> ObsFile {
    let text = rinex(epochs, time_system);
    match parse_obs_text(&text, "test") {
        Ok(f) => f,
        Err(e) => panic!("{e}\n{text}"),
    }
}

/// Range (m) and range rate (m/s) of a satellite in a circular orbit of radius
/// 26,560 km seen from the equator, overhead at `t_zenith` (s).
pub fn range(t_zenith: f64, t: f64) -> (f64, f64) {
    let (a, r, n) = (26_560e3_f64, 6_378e3_f64, 1.458e-4 - 7.292e-5);
    let th = n * (t - t_zenith);
    let rho = (a * a + r * r - 2.0 * a * r * th.cos()).sqrt();
    (rho, a * r * n * th.sin() / rho)
}
