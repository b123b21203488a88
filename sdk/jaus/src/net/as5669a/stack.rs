//! The AS5669A transport of one socket, sans-IO ([`As4Stack`]): datagrams in, whole
//! messages out, with acknowledgements, reassembly, splitting, sequence numbers and
//! packing; and, with [`As4Config::reliable`], messages that arrive
//! ([`crate::net::reliable`], the RA 3.3 node's mechanism): a packet asking for an
//! acknowledgement is resent until acknowledged, a retransmission received is handed
//! on once and acknowledged again.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::time::Instant;

use super::datagram::{parse_datagram, write_datagrams};
use super::error::As4Error;
use super::header::As4Id;
use super::header::{AckNak, As4Packet, MAX_PAYLOAD};
use super::message::As4Message;
use super::reassembly::{As4Reassembler, As4ReassemblyLimits};
use super::split::{ack, split};
use crate::net::framing::ReassemblyStats;
use crate::net::reliable::{
    content_hash, random_start, Arrival, Delivery, Receiver, ReliableStats, RetryPolicy, Sender,
    Tracked,
};
use crate::net::{Datagram, PeerAddr, Via};

/// Settings of an [`As4Stack`].
#[derive(Debug, Clone, Copy)]
pub struct As4Config {
    /// Reassembly limits (defaults there).
    pub reassembly: As4ReassemblyLimits,
    /// Largest payload per packet when a message is split. Default [`MAX_PAYLOAD`]
    /// (4079).
    pub max_payload: usize,
    /// Largest datagram written; several messages share one up to it. Default 4096.
    pub max_datagram: usize,
    /// Most datagrams waiting to be sent (more are dropped and counted). Default 8192.
    pub max_outbox: usize,
    /// Messages that arrive: when set, a message to one component whose ID is in the
    /// command range (below 0x2000) asks for an acknowledgement of each packet, and a
    /// packet that asked for one (whoever set it) is resent as the policy says until it
    /// is acknowledged, one at a time per peer and id, in order. Default `None`: sent
    /// once. A retransmission received is handed on once either way.
    pub reliable: Option<RetryPolicy>,
}

/// The defaults the field documentation states:
///
/// ```
/// let c = jaus::net::as5669a::As4Config::default();
/// assert_eq!((c.max_payload, c.max_datagram, c.max_outbox), (4079, 4096, 8192));
/// assert_eq!(c.reassembly.max_in_progress, 256);
/// assert!(c.reliable.is_none());
/// ```
impl Default for As4Config {
    fn default() -> Self {
        Self {
            reassembly: As4ReassemblyLimits::default(),
            max_payload: MAX_PAYLOAD,
            max_datagram: 4096,
            max_outbox: 8192,
            reliable: None,
        }
    }
}

/// Counters of an [`As4Stack`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct As4Stats {
    /// Datagrams received.
    pub datagrams_received: u64,
    /// Datagrams refused whole (an [`As4Error`]).
    pub bad_datagrams: u64,
    /// Packets (messages on the wire) received.
    pub packets_received: u64,
    /// Whole messages handed on.
    pub messages_received: u64,
    /// Acknowledgements sent for packets that asked.
    pub acks_sent: u64,
    /// Acknowledgements received.
    pub acks_received: u64,
    /// Negative acknowledgements received.
    pub naks_received: u64,
    /// Messages sent.
    pub messages_sent: u64,
    /// Datagrams queued.
    pub datagrams_sent: u64,
    /// Dropped: the outgoing queue was full.
    pub outbox_full: u64,
    /// Dropped: a message that could not be split or written.
    pub encode_errors: u64,
}

/// The AS5669A transport of one socket, sans-IO: datagrams in, whole messages out (and
/// acknowledgements queued); whole messages in, datagrams queued.
#[derive(Debug)]
pub struct As4Stack<A = SocketAddr> {
    config: As4Config,
    reassembler: As4Reassembler,
    sequence: u16,
    outbox: VecDeque<Datagram<A>>,
    stats: As4Stats,
    /// Packets waiting for their acknowledgement: keyed by peer, destination id and
    /// sequence number; one at a time per peer and destination.
    sender: Sender<As4AckKey<A>, (A, As4Id), As4Packet>,
    /// Packets that asked for one: by peer, source id, sequence number and content.
    receiver: Receiver<(A, As4Id, u16, u64), ()>,
    /// The time of the last datagram or timeout handled.
    now: Option<Instant>,
}

/// A packet waiting for its acknowledgement: the peer it went to, its destination id
/// and its sequence number.
pub type As4AckKey<A> = (A, As4Id, u16);

impl<A: PeerAddr> As4Stack<A> {
    /// With `config`.
    pub fn new(config: As4Config) -> Self {
        let retry = config.reliable.unwrap_or_default();
        Self {
            reassembler: As4Reassembler::new(config.reassembly),
            config,
            // Numbered from a random point: a restarted stack's packets are not taken
            // for retransmissions of its former self's.
            sequence: random_start(),
            outbox: VecDeque::new(),
            stats: As4Stats::default(),
            sender: Sender::new(retry),
            receiver: Receiver::new(&retry),
            now: None,
        }
    }

    /// How the tracked packets ended, oldest first ([`As4Config::reliable`]).
    pub fn poll_delivery(&mut self) -> Option<Delivery<As4AckKey<A>>> {
        self.sender.poll_delivery()
    }

    /// Counters of messages that arrive.
    pub fn reliable_stats(&self) -> ReliableStats {
        let mut s = self.sender.stats();
        self.receiver.add_stats(&mut s);
        s
    }

    /// Counters.
    pub fn stats(&self) -> As4Stats {
        self.stats
    }

    /// Reassembly counters and the bytes held.
    pub fn reassembly(&self) -> (ReassemblyStats, usize) {
        (self.reassembler.stats(), self.reassembler.buffered())
    }

    /// A datagram from `from`: the whole messages it completes. Packets that ask for
    /// an acknowledgement are acknowledged (queued for `from`); acks and naks are
    /// counted, not handed on. A malformed datagram is refused whole and counted.
    pub fn receive(
        &mut self,
        now: Instant,
        from: A,
        datagram: &[u8],
    ) -> Result<Vec<As4Message>, As4Error> {
        self.now = Some(now);
        self.stats.datagrams_received += 1;
        let packets = parse_datagram(datagram).inspect_err(|_| self.stats.bad_datagrams += 1)?;
        let mut acks = Vec::new();
        let mut out = Vec::new();
        for p in packets {
            self.stats.packets_received += 1;
            match p.header.ack_nak {
                AckNak::Ack | AckNak::Nak => {
                    let ok = p.header.ack_nak == AckNak::Ack;
                    if ok {
                        self.stats.acks_received += 1;
                    } else {
                        self.stats.naks_received += 1;
                    }
                    let peer = (from, p.header.source);
                    let key = (from, p.header.source, p.sequence);
                    if self.sender.waiting() > 0
                        && self.sender.answered(now, key, peer, ok, |_| false)
                    {
                        // What waited behind it goes now.
                        self.resend_due(now);
                    }
                    continue;
                }
                AckNak::Request => {
                    acks.push(ack(&p));
                    let key = (from, p.header.source, p.sequence, content_hash(&p.payload));
                    if let Arrival::Duplicate(_) = self.receiver.arrived(now, key) {
                        // Handed on once; acknowledged again (that is what was lost).
                        continue;
                    }
                }
                AckNak::None => {}
            }
            if let Some(m) = self
                .reassembler
                .message(now, p)
                .and_then(As4Message::from_packet)
            {
                self.stats.messages_received += 1;
                out.push(m);
            }
        }
        self.stats.acks_sent += acks.len() as u64;
        self.queue(from, &acks);
        Ok(out)
    }

    /// Sends `messages` to `to`: each split as needed, numbered from the stack's running
    /// sequence number, packed several to a datagram. Retry timers count from the last
    /// datagram or timeout the stack handled (the clock's time before any):
    /// [`send_at`](Self::send_at) gives the time.
    pub fn send(&mut self, to: A, messages: &[As4Message]) {
        let now = self.now.unwrap_or_else(Instant::now);
        self.send_at(now, to, messages);
    }

    /// [`send`](Self::send) at `now`.
    pub fn send_at(&mut self, now: Instant, to: A, messages: &[As4Message]) {
        self.now = Some(now);
        let mut packets = Vec::new();
        for m in messages {
            let mut header = m.header();
            let unicast = m.destination.subsystem != 0xFFFF
                && m.destination.node != 0xFF
                && m.destination.component != 0xFF;
            if self.config.reliable.is_some()
                && unicast
                && m.message_id < 0x2000
                && header.ack_nak == AckNak::None
                && self.sender.ask((to, m.destination))
            {
                header.ack_nak = AckNak::Request;
            }
            match split(
                &header,
                &m.payload(),
                self.sequence,
                self.config.max_payload,
            ) {
                Ok(ps) => {
                    self.sequence = self.sequence.wrapping_add(ps.len() as u16);
                    self.stats.messages_sent += 1;
                    for p in ps {
                        if self.config.reliable.is_some() && p.header.ack_nak == AckNak::Request {
                            let key = (to, p.header.destination, p.sequence);
                            let peer = (to, p.header.destination);
                            if self.sender.track(now, key, peer, p.clone()) == Tracked::Held {
                                continue;
                            }
                        }
                        packets.push(p);
                    }
                }
                Err(e) => {
                    self.stats.encode_errors += 1;
                    tracing::warn!(id = m.message_id, "AS5669A message not sent: {e}");
                }
            }
        }
        self.queue(to, &packets);
    }

    fn queue(&mut self, to: A, packets: &[As4Packet]) {
        if packets.is_empty() {
            return;
        }
        let datagrams = match write_datagrams(packets, self.config.max_datagram) {
            Ok(d) => d,
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!("AS5669A datagram not written: {e}");
                return;
            }
        };
        for bytes in datagrams {
            if self.outbox.len() >= self.config.max_outbox {
                self.stats.outbox_full += 1;
                return;
            }
            self.stats.datagrams_sent += 1;
            self.outbox.push_back(Datagram {
                to,
                bytes,
                via: Via::Network,
            });
        }
    }

    /// The next datagram to send.
    pub fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.outbox.pop_front()
    }

    /// Time passed: incomplete messages past the timeout are dropped; packets due are
    /// resent, and those out of attempts given up.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.now = Some(now);
        self.reassembler.expire(now);
        self.resend_due(now);
    }

    /// When [`handle_timeout`](Self::handle_timeout) must next be called.
    pub fn poll_timeout(&self) -> Option<Instant> {
        [self.reassembler.next_timeout(), self.sender.next_timeout()]
            .into_iter()
            .flatten()
            .min()
    }

    /// Sends what is due: a held packet's first copy, another copy.
    fn resend_due(&mut self, now: Instant) {
        if self.sender.next_timeout().is_none_or(|t| t > now) {
            return;
        }
        let mut due = Vec::new();
        self.sender.poll(now, |k, p| due.push((k.0, p.clone())));
        for (to, p) in due {
            self.queue(to, std::slice::from_ref(&p));
        }
    }
}
