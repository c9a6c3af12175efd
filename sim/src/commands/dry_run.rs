//! `skyforge synth --dry-run`: what a synthesis would write and the memory it needs,
//! without writing anything.

use skyforge_formats::truth::size_bound;
use skyforge_gnss::signal::Signal;
use skyforge_scenarios::Scenario;
use skyforge_signals::synth::Budget;
use skyforge_signals::synth::SynthSession;
use skyforge_signals::synth::recording_name;

/// Rendering throughput the time estimate assumes: channel-samples (one path of one
/// satellite at one antenna, one sample) per CPU-second.
// assumed: issue #14's end-to-end figure on this project's 2-core VM writing ci16 to disk
// (5.7e8-5.9e8 per CPU-second, BENCHMARKS.md); other machines differ, hence "about".
const CHANNEL_SAMPLES_PER_CPU_S: f64 = 5.7e8;
/// Output samples (one complex sample of one recording: noise, filter, quantisation,
/// disk) per CPU-second, the cost beside the channel-samples.
// assumed: session 27's GPS L1 C/A run of 10 s at 20.46 Msps (BENCHMARKS.md, "GPS L5
// beside GPS L1 C/A"): 12.7 CPU-s for 2.46e9 channel-samples and 2.05e8 output samples;
// less 4.3 s for the channel-samples at 5.7e8 per CPU-second, 8.4 s: 2.4e7 per CPU-second.
const OUTPUT_SAMPLES_PER_CPU_S: f64 = 2.4e7;

/// RINEX observation bytes per satellite and epoch, at most (one record line).
const RINEX_BYTES_PER_RECORD: u64 = 80;
/// RINEX observation bytes per epoch line and the header, at most.
const RINEX_BYTES_PER_EPOCH: u64 = 40;
const RINEX_HEADER_BYTES: u64 = 4096;

/// The figures of a dry run, printed.
pub fn print(scenario: &Scenario, session: &SynthSession<'_>, chunk_epochs: usize) {
    let threads = rayon::current_num_threads();
    let b = session.budget(chunk_epochs, threads);
    let n_ant = session.world().antennas.len() as u64;
    let n_sats = session.satellites().len() as u64;
    println!("scenario   {} ({})", scenario.name, scenario.source);
    println!("dry run    nothing is written");
    for band in session.bands().iter().filter(|_| b.recordings > 0) {
        for ant in session.world().antennas {
            println!(
                "recording  {}.sigmf-data  {} (exact)",
                recording_name(&ant.name, band),
                human(b.recording_bytes)
            );
        }
    }
    let truth = size_bound(
        b.epochs,
        n_ant,
        n_sats,
        b.truth_records_max,
        scenario.errors.satellite.is_some(),
    );
    println!(
        "truth.h5   at most {} ({} signal-truth records at most)",
        human(truth),
        b.truth_records_max
    );
    let rinex = rinex_bound(&b, n_ant, n_sats, session.renders_samples());
    println!("RINEX obs  at most {}", human(rinex));
    let disk = (b.recordings as u64)
        .saturating_mul(b.recording_bytes)
        .saturating_add(truth)
        .saturating_add(rinex);
    if disk == u64::MAX {
        println!(
            "disk       more than {} (beyond 64-bit byte counts)",
            human(disk)
        );
    } else {
        println!("disk       at most {}", human(disk));
    }
    println!(
        "memory     at most {} ({threads} rendering threads; RAYON_NUM_THREADS sets them)",
        human(b.memory_bytes)
    );
    if session.renders_samples() {
        let work = channel_samples(scenario, session, |_| 1.0);
        // A signal with a pilot in quadrature mixes two components per path (Galileo E1's
        // pilot is in phase, summed into its sub-chip levels: one).
        let components = channel_samples(scenario, session, |s| {
            if s.pilot_in_quadrature() { 2.0 } else { 1.0 }
        });
        let outputs = (b.recordings as f64)
            * session.world().duration_s
            * session.signal_config().sample_rate_hz;
        let cpu_s = components / CHANNEL_SAMPLES_PER_CPU_S + outputs / OUTPUT_SAMPLES_PER_CPU_S;
        println!(
            "time       at most about {} to render ({work:.3e} channel-samples: every \
             satellite at every antenna as if always visible, each reflected path one more, \
             a pilot's component one more; at {CHANNEL_SAMPLES_PER_CPU_S:.1e} per \
             CPU-second, plus {outputs:.3e} output samples at \
             {OUTPUT_SAMPLES_PER_CPU_S:.1e} per CPU-second; measured on a 2-core VM, \
             BENCHMARKS.md)",
            duration(cpu_s / threads as f64)
        );
    }
}

/// Paths mixed over the run, times samples, each band's weighted by `weight` of its
/// signal: per band, its sample rate x the duration x, for every antenna and satellite of
/// the band, the direct path and the reflected paths that apply to the link.
fn channel_samples(
    scenario: &Scenario,
    session: &SynthSession<'_>,
    weight: impl Fn(Signal) -> f64,
) -> f64 {
    let multipath = &scenario.errors.multipath;
    let samples = session.world().duration_s * session.signal_config().sample_rate_hz;
    let paths: f64 = session
        .bands()
        .iter()
        .map(|band| {
            let weighted: f64 = session
                .band_transmitters(band)
                .iter()
                .map(|&(sat, signal)| {
                    let paths: usize = (session.world().antennas.iter())
                        .map(|ant| 1 + multipath.paths_of(&ant.name, sat))
                        .sum();
                    weight(signal) * paths as f64
                })
                .sum();
            weighted
        })
        .sum();
    samples * paths
}

/// Seconds as a human reads them: seconds, minutes, hours or days.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 120.0 => format!("{s:.1} s"),
        s if s < 7200.0 => format!("{:.1} min", s / 60.0),
        s if s < 172_800.0 => format!("{:.1} h", s / 3600.0),
        s => format!("{:.1} days", s / 86_400.0),
    }
}

/// RINEX observation files of every antenna (truth, plus the observables at the
/// observation level), every satellite counted at every whole second.
fn rinex_bound(b: &Budget, n_ant: u64, n_sats: u64, samples: bool) -> u64 {
    let files = if samples { 1 } else { 2 } * n_ant;
    files
        * (RINEX_HEADER_BYTES
            + b.epochs * (RINEX_BYTES_PER_EPOCH + n_sats * RINEX_BYTES_PER_RECORD))
}

/// Bytes in decimal units, three significant figures.
fn human(bytes: u64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1000.0 && unit + 1 < units.len() {
        value /= 1000.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} B")
    } else {
        format!("{value:.3} {} ({bytes} bytes)", units[unit])
    }
}
