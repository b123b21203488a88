//! The datagrams of a run, kept as evidence for `jaus conform --pcap`: every datagram
//! the tester's socket sent or received (the target's answers, the malformed packets,
//! discovery), with its time and its two socket addresses, in the order they crossed.
//!
//! The recording is bounded (a target flooding the tester cannot grow it without
//! limit): past [`MAX_DATAGRAMS`] datagrams or [`MAX_BYTES`] bytes the rest are counted
//! in [`Recording::dropped`], not kept.

use std::net::SocketAddr;
use std::time::Duration;

/// Most datagrams kept.
pub const MAX_DATAGRAMS: usize = 200_000;
/// Most payload bytes kept.
pub const MAX_BYTES: usize = 64 << 20;

/// One datagram as it crossed the tester's socket.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Wire {
    /// When, since 1970-01-01 UTC.
    pub time: Duration,
    /// Sender.
    pub from: SocketAddr,
    /// Receiver.
    pub to: SocketAddr,
    /// The UDP payload (transport framing included).
    pub bytes: Vec<u8>,
}

/// The datagrams kept so far.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Recording {
    /// What was kept, in order.
    pub datagrams: Vec<Wire>,
    /// Datagrams not kept because a bound was reached.
    pub dropped: u64,
    bytes: usize,
}

impl Recording {
    /// Keeps one datagram, or counts it as dropped when a bound is reached.
    pub fn push(&mut self, time: Duration, from: SocketAddr, to: SocketAddr, bytes: &[u8]) {
        if self.datagrams.len() >= MAX_DATAGRAMS || self.bytes + bytes.len() > MAX_BYTES {
            self.dropped += 1;
            return;
        }
        self.bytes += bytes.len();
        self.datagrams.push(Wire {
            time,
            from,
            to,
            bytes: bytes.to_vec(),
        });
    }
}

/// A session's recording: off until [`start`](Tap::start)ed, then keeping what it is
/// given.
#[derive(Debug, Clone, Default)]
pub struct Tap(Option<Recording>);

impl Tap {
    /// Keeps every datagram pushed from now on.
    pub fn start(&mut self) {
        self.0.get_or_insert_with(Recording::default);
    }

    /// What was kept since [`start`](Tap::start), leaving an empty recording.
    pub fn take(&mut self) -> Recording {
        self.0.as_mut().map(std::mem::take).unwrap_or_default()
    }

    /// Keeps one datagram if recording.
    pub fn push(&mut self, time: Duration, from: SocketAddr, to: SocketAddr, bytes: &[u8]) {
        if let Some(r) = self.0.as_mut() {
            r.push(time, from, to, bytes);
        }
    }
}

/// The wall-clock time now, since the Unix epoch (zero if the clock is before it).
pub(crate) fn wall_now() -> Duration {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_recording_is_bounded_and_counts_what_it_drops() {
        let a: SocketAddr = "127.0.0.1:1".parse().unwrap();
        let mut r = Recording::default();
        let big = vec![0u8; MAX_BYTES / 2];
        r.push(Duration::ZERO, a, a, &big);
        r.push(Duration::ZERO, a, a, &big);
        r.push(Duration::ZERO, a, a, &[1]);
        assert_eq!((r.datagrams.len(), r.dropped), (2, 1));
        let mut r = Recording::default();
        for _ in 0..MAX_DATAGRAMS + 3 {
            r.push(Duration::ZERO, a, a, &[]);
        }
        assert_eq!((r.datagrams.len(), r.dropped), (MAX_DATAGRAMS, 3));
    }
}
