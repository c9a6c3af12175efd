//! Transmit time of a channel's code epochs: the code periods are counted from the
//! hand-over, each data bit remembers the period it began in, and a decoded subframe ties
//! the period of its first bit to the time of week it carries. From then on every code
//! epoch has a transmit time `t_anchor + (period - period_anchor) T_code`. A signal with a
//! pilot may instead be anchored by another signal of its satellite (a hand-over).

use std::collections::VecDeque;

/// Records kept to find the code period a data bit began in (a bit spans at most 20).
const RECENT_RECORDS: usize = 64;
/// Bits kept to find the start of a decoded subframe: the decoder reports a subframe after
/// its 300 bits, a B-CNAV1 frame after its 1800 symbols, possibly a few more later.
const RECENT_BITS: usize = 2048;

/// Code-period bookkeeping of one channel.
#[derive(Debug, Clone)]
pub(crate) struct CodeClock {
    code_period_s: f64,
    /// Code periods before the next record's first period.
    periods: u64,
    /// (first sample, code period) of recent records.
    records: VecDeque<(u64, u64)>,
    /// Data bits fed to the decoder so far.
    bits: u64,
    /// (bit index, code period of its start) of recent bits.
    bit_periods: VecDeque<(u64, u64)>,
    /// (code period, transmit time (s)) of the last decoded subframe start.
    anchor: Option<(u64, f64)>,
}

impl CodeClock {
    pub(crate) fn new(code_period_s: f64) -> Self {
        Self {
            code_period_s,
            periods: 0,
            records: VecDeque::with_capacity(RECENT_RECORDS),
            bits: 0,
            bit_periods: VecDeque::with_capacity(RECENT_BITS),
            anchor: None,
        }
    }

    /// A tracking record starting at `first_sample` and integrating `periods` code
    /// periods: returns the code period it starts with.
    pub(crate) fn record(&mut self, first_sample: u64, periods: u32) -> u64 {
        let k = self.periods;
        if self.records.len() == RECENT_RECORDS {
            self.records.pop_front();
        }
        self.records.push_back((first_sample, k));
        self.periods += u64::from(periods);
        k
    }

    /// A data bit whose first code period starts at `first_sample` was fed to the decoder;
    /// returns its bit index.
    pub(crate) fn bit(&mut self, first_sample: u64) -> u64 {
        let index = self.bits;
        self.bits += 1;
        if let Some(&(_, k)) = self.records.iter().rev().find(|r| r.0 == first_sample) {
            if self.bit_periods.len() == RECENT_BITS {
                self.bit_periods.pop_front();
            }
            self.bit_periods.push_back((index, k));
        }
        index
    }

    /// A subframe whose first bit is `start_bit` was sent at `t_tx_s`: anchor the code
    /// periods to it. Returns false when that bit is no longer known.
    pub(crate) fn subframe(&mut self, start_bit: u64, t_tx_s: f64) -> bool {
        match self.bit_periods.iter().find(|b| b.0 == start_bit) {
            Some(&(_, k)) => {
                self.anchor = Some((k, t_tx_s));
                true
            }
            None => false,
        }
    }

    /// Code period `k` was sent at `t_tx_s`, as another signal of the same satellite says
    /// ([`super::channel::Channel::time_from`]): anchor the code periods to it.
    pub(crate) fn hand_over(&mut self, k: u64, t_tx_s: f64) {
        self.anchor = Some((k, t_tx_s));
    }

    /// Transmit time of the start of code period `k`, once anchored.
    pub(crate) fn transmit_time(&self, k: u64) -> Option<f64> {
        self.anchor
            .map(|(ka, ta)| ta + (k as f64 - ka as f64) * self.code_period_s)
    }
}

/// The whole multiple of `period_s` nearest `t_s`, if within `tolerance_s` of it: a code
/// epoch's transmit time from a prediction (code periods start at whole multiples of the
/// period in system time).
pub(crate) fn whole_periods_near(t_s: f64, period_s: f64, tolerance_s: f64) -> Option<f64> {
    let t = (t_s / period_s).round() * period_s;
    ((t - t_s).abs() <= tolerance_s).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_prediction_snaps_to_the_nearest_code_epoch_or_is_refused() {
        // 1 ms periods a day into the week: 0.2 us late, 3 us early, 0.4 ms off.
        let t = 86_400.123;
        assert!((whole_periods_near(t + 0.2e-6, 1e-3, 10e-6).unwrap() - t).abs() < 1e-9);
        assert!((whole_periods_near(t - 3e-6, 1e-3, 10e-6).unwrap() - t).abs() < 1e-9);
        assert_eq!(whole_periods_near(t + 0.4e-3, 1e-3, 10e-6), None);
        // 4 ms periods (E1): 86 400.124 is one, 86 400.123 is not.
        assert!(
            (whole_periods_near(86_400.124 - 1e-6, 4e-3, 10e-6).unwrap() - 86_400.124).abs() < 1e-9
        );
        assert_eq!(whole_periods_near(t, 4e-3, 10e-6), None);
    }

    #[test]
    fn code_epochs_get_the_time_of_the_subframe_that_contains_them() {
        // 1 ms periods of 4000 samples, 20-period bits from period 7 on.
        let mut c = CodeClock::new(1e-3);
        let mut bit_of_period = std::collections::HashMap::new();
        for k in 0..400u64 {
            let first = 1000 + 4000 * k;
            assert_eq!(c.record(first, 1), k);
            if k >= 7 && (k - 7) % 20 == 19 {
                let start = k - 19;
                let b = c.bit(1000 + 4000 * start);
                bit_of_period.insert(b, start);
            }
        }
        assert_eq!(c.transmit_time(10), None);
        // Bit 5 started a subframe sent at t = 100 s: period 7 + 5 x 20 = 107.
        assert!(c.subframe(5, 100.0));
        assert_eq!(bit_of_period[&5], 107);
        assert!((c.transmit_time(107).unwrap() - 100.0).abs() < 1e-12);
        assert!((c.transmit_time(399).unwrap() - 100.292).abs() < 1e-9);
        assert!(!c.subframe(10_000, 1.0));
    }
}
