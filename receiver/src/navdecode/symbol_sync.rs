//! Message synchronisation on channel symbols, shared by the GPS L5 CNAV, Galileo F/NAV and
//! I/NAV and BeiDou B-CNAV2 and B-CNAV1 decoders: a buffer of soft symbols, a search for a message start (the format proposes
//! candidates, its own decoding with CRC confirms one), and the locked state that decodes
//! one message every period, giving up after repeated failures as [`super::framer`]
//! does for the 300-bit subframes.

use super::{DecodeStats, NavDecoder, NavEvent};
use skyforge_orbits::ephemeris::SatId;

/// Consecutive failed messages that end the lock.
const MAX_FAILURES: u8 = 3;
/// When the lock is lost, the search restarts this many symbols before the expected
/// message start (a slip moves the start by a symbol or two).
const SEARCH_BACK_SYMBOLS: u64 = 8;
/// Buffered symbols before the oldest one still needed, kept before the buffer is cut.
const TRIM_SLACK_SYMBOLS: u64 = 1024;

/// What a message format tells the synchroniser.
pub(crate) trait SymbolFormat {
    /// A decoded message.
    type Message;
    /// Symbols from one message start to the next.
    const PERIOD: u64;
    /// Symbols before a message start that its decoding takes (the start of a stream
    /// reads as erasures, 0.0).
    const LEAD_IN: u64;
    /// Symbols from a message start on that its decoding takes.
    const SPAN: u64;

    /// The candidate message starts of a search window, which holds `LEAD_IN` symbols,
    /// then the `PERIOD` candidate positions, then `SPAN` symbols: offsets below `PERIOD`
    /// from the first candidate position, each with the polarity it suggests.
    fn candidates(&self, window: &[f32]) -> Vec<(u64, bool)>;

    /// Decode the message whose `LEAD_IN + SPAN` symbols are `window`, trying polarity
    /// `inverted` first: the message and the polarity it was received in.
    fn decode(&self, window: &[f32], inverted: bool) -> Option<(Self::Message, bool)>;
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    /// The next candidate position to examine.
    Search { next: u64 },
    /// Locked since the message at `since`; the next message starts at `next`.
    Locked {
        since: u64,
        next: u64,
        inverted: bool,
        failures: u8,
    },
}

/// A decoder built on a [`SymbolSync`] (GPS CNAV, Galileo F/NAV and I/NAV, BeiDou
/// B-CNAV2): its synchroniser and format, its satellite and what it makes of a message;
/// the [`NavDecoder`] around them is written once, below.
pub(crate) trait SyncedDecoder: Send {
    type Format: SymbolFormat;
    /// The synchroniser and the format it frames.
    fn parts(&mut self) -> (&mut SymbolSync, &Self::Format);
    /// The synchroniser.
    fn symbol_sync(&self) -> &SymbolSync;
    /// The satellite whose message this is.
    fn sat(&self) -> SatId;
    /// Use the message decoded at stream symbol `start` (`inverted`: its polarity).
    fn message(
        &mut self,
        start: u64,
        inverted: bool,
        msg: &<Self::Format as SymbolFormat>::Message,
        out: &mut Vec<NavEvent>,
    );
}

impl<D: SyncedDecoder> NavDecoder for D {
    fn feed(&mut self, soft_bits: &[f32]) -> Vec<NavEvent> {
        let mut out = Vec::new();
        self.parts().0.push(soft_bits);
        loop {
            let (sync, format) = self.parts();
            let Some((start, inverted, msg)) = sync.next(format, &mut out) else {
                return out;
            };
            self.message(start, inverted, &msg, &mut out);
        }
    }

    fn restart(&mut self) {
        self.parts().0.restart();
    }

    fn stats(&self) -> DecodeStats {
        self.symbol_sync().stats
    }

    fn satellite(&self) -> SatId {
        self.sat()
    }
}

/// Soft-symbol buffer, synchronisation state and counters.
#[derive(Debug, Clone)]
pub(crate) struct SymbolSync {
    /// Soft symbols; `soft[0]` is stream symbol `base`.
    soft: Vec<f32>,
    base: u64,
    state: State,
    pub stats: DecodeStats,
}

impl SymbolSync {
    pub fn new() -> Self {
        Self {
            soft: Vec::new(),
            base: 0,
            state: State::Search { next: 0 },
            stats: DecodeStats::default(),
        }
    }

    /// A synchroniser whose stream has a message start at symbol `start` (known from
    /// elsewhere, as B1C's secondary code gives B-CNAV1's frames): locked from there on,
    /// in normal polarity.
    pub fn locked_at(start: u64) -> Self {
        Self {
            state: State::Locked {
                since: start,
                next: start,
                inverted: false,
                failures: 0,
            },
            ..Self::new()
        }
    }

    /// Append soft symbols (non-finite values become erasures).
    pub fn push(&mut self, soft: &[f32]) {
        self.stats.bits += soft.len() as u64;
        let finite = |x: f32| if x.is_finite() { x } else { 0.0 };
        self.soft.extend(soft.iter().map(|&x| finite(x)));
    }

    /// Forget the buffered symbols and search again from the next one pushed.
    pub fn restart(&mut self) {
        self.base = self.end();
        self.soft.clear();
        self.state = State::Search { next: self.base };
    }

    /// The message start where the current lock began, if locked.
    pub fn locked_since(&self) -> Option<u64> {
        match self.state {
            State::Locked { since, .. } => Some(since),
            State::Search { .. } => None,
        }
    }

    /// The next decoded message (its first symbol's index, its polarity, the message) of
    /// the symbols pushed so far; sync events and dropped messages go to `out` on the
    /// way. `None` when more symbols are needed.
    pub fn next<F: SymbolFormat>(
        &mut self,
        format: &F,
        out: &mut Vec<NavEvent>,
    ) -> Option<(u64, bool, F::Message)> {
        loop {
            match self.state {
                State::Search { next } => {
                    let next = next.max(self.base);
                    self.state = State::Search { next };
                    if next + F::PERIOD + F::SPAN > self.end() {
                        self.trim(next.saturating_sub(F::LEAD_IN));
                        return None;
                    }
                    if let Some(found) = self.search(format, next, out) {
                        return Some(found);
                    }
                    self.state = State::Search {
                        next: next + F::PERIOD,
                    };
                }
                State::Locked {
                    since,
                    next,
                    inverted,
                    failures,
                } => {
                    if next + F::SPAN > self.end() {
                        let keep = next.saturating_sub(F::LEAD_IN + SEARCH_BACK_SYMBOLS);
                        self.trim(keep);
                        return None;
                    }
                    let window = self.window(next, F::LEAD_IN, F::SPAN);
                    if let Some((message, inv)) = format.decode(&window, inverted) {
                        self.state = State::Locked {
                            since,
                            next: next + F::PERIOD,
                            inverted: inv,
                            failures: 0,
                        };
                        self.stats.subframes += 1;
                        return Some((next, inv, message));
                    }
                    self.fail::<F>(since, next, inverted, failures, out);
                }
            }
        }
    }

    /// Examine the candidates at `next .. next + PERIOD`; lock on the first that decodes.
    fn search<F: SymbolFormat>(
        &mut self,
        format: &F,
        next: u64,
        out: &mut Vec<NavEvent>,
    ) -> Option<(u64, bool, F::Message)> {
        let window = self.window(next, F::LEAD_IN, F::PERIOD + F::SPAN);
        for (offset, hint) in format.candidates(&window) {
            let start = next + offset;
            let window = self.window(start, F::LEAD_IN, F::SPAN);
            if let Some((message, inverted)) = format.decode(&window, hint) {
                self.state = State::Locked {
                    since: start,
                    next: start + F::PERIOD,
                    inverted,
                    failures: 0,
                };
                self.stats.subframes += 1;
                out.push(NavEvent::SyncAcquired {
                    start_bit: start,
                    inverted,
                });
                return Some((start, inverted, message));
            }
        }
        None
    }

    /// The message at `start` failed: drop it, and end the lock after
    /// [`MAX_FAILURES`] in a row.
    fn fail<F: SymbolFormat>(
        &mut self,
        since: u64,
        start: u64,
        inverted: bool,
        failures: u8,
        out: &mut Vec<NavEvent>,
    ) {
        self.stats.dropped_subframes += 1;
        out.push(NavEvent::SubframeDropped {
            start_bit: start,
            words: 0,
        });
        let failures = failures + 1;
        self.state = if failures >= MAX_FAILURES {
            self.stats.sync_losses += 1;
            out.push(NavEvent::SyncLost { at_bit: start });
            State::Search {
                next: start.saturating_sub(SEARCH_BACK_SYMBOLS),
            }
        } else {
            State::Locked {
                since,
                next: start + F::PERIOD,
                inverted,
                failures,
            }
        };
    }

    /// Index of the next symbol to be pushed.
    fn end(&self) -> u64 {
        self.base + self.soft.len() as u64
    }

    /// `before` symbols before stream symbol `start` and `len` from it; symbols not
    /// buffered (before the stream or a restart) read as erasures.
    fn window(&self, start: u64, before: u64, len: u64) -> Vec<f32> {
        let at = |abs: u64| {
            let k = usize::try_from(abs.checked_sub(self.base)?).ok()?;
            self.soft.get(k).copied()
        };
        (0..before + len)
            .map(|k| (start + k).checked_sub(before).and_then(at).unwrap_or(0.0))
            .collect()
    }

    /// Drop symbols before `keep_from` once enough have piled up.
    fn trim(&mut self, keep_from: u64) {
        if keep_from > self.base + TRIM_SLACK_SYMBOLS {
            let n = usize::try_from(keep_from - self.base)
                .unwrap_or(usize::MAX)
                .min(self.soft.len());
            self.soft.drain(..n);
            self.base += n as u64;
        }
    }
}

/// `window` with every sign flipped if `inverted`.
pub(crate) fn with_polarity(window: &[f32], inverted: bool) -> Vec<f32> {
    let s = if inverted { -1.0 } else { 1.0 };
    window.iter().map(|x| s * x).collect()
}
