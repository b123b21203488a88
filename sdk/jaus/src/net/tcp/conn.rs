//! One TCP connection of a [`TcpTransport`](super::TcpTransport): its non-blocking
//! stream, the JTCP decoder of what comes in and encoder of what goes out, and its
//! bounded send queue.

use std::collections::VecDeque;
use std::io::{ErrorKind, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Instant;

use crate::net::stream::jtcp::JtcpEncoder;
use crate::net::stream::{EncodeError, JtcpDecoder, Version};

/// How a connection came to be.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Origin {
    /// Dialed by this transport (to a configured peer or a destination it was given).
    Dialed,
    /// Accepted on the listening socket.
    Accepted,
}

/// Why a connection ended.
#[derive(Debug)]
pub(super) enum Closed {
    /// The peer closed it.
    Eof,
    /// Reading or writing failed.
    Io(std::io::Error),
    /// The peer's stream does not parse.
    Stream(crate::net::stream::JtcpError),
    /// Nothing could be written for the stall bound while data waited.
    Stalled,
}

impl std::fmt::Display for Closed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Closed::Eof => write!(f, "closed by the peer"),
            Closed::Io(e) => write!(f, "{e}"),
            Closed::Stream(e) => write!(f, "{e}"),
            Closed::Stalled => write!(f, "the peer stopped reading"),
        }
    }
}

/// A live connection.
#[derive(Debug)]
pub(super) struct Conn {
    pub(super) stream: TcpStream,
    /// The address the node knows the peer by: the dialed address, or the remote
    /// address of an accepted connection.
    pub(super) key: SocketAddr,
    pub(super) origin: Origin,
    decoder: JtcpDecoder,
    encoder: JtcpEncoder,
    /// Encoded bytes waiting, one entry per datagram; `written` of the front are out.
    queue: VecDeque<Vec<u8>>,
    queued_bytes: usize,
    written: usize,
    /// When a write last made progress or the queue was last empty.
    progress: Instant,
    /// A frame came in (the peer speaks JTCP).
    pub(super) heard: bool,
}

/// What one read of a connection gave.
pub(super) struct Received {
    /// Frames handed on.
    pub(super) frames: u64,
    /// Bytes read.
    pub(super) bytes: u64,
}

impl Conn {
    pub(super) fn new(
        stream: TcpStream,
        key: SocketAddr,
        origin: Origin,
        max_frame: usize,
        now: Instant,
    ) -> std::io::Result<Self> {
        stream.set_nonblocking(true)?;
        stream.set_nodelay(true)?;
        Ok(Self {
            stream,
            key,
            origin,
            decoder: JtcpDecoder::new(max_frame),
            encoder: JtcpEncoder::default(),
            queue: VecDeque::new(),
            queued_bytes: 0,
            written: 0,
            progress: now,
            heard: false,
        })
    }

    /// The version this connection carries, once either side spoke.
    pub(super) fn version(&self) -> Option<Version> {
        self.encoder.version().or(self.decoder.version())
    }

    /// Whether bytes wait to be written.
    pub(super) fn wants_write(&self) -> bool {
        !self.queue.is_empty()
    }

    /// Datagrams waiting.
    pub(super) fn queued(&self) -> usize {
        self.queue.len()
    }

    /// Bytes waiting.
    pub(super) fn queued_bytes(&self) -> usize {
        self.queued_bytes
    }

    /// Queues the frames of `datagram` (the caller checked the bounds).
    pub(super) fn enqueue(&mut self, datagram: &[u8], now: Instant) -> Result<(), EncodeError> {
        let mut frame = Vec::with_capacity(datagram.len() + 1);
        self.encoder.encode(datagram, &mut frame)?;
        if self.queue.is_empty() {
            self.progress = now;
        }
        self.queued_bytes += frame.len();
        self.queue.push_back(frame);
        Ok(())
    }

    /// Writes what the socket takes now. Returns the datagrams fully written.
    pub(super) fn flush(&mut self, now: Instant) -> Result<u64, Closed> {
        let mut done = 0;
        while let Some(front) = self.queue.front() {
            let rest = front.get(self.written..).unwrap_or_default();
            match self.stream.write(rest) {
                Ok(0) => return Err(Closed::Io(ErrorKind::WriteZero.into())),
                Ok(n) => {
                    self.progress = now;
                    self.written += n;
                    if self.written >= front.len() {
                        self.queued_bytes -= front.len();
                        self.queue.pop_front();
                        self.written = 0;
                        done += 1;
                    }
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(Closed::Io(e)),
            }
        }
        if self.queue.is_empty() {
            self.progress = now;
        }
        Ok(done)
    }

    /// Whether data has waited without any write progress for longer than `bound`.
    pub(super) fn stalled(&self, now: Instant, bound: std::time::Duration) -> bool {
        !self.queue.is_empty() && now.saturating_duration_since(self.progress) > bound
    }

    /// Reads what the socket has (at most `budget` bytes), handing each datagram to
    /// `on`.
    pub(super) fn read(
        &mut self,
        buf: &mut [u8],
        budget: usize,
        mut on: impl FnMut(SocketAddr, &[u8]),
    ) -> Result<Received, Closed> {
        let mut r = Received {
            frames: 0,
            bytes: 0,
        };
        let key = self.key;
        while (r.bytes as usize) < budget {
            match self.stream.read(buf) {
                Ok(0) => return Err(Closed::Eof),
                Ok(n) => {
                    r.bytes += n as u64;
                    let frames = &mut r.frames;
                    self.decoder
                        .decode(buf.get(..n).unwrap_or_default(), |d| {
                            *frames += 1;
                            on(key, d);
                        })
                        .map_err(Closed::Stream)?;
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(Closed::Io(e)),
            }
        }
        if r.frames > 0 {
            self.heard = true;
        }
        Ok(r)
    }
}
