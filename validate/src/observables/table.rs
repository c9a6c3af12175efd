//! The printed form of an [`ObsComparison`]: one line per satellite, per system and
//! overall.

use super::compare::{ObsComparison, ObservableErrors};
use super::error_stats::ErrorStats;
use skyforge_orbits::ephemeris::{SatId, System};
use std::io::Write;

/// `v` times `scale` with `decimals` decimals, or `-`: one cell of a printed table.
pub fn cell(v: Option<f64>, scale: f64, decimals: usize) -> String {
    v.map_or("-".to_string(), |x| format!("{:.*}", decimals, x * scale))
}

/// Per-satellite stats of `e` for `sat`.
fn of_sat(e: &ObservableErrors, sat: SatId) -> Option<ErrorStats> {
    e.per_satellite
        .iter()
        .find(|s| s.sat == sat)
        .map(|s| s.stats)
}

fn of_system(e: &ObservableErrors, system: System) -> Option<ErrorStats> {
    e.per_system
        .iter()
        .find(|s| s.system == system)
        .map(|s| s.stats)
}

fn line(out: &mut impl Write, label: &str, stats: [Option<ErrorStats>; 4]) -> std::io::Result<()> {
    let [pr, ph, dop, cn0] = stats;
    writeln!(
        out,
        "{label:<8} {:>6} {:>10} {:>9} {:>6} {:>10} {:>9} {:>8} {:>8}",
        pr.map_or(0, |s| s.count),
        cell(pr.and_then(|s| s.mean), 1.0, 3),
        cell(pr.and_then(|s| s.std), 1.0, 3),
        ph.map_or(0, |s| s.count),
        cell(ph.and_then(|s| s.std), 1e3, 3),
        cell(dop.and_then(|s| s.std), 1.0, 3),
        cell(cn0.and_then(|s| s.mean), 1.0, 2),
        cell(cn0.and_then(|s| s.std), 1.0, 2),
    )
}

/// Print `c` as a table.
pub fn print_comparison(c: &ObsComparison, out: &mut impl Write) -> std::io::Result<()> {
    writeln!(out, "estimate: {}", c.estimate.display())?;
    writeln!(out, "truth:    {}", c.truth.display())?;
    writeln!(
        out,
        "epochs: {} in the estimate, {} matched with the truth; estimate tag - sample time: {} s (std {} s)",
        c.estimate_epochs,
        c.matched_epochs,
        cell(c.time_offset_s.mean, 1.0, 9),
        cell(c.time_offset_s.std, 1.0, 9),
    )?;
    writeln!(
        out,
        "sample times of the matched epochs: {} .. {}",
        c.sample_span.first, c.sample_span.last
    )?;
    if let Some(t) = c.tag_error {
        writeln!(
            out,
            "time-tag error seen by the pseudoranges: {:.6} s +/- {:.6} s ({} satellites){}",
            t.delta_s,
            t.std_error_s,
            t.satellites,
            if t.delta_s.abs() > 5.0 * t.std_error_s && t.delta_s.abs() > 1e-3 {
                "  <- tags in another time scale? retry with --tag-offset-s"
            } else {
                ""
            }
        )?;
    }
    writeln!(
        out,
        "{:<8} {:>6} {:>10} {:>9} {:>6} {:>10} {:>9} {:>8} {:>8}",
        "", "code", "PR bias", "PR std", "phase", "phase std", "Dop std", "C/N0", "C/N0"
    )?;
    writeln!(
        out,
        "{:<8} {:>6} {:>10} {:>9} {:>6} {:>10} {:>9} {:>8} {:>8}",
        "sat", "n", "m", "m", "n", "mm", "Hz", "bias dB", "std dB"
    )?;
    let obs = [
        &c.pseudorange_m,
        &c.carrier_phase_m,
        &c.doppler_hz,
        &c.cn0_dbhz,
    ];
    for s in &c.pseudorange_m.per_satellite {
        line(out, &s.sat.to_string(), obs.map(|o| of_sat(o, s.sat)))?;
    }
    for s in &c.pseudorange_m.per_system {
        line(out, s.system.name(), obs.map(|o| of_system(o, s.system)))?;
    }
    line(out, "overall", obs.map(|o| Some(o.overall)))?;
    let integer = c.arcs.iter().filter(|a| a.integer_like).count();
    writeln!(
        out,
        "carrier-phase arcs: {}, {} with an offset within 0.05 cycle of a multiple of 1/2 (relative to each system's reference arc)",
        c.arcs.len(),
        integer
    )?;
    if !c.satellites_without_truth.is_empty() {
        let list: Vec<String> = c
            .satellites_without_truth
            .iter()
            .map(ToString::to_string)
            .collect();
        writeln!(out, "satellites without truth: {}", list.join(" "))?;
    }
    writeln!(
        out,
        "PR bias: relative to the system's satellites (clock removed); stds after removing per-epoch clock terms and per-satellite (code, Doppler) or per-arc (phase) offsets."
    )
}
