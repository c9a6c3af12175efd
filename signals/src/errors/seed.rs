//! Per-source random streams derived from the one scenario seed (DESIGN.md, "Randomness").
//!
//! Every noise source draws from its own `ChaCha20Rng`, keyed by
//! [`stream_seed`]`(scenario seed, source, index)`: the receiver oscillator of receiver `i`
//! uses `(Stream::ReceiverClock, i)`, and so on. A stream depends only on these three
//! inputs, never on thread count, block size or the order in which other sources are
//! drawn. Every source of the project is named once, in [`Stream`].
//!
//! Derivation: `source` is hashed with 64-bit FNV-1a (offset basis 0xcbf29ce484222325,
//! prime 0x100000001b3); the inputs are chained through SplitMix64 (Steele, Lea & Flood,
//! "Fast splittable pseudorandom number generators", OOPSLA 2014):
//! `a = splitmix(seed) ^ fnv1a(source)`, `b = splitmix(a) ^ index`, and the 32-byte
//! ChaCha20 key is the next four SplitMix64 outputs from state `b`, little-endian.

use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;

const FNV_OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;
const SPLITMIX_GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// The random sources of the project, each with the name its key is derived from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stream {
    /// The receiver oscillator's noise; index: the receiver (or antenna, with one
    /// oscillator per antenna).
    ReceiverClock,
    /// Thermal noise of an antenna's samples; index: the antenna.
    Thermal,
    /// The random data symbols of validate's T-3.3-S signal; index 0.
    FastSyncData,
    /// Tracking noise of the observation-level model; index: the antenna.
    ObservationNoise,
    /// Doppler noise of the observation-level model (`[observation] doppler_noise`);
    /// index: the antenna.
    DopplerNoise,
    /// Integer carrier ambiguities of the observation-level model; index 0.
    CarrierAmbiguity,
    /// A satellite's radial, along-track and cross-track orbit error and its clock error
    /// (`[errors.satellite]`); index: the satellite (system and PRN), so every antenna
    /// and platform of a run sees the same error.
    SatelliteRadial,
    SatelliteAlong,
    SatelliteCross,
    SatelliteClock,
    /// An IMU's gyro triad (turn-on errors, then bias instability and noise), its
    /// accelerometer triad, and its vibration phases; index: the IMU.
    ImuGyro,
    ImuAccel,
    ImuVibration,
    /// A barometric altimeter's bias and noise; index: the barometer.
    Barometer,
    /// A noise jammer's waveform (`[[jammers]]`); index: the jammer, so every antenna
    /// receives the one waveform it transmits.
    JammerNoise,
    /// A test's own stream, by name (never used by a scenario).
    Named(&'static str),
}

impl Stream {
    /// The name the stream's key is derived from (fixed: changing one changes every
    /// output drawn from it).
    pub fn name(self) -> &'static str {
        match self {
            Stream::ReceiverClock => "receiver-clock",
            Stream::Thermal => "thermal",
            Stream::FastSyncData => "t-3.3-s data",
            Stream::ObservationNoise => "observation-noise",
            Stream::CarrierAmbiguity => "carrier-ambiguity",
            Stream::DopplerNoise => "doppler-noise",
            Stream::SatelliteRadial => "satellite-radial",
            Stream::SatelliteAlong => "satellite-along",
            Stream::SatelliteCross => "satellite-cross",
            Stream::SatelliteClock => "satellite-clock",
            Stream::ImuGyro => "imu-gyro",
            Stream::ImuAccel => "imu-accel",
            Stream::ImuVibration => "imu-vibration",
            Stream::Barometer => "barometer",
            Stream::JammerNoise => "jammer-noise",
            Stream::Named(name) => name,
        }
    }
}

/// 64-bit FNV-1a hash of `bytes`.
fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(FNV_OFFSET_BASIS, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(FNV_PRIME)
    })
}

/// One SplitMix64 step: advances `state` and returns the mixed output.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(SPLITMIX_GAMMA);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The 32-byte ChaCha20 key of the stream `(seed, source, index)` (see the module docs).
pub fn stream_seed(seed: u64, source: Stream, index: u32) -> [u8; 32] {
    let mut state = seed;
    let mut state_b = splitmix64(&mut state) ^ fnv1a64(source.name().as_bytes());
    let mut key_state = splitmix64(&mut state_b) ^ u64::from(index);
    let mut key = [0_u8; 32];
    for word in key.chunks_exact_mut(8) {
        word.copy_from_slice(&splitmix64(&mut key_state).to_le_bytes());
    }
    key
}

/// The seed of a vehicle's receiver-side streams in a scenario with several:
/// `splitmix(seed) ^ fnv1a("vehicle " + name)`, so each vehicle's oscillator and noise
/// differ from every other's and from a single-platform run's under the same seed.
pub fn vehicle_seed(seed: u64, name: &str) -> u64 {
    let mut state = seed;
    splitmix64(&mut state) ^ fnv1a64(format!("vehicle {name}").as_bytes())
}

/// The random stream `(seed, source, index)`.
pub fn stream_rng(seed: u64, source: Stream, index: u32) -> ChaCha20Rng {
    ChaCha20Rng::from_seed(stream_seed(seed, source, index))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_matches_published_reference_outputs() {
        // Vigna's reference splitmix64.c seeded with 0.
        let mut s = 0_u64;
        assert_eq!(splitmix64(&mut s), 0xe220_a839_7b1d_cdaf);
        assert_eq!(splitmix64(&mut s), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(splitmix64(&mut s), 0x06c4_5d18_8009_454f);
    }

    #[test]
    fn fnv1a64_matches_published_test_vectors() {
        // Fowler/Noll/Vo reference test vectors for FNV-1a 64.
        assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn streams_differ_in_every_input_and_repeat_exactly() {
        let base = stream_seed(7, Stream::ReceiverClock, 0);
        assert_eq!(base, stream_seed(7, Stream::ReceiverClock, 0));
        assert_ne!(base, stream_seed(8, Stream::ReceiverClock, 0));
        assert_ne!(base, stream_seed(7, Stream::ReceiverClock, 1));
        assert_ne!(base, stream_seed(7, Stream::Thermal, 0));
    }

    #[test]
    fn vehicles_get_seeds_of_their_own() {
        let (a, b) = (vehicle_seed(7, "chaser"), vehicle_seed(7, "target"));
        assert_ne!(a, b);
        assert_ne!(a, 7);
        assert_eq!(a, vehicle_seed(7, "chaser"));
        assert_ne!(a, vehicle_seed(8, "chaser"));
    }
}
