//! One antenna x satellite channel of the pipeline: its tracking loop, its navigation
//! decoder and the transmit-time bookkeeping that turns code epochs into
//! [`ChannelSample`]s for the observables.

use super::navdata::NavData;
use super::timing::{CodeClock, whole_periods_near};
use crate::navdecode::{NavDecoder, NavEvent, decoder_for};
use crate::observables::ChannelSample;
use crate::tracking::TrackingError;
use crate::tracking::channel::{ChannelTracker, TrackingRecord};
use num_complex::Complex32;
use skyforge_orbits::ephemeris::SatId;
use std::collections::VecDeque;

/// A tracking channel and what follows it.
pub(crate) struct Channel {
    /// Input group (band) and antenna within it, and the receiver's antenna index.
    pub(crate) group: usize,
    pub(crate) local: usize,
    pub(crate) antenna: usize,
    pub(crate) sat: SatId,
    tracker: ChannelTracker,
    decoder: Box<dyn NavDecoder>,
    clock: CodeClock,
    sample_rate_hz: f64,
    /// The carrier loop holds the carrier half a cycle off (Costas lock at 180 deg): the
    /// last subframe arrived inverted, or the pilot's secondary code did.
    inverted: bool,
    /// A slip or unlocked stretch happened since the last sample handed on.
    slip: bool,
    /// The carrier loop reported lock at least once.
    ever_locked: bool,
    /// Carrier Doppler of the last record, the acquisition's before the first (Hz).
    doppler_hz: f64,
    /// Records of the last block, digested after the (parallel) tracking step.
    records: Vec<TrackingRecord>,
    /// Timed code epochs not yet handed to the observables, oldest first.
    pub(crate) queue: VecDeque<ChannelSample>,
    /// Code period and (fractional) sample index of the last locked record's code epoch.
    last_epoch: Option<(u64, f64)>,
}

/// Farthest a code epoch's transmit time predicted from another signal of the satellite
/// may lie from a whole number of code periods for the hand-over (s). # assumed: 10 us
/// (3 km): the signals' group delays and ionospheric delays differ by well under a
/// microsecond, the prediction's Doppler neglect over a few milliseconds by nanoseconds;
/// a misfit beyond it (a false lock, a sibling timed wrongly) refuses the hand-over.
const HANDOVER_TOLERANCE_S: f64 = 10e-6;

impl Channel {
    pub(crate) fn new(
        group: usize,
        local: usize,
        antenna: usize,
        sat: SatId,
        tracker: ChannelTracker,
        sample_rate_hz: f64,
        acquired_doppler_hz: f64,
    ) -> Result<Self, crate::navdecode::NavDecodeError> {
        let code_period_s = tracker.signal().code_period_s();
        let decoder = decoder_for(sat, tracker.signal())?;
        Ok(Self {
            group,
            local,
            antenna,
            sat,
            tracker,
            decoder,
            clock: CodeClock::new(code_period_s),
            sample_rate_hz,
            inverted: false,
            slip: true,
            ever_locked: false,
            doppler_hz: acquired_doppler_hz,
            records: Vec::new(),
            queue: VecDeque::new(),
            last_epoch: None,
        })
    }

    /// Track one block (runs in parallel with the other channels).
    pub(crate) fn track(
        &mut self,
        samples: &[Complex32],
        first_sample: u64,
    ) -> Result<(), TrackingError> {
        self.records = self.tracker.process(samples, first_sample)?;
        Ok(())
    }

    /// The tracked signal.
    pub(crate) fn signal(&self) -> skyforge_gnss::signal::Signal {
        self.tracker.signal()
    }

    /// The channel declared loss of lock.
    pub(crate) fn is_lost(&self) -> bool {
        self.tracker.is_lost()
    }

    /// The carrier Doppler the loop tracks (Hz); before its first block, the acquisition's.
    pub(crate) fn doppler_hz(&self) -> f64 {
        self.doppler_hz
    }

    /// Whether the carrier loop ever locked (a channel lost before that was a false or
    /// too weak detection).
    pub(crate) fn ever_locked(&self) -> bool {
        self.ever_locked
    }

    /// Whether the channel is anchored in time (a subframe was decoded).
    pub(crate) fn is_timed(&self) -> bool {
        self.clock.transmit_time(0).is_some()
    }

    /// Decode the last block's bits and time its code epochs. `approx_time` gives the
    /// receiver's approximate GPST (s since the origin) at a sample, when it has one.
    pub(crate) fn digest(&mut self, nav: &mut NavData, approx_time: &dyn Fn(f64) -> Option<f64>) {
        let fs = self.sample_rate_hz;
        for r in std::mem::take(&mut self.records) {
            let k = self.clock.record(r.sample_index, r.integration_periods);
            if let Some(bit) = r.bit {
                self.clock.bit(bit.first_sample_index);
                for event in self.decoder.feed(&[bit.soft as f32]) {
                    if let NavEvent::Subframe(info) = &event {
                        let approx = approx_time(bit.first_sample_index as f64);
                        match nav.time_of_week(self.sat.system, info.week, info.tow_s, approx) {
                            Some(t) if self.clock.subframe(info.start_bit, t) => {
                                // A pilot's polarity was corrected before the decoder.
                                self.inverted = info.inverted != self.tracker.pilot_inverted();
                            }
                            _ => {}
                        }
                    }
                    nav.absorb(&event);
                }
            }
            self.ever_locked |= r.locked;
            self.doppler_hz = r.doppler_hz;
            if r.cycle_slip || r.loss_of_lock || !r.locked {
                self.slip = true;
            }
            if !r.locked {
                self.last_epoch = None;
                continue;
            }
            // The code epoch lies code_phase / code_rate before the record's first sample.
            let lead_s = r.code_phase_chips / r.code_rate_chips_per_s;
            let epoch_sample = r.sample_index as f64 - lead_s * fs;
            self.last_epoch = Some((k, epoch_sample));
            let Some(t_tx_s) = self.clock.transmit_time(k) else {
                continue;
            };
            self.queue.push_back(ChannelSample {
                sample_index: epoch_sample,
                t_tx_s,
                nco_phase_cycles: r.carrier_phase_cycles - r.doppler_hz * lead_s,
                doppler_hz: r.doppler_hz,
                cn0_dbhz: r.cn0_dbhz.unwrap_or(f64::NAN),
                slip: std::mem::take(&mut self.slip),
                inverted: self.inverted,
            });
        }
    }

    /// The sample index of the last code epoch of a channel that can take its time from
    /// another signal ([`Self::time_from`]): not yet timed, tracked on its pilot with the
    /// secondary code found (its carrier polarity then known without the data), locked.
    pub(crate) fn awaiting_time(&self) -> Option<f64> {
        let (_, sample) = self.last_epoch?;
        (!self.is_timed() && self.tracker.pilot_synchronised()).then_some(sample)
    }

    /// Time this channel from `sibling`, the timed code epoch of another signal of the
    /// same satellite at the same antenna nearest its own last one (a hand-over, as a
    /// multi-frequency receiver times its second signal from its first instead of waiting
    /// for that signal's own message; only where [`Self::awaiting_time`]). It gives this
    /// channel's epoch its transmit time to within the signals' delay differences; every
    /// signal's code periods start at whole multiples of the period in system time, so the
    /// nearest multiple is taken, and the hand-over is refused where that lies beyond
    /// [`HANDOVER_TOLERANCE_S`].
    pub(crate) fn time_from(&mut self, s: &ChannelSample) {
        let Some((k, sample)) = self.last_epoch else {
            return;
        };
        if self.awaiting_time().is_none() {
            return;
        }
        let predicted = s.t_tx_s + (sample - s.sample_index) / self.sample_rate_hz;
        let period = self.signal().code_period_s();
        let Some(t_tx_s) = whole_periods_near(predicted, period, HANDOVER_TOLERANCE_S) else {
            return;
        };
        self.clock.hand_over(k, t_tx_s);
        self.inverted = self.tracker.pilot_inverted();
    }
}
