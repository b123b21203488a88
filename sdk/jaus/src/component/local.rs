//! In-process transport with a virtual clock: several components exchanging encoded
//! messages deterministically, for tests, simulations and single-process systems.
//!
//! ```
//! use std::time::{Duration, Instant};
//! use jaus::component::local::{LocalBus, Probe};
//! use jaus::messages::{QueryComponentStatus, Message};
//! use jaus::Address;
//!
//! let mut bus = LocalBus::new(Instant::now());
//! let probe = Address::new(1, 1, 200, 1);
//! bus.add(Probe::new(probe));
//! // A probe asking a probe: nobody answers, but the message is delivered.
//! bus.send(probe, probe, QueryComponentStatus {});
//! bus.run_for(Duration::from_millis(10));
//! let p: &Probe = bus.get(probe).unwrap();
//! assert!(matches!(p.received()[0].message, Message::QueryComponentStatus(_)));
//! ```

use std::any::Any;
use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

pub use super::Endpoint;
use super::Outgoing;
use crate::codec::{Encode, EncodeError};
use crate::messages::Message;
use crate::{Address, Header, MessageSet};

/// A message as it crossed the bus.
#[derive(Debug, Clone, PartialEq)]
pub struct Delivery {
    /// When it was delivered.
    pub at: Instant,
    /// Its header.
    pub header: Header,
    /// The decoded message (`None` for ACK/NAK or a body that did not decode).
    pub message: Option<Message>,
}

/// A received message recorded by a [`Probe`].
#[derive(Debug, Clone, PartialEq)]
pub struct Received<M = Message> {
    /// When it arrived.
    pub at: Instant,
    /// Its header.
    pub header: Header,
    /// The message.
    pub message: M,
}

/// An endpoint that only records what it receives (at most `capacity` messages; the
/// rest are counted in [`Probe::dropped`]), decoded as messages of set `M` (the
/// standard set unless a vendor's is named: `Probe::<acme::Message>::new(a)`).
#[derive(Debug)]
pub struct Probe<M = Message> {
    address: Address,
    received: Vec<Received<M>>,
    capacity: usize,
    dropped: u64,
}

impl Probe {
    /// A probe at `address` decoding standard messages, keeping up to 100,000 of them.
    pub fn new(address: Address) -> Self {
        Probe::for_set(address)
    }
}

impl<M: MessageSet> Probe<M> {
    /// A probe at `address` decoding messages of set `M`, keeping up to 100,000 of them.
    pub fn for_set(address: Address) -> Self {
        Self {
            address,
            received: Vec::new(),
            capacity: 100_000,
            dropped: 0,
        }
    }

    /// Everything received, in order.
    pub fn received(&self) -> &[Received<M>] {
        &self.received
    }

    /// The messages received, in order.
    pub fn messages(&self) -> impl Iterator<Item = &M> {
        self.received.iter().map(|r| &r.message)
    }

    /// Forgets what was received.
    pub fn clear(&mut self) {
        self.received.clear();
    }

    /// Messages not kept (capacity reached or undecodable).
    pub fn dropped(&self) -> u64 {
        self.dropped
    }
}

impl<M: MessageSet> Endpoint for Probe<M> {
    fn address(&self) -> Address {
        self.address
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        match M::decode(header.command_code, body) {
            Ok(message) if self.received.len() < self.capacity => self.received.push(Received {
                at: now,
                header: *header,
                message,
            }),
            _ => self.dropped += 1,
        }
    }
    fn handle_timeout(&mut self, _now: Instant) {}
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        None
    }
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Counters of the bus.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BusStats {
    /// Messages handed to at least one endpoint.
    pub delivered: u64,
    /// Messages no endpoint's address matched.
    pub undeliverable: u64,
    /// Messages whose body could not be encoded.
    pub encode_errors: u64,
    /// Messages dropped by the drop filter.
    pub filtered: u64,
}

type Filter = Box<dyn FnMut(&Header) -> bool + Send>;

/// Endpoints exchanging encoded messages on a virtual clock. Every message is encoded
/// by its sender and decoded by its receivers, after a fixed latency; timers and
/// deliveries run in time order, ties in the order they were queued, so a run is
/// reproducible exactly.
pub struct LocalBus {
    now: Instant,
    latency: Duration,
    endpoints: Vec<Box<dyn Endpoint>>,
    in_flight: BTreeMap<(Instant, u64), (Header, Vec<u8>)>,
    next_seq: u64,
    trace: VecDeque<Delivery>,
    trace_capacity: usize,
    stats: BusStats,
    filter: Option<Filter>,
}

impl std::fmt::Debug for LocalBus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LocalBus")
            .field("now", &self.now)
            .field("endpoints", &self.endpoints.len())
            .field("in_flight", &self.in_flight.len())
            .field("stats", &self.stats)
            .finish()
    }
}

impl LocalBus {
    /// An empty bus whose clock starts at `start`, with a 1 ms latency.
    pub fn new(start: Instant) -> Self {
        Self {
            now: start,
            latency: Duration::from_millis(1),
            endpoints: Vec::new(),
            in_flight: BTreeMap::new(),
            next_seq: 0,
            trace: VecDeque::new(),
            trace_capacity: 0,
            stats: BusStats::default(),
            filter: None,
        }
    }

    /// Sets the delivery latency.
    pub fn with_latency(mut self, latency: Duration) -> Self {
        self.latency = latency;
        self
    }

    /// Keeps the last `capacity` deliveries for [`trace`](Self::trace).
    pub fn with_trace(mut self, capacity: usize) -> Self {
        self.trace_capacity = capacity;
        self
    }

    /// Drops every message for which `keep` returns false (to cut a link in a test).
    pub fn set_filter(&mut self, keep: impl FnMut(&Header) -> bool + Send + 'static) {
        self.filter = Some(Box::new(keep));
    }

    /// Removes the drop filter.
    pub fn clear_filter(&mut self) {
        self.filter = None;
    }

    /// Adds an endpoint; returns its address.
    pub fn add(&mut self, endpoint: impl Endpoint) -> Address {
        let a = endpoint.address();
        self.endpoints.push(Box::new(endpoint));
        a
    }

    /// Adds a boxed endpoint; returns its address.
    pub fn add_boxed(&mut self, endpoint: Box<dyn Endpoint>) -> Address {
        let a = endpoint.address();
        self.endpoints.push(endpoint);
        a
    }

    /// Removes the endpoint at `address` (a crash, in a test).
    pub fn remove(&mut self, address: Address) -> bool {
        let before = self.endpoints.len();
        self.endpoints.retain(|e| e.address() != address);
        before != self.endpoints.len()
    }

    /// The virtual time.
    pub fn now(&self) -> Instant {
        self.now
    }

    /// Counters.
    pub fn stats(&self) -> BusStats {
        self.stats
    }

    /// The endpoint at `address`, as a `T`.
    pub fn get<T: 'static>(&self, address: Address) -> Option<&T> {
        self.endpoints
            .iter()
            .find(|e| e.address() == address)
            .and_then(|e| e.as_any().downcast_ref())
    }

    /// The endpoint at `address`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, address: Address) -> Option<&mut T> {
        self.endpoints
            .iter_mut()
            .find(|e| e.address() == address)
            .and_then(|e| e.as_any_mut().downcast_mut())
    }

    /// The last deliveries (see [`with_trace`](Self::with_trace)).
    pub fn trace(&self) -> impl Iterator<Item = &Delivery> {
        self.trace.iter()
    }

    /// Queues `msg` from `from` to `to`, as if `from` had sent it.
    pub fn send(&mut self, from: Address, to: Address, msg: impl Into<Message>) {
        let msg = msg.into();
        let header = Header::new(msg.code(), to, from);
        self.send_with(header, Some(&msg));
    }

    /// Queues a message of any set (a vendor's, say) from `from` to `to`.
    pub fn send_set<M: MessageSet>(&mut self, from: Address, to: Address, msg: &M) {
        let header = Header::new(msg.code(), to, from);
        self.send_encoded(header, msg.to_bytes());
    }

    /// Queues a message under a header of the caller's choosing.
    pub fn send_with(&mut self, header: Header, msg: Option<&Message>) {
        self.send_encoded(header, msg.map_or(Ok(Vec::new()), |m| m.to_bytes()));
    }

    fn send_encoded(&mut self, header: Header, body: Result<Vec<u8>, EncodeError>) {
        let body = match body {
            Ok(b) => b,
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, source = %header.source, "not sent: {e}");
                return;
            }
        };
        let at = self.now + self.latency;
        self.in_flight.insert((at, self.next_seq), (header, body));
        self.next_seq += 1;
    }

    /// Runs for `d` of virtual time.
    pub fn run_for(&mut self, d: Duration) {
        let t = self.now + d;
        self.run_until(t);
    }

    /// Runs until the virtual clock reaches `t`.
    pub fn run_until(&mut self, t: Instant) {
        loop {
            self.collect();
            let next_packet = self.in_flight.keys().next().map(|k| k.0);
            let next_timer = self.endpoints.iter().filter_map(|e| e.poll_timeout()).min();
            let next = match (next_packet, next_timer) {
                (Some(p), Some(q)) => p.min(q),
                (Some(p), None) => p,
                (None, Some(q)) => q,
                (None, None) => break,
            };
            if next > t {
                break;
            }
            if next > self.now {
                self.now = next;
            }
            let now = self.now;
            if next_packet.is_some_and(|p| p <= now) {
                if let Some(((_, _), (header, body))) = self.in_flight.pop_first() {
                    self.deliver(&header, &body);
                }
                continue;
            }
            for e in &mut self.endpoints {
                if e.poll_timeout().is_some_and(|w| w <= now) {
                    e.handle_timeout(now);
                }
            }
        }
        if t > self.now {
            self.now = t;
        }
    }

    fn collect(&mut self) {
        let mut out = Vec::new();
        for e in &mut self.endpoints {
            while let Some(t) = e.poll_transmit() {
                out.push(t);
            }
        }
        for t in out {
            self.send_encoded(t.header, t.body);
        }
    }

    fn deliver(&mut self, header: &Header, body: &[u8]) {
        if let Some(keep) = &mut self.filter {
            if !keep(header) {
                self.stats.filtered += 1;
                return;
            }
        }
        if self.trace_capacity > 0 {
            if self.trace.len() == self.trace_capacity {
                self.trace.pop_front();
            }
            self.trace.push_back(Delivery {
                at: self.now,
                header: *header,
                message: Message::decode(header.command_code, body).ok(),
            });
        }
        let mut any = false;
        for e in &mut self.endpoints {
            if header.destination.matches(&e.address()) {
                any = true;
                e.handle(self.now, header, body);
            }
        }
        if any {
            self.stats.delivered += 1;
        } else {
            self.stats.undeliverable += 1;
        }
    }
}
