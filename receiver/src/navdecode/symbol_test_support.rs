//! Test helpers of the CNAV, F/NAV and I/NAV decoders: noisy soft symbols, uneven feeding
//! and the events of one kind.

use super::{DecodedEphemeris, NavDecoder, NavEvent, SubframeInfo};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Symbols 0/1 as BPSK soft values (0 -> +1, 1 -> -1; negated if `invert`) plus white
/// Gaussian noise of variance 1 / (2 Es/N0), `es_n0_db` in dB (no noise if infinite).
pub fn noisy(symbols: &[u8], es_n0_db: f64, invert: bool, seed: u64) -> Vec<f32> {
    let sigma = (0.5 / 10f64.powf(es_n0_db / 10.0)).sqrt();
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let sign = if invert { -1.0 } else { 1.0 };
    symbols
        .iter()
        .map(|&s| {
            let x = if s == 0 { sign } else { -sign };
            (x + normal.sample(&mut rng)) as f32
        })
        .collect()
}

/// Chunk sizes of an uneven feed (1 to 97 symbols).
pub const UNEVEN: [usize; 7] = [1, 13, 97, 5, 41, 2, 64];

/// Pure white Gaussian noise, unit variance.
pub fn noise(n: usize, seed: u64) -> Vec<f32> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Normal::new(0.0f32, 1.0).unwrap().sample(&mut rng))
        .collect()
}

/// Feed `soft` in chunks of the sizes `chunks` (cycled); each event with the number of
/// symbols fed when it came out.
pub fn feed(dec: &mut dyn NavDecoder, soft: &[f32], chunks: &[usize]) -> Vec<(u64, NavEvent)> {
    let mut out = Vec::new();
    let (mut fed, mut k) = (0, 0);
    while fed < soft.len() {
        let n = chunks[k % chunks.len()].min(soft.len() - fed);
        let events = dec.feed(&soft[fed..fed + n]);
        fed += n;
        k += 1;
        out.extend(events.into_iter().map(|e| (fed as u64, e)));
    }
    out
}

/// The subframes among `events`, with the symbol count at which each came out.
pub fn subframes(events: &[(u64, NavEvent)]) -> Vec<(u64, SubframeInfo)> {
    events
        .iter()
        .filter_map(|(at, e)| match e {
            NavEvent::Subframe(s) => Some((*at, *s)),
            _ => None,
        })
        .collect()
}

/// The ephemerides among `events`.
pub fn ephemerides(events: &[(u64, NavEvent)]) -> Vec<DecodedEphemeris> {
    events
        .iter()
        .filter_map(|(_, e)| match e {
            NavEvent::Ephemeris(d) => Some((**d).clone()),
            _ => None,
        })
        .collect()
}

/// How many of `events` are sync acquisitions and sync losses.
pub fn sync_counts(events: &[(u64, NavEvent)]) -> (usize, usize) {
    let count = |f: fn(&NavEvent) -> bool| events.iter().filter(|(_, e)| f(e)).count();
    (
        count(|e| matches!(e, NavEvent::SyncAcquired { .. })),
        count(|e| matches!(e, NavEvent::SyncLost { .. })),
    )
}

/// Stream starts of the messages (`period` symbols apart on the encoder's count) that
/// begin at or after stream symbol `from` and are reported within `len` symbols (`span`
/// symbols from their start), stream symbol 0 being encoder symbol `k0`.
pub fn expected_starts(k0: u64, from: u64, len: u64, period: u64, span: u64) -> Vec<u64> {
    ((k0 + from).div_ceil(period)..)
        .map(|n| n * period - k0)
        .take_while(|s| s + span <= len)
        .collect()
}

/// The first symbols of the reported subframes.
pub fn starts(subs: &[(u64, SubframeInfo)]) -> Vec<u64> {
    subs.iter().map(|(_, s)| s.start_bit).collect()
}
