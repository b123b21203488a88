//! A data link ([`DataLink`]): the hardware a subsystem's Communicator reaches other
//! subsystems through, a radio or any other channel that carries JAUS packets. It sits
//! below both the network layer (`jaus::net::udp::link` is one) and the stock
//! Communicator (`jaus::stock::communicator`, which drives any of them), so neither
//! imports the other. Sans-IO like the rest of the
//! SDK: every call takes the time, nothing blocks, no thread or socket is implied.

use std::time::Instant;

/// Why a data link did not take a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum LinkError {
    /// The link is down (no carrier, no peer): the frame is lost.
    #[error("data link down")]
    Down,
    /// The link cannot take the frame now (its transmit buffer is full); the frame may
    /// be offered again later (see [`DataLink::poll_timeout`]).
    #[error("data link busy: its transmit buffer is full")]
    Busy,
    /// The frame is larger than the link carries.
    #[error("frame of {len} bytes is larger than the data link's {max}-byte limit")]
    TooLarge {
        /// The frame's length, bytes.
        len: usize,
        /// The largest frame the link carries, bytes.
        max: usize,
    },
}

/// A data link to other subsystems: it carries frames, each one JAUS packet (a 16-byte
/// header and its body, as `jaus::net::Framing::Raw` writes it), in both
/// directions.
///
/// A vendor implements it over a radio modem, a serial line, a tether; `jaus-sim`
/// implements it with a simulated radio (loss, latency, bandwidth, up/down).
pub trait DataLink: Send + 'static {
    /// The link's id, as Data Link ID in the communications messages.
    fn id(&self) -> u8;
    /// Offers `frame` for transmission at `now`.
    fn send(&mut self, now: Instant, frame: &[u8]) -> Result<(), LinkError>;
    /// The next frame received by `now`, written into `buf` (cleared first); false when
    /// there is none.
    fn recv(&mut self, now: Instant, buf: &mut Vec<u8>) -> bool;
    /// Whether the hardware reports the link up (carrier, association) at `now`.
    fn is_up(&self, now: Instant) -> bool;
    /// When the next frame arrives (to be woken then). `None`: none expected (the
    /// default). A time not after the last time the link was read to the end is not
    /// woken for (a frame arriving at that very instant is read at the next wake-up),
    /// so that a link repeating a past time cannot make its host spin.
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    /// When a link that answered [`LinkError::Busy`] takes a frame again; asked only
    /// while frames wait for it. `None` (the default): unknown, frames are offered again
    /// at the next wake-up.
    fn ready_at(&self) -> Option<Instant> {
        None
    }
    /// The commanded power state changed at `now` (true: On; false: Off or Standby);
    /// the hardware may power the transmitter up or down. Ignored by default.
    fn set_powered(&mut self, now: Instant, on: bool) {
        let _ = (now, on);
    }
}

/// A boxed link is a link: a Communicator over links of different kinds (a UDP link and
/// a QUIC link, say) is a `StockCommunicator<Box<dyn DataLink>>`.
impl<L: DataLink + ?Sized> DataLink for Box<L> {
    fn id(&self) -> u8 {
        (**self).id()
    }
    fn send(&mut self, now: Instant, frame: &[u8]) -> Result<(), LinkError> {
        (**self).send(now, frame)
    }
    fn recv(&mut self, now: Instant, buf: &mut Vec<u8>) -> bool {
        (**self).recv(now, buf)
    }
    fn is_up(&self, now: Instant) -> bool {
        (**self).is_up(now)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        (**self).poll_timeout()
    }
    fn ready_at(&self) -> Option<Instant> {
        (**self).ready_at()
    }
    fn set_powered(&mut self, now: Instant, on: bool) {
        (**self).set_powered(now, on);
    }
}
