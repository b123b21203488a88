//! A serial line, the carrier of JSerial ([`stream::jserial`](super::stream::jserial)):
//! a [`Transport`] over a tty (a USB serial adapter, a radio modem, a pseudo-terminal).
//!
//! The line is point to point: whatever comes in is from the far end, whatever goes
//! out is for it. The node names the far end with an address of its own carrier type
//! (`far_end`, e.g. [`SerialLine`]); every datagram received is from it, every
//! datagram sent goes down the line whatever its destination.
//!
//! The tty is put in raw mode (8 data bits, no parity, one stop bit, no flow control,
//! no echo, no line editing) at the configured speed, and read and written without
//! blocking: the loop waits on it with `poll(2)`. Bytes to write queue up to
//! [`SerialConfig::max_queue_bytes`] (a slow line fills it; more is dropped and
//! counted); a write the tty refuses drops what waits (counted) and the node runs on,
//! since a line may come back. What the decoder skips (garbage, lost bytes, damaged
//! packets) is counted in [`JSerialStats`].

use std::fs::File;
use std::io::{ErrorKind, Read, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::stream::{jserial, JSerialDecoder, JSerialStats, DEFAULT_MAX_FRAME};
use super::{Datagram, PeerAddr, Transport, Via};

mod tty;

/// The name of the far end of a node's serial line: line `0` for a node with one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct SerialLine(pub u8);

impl std::fmt::Display for SerialLine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "serial line {}", self.0)
    }
}

/// Settings of a [`SerialTransport`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SerialConfig {
    /// The tty.
    pub path: PathBuf,
    /// Bits per second (50 to 4,000,000, a speed the OS names).
    pub baud: u32,
    /// Largest packet payload taken. Default [`DEFAULT_MAX_FRAME`].
    pub max_frame: usize,
    /// Most bytes waiting to be written. Default 64 KiB.
    pub max_queue_bytes: usize,
}

impl SerialConfig {
    /// `path` at `baud`, the other settings at their defaults.
    pub fn new(path: impl Into<PathBuf>, baud: u32) -> Self {
        Self {
            path: path.into(),
            baud,
            max_frame: DEFAULT_MAX_FRAME,
            max_queue_bytes: 64 * 1024,
        }
    }
}

/// What a [`SerialTransport`] counted (the decoder's own counters are in
/// [`SerialTransport::line_stats`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SerialStats {
    /// Datagrams handed to the node.
    pub datagrams_received: u64,
    /// Datagrams queued for the line.
    pub datagrams_sent: u64,
    /// Bytes written.
    pub bytes_written: u64,
    /// Dropped: the write queue was full.
    pub queue_full: u64,
    /// Dropped: not JUDP version 1 or 2, or malformed.
    pub not_carried: u64,
    /// Writes the tty refused.
    pub write_errors: u64,
    /// Bytes dropped by those.
    pub bytes_lost: u64,
}

/// JSerial on a tty as a [`Transport`] (see the [module documentation](self)).
#[derive(Debug)]
pub struct SerialTransport<A: PeerAddr = SerialLine> {
    file: File,
    config: SerialConfig,
    far_end: A,
    decoder: JSerialDecoder,
    /// Bytes waiting to be written.
    out: Vec<u8>,
    /// Bytes of `out` written by the current flush.
    written: usize,
    stats: SerialStats,
    buf: Vec<u8>,
}

impl<A: PeerAddr> SerialTransport<A> {
    /// Opens and configures the tty of `config`; the node knows its far end as
    /// `far_end`. Errors name the line.
    pub fn open(config: SerialConfig, far_end: A) -> std::io::Result<Self> {
        let file = tty::open_raw(&config.path, config.baud).map_err(|e| {
            std::io::Error::new(
                e.kind(),
                format!("serial line {}: {e}", config.path.display()),
            )
        })?;
        Ok(Self {
            file,
            decoder: JSerialDecoder::new(config.max_frame),
            config,
            far_end,
            out: Vec::new(),
            written: 0,
            stats: SerialStats::default(),
            buf: vec![0; 4096],
        })
    }

    /// The counters of the transport.
    pub fn stats(&self) -> SerialStats {
        self.stats
    }

    /// The counters of the line: packets, bytes skipped, resynchronisations, bad
    /// checksums.
    pub fn line_stats(&self) -> JSerialStats {
        self.decoder.stats()
    }

    /// The settings.
    pub fn config(&self) -> &SerialConfig {
        &self.config
    }

    fn error(&self, e: std::io::Error) -> std::io::Error {
        std::io::Error::new(
            e.kind(),
            format!("serial line {}: {e}", self.config.path.display()),
        )
    }

    /// Writes what the tty takes now.
    fn flush(&mut self) -> std::io::Result<()> {
        while self.written < self.out.len() {
            match self.file.write(&self.out[self.written..]) {
                Ok(0) => return Err(self.error(ErrorKind::WriteZero.into())),
                Ok(n) => {
                    self.written += n;
                    self.stats.bytes_written += n as u64;
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => {
                    // The line refuses bytes (a pseudo-terminal without its far side,
                    // an unplugged adapter): what waits is lost, and counted.
                    self.stats.write_errors += 1;
                    self.stats.bytes_lost += (self.out.len() - self.written) as u64;
                    self.out.clear();
                    self.written = 0;
                    return Err(self.error(e));
                }
            }
        }
        // What is out leaves the buffer, so that it holds only what waits.
        self.out.drain(..self.written);
        self.written = 0;
        Ok(())
    }

    /// Reads what the tty has, handing each datagram to `on`; returns how many.
    fn read(&mut self, on: &mut impl FnMut(Via, A, &[u8])) -> std::io::Result<u64> {
        let mut handed = 0;
        loop {
            match self.file.read(&mut self.buf) {
                // A pseudo-terminal whose other side is closed reads 0 (or EIO): the
                // line is quiet, not gone (the far end may come back).
                Ok(0) => return Ok(handed),
                Ok(n) => {
                    let far_end = self.far_end;
                    let got = &mut handed;
                    self.decoder
                        .decode(self.buf.get(..n).unwrap_or_default(), |d| {
                            *got += 1;
                            on(Via::Network, far_end, d);
                        });
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => return Ok(handed),
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) if e.raw_os_error() == Some(nix::libc::EIO) => return Ok(handed),
                Err(e) => return Err(self.error(e)),
            }
        }
    }
}

impl<A: PeerAddr> Transport for SerialTransport<A> {
    type Addr = A;

    fn recv<F: FnMut(Via, A, &[u8])>(&mut self, wait: Duration, mut on: F) -> std::io::Result<()> {
        let deadline = Instant::now() + wait;
        loop {
            let n = self.read(&mut on)?;
            self.stats.datagrams_received += n;
            if let Err(e) = self.flush() {
                // Counted; the line may come back, and reading goes on.
                tracing::debug!("{e}");
            }
            let now = Instant::now();
            if n > 0 || now >= deadline {
                return Ok(());
            }
            tty::wait(&self.file, !self.out.is_empty(), deadline - now)
                .map_err(|e| self.error(e))?;
        }
    }

    fn send(&mut self, d: &Datagram<A>) -> std::io::Result<()> {
        let before = self.out.len();
        if let Err(e) = jserial::encode_into(&d.bytes, &mut self.out) {
            self.out.truncate(before);
            self.stats.not_carried += 1;
            return Err(self.error(std::io::Error::new(ErrorKind::InvalidInput, e)));
        }
        if self.out.len() > self.config.max_queue_bytes {
            self.out.truncate(before);
            self.stats.queue_full += 1;
            return Err(self.error(std::io::Error::new(
                ErrorKind::WouldBlock,
                "write queue full",
            )));
        }
        self.stats.datagrams_sent += 1;
        self.flush()
    }

    fn describe(&self) -> String {
        format!(
            "serial {} at {} baud (far end: {})",
            self.config.path.display(),
            self.config.baud,
            self.far_end
        )
    }
}
