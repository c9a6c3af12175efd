//! Samples handed over in memory while a synthesis session makes them, for a receiver
//! running beside it on another thread: synthesis and reception without a recording on
//! disk (an 1800 s run of four 4 Msps antennas would be 58 GB of I/Q).
//!
//! [`sample_stream`] gives the two ends. The [`SampleFeed`] takes each band's and antenna's
//! bytes as they are rendered (the caller adapts it to the synthesis session's sample
//! sink: the receiver knows nothing of the synthesiser) and sends them as frames on one
//! bounded channel. Each [`StreamReader`] reads one band's and antenna's bytes for the
//! [`BlockReader`](super::BlockReader): all of them share one demultiplexer that takes the
//! next frame off the channel, whichever source it belongs to, and queues it until that
//! source's reader asks. One channel rather than one per source cannot deadlock: the
//! synthesiser renders every antenna of a slice before the next slice, so the queues hold
//! at most a block and a slice per source beyond what the receiver has read, and the
//! channel itself bounds what is in flight.
//!
//! When the feed is dropped (the synthesis ended or failed) the readers see the end of
//! their streams; when the readers are dropped (the receiver stopped) the feed's next send
//! fails, so neither side waits for the other forever.

use std::collections::VecDeque;
use std::io::{Read, Seek, SeekFrom};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::sync::{Arc, Mutex};

/// One rendered piece of one source's bytes.
type Frame = (usize, Vec<u8>);

/// The synthesis end of a stream.
#[derive(Debug)]
pub struct SampleFeed {
    tx: SyncSender<Frame>,
    antennas: usize,
    sources: usize,
}

/// The queues of frames taken off the channel, per source.
#[derive(Debug)]
struct Demux {
    rx: Receiver<Frame>,
    /// Per source: frames not yet read, and how far into the first one reading got.
    queues: Vec<(VecDeque<Vec<u8>>, usize)>,
}

/// The receiving end of one source (band `b`, antenna `a`: source `b * antennas + a`).
#[derive(Debug)]
pub struct StreamReader {
    demux: Arc<Mutex<Demux>>,
    source: usize,
    position: u64,
}

/// A stream for `bands` x `antennas` sources with at most `frames_in_flight` frames on the
/// channel: the feed, and the readers in source order (band-major).
pub fn sample_stream(
    bands: usize,
    antennas: usize,
    frames_in_flight: usize,
) -> (SampleFeed, Vec<StreamReader>) {
    let sources = bands * antennas;
    let (tx, rx) = sync_channel(frames_in_flight);
    let demux = Arc::new(Mutex::new(Demux {
        rx,
        queues: (0..sources).map(|_| (VecDeque::new(), 0)).collect(),
    }));
    let readers = (0..sources)
        .map(|source| StreamReader {
            demux: Arc::clone(&demux),
            source,
            position: 0,
        })
        .collect();
    (
        SampleFeed {
            tx,
            antennas,
            sources,
        },
        readers,
    )
}

/// Why a feed could not send.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FeedError {
    #[error("sample stream: band {band} antenna {antenna} is not one of its {sources} sources")]
    NoSuchSource {
        band: usize,
        antenna: usize,
        sources: usize,
    },
    #[error("the receiver stopped reading the sample stream")]
    ReceiverStopped,
}

impl SampleFeed {
    /// Send the next `bytes` of band `band`'s recording of antenna `antenna`.
    pub fn send(&mut self, band: usize, antenna: usize, bytes: &[u8]) -> Result<(), FeedError> {
        let source = band * self.antennas + antenna;
        if antenna >= self.antennas || source >= self.sources {
            return Err(FeedError::NoSuchSource {
                band,
                antenna,
                sources: self.sources,
            });
        }
        self.tx
            .send((source, bytes.to_vec()))
            .map_err(|_| FeedError::ReceiverStopped)
    }
}

impl Read for StreamReader {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if buf.is_empty() {
            return Ok(0);
        }
        let mut demux = self
            .demux
            .lock()
            .map_err(|_| std::io::Error::other("sample stream: a reader panicked"))?;
        while demux.queues[self.source].0.is_empty() {
            match demux.rx.recv() {
                Ok((source, bytes)) => demux.queues[source].0.push_back(bytes),
                // The feed is gone: the end of every stream.
                Err(_) => return Ok(0),
            }
        }
        let (queue, offset) = &mut demux.queues[self.source];
        let Some(front) = queue.front() else {
            return Ok(0);
        };
        let n = (front.len() - *offset).min(buf.len());
        buf[..n].copy_from_slice(&front[*offset..*offset + n]);
        *offset += n;
        if *offset == front.len() {
            queue.pop_front();
            *offset = 0;
        }
        self.position += n as u64;
        Ok(n)
    }
}

impl Seek for StreamReader {
    /// A stream only reports where it is: seeking to its own position is allowed (the
    /// block reader seeks to the first common sample, 0 for a stream), anything else is
    /// not supported.
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        let here = match to {
            SeekFrom::Start(p) => p == self.position,
            SeekFrom::Current(d) => d == 0,
            SeekFrom::End(_) => false,
        };
        if here {
            Ok(self.position)
        } else {
            Err(std::io::Error::new(
                std::io::ErrorKind::Unsupported,
                format!(
                    "a sample stream cannot seek ({to:?} from byte {})",
                    self.position
                ),
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads exactly `n` bytes of `r`.
    fn take(r: &mut StreamReader, n: usize) -> Vec<u8> {
        let mut out = vec![0; n];
        r.read_exact(&mut out).unwrap();
        out
    }

    #[test]
    fn interleaved_frames_reach_their_own_readers_in_order() {
        let (mut feed, mut readers) = sample_stream(2, 2, 2);
        let producer = std::thread::spawn(move || {
            for slice in 0u8..20 {
                for band in 0..2 {
                    for antenna in 0..2 {
                        let tag = (band * 2 + antenna) as u8;
                        feed.send(band, antenna, &[tag, slice, tag, slice]).unwrap();
                    }
                }
            }
        });
        // Read in a different rhythm from the writer's: 6 bytes of each source in turn.
        let mut got: Vec<Vec<u8>> = vec![Vec::new(); 4];
        for _ in 0..(80 / 6) {
            for (s, r) in readers.iter_mut().enumerate() {
                got[s].extend(take(r, 6));
            }
        }
        for (s, r) in readers.iter_mut().enumerate() {
            let mut rest = Vec::new();
            r.read_to_end(&mut rest).unwrap();
            got[s].extend(rest);
        }
        producer.join().unwrap();
        for (s, bytes) in got.iter().enumerate() {
            let want: Vec<u8> = (0u8..20).flat_map(|k| [s as u8, k, s as u8, k]).collect();
            assert_eq!(bytes, &want, "source {s}");
        }
    }

    #[test]
    fn a_stopped_receiver_fails_the_feed_and_a_finished_feed_ends_the_streams() {
        let (mut feed, readers) = sample_stream(1, 2, 1);
        drop(readers);
        let e = feed.send(0, 0, &[1, 2]).unwrap_err();
        assert!(e.to_string().contains("stopped reading"), "{e}");

        let (mut feed, mut readers) = sample_stream(1, 2, 4);
        feed.send(0, 1, &[7, 8, 9]).unwrap();
        assert!(feed.send(1, 0, &[1]).is_err(), "band 1 does not exist");
        drop(feed);
        let mut rest = Vec::new();
        readers[1].read_to_end(&mut rest).unwrap();
        assert_eq!(rest, [7, 8, 9]);
        assert_eq!(readers[0].read(&mut [0; 4]).unwrap(), 0);
    }

    #[test]
    fn a_stream_seeks_only_to_where_it_is() {
        let (mut feed, mut readers) = sample_stream(1, 1, 4);
        feed.send(0, 0, &[1, 2, 3, 4]).unwrap();
        let r = &mut readers[0];
        assert_eq!(r.seek(SeekFrom::Start(0)).unwrap(), 0);
        assert_eq!(take(r, 2), [1, 2]);
        assert_eq!(r.stream_position().unwrap(), 2);
        assert!(r.seek(SeekFrom::Start(0)).is_err());
        assert!(r.seek(SeekFrom::End(0)).is_err());
    }
}
