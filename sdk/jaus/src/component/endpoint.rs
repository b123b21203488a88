//! [`Endpoint`]: the interface through which a node or a [`LocalBus`] drives any
//! component it hosts, and its implementation for [`Component`].
//!
//! [`LocalBus`]: super::local::LocalBus

use std::any::Any;
use std::time::Instant;

use super::{Behaviour, Component};
use crate::codec::{Encode, EncodeError};
use crate::{Address, Header};

/// A message a hosted component sends, encoded for the wire (the node does not need to
/// know the component's message set).
#[derive(Debug, Clone, PartialEq)]
pub struct Outgoing {
    /// Header; the data size is set when the packet is built.
    pub header: Header,
    /// Name of the message (`"ack/nak"` for an acknowledgement), for logs.
    pub name: &'static str,
    /// The body, or why it could not be encoded (the message is then not sent; the
    /// node counts it).
    pub body: Result<Vec<u8>, EncodeError>,
}

/// Anything a node or a [`LocalBus`](super::local::LocalBus) hosts: a [`Component`] (of
/// any behaviour) or a test [`Probe`](super::local::Probe). The node and the bus drive it
/// through this trait alone.
pub trait Endpoint: Send + 'static {
    /// Its address.
    fn address(&self) -> Address;
    /// A message arrives.
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]);
    /// Time passes.
    fn handle_timeout(&mut self, now: Instant);
    /// Something to send, encoded.
    fn poll_transmit(&mut self) -> Option<Outgoing>;
    /// Something to send, its body encoded into `buf` (a reused buffer, whatever it
    /// held); `Err(buf)` gives the buffer back when there is nothing to send. Hosts use
    /// this to route without allocating; the default goes through
    /// [`poll_transmit`](Self::poll_transmit).
    fn poll_transmit_with(&mut self, buf: Vec<u8>) -> Result<Outgoing, Vec<u8>> {
        self.poll_transmit().ok_or(buf)
    }
    /// When to be woken next.
    fn poll_timeout(&self) -> Option<Instant>;
    /// A component this endpoint may have dealt with is gone (the node layer saw it
    /// time out): end control, service connections and events involving it.
    fn forget(&mut self, gone: Address) {
        let _ = gone;
    }
    /// The wall clock, from an I/O shell that reads one: UTC (since 1970-01-01) at
    /// `now`. A component whose clock nobody set (no `Config::utc`, no Set Time yet)
    /// takes it, so its time stamps carry the system's time. Ignored by default.
    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        let _ = (now, utc);
    }
    /// How a command it sent to a component of another node ended, when its node makes
    /// commands arrive (`jaus::net::NodeConfig::reliable`): acknowledged, refused or
    /// given up. Ignored by default; a [`Component`] keeps it for its behaviour
    /// ([`Context::take_settled`](super::Context::take_settled)).
    fn settled(&mut self, now: Instant, settled: super::Settled) {
        let _ = (now, settled);
    }
    /// The runtime's counters, for a component (`None` for anything else).
    fn stats(&self) -> Option<super::Stats> {
        None
    }
    /// For a gateway to other subsystems (the Communicator a node names in its
    /// `NodeConfig::communicator`, Part 1 Figure 5-1): takes one packet (a 16-byte JAUS
    /// header and its body) leaving the subsystem at `now`. Returns false when this
    /// endpoint is no gateway (the default); the node then counts the packet as dropped.
    fn gateway_send(&mut self, now: Instant, packet: &[u8]) -> bool {
        let _ = (now, packet);
        false
    }
    /// For a gateway: the next packet received from another subsystem by `now`,
    /// written into `buf` (a reused buffer, whatever it held); `Err(buf)` gives the
    /// buffer back when there is none (always, by default).
    fn gateway_recv(&mut self, now: Instant, buf: Vec<u8>) -> Result<Vec<u8>, Vec<u8>> {
        let _ = now;
        Err(buf)
    }
    /// For [`LocalBus::get`](super::local::LocalBus::get).
    fn as_any(&self) -> &dyn Any;
    /// For [`LocalBus::get_mut`](super::local::LocalBus::get_mut).
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<B: Behaviour> Endpoint for Component<B> {
    fn address(&self) -> Address {
        Component::address(self)
    }
    fn stats(&self) -> Option<super::Stats> {
        Some(Component::stats(self))
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        Component::handle(self, now, header, body);
    }
    fn handle_timeout(&mut self, now: Instant) {
        Component::handle_timeout(self, now);
    }
    fn poll_transmit_with(&mut self, mut buf: Vec<u8>) -> Result<Outgoing, Vec<u8>> {
        let Some(t) = Component::poll_transmit(self) else {
            return Err(buf);
        };
        buf.clear();
        let (name, body) = match &t.message {
            Some(m) => {
                buf.resize(m.encoded_len(), 0);
                let mut w = crate::codec::Writer::new(&mut buf);
                (crate::MessageSet::name(m), m.encode(&mut w).map(|()| buf))
            }
            None => ("ack/nak", Ok(buf)),
        };
        Ok(Outgoing {
            header: t.header,
            name,
            body,
        })
    }
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        let t = Component::poll_transmit(self)?;
        Some(match &t.message {
            Some(m) => Outgoing {
                header: t.header,
                name: crate::MessageSet::name(m),
                body: m.to_bytes(),
            },
            None => Outgoing {
                header: t.header,
                name: "ack/nak",
                body: Ok(Vec::new()),
            },
        })
    }
    fn poll_timeout(&self) -> Option<Instant> {
        Component::poll_timeout(self)
    }
    fn forget(&mut self, gone: Address) {
        Component::forget(self, gone);
    }
    fn settled(&mut self, _now: Instant, settled: super::Settled) {
        Component::settled(self, settled);
    }
    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        Component::wall_clock(self, now, utc);
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Components hosted together (by a node, or attached to a node from another process):
/// found by address, woken when due, drained of what they send, handed what arrives.
#[derive(Default)]
pub struct Endpoints(Vec<Box<dyn Endpoint>>);

impl std::fmt::Debug for Endpoints {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.0.iter().map(|e| e.address()))
            .finish()
    }
}

impl Endpoints {
    /// The counters of every component, with its address.
    pub fn stats(&self) -> impl Iterator<Item = (Address, super::Stats)> + '_ {
        self.0
            .iter()
            .filter_map(|e| Some((e.address(), e.stats()?)))
    }

    /// How many.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// None hosted.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Whether a component has address `a`.
    pub fn contains(&self, a: Address) -> bool {
        self.0.iter().any(|e| e.address() == a)
    }

    /// Whether a component matches destination `d` (broadcast ids included).
    pub fn any_matches(&self, d: Address) -> bool {
        self.0.iter().any(|e| d.matches(&e.address()))
    }

    /// Adds one (the caller has checked its address).
    pub fn push(&mut self, e: Box<dyn Endpoint>) {
        self.0.push(e);
    }

    /// The component at `a`, as a `T`.
    pub fn get<T: 'static>(&self, a: Address) -> Option<&T> {
        self.0
            .iter()
            .find(|e| e.address() == a)
            .and_then(|e| e.as_any().downcast_ref())
    }

    /// The component at `a`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, a: Address) -> Option<&mut T> {
        self.0
            .iter_mut()
            .find(|e| e.address() == a)
            .and_then(|e| e.as_any_mut().downcast_mut())
    }

    /// The component at `a`, as the endpoint the node drives.
    pub fn endpoint_mut(&mut self, a: Address) -> Option<&mut dyn Endpoint> {
        self.0
            .iter_mut()
            .find(|e| e.address() == a)
            .map(|e| &mut **e as &mut dyn Endpoint)
    }

    /// The earliest instant one of them wants to be woken.
    pub fn next_timeout(&self) -> Option<Instant> {
        self.0.iter().filter_map(|e| e.poll_timeout()).min()
    }

    /// Wakes those that are due at `now`.
    pub fn run_due(&mut self, now: Instant) {
        for e in &mut self.0 {
            if e.poll_timeout().is_some_and(|t| t <= now) {
                e.handle_timeout(now);
            }
        }
    }

    /// Like [`drain_transmits`](Self::drain_transmits), each body encoded into a buffer
    /// taken from `pool` (unused buffers go back to it).
    pub fn drain_transmits_with(&mut self, out: &mut Vec<Outgoing>, pool: &mut Vec<Vec<u8>>) {
        for e in &mut self.0 {
            loop {
                let buf = pool.pop().unwrap_or_default();
                match e.poll_transmit_with(buf) {
                    Ok(t) => out.push(t),
                    Err(buf) => {
                        pool.push(buf);
                        break;
                    }
                }
            }
        }
    }

    /// Moves everything they want to send into `out`.
    pub fn drain_transmits(&mut self, out: &mut Vec<Outgoing>) {
        for e in &mut self.0 {
            while let Some(t) = e.poll_transmit() {
                out.push(t);
            }
        }
    }

    /// Hands a message to every component its destination matches, except its sender;
    /// true if one took it.
    pub fn deliver(&mut self, now: Instant, header: &Header, body: &[u8]) -> bool {
        let mut any = false;
        for e in &mut self.0 {
            let a = e.address();
            if header.destination.matches(&a) && header.source != a {
                e.handle(now, header, body);
                any = true;
            }
        }
        any
    }

    /// Gives every one the wall clock ([`Endpoint::wall_clock`]).
    pub fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        for e in &mut self.0 {
            e.wall_clock(now, utc);
        }
    }

    /// Tells every one that `gone` disappeared.
    pub fn forget(&mut self, gone: Address) {
        for e in &mut self.0 {
            e.forget(gone);
        }
    }
}
