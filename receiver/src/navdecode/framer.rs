//! Subframe synchronisation shared by the GPS and BeiDou decoders: a buffer of hard bits,
//! a preamble search in both polarities confirmed by a message-specific header check, and
//! the locked state that hands out one 300-bit subframe after another.

use super::{DecodeStats, NavEvent, SUBFRAME_BITS, WEEK_S, hard_bit};

/// Consecutive failures (missing preamble or rejected subframe) that end the lock.
const MAX_FAILURES: u8 = 3;
/// When the lock is lost, the search restarts this many bits before the expected
/// subframe start (a bit slip moves the preamble by one or two bits).
const SEARCH_BACK_BITS: u64 = 8;
/// Bits kept before the read position (the previous word's D29, D30 and the search-back
/// margin).
const KEEP_BEFORE_BITS: u64 = 16;

/// What a message looks like to the framer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct FrameSpec {
    /// The preamble, right-aligned, first transmitted bit most significant.
    pub preamble: u32,
    /// Preamble length (bits).
    pub preamble_len: u32,
    /// Bits from a candidate subframe start that the confirmation needs.
    pub confirm_len: usize,
    /// Preamble bits that may be wrong at an expected subframe start while locked.
    pub locked_tolerance: u32,
}

/// One step of the framer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Framed {
    /// The search confirmed a subframe start.
    SyncAcquired { start_bit: u64, inverted: bool },
    /// Too many failures: searching again.
    SyncLost { at_bit: u64 },
    /// No preamble where the next subframe should start; the subframe is skipped.
    NoPreamble { start_bit: u64 },
    /// A subframe, polarity corrected: the two bits before it then its 300 bits.
    Subframe {
        start_bit: u64,
        inverted: bool,
        bits: Vec<u8>,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    Search {
        next: u64,
    },
    Locked {
        next: u64,
        inverted: bool,
        failures: u8,
    },
}

/// Bit buffer and synchronisation state.
#[derive(Debug, Clone)]
pub(crate) struct Framer {
    spec: FrameSpec,
    /// Hard bits; `bits[0]` is stream bit `base`.
    bits: Vec<u8>,
    base: u64,
    state: State,
}

impl Framer {
    pub fn new(spec: FrameSpec) -> Self {
        Self {
            spec,
            bits: Vec::with_capacity(4 * SUBFRAME_BITS),
            base: 0,
            state: State::Search { next: 0 },
        }
    }

    /// Append soft bits (hard decisions are stored).
    pub fn push(&mut self, soft: &[f32]) {
        self.bits.extend(soft.iter().map(|&s| hard_bit(s)));
    }

    /// Forget the buffered bits and search again from the next bit pushed.
    pub fn restart(&mut self) {
        self.base = self.end();
        self.bits.clear();
        self.state = State::Search { next: self.base };
    }

    /// Index of the next bit to be pushed.
    pub fn end(&self) -> u64 {
        self.base + self.bits.len() as u64
    }

    /// Whether a subframe start is being tracked.
    pub fn is_locked(&self) -> bool {
        matches!(self.state, State::Locked { .. })
    }

    /// The next step, or `None` when more bits are needed. `confirm` judges a search
    /// candidate from its polarity-corrected window (two bits before, then
    /// `spec.confirm_len` bits).
    pub fn poll(&mut self, confirm: impl Fn(&[u8]) -> bool) -> Option<Framed> {
        loop {
            match self.state {
                State::Search { next } => {
                    let next = next.max(self.base);
                    if next + self.spec.confirm_len as u64 > self.end() {
                        self.state = State::Search { next };
                        self.trim(next);
                        return None;
                    }
                    for inverted in [false, true] {
                        if self.preamble_errors(next, inverted) == 0
                            && confirm(&self.window(next, self.spec.confirm_len, inverted))
                        {
                            self.state = State::Locked {
                                next,
                                inverted,
                                failures: 0,
                            };
                            return Some(Framed::SyncAcquired {
                                start_bit: next,
                                inverted,
                            });
                        }
                    }
                    self.state = State::Search { next: next + 1 };
                }
                State::Locked {
                    next,
                    inverted,
                    failures,
                } => {
                    if next + SUBFRAME_BITS as u64 > self.end() {
                        self.trim(next);
                        return None;
                    }
                    let polarity =
                        if self.preamble_errors(next, inverted) <= self.spec.locked_tolerance {
                            Some(inverted)
                        } else if self.preamble_errors(next, !inverted) == 0 {
                            Some(!inverted)
                        } else {
                            None
                        };
                    let after = next + SUBFRAME_BITS as u64;
                    return Some(match polarity {
                        Some(inv) => {
                            self.state = State::Locked {
                                next: after,
                                inverted: inv,
                                failures,
                            };
                            Framed::Subframe {
                                start_bit: next,
                                inverted: inv,
                                bits: self.window(next, SUBFRAME_BITS, inv),
                            }
                        }
                        None => {
                            self.state = State::Locked {
                                next: after,
                                inverted,
                                failures,
                            };
                            match self.record(false, next) {
                                Some(lost) => lost,
                                None => Framed::NoPreamble { start_bit: next },
                            }
                        }
                    });
                }
            }
        }
    }

    /// Tell the framer whether the last subframe of the subframe starting at `start_bit`
    /// was accepted; after [`MAX_FAILURES`] consecutive failures the lock ends and the
    /// search restarts just before `start_bit`, which is returned as [`Framed::SyncLost`].
    pub fn record(&mut self, ok: bool, start_bit: u64) -> Option<Framed> {
        let State::Locked {
            next,
            inverted,
            failures,
        } = self.state
        else {
            return None;
        };
        let failures = if ok { 0 } else { failures + 1 };
        if failures >= MAX_FAILURES {
            self.state = State::Search {
                next: start_bit.saturating_sub(SEARCH_BACK_BITS),
            };
            return Some(Framed::SyncLost { at_bit: start_bit });
        }
        self.state = State::Locked {
            next,
            inverted,
            failures,
        };
        None
    }

    /// Stream bit `abs`, if still buffered.
    fn bit(&self, abs: u64) -> Option<u8> {
        let k = abs.checked_sub(self.base)?;
        self.bits.get(usize::try_from(k).ok()?).copied()
    }

    /// Number of preamble bits that differ from the bits at `start` (complemented if
    /// `inverted`); bits not available count as wrong.
    fn preamble_errors(&self, start: u64, inverted: bool) -> u32 {
        let n = self.spec.preamble_len;
        (0..n)
            .filter(|&k| {
                let want = ((self.spec.preamble >> (n - 1 - k)) & 1) as u8;
                self.bit(start + u64::from(k))
                    .is_none_or(|b| (b ^ u8::from(inverted)) != want)
            })
            .count() as u32
    }

    /// Two bits before `start` then `len` bits from it, complemented if `inverted`.
    /// Missing earlier bits read as 0 (the true-polarity value the GPS t bits force at the
    /// end of every subframe, IS-GPS-200 20.3.5.2; BeiDou does not use them).
    fn window(&self, start: u64, len: usize, inverted: bool) -> Vec<u8> {
        let inv = u8::from(inverted);
        (0..len as u64 + 2)
            .map(|k| {
                (start + k)
                    .checked_sub(2)
                    .and_then(|abs| self.bit(abs))
                    .map_or(0, |b| b ^ inv)
            })
            .collect()
    }

    /// Drop bits well before `cursor`.
    fn trim(&mut self, cursor: u64) {
        let keep_from = cursor.saturating_sub(KEEP_BEFORE_BITS);
        if keep_from > self.base + 2 * SUBFRAME_BITS as u64 {
            let n = (keep_from - self.base) as usize;
            self.bits.drain(..n.min(self.bits.len()));
            self.base = keep_from;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> FrameSpec {
        FrameSpec {
            preamble: 0b1011,
            preamble_len: 4,
            confirm_len: 8,
            locked_tolerance: 0,
        }
    }

    /// Soft values of hard bits (0 -> +1, 1 -> -1).
    fn soft(bits: &[u8]) -> Vec<f32> {
        bits.iter()
            .map(|&b| if b == 0 { 1.0 } else { -1.0 })
            .collect()
    }

    /// Subframes of 300 bits starting with the preamble, the rest zeros except, with
    /// `marker`, bit 10 of odd subframes.
    fn stream(n: usize, invert: bool, marker: bool) -> Vec<u8> {
        let mut out = Vec::new();
        for k in 0..n {
            let mut sf = vec![0u8; SUBFRAME_BITS];
            sf[..4].copy_from_slice(&[1, 0, 1, 1]);
            sf[10] = u8::from(marker && k % 2 == 1);
            out.extend(sf);
        }
        if invert {
            out.iter_mut().for_each(|b| *b ^= 1);
        }
        out
    }

    #[test]
    fn finds_subframes_in_both_polarities_from_mid_stream() {
        for invert in [false, true] {
            let bits = stream(4, invert, true);
            let mut f = Framer::new(spec());
            f.push(&soft(&bits[123..]));
            let mut starts = Vec::new();
            let mut acquired = None;
            while let Some(x) = f.poll(|w| w.len() == 10) {
                match x {
                    Framed::SyncAcquired {
                        start_bit,
                        inverted,
                    } => acquired = Some((start_bit, inverted)),
                    Framed::Subframe {
                        start_bit,
                        inverted,
                        bits,
                    } => {
                        assert_eq!(inverted, invert);
                        assert_eq!(&bits[2..6], &[1, 0, 1, 1]);
                        starts.push(start_bit);
                    }
                    other => panic!("{other:?}"),
                }
            }
            assert_eq!(acquired, Some((177, invert)));
            assert_eq!(starts, [177, 477, 777]);
        }
    }

    #[test]
    fn missing_preambles_end_the_lock() {
        let mut bits = stream(8, false, false);
        for k in 3..8 {
            bits[k * SUBFRAME_BITS] ^= 1;
        }
        let mut f = Framer::new(spec());
        f.push(&soft(&bits));
        let mut seen = Vec::new();
        while let Some(x) = f.poll(|_| true) {
            seen.push(x);
        }
        let lost = seen
            .iter()
            .position(|x| matches!(x, Framed::SyncLost { at_bit: 1500 }));
        assert!(lost.is_some(), "{seen:?}");
        let no_preamble = seen
            .iter()
            .filter(|x| matches!(x, Framed::NoPreamble { .. }))
            .count();
        assert_eq!(no_preamble, 2, "{seen:?}");
    }
}

/// What every decoder keeps around its framer: the statistics and the time anchor (stream
/// bit and time of week of the last accepted subframe start), and the handling of the
/// framer's bookkeeping steps.
#[derive(Debug, Clone)]
pub(crate) struct FramedStream {
    pub framer: Framer,
    pub stats: DecodeStats,
    pub anchor: Option<(u64, f64)>,
}

impl FramedStream {
    pub fn new(spec: FrameSpec) -> Self {
        Self {
            framer: Framer::new(spec),
            stats: DecodeStats::default(),
            anchor: None,
        }
    }

    /// Buffer the next soft bits.
    pub fn push(&mut self, soft_bits: &[f32]) {
        self.stats.bits += soft_bits.len() as u64;
        self.framer.push(soft_bits);
    }

    /// The next subframe (start bit, inversion, bits) of the bits pushed so far, the
    /// framer's other steps turned into events on the way; `None` when more bits are
    /// needed.
    pub fn next_subframe(
        &mut self,
        confirm: impl Fn(&[u8]) -> bool,
        out: &mut Vec<NavEvent>,
    ) -> Option<(u64, bool, Vec<u8>)> {
        while let Some(step) = self.framer.poll(&confirm) {
            if let Some(subframe) = self.bookkeeping(step, out) {
                return Some(subframe);
            }
        }
        None
    }

    /// Sync acquired or lost and missing preambles become events (and counts); a subframe
    /// (start bit, inversion, bits) is handed back for the message-specific decoding.
    fn bookkeeping(
        &mut self,
        step: Framed,
        out: &mut Vec<NavEvent>,
    ) -> Option<(u64, bool, Vec<u8>)> {
        match step {
            Framed::SyncAcquired {
                start_bit,
                inverted,
            } => {
                self.anchor = None;
                out.push(NavEvent::SyncAcquired {
                    start_bit,
                    inverted,
                });
                None
            }
            Framed::SyncLost { at_bit } => {
                self.sync_lost(at_bit, out);
                None
            }
            Framed::NoPreamble { start_bit } => {
                self.stats.dropped_subframes += 1;
                out.push(NavEvent::SubframeDropped {
                    start_bit,
                    words: 0,
                });
                None
            }
            Framed::Subframe {
                start_bit,
                inverted,
                bits,
            } => Some((start_bit, inverted, bits)),
        }
    }

    /// The subframe at `start_bit` was rejected (`words`: which of its words were bad).
    pub fn drop_subframe(&mut self, start_bit: u64, words: u16, out: &mut Vec<NavEvent>) {
        self.stats.dropped_subframes += 1;
        out.push(NavEvent::SubframeDropped { start_bit, words });
        self.record(false, start_bit, out);
    }

    /// The subframe at `start_bit`, time of week `tow_s`, was accepted: it becomes the
    /// anchor, and `week` moves on when the time of week went back by more than half a
    /// week since the last anchor (a week crossing).
    pub fn accept(
        &mut self,
        start_bit: u64,
        tow_s: f64,
        week: &mut Option<u32>,
        out: &mut Vec<NavEvent>,
    ) {
        self.record(true, start_bit, out);
        if let (Some(w), Some((_, last))) = (*week, self.anchor)
            && tow_s < last - WEEK_S / 2.0
        {
            *week = Some(w + 1);
        }
        self.anchor = Some((start_bit, tow_s));
        self.stats.subframes += 1;
    }

    /// Tell the framer whether the subframe at `start_bit` was accepted.
    fn record(&mut self, ok: bool, start_bit: u64, out: &mut Vec<NavEvent>) {
        if let Some(Framed::SyncLost { at_bit }) = self.framer.record(ok, start_bit) {
            self.sync_lost(at_bit, out);
        }
    }

    fn sync_lost(&mut self, at_bit: u64, out: &mut Vec<NavEvent>) {
        self.stats.sync_losses += 1;
        self.anchor = None;
        out.push(NavEvent::SyncLost { at_bit });
    }

    /// Forget the stream (after a tracking gap).
    pub fn restart(&mut self) {
        self.framer.restart();
        self.anchor = None;
    }
}
