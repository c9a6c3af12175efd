//! What the GPS LNAV and BeiDou D1/D2 decoders share, written once: the generic
//! [`Decoder`] over a message format's own decoding ([`MessageFormat`]), holding the
//! satellite, the framed bit stream, the week and the last ephemeris, with the
//! accessors and the [`NavDecoder`] implementation of both.

use super::framer::{FrameSpec, FramedStream};
use super::{DecodeStats, DecodedEphemeris, NavDecoder, NavEvent};
use skyforge_orbits::ephemeris::SatId;

/// The state every decoder keeps besides its message's own parts (what a
/// [`MessageFormat`] reads and updates).
#[derive(Debug, Clone)]
pub struct Common {
    pub(super) sat: SatId,
    pub(super) stream: FramedStream,
    /// Full week of the last decoded subframe, once known.
    pub(super) week: Option<u32>,
    ephemeris: Option<DecodedEphemeris>,
}

impl Common {
    /// Emit `eph` when it differs from the last one.
    pub(super) fn offer_ephemeris(&mut self, eph: DecodedEphemeris, out: &mut Vec<NavEvent>) {
        if self.ephemeris.as_ref() != Some(&eph) {
            self.ephemeris = Some(eph.clone());
            out.push(NavEvent::Ephemeris(Box::new(eph)));
        }
    }
}

/// A message format's own decoding: which windows start a subframe, and what a
/// polarity-corrected subframe holds.
pub trait MessageFormat: std::fmt::Debug + Clone + Send {
    /// Whether a polarity-corrected window starts a subframe.
    fn confirm(&self, window: &[u8]) -> bool;
    /// Decode one polarity-corrected subframe starting at `start_bit`.
    fn subframe(
        &mut self,
        common: &mut Common,
        start_bit: u64,
        inverted: bool,
        bits: &[u8],
        out: &mut Vec<NavEvent>,
    );
}

/// Decoder of one satellite's message in format `M`.
///
/// Feed soft bits with [`NavDecoder::feed`].
#[derive(Debug, Clone)]
pub struct Decoder<M> {
    common: Common,
    pub(super) message: M,
}

impl<M: MessageFormat> Decoder<M> {
    /// A decoder of `sat`'s stream, framed by `spec`, in the format `message`.
    pub(super) fn with(sat: SatId, spec: FrameSpec, message: M) -> Self {
        Self {
            common: Common {
                sat,
                stream: FramedStream::new(spec),
                week: None,
                ephemeris: None,
            },
            message,
        }
    }

    /// The last complete ephemeris.
    pub fn ephemeris(&self) -> Option<&DecodedEphemeris> {
        self.common.ephemeris.as_ref()
    }

    /// Full week (GPS) or BDT week (BeiDou) of the last decoded subframe, once known.
    pub fn week(&self) -> Option<u32> {
        self.common.week
    }

    /// Whether subframe synchronisation is held.
    pub fn is_synchronised(&self) -> bool {
        self.common.stream.framer.is_locked()
    }
}

impl<M: MessageFormat> NavDecoder for Decoder<M> {
    fn feed(&mut self, soft_bits: &[f32]) -> Vec<NavEvent> {
        self.common.stream.push(soft_bits);
        let mut out = Vec::new();
        let message = &mut self.message;
        while let Some((start_bit, inverted, bits)) = self
            .common
            .stream
            .next_subframe(|w| message.confirm(w), &mut out)
        {
            message.subframe(&mut self.common, start_bit, inverted, &bits, &mut out);
        }
        out
    }

    fn restart(&mut self) {
        self.common.stream.restart();
    }

    fn stats(&self) -> DecodeStats {
        self.common.stream.stats
    }

    fn satellite(&self) -> SatId {
        self.common.sat
    }
}
