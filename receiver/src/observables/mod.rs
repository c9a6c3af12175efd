//! Observables on a common receive time: every channel of every antenna reports, at each
//! code-period boundary it tracks, the sample index of that boundary, the transmit time it
//! carries (from the decoded time of week and the code count), the accumulated carrier
//! phase of its NCO and its Doppler; at each observation epoch (a sample index shared by
//! all antennas, which run on one sample clock) this module interpolates every channel to
//! that sample and forms
//! - pseudorange `c (t_rx - t_tx)` with `t_rx` the receiver's clock at the epoch sample,
//! - carrier phase in the RINEX sign convention (`L` grows with the range: minus the NCO's
//!   accumulated Doppler phase), half a cycle added when the navigation data showed the
//!   carrier loop locked with inverted polarity,
//! - Doppler (RINEX sign: positive when approaching), C/N0, lock time and a loss-of-lock
//!   indicator for the epoch.

use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::SatId;
use std::collections::BTreeMap;

/// What one channel knows at one of its code-period boundaries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChannelSample {
    /// Index of the sample at the boundary (fractional: the code phase is sub-sample).
    pub sample_index: f64,
    /// Transmit time of that boundary in system time (s, GPST-aligned, same origin as the
    /// receiver clock).
    pub t_tx_s: f64,
    /// Accumulated carrier NCO phase (cycles, positive Doppler -> growing).
    pub nco_phase_cycles: f64,
    pub doppler_hz: f64,
    pub cn0_dbhz: f64,
    /// The phase lock was lost or a cycle slip flagged since the previous sample.
    pub slip: bool,
    /// The data showed the carrier loop locked at 180 deg (data bits inverted).
    pub inverted: bool,
}

/// One observation of one satellite at one antenna and epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation {
    pub antenna: usize,
    pub sat: SatId,
    pub signal: Signal,
    pub pseudorange_m: f64,
    /// RINEX-signed carrier phase (cycles).
    pub carrier_phase_cycles: f64,
    pub doppler_hz: f64,
    pub cn0_dbhz: f64,
    /// Continuous tracking time up to the epoch (s).
    pub lock_time_s: f64,
    /// Loss of lock between the previous epoch and this one (RINEX LLI bit 0).
    pub loss_of_lock: bool,
}

impl Observation {
    /// The observation in the project's vocabulary (what RINEX files hold): a Doppler that
    /// is not finite is not measured.
    pub fn record(&self) -> ObsRecord {
        ObsRecord {
            sat: self.sat,
            signal: self.signal,
            pseudorange_m: Some(self.pseudorange_m),
            carrier_phase_cycles: Some(self.carrier_phase_cycles),
            doppler_hz: self.doppler_hz.is_finite().then_some(self.doppler_hz),
            cn0_dbhz: Some(self.cn0_dbhz),
            phase_lli: if self.loss_of_lock {
                LLI_LOSS_OF_LOCK
            } else {
                0
            },
        }
    }
}

/// The channels' recent history and the observation epochs.
#[derive(Debug, Clone)]
pub struct ObservablesBuilder {
    sample_rate_hz: f64,
    channels: BTreeMap<(usize, SatId, Signal), Track>,
}

#[derive(Debug, Clone)]
struct Track {
    /// The two newest samples.
    last: [Option<ChannelSample>; 2],
    /// Sample index where continuous tracking began.
    locked_since: f64,
    /// A slip happened after the last epoch that used this channel.
    slip_pending: bool,
}

impl ObservablesBuilder {
    pub fn new(sample_rate_hz: f64) -> Self {
        Self {
            sample_rate_hz,
            channels: BTreeMap::new(),
        }
    }

    /// Record a code-period boundary of `sat`'s `signal` at `antenna`.
    pub fn push(&mut self, antenna: usize, sat: SatId, signal: Signal, s: ChannelSample) {
        let track = self
            .channels
            .entry((antenna, sat, signal))
            .or_insert(Track {
                last: [None, None],
                locked_since: s.sample_index,
                slip_pending: true,
            });
        if s.slip {
            track.locked_since = s.sample_index;
            track.slip_pending = true;
            track.last = [None, None];
        }
        track.last = [track.last[1], Some(s)];
    }

    /// The loss-of-lock flags of `observations` (of an epoch not reported) stay pending
    /// for the next epoch.
    pub fn keep_pending(&mut self, observations: &[Observation]) {
        for o in observations.iter().filter(|o| o.loss_of_lock) {
            if let Some(track) = self.channels.get_mut(&(o.antenna, o.sat, o.signal)) {
                track.slip_pending = true;
            }
        }
    }

    /// Forget a channel (it stopped tracking).
    pub fn drop_channel(&mut self, antenna: usize, sat: SatId, signal: Signal) {
        self.channels.remove(&(antenna, sat, signal));
    }

    /// Observations at sample `epoch_sample` with receiver time `t_rx_s` there: every
    /// channel whose two newest boundaries bracket the epoch (or end within one code
    /// period before it: then extrapolated linearly). `clock_steps_s` is the sum of the
    /// re-anchoring corrections the receiver clock has had: the carrier phase moves by
    /// `f clock_steps_s` cycles with the pseudorange's `c clock_steps_s`, so code and
    /// carrier stay consistent across a clock jump.
    pub fn at(&mut self, epoch_sample: f64, t_rx_s: f64, clock_steps_s: f64) -> Vec<Observation> {
        let fs = self.sample_rate_hz;
        let mut out = Vec::new();
        for (&(antenna, sat, signal), track) in &mut self.channels {
            let [Some(a), Some(b)] = track.last else {
                continue;
            };
            let span = b.sample_index - a.sample_index;
            if span <= 0.0 || epoch_sample < a.sample_index || epoch_sample > b.sample_index + span
            {
                continue;
            }
            let u = (epoch_sample - a.sample_index) / span;
            let lerp = |x: f64, y: f64| x + (y - x) * u;
            let t_tx = lerp(a.t_tx_s, b.t_tx_s);
            let nco = lerp(a.nco_phase_cycles, b.nco_phase_cycles);
            let half = if b.inverted { 0.5 } else { 0.0 };
            out.push(Observation {
                antenna,
                sat,
                signal,
                pseudorange_m: C_MPS * (t_rx_s - t_tx),
                carrier_phase_cycles: -nco + half + clock_steps_s * signal.carrier_hz(),
                doppler_hz: lerp(a.doppler_hz, b.doppler_hz),
                cn0_dbhz: b.cn0_dbhz,
                lock_time_s: (epoch_sample - track.locked_since).max(0.0) / fs,
                loss_of_lock: track.slip_pending,
            });
            track.slip_pending = false;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::ephemeris::System;

    /// A satellite whose range grows at 500 m/s with 2 m/s^2: the channel's code
    /// boundaries (every 1 ms of transmit time) at the samples where they arrive.
    fn boundary(k: u32, fs: f64, t0_rx: f64, range0: f64) -> ChannelSample {
        let t_tx = 100.0 + f64::from(k) * 1e-3;
        // Receive time of that boundary: t_tx + range(t)/c, solved by iteration.
        let range = |t: f64| range0 + 500.0 * t + t * t;
        let mut t_rx = t_tx + range0 / C_MPS;
        for _ in 0..5 {
            t_rx = t_tx + range(t_rx - t0_rx) / C_MPS;
        }
        let lambda = C_MPS / 1575.42e6;
        ChannelSample {
            sample_index: (t_rx - t0_rx) * fs,
            t_tx_s: t_tx,
            nco_phase_cycles: -range(t_rx - t0_rx) / lambda + 17.0,
            doppler_hz: -(500.0 + 2.0 * (t_rx - t0_rx)) / lambda,
            cn0_dbhz: 45.0,
            slip: false,
            inverted: false,
        }
    }

    #[test]
    fn pseudorange_and_phase_follow_the_range_at_the_epoch() {
        let (fs, t0_rx, range0) = (4.092e6, 100.07, 2.1e7);
        let sat = SatId {
            system: System::Gps,
            prn: 7,
        };
        let lambda = C_MPS / 1575.42e6;
        let mut checked = 0;
        // Epoch 2.5 s after t0_rx, sample index 2.5 fs: feed boundaries until the two
        // newest bracket it.
        let mut b = ObservablesBuilder::new(fs);
        let epoch_t = 2.5;
        for k in 0..3000 {
            let s = boundary(k, fs, t0_rx, range0);
            if s.sample_index > epoch_t * fs {
                b.push(0, sat, Signal::GpsL1Ca, s);
                let obs = b.at(epoch_t * fs, t0_rx + epoch_t, 0.0);
                assert_eq!(obs.len(), 1);
                let o = obs[0];
                let range = range0 + 500.0 * epoch_t + epoch_t * epoch_t;
                assert!(
                    (o.pseudorange_m - range).abs() < 1e-4,
                    "{}",
                    o.pseudorange_m - range
                );
                let phase = range / lambda - 17.0;
                assert!(
                    (o.carrier_phase_cycles - phase).abs() < 1e-4,
                    "{}",
                    o.carrier_phase_cycles - phase
                );
                assert!((o.doppler_hz + (500.0 + 5.0) / lambda).abs() < 1e-3);
                assert!(o.loss_of_lock && (o.lock_time_s - epoch_t).abs() < 0.1);
                checked += 1;
                break;
            }
            b.push(0, sat, Signal::GpsL1Ca, s);
        }
        assert_eq!(checked, 1);
    }

    /// A re-anchored receiver clock moves the pseudorange and the carrier phase alike:
    /// code minus carrier does not jump.
    #[test]
    fn a_clock_jump_moves_code_and_carrier_alike() {
        let (fs, t0_rx, range0) = (4.092e6, 100.07, 2.1e7);
        let sat = SatId {
            system: System::Gps,
            prn: 3,
        };
        let mut b = ObservablesBuilder::new(fs);
        let epoch = 1.5 * fs;
        for k in 0..1600 {
            let s = boundary(k, fs, t0_rx, range0);
            b.push(0, sat, Signal::GpsL1Ca, s);
            if s.sample_index > epoch {
                break;
            }
        }
        let before = b.at(epoch, t0_rx + 1.5, 0.0)[0];
        let jump_s = 8.1e-3;
        let after = b.at(epoch, t0_rx + 1.5 - jump_s, -jump_s)[0];
        assert!((before.pseudorange_m - after.pseudorange_m - C_MPS * jump_s).abs() < 1e-6);
        let lambda = Signal::GpsL1Ca.wavelength_m();
        let cmc = |o: &Observation| o.pseudorange_m - o.carrier_phase_cycles * lambda;
        assert!(
            (cmc(&before) - cmc(&after)).abs() < 1e-6,
            "{}",
            cmc(&before) - cmc(&after)
        );
    }

    #[test]
    fn a_slip_restarts_the_lock_time_and_flags_the_next_epoch_only() {
        let (fs, t0_rx, range0) = (4.092e6, 100.07, 2.1e7);
        let sat = SatId {
            system: System::Beidou,
            prn: 19,
        };
        let mut b = ObservablesBuilder::new(fs);
        let mut flags = Vec::new();
        for k in 0..2000u32 {
            let mut s = boundary(k, fs, t0_rx, range0);
            s.slip = k == 1200;
            b.push(1, sat, Signal::GpsL1Ca, s);
            if k % 100 == 50 && k > 0 {
                let o = b.at(s.sample_index, t0_rx + s.sample_index / fs, 0.0);
                flags.push((k, o[0].loss_of_lock, o[0].lock_time_s));
            }
        }
        // First epoch: a new channel; after the slip at 1200 the next epoch (1250) only.
        let lli: Vec<u32> = flags.iter().filter(|f| f.1).map(|f| f.0).collect();
        assert_eq!(lli, vec![50, 1250]);
        let at_1250 = flags.iter().find(|f| f.0 == 1250).unwrap().2;
        assert!((at_1250 - 0.05).abs() < 1e-3, "{at_1250}");
        // An epoch beyond the newest boundary by more than a period is not extrapolated.
        assert!(b.at(1e12, 0.0, 0.0).is_empty());
    }
}
