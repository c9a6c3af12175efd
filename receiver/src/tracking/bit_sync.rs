//! Bit (and secondary-code) synchronisation from the signs of 1 ms prompts.
//!
//! - GPS LNAV and BeiDou D2: a histogram of sign changes between successive code periods
//!   over the period index modulo the bit length (20 or 2); data bits change sign only on
//!   bit edges, so one bin collects every true transition (Kaplan & Hegarty, 2nd ed.,
//!   section 5.12 "bit synchronization", the histogram method).
//! - BeiDou D1: the 20-chip Neumann-Hoffman code is found by correlating the prompt signs
//!   with it over `nh_bits` consecutive 20 ms windows at each of the 20 offsets; the NH
//!   code starts together with each data bit (BDS-SIS-ICD-B1I-3.0 §5.2.1), so the offset
//!   is also the bit edge.
//! - Pilot signals (GPS L5 Q5, Galileo E5a-Q): the same correlation with the pilot's
//!   secondary code (20 or 100 chips); the secondary code and the data symbols both start
//!   at the week start (a whole number of their periods), so the code's start gives the
//!   symbol edge, and the sign of the correlation the polarity of the carrier loop
//!   (the pilot carries no data).
//! - A long secondary code (BeiDou B1C's 1800 chips, 18 s): the signs of
//!   [`LONG_CODE_WINDOW`] consecutive periods are correlated with the code at each of its
//!   cyclic offsets, a window being far shorter than the code.

use std::collections::VecDeque;

use skyforge_gnss::codes::neumann_hoffman;

use skyforge_gnss::signal::DataModulation;

/// Secondary codes longer than this (chips) are searched by partial correlation over
/// [`LONG_CODE_WINDOW`] periods at every cyclic offset, not over whole code periods.
const LONG_CODE_CHIPS: usize = 200;
/// Periods (chips) correlated per offset in the search for a long code. # assumed: 200: a
/// wrong offset of a random code correlates with standard deviation sqrt(200) = 14 chips,
/// the largest of B1C's 1799 wrong offsets about 4 of them (57 chips), well inside the
/// decision's margins (at least 140 for the best, 60 above the runner-up).
const LONG_CODE_WINDOW: usize = 200;

/// Decision thresholds of the synchroniser.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct BitSyncConfig {
    /// Histogram: transitions the winning bin needs before a decision.
    pub min_transitions: u32,
    /// Histogram: the winning bin must hold at least this many times the runner-up.
    pub dominance: f64,
    /// NH correlation: 20 ms windows summed per offset.
    pub nh_bits: usize,
}

impl Default for BitSyncConfig {
    fn default() -> Self {
        Self {
            min_transitions: 8,
            dominance: 3.0,
            nh_bits: 5,
        }
    }
}

/// Bit synchroniser of one channel. Feed it the in-phase prompt of every code period, in
/// order; it returns the bit-edge phase (period index modulo the bit length at which bits
/// start) once it has decided.
#[derive(Debug, Clone, PartialEq)]
pub struct BitSynchroniser {
    modulation: DataModulation,
    config: BitSyncConfig,
    histogram: [u32; 20],
    last: Option<(u64, bool)>,
    /// The code the correlation search looks for: BeiDou D1's NH code, or a pilot's
    /// secondary code (empty for the histogram method).
    secondary: Vec<i8>,
    /// Correlation search: signs of consecutive periods, the first at `first_index`.
    signs: VecDeque<i8>,
    first_index: u64,
    edge: Option<u32>,
    /// Correlation search: period index modulo the code length where the code starts,
    /// and whether the prompts carried it inverted.
    found: Option<(u32, bool)>,
    /// The search is on a pilot's prompts ([`Self::for_pilot`]).
    pilot: bool,
}

impl BitSynchroniser {
    /// A synchroniser for `modulation`.
    pub fn new(modulation: DataModulation, config: BitSyncConfig) -> Self {
        let secondary = match modulation {
            DataModulation::BdsD1 => neumann_hoffman::NH20.to_vec(),
            _ => Vec::new(),
        };
        Self::searching(modulation, secondary, config, false)
    }

    /// A synchroniser for a signal with a pilot, on the pilot's prompts: it searches the
    /// pilot's secondary code `pilot_secondary` (a whole number of data symbols long).
    pub fn for_pilot(
        modulation: DataModulation,
        pilot_secondary: Vec<i8>,
        config: BitSyncConfig,
    ) -> Self {
        Self::searching(modulation, pilot_secondary, config, true)
    }

    fn searching(
        modulation: DataModulation,
        secondary: Vec<i8>,
        config: BitSyncConfig,
        pilot: bool,
    ) -> Self {
        Self {
            modulation,
            config: BitSyncConfig {
                nh_bits: config.nh_bits.max(1),
                ..config
            },
            histogram: [0; 20],
            last: None,
            secondary,
            signs: VecDeque::new(),
            first_index: 0,
            edge: None,
            found: None,
            pilot,
        }
    }

    /// The bit-edge phase once decided: bits start at period indices `k` with
    /// `k % periods_per_bit == edge`.
    pub fn edge_phase(&self) -> Option<u32> {
        self.edge
    }

    /// After a correlation search: the period index modulo the searched code's length at
    /// which the code starts, and whether the prompts carried it inverted.
    pub fn secondary_start(&self) -> Option<(u32, bool)> {
        self.found
    }

    /// A pilot synchroniser's wipe-off once the code is found: the secondary chip of code
    /// period `period_index` times the polarity (-1 when the prompts carried it inverted).
    pub fn pilot_wipe(&self, period_index: u64) -> Option<f64> {
        let (start, inverted) = self.secondary_start().filter(|_| self.pilot)?;
        let l = self.secondary.len() as u64;
        let chip = self.secondary[((period_index + l - u64::from(start) % l) % l) as usize];
        Some(if inverted {
            -f64::from(chip)
        } else {
            f64::from(chip)
        })
    }

    /// Whether a pilot synchroniser found the pilot inverted (the carrier loop half a
    /// cycle off).
    pub fn pilot_inverted(&self) -> bool {
        self.pilot && self.secondary_start().is_some_and(|(_, inverted)| inverted)
    }

    /// Add the in-phase prompt of code period `period_index`; returns the edge phase when
    /// (or once) decided. A gap in the period indices restarts the evidence chain.
    pub fn feed(&mut self, period_index: u64, prompt_i: f64) -> Option<u32> {
        if self.edge.is_some() {
            return self.edge;
        }
        let positive = prompt_i >= 0.0;
        let contiguous = self.last.is_some_and(|(k, _)| k + 1 == period_index);
        let ppb = self.modulation.periods_per_bit();
        if self.secondary.is_empty() {
            // GPS LNAV, BeiDou D2: the histogram.
            if let Some((_, was)) = self.last.filter(|_| contiguous)
                && was != positive
            {
                self.histogram[(period_index % u64::from(ppb)) as usize] += 1;
            }
            self.edge = self.histogram_decision(ppb as usize);
        } else {
            if !contiguous {
                self.signs.clear();
                self.first_index = period_index;
            }
            self.signs.push_back(if positive { 1 } else { -1 });
            self.found = if self.secondary.len() > LONG_CODE_CHIPS {
                self.cyclic_decision()
            } else {
                self.correlation_decision()
            };
            self.edge = self.found.map(|(start, _)| start % ppb);
        }
        self.last = Some((period_index, positive));
        self.edge
    }

    fn histogram_decision(&self, ppb: usize) -> Option<u32> {
        let bins = &self.histogram[..ppb];
        let (best, count, runner_up) = best_and_runner_up(bins)?;
        (count >= self.config.min_transitions
            && f64::from(count) >= self.config.dominance * f64::from(runner_up))
        .then_some(best as u32)
    }

    /// The code's start (period index modulo its length) and polarity once the signs of
    /// `windows` code lengths correlate with it clearly at one offset: `nh_bits` 20 ms
    /// windows' worth, and at least one code length.
    fn correlation_decision(&mut self) -> Option<(u32, bool)> {
        let code = &self.secondary;
        let l = code.len();
        let windows = (self.config.nh_bits * neumann_hoffman::NH20_LENGTH).div_ceil(l);
        if self.signs.len() < l * windows + l - 1 {
            return None;
        }
        // Per offset: the sum of each window's |correlation|, and of the signed ones.
        let mut scores = vec![0i32; l];
        let mut signed = vec![0i32; l];
        for r in 0..l {
            for w in 0..windows {
                let corr: i32 = (0..l)
                    .map(|m| i32::from(self.signs[r + l * w + m]) * i32::from(code[m]))
                    .sum();
                scores[r] += corr.abs();
                signed[r] += corr;
            }
        }
        let (best, top, runner_up) = best_and_runner_up(&scores)?;
        let full = (l * windows) as i32;
        if 10 * top >= 7 * full && 10 * (top - runner_up) >= 3 * full {
            let start = ((self.first_index + best as u64) % l as u64) as u32;
            return Some((start, signed[best] < 0));
        }
        // Slide the search on by one window.
        self.signs.drain(..l);
        self.first_index += l as u64;
        None
    }
}

impl BitSynchroniser {
    /// A long code's start and polarity once the signs of [`LONG_CODE_WINDOW`] periods
    /// correlate clearly with it at one cyclic offset (the same margins as
    /// [`Self::correlation_decision`]); otherwise the window moves on by its length.
    fn cyclic_decision(&mut self) -> Option<(u32, bool)> {
        let (code, n) = (&self.secondary, LONG_CODE_WINDOW);
        let l = code.len();
        if self.signs.len() < n {
            return None;
        }
        // signed[r]: the window's correlation with the code from chip r on.
        let signed: Vec<i32> = (0..l)
            .map(|r| {
                (0..n)
                    .map(|m| i32::from(self.signs[m]) * i32::from(code[(r + m) % l]))
                    .sum()
            })
            .collect();
        let scores: Vec<i32> = signed.iter().map(|c| c.abs()).collect();
        let (best, top, runner_up) = best_and_runner_up(&scores)?;
        let full = n as i32;
        if 10 * top >= 7 * full && 10 * (top - runner_up) >= 3 * full {
            // The window's first period carries chip `best`: the code started `best`
            // periods before it.
            let start = (self.first_index + (l - best) as u64) % l as u64;
            return Some((start as u32, signed[best] < 0));
        }
        self.signs.drain(..n);
        self.first_index += n as u64;
        None
    }

    /// Once a pilot's secondary code is found: the chip of it that code period
    /// `period_index` carries (0: the code, and for B1C the frame, starts there).
    pub fn secondary_chip(&self, period_index: u64) -> Option<u64> {
        let (start, _) = self.secondary_start().filter(|_| self.pilot)?;
        let l = self.secondary.len() as u64;
        Some((period_index + l - u64::from(start) % l) % l)
    }
}

/// The index of the largest score (the last of equals), that score, and the largest of the
/// others (zero when there are none); `None` for no scores.
fn best_and_runner_up<T: Copy + Ord + Default>(scores: &[T]) -> Option<(usize, T, T)> {
    let (best, &top) = scores.iter().enumerate().max_by_key(|(_, s)| **s)?;
    let runner_up = scores
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != best)
        .map(|(_, s)| *s)
        .max()
        .unwrap_or_default();
    Some((best, top, runner_up))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Prompt I of period k for bits starting at `edge`, with `sign_at(k)` (NH or 1).
    fn feed_bits(
        sync: &mut BitSynchroniser,
        ppb: u64,
        edge: u64,
        periods: u64,
        nh: bool,
    ) -> Option<(u64, u32)> {
        let mut x: u32 = 99;
        let mut bit = 1.0;
        for k in 0..periods {
            if k % ppb == edge {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                bit = if x >> 30 & 1 == 0 { 1.0 } else { -1.0 };
            }
            let chip = if nh {
                f64::from(neumann_hoffman::NH20[((k + ppb - edge) % ppb) as usize])
            } else {
                1.0
            };
            // Start at period 1000 so the phase is not trivially the index.
            if let Some(e) = sync.feed(1000 + k, bit * chip * 3.0) {
                return Some((k, e));
            }
        }
        None
    }

    #[test]
    fn gps_histogram_finds_the_edge() {
        for edge in [0u64, 7, 19] {
            let mut sync = BitSynchroniser::new(DataModulation::GpsLnav, BitSyncConfig::default());
            let (after, e) = feed_bits(&mut sync, 20, edge, 2000, false).unwrap();
            assert_eq!(u64::from(e), (1000 + edge) % 20);
            assert!(after < 1000, "{after}");
        }
    }

    #[test]
    fn d2_histogram_finds_the_two_millisecond_edge() {
        for edge in [0u64, 1] {
            let mut sync = BitSynchroniser::new(DataModulation::BdsD2, BitSyncConfig::default());
            let (_, e) = feed_bits(&mut sync, 2, edge, 200, false).unwrap();
            assert_eq!(u64::from(e), (1000 + edge) % 2);
        }
    }

    #[test]
    fn nh_correlation_finds_the_code_start() {
        for edge in [0u64, 5, 13, 19] {
            let mut sync = BitSynchroniser::new(DataModulation::BdsD1, BitSyncConfig::default());
            let (after, e) = feed_bits(&mut sync, 20, edge, 1000, true).unwrap();
            assert_eq!(u64::from(e), (1000 + edge) % 20, "edge {edge}");
            assert!(after < 140, "{after}");
        }
    }

    #[test]
    fn nh_signs_without_the_code_do_not_sync() {
        let mut sync = BitSynchroniser::new(DataModulation::BdsD1, BitSyncConfig::default());
        assert!(feed_bits(&mut sync, 20, 3, 2000, false).is_none());
    }

    /// A pilot's secondary code (E5a-Q's and B2a_p's 100 chips of PRN 7, L5 Q5's NH20)
    /// found at its start with the prompts' polarity; the symbol edge follows from the
    /// start.
    #[test]
    fn pilot_secondary_code_gives_start_edge_and_polarity() {
        use skyforge_gnss::signal::Signal;
        for (signal, start, inverted) in [
            (Signal::GalE5a, 0u64, false),
            (Signal::GalE5a, 63, true),
            (Signal::GpsL5, 17, true),
            (Signal::GpsL5, 4, false),
            (Signal::BdsB2a, 37, true),
            (Signal::BdsB2a, 2, false),
        ] {
            let code = signal.pilot(7).unwrap().secondary;
            let l = code.len() as u64;
            let m = signal.data_modulation(7).unwrap();
            let mut sync = BitSynchroniser::for_pilot(m, code.clone(), BitSyncConfig::default());
            let sign = if inverted { -2.0 } else { 2.0 };
            let decided = (0..1000u64).find_map(|k| {
                let chip = f64::from(code[((k + l - start % l) % l) as usize]);
                sync.feed(1000 + k, sign * chip)
            });
            let expected_start = ((1000 + start) % l) as u32;
            assert_eq!(
                sync.secondary_start(),
                Some((expected_start, inverted)),
                "{signal} {start}"
            );
            assert_eq!(decided, Some(expected_start % m.periods_per_bit()));
        }
        // Another satellite's E5a-Q code does not sync.
        assert_eq!(
            BitSynchroniser::new(DataModulation::GpsLnav, BitSyncConfig::default())
                .secondary_chip(5),
            None
        );
        let other = Signal::GalE5a.pilot(8).unwrap().secondary;
        let code = Signal::GalE5a.pilot(7).unwrap().secondary;
        let mut sync =
            BitSynchroniser::for_pilot(DataModulation::GalFnav, code, BitSyncConfig::default());
        assert!((0..1000u64).all(|k| sync.feed(k, f64::from(other[(k % 100) as usize])).is_none()));
    }

    /// B1C's 1800-chip secondary code (PRN 30), fed from chip 1234 on, inverted: found
    /// from one window of 200 periods, with the chip each later period carries; another
    /// PRN's code never syncs.
    #[test]
    fn b1c_long_secondary_code_is_found_from_a_window() {
        use skyforge_gnss::signal::Signal;
        let code = Signal::BdsB1C.pilot(30).unwrap().secondary;
        let m = DataModulation::BdsCnav1;
        let mut sync = BitSynchroniser::for_pilot(m, code.clone(), BitSyncConfig::default());
        let decided = (0..1000u64).find_map(|k| {
            let chip = f64::from(code[((1234 + k) % 1800) as usize]);
            sync.feed(500 + k, -chip).map(|e| (k, e))
        });
        assert_eq!(decided, Some((199, 0)));
        // Period 500 carried chip 1234: the code started at period 500 - 1234 (mod 1800),
        // 1066.
        assert_eq!(sync.secondary_start(), Some((1066, true)));
        assert_eq!(sync.secondary_chip(500 + 566), Some(0));
        assert_eq!(sync.pilot_wipe(501), Some(-f64::from(code[1235])));
        let other = Signal::BdsB1C.pilot(31).unwrap().secondary;
        let mut sync = BitSynchroniser::for_pilot(m, code, BitSyncConfig::default());
        assert!((0..3600u64).all(|k| {
            sync.feed(k, f64::from(other[(k % 1800) as usize]))
                .is_none()
        }));
    }
}
