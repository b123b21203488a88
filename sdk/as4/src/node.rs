//! An AS-4 node: one or more [`As4Component`]s and their environment behind one
//! AS5669A endpoint ([`As4Endpoint`]), sans-IO.
//!
//! [`As4Node`] takes the whole messages an [`As4Stack`](jaus::net::as5669a::As4Stack)
//! (or an [`As4Mux`](jaus::net::as5669a::As4Mux)) hands it, decodes each (a body that
//! does not decode is counted and logged, never a panic), gives it to the component its
//! destination names (every matching component for a broadcast id: 0xFFFF subsystem,
//! 0xFF node or component) and encodes what the components answer.
//!
//! It remembers the address each AS-4 sender id last came from (at most
//! [`DEFAULT_MAX_PEERS`] ids by default; the one heard from least recently leaves first,
//! counted), so that messages for others than the sender (the Reject Control of a
//! preempted controller, Events) reach them. Answers for the sender's address go back
//! with [`As4Endpoint::handle`]'s return; messages for other addresses wait for
//! [`As4Endpoint::handle_timeout`], which [`As4Endpoint::poll_timeout`] makes due at
//! once. A message for an id never heard from is dropped and counted.
//!
//! The owner may change the environment between calls ([`As4Node::env_mut`]); it then
//! calls [`As4Node::poll`] so that the services notice ([`Service::tick`]) and events due
//! go out. Every-change events also notice at their own tick (20 Hz by default) through
//! [`As4Endpoint::handle_timeout`].
//!
//! [`Service::tick`]: crate::service::Service::tick

use std::collections::HashMap;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Endpoint, As4Id, As4Message, As4Send};
use jaus::net::PeerAddr;
use jaus::CommandCode;

use crate::component::{As4Component, Outgoing};
use crate::messages::Message;

/// Default bound on the AS-4 ids whose address a node remembers.
pub const DEFAULT_MAX_PEERS: usize = 1024;

/// Counters of a node.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NodeStats {
    /// Messages received.
    pub received: u64,
    /// Messages whose body did not decode.
    pub decode_errors: u64,
    /// Messages for no component of the node.
    pub no_destination: u64,
    /// Messages sent (answers and others).
    pub sent: u64,
    /// Messages not sent: no address known for the destination.
    pub unknown_peer: u64,
    /// Messages not sent: the body did not encode.
    pub encode_errors: u64,
    /// Remembered addresses dropped for newer ones (the bound).
    pub peers_evicted: u64,
}

/// A node hosting AS-4 components (by id) and their environment `E`, speaking AS5669A
/// to peers at addresses `A`.
#[derive(Debug)]
pub struct As4Node<E, A: PeerAddr = SocketAddr> {
    components: Vec<As4Component<E>>,
    env: E,
    peers: HashMap<As4Id, (A, u64)>,
    heard: u64,
    max_peers: usize,
    pending: Vec<As4Send<A>>,
    pending_since: Option<Instant>,
    stats: NodeStats,
}

impl<E: std::fmt::Debug + Send + 'static, A: PeerAddr> As4Node<E, A> {
    /// A node without components, with environment `env`.
    pub fn new(env: E) -> Self {
        Self {
            components: Vec::new(),
            env,
            peers: HashMap::new(),
            heard: 0,
            max_peers: DEFAULT_MAX_PEERS,
            pending: Vec::new(),
            pending_since: None,
            stats: NodeStats::default(),
        }
    }

    /// With `component` added ([`add_component`](Self::add_component)).
    pub fn with_component(mut self, component: As4Component<E>) -> Self {
        self.add_component(component);
        self
    }

    /// Adds `component` (replacing one of the same id). The components of the node know
    /// each other's services (Discovery); add a component's services before adding it.
    pub fn add_component(&mut self, mut component: As4Component<E>) {
        self.components.retain(|c| c.id() != component.id());
        let (id, services) = (component.id(), component.service_infos());
        for other in &mut self.components {
            let mine = other
                .core_mut()
                .discovery_mut()
                .register(id, services.clone());
            let theirs = component
                .core_mut()
                .discovery_mut()
                .register(other.id(), other.service_infos());
            if let Err(e) = mine.and(theirs) {
                tracing::warn!(component = %id, sibling = %other.id(), "not registered: {e}");
            }
        }
        self.components.push(component);
    }

    /// Bounds the remembered addresses to `max` ids (at least 1).
    pub fn set_max_peers(&mut self, max: usize) {
        self.max_peers = max.max(1);
    }

    /// The environment.
    pub fn env(&self) -> &E {
        &self.env
    }

    /// The environment, mutably (call [`poll`](Self::poll) after changing it).
    pub fn env_mut(&mut self) -> &mut E {
        &mut self.env
    }

    /// Component `id`.
    pub fn component(&self, id: As4Id) -> Option<&As4Component<E>> {
        self.components.iter().find(|c| c.id() == id)
    }

    /// Component `id`, mutably.
    pub fn component_mut(&mut self, id: As4Id) -> Option<&mut As4Component<E>> {
        self.components.iter_mut().find(|c| c.id() == id)
    }

    /// Every component.
    pub fn components(&self) -> impl Iterator<Item = &As4Component<E>> + '_ {
        self.components.iter()
    }

    /// Counters.
    pub fn stats(&self) -> NodeStats {
        self.stats
    }

    /// The address remembered for `id`.
    pub fn peer(&self, id: As4Id) -> Option<A> {
        self.peers.get(&id).map(|(a, _)| *a)
    }

    /// Remembers that `id` is at `addr` (as if a message had come from there).
    pub fn learn_peer(&mut self, id: As4Id, addr: A) {
        self.heard += 1;
        if !self.peers.contains_key(&id) && self.peers.len() >= self.max_peers {
            if let Some(oldest) = self
                .peers
                .iter()
                .min_by_key(|(_, (_, t))| *t)
                .map(|(k, _)| *k)
            {
                self.peers.remove(&oldest);
                self.stats.peers_evicted += 1;
            }
        }
        self.peers.insert(id, (addr, self.heard));
    }

    /// The wall clock for every component: UTC (since 1970-01-01) is `utc` at `now`.
    pub fn set_utc(&mut self, now: Instant, utc: Duration) {
        for c in &mut self.components {
            c.set_utc(now, utc);
        }
    }

    /// After the owner changed the environment: the services' ticks and the events
    /// due, as messages for their peers (with anything else waiting to be sent).
    pub fn poll(&mut self, now: Instant) -> Vec<As4Send<A>> {
        for i in 0..self.components.len() {
            let c = &mut self.components[i];
            let out = c.tick(now, &mut self.env);
            let source = c.id();
            self.queue(now, source, out);
        }
        self.take_pending()
    }

    fn take_pending(&mut self) -> Vec<As4Send<A>> {
        self.pending_since = None;
        std::mem::take(&mut self.pending)
    }

    fn encode(&mut self, source: As4Id, o: &Outgoing) -> Option<As4Message> {
        match o.message.body().to_bytes() {
            Ok(body) => Some(As4Message::new(o.message.code().0, o.to, source, body)),
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(message = o.message.name(), to = %o.to, "not encoded: {e}");
                None
            }
        }
    }

    /// Queues `out` from `source` for the remembered addresses.
    fn queue(&mut self, now: Instant, source: As4Id, out: Vec<Outgoing>) {
        for o in out {
            let Some(to) = self.peer(o.to) else {
                self.stats.unknown_peer += 1;
                tracing::debug!(message = o.message.name(), to = %o.to, "no address known");
                continue;
            };
            if let Some(message) = self.encode(source, &o) {
                self.stats.sent += 1;
                self.pending.push(As4Send { to, message });
                self.pending_since.get_or_insert(now);
            }
        }
    }

    fn decode(&mut self, m: &As4Message) -> Option<Message> {
        match Message::decode(CommandCode(m.message_id), &m.body) {
            Ok(msg) => Some(msg),
            Err(e) => {
                self.stats.decode_errors += 1;
                tracing::debug!(
                    id = %format_args!("{:#06X}", m.message_id),
                    from = %m.source,
                    "AS-4 message does not decode: {e}"
                );
                None
            }
        }
    }
}

/// Whether a message for `dest` is for component `id` (equal, or a broadcast id that
/// covers it: 0xFFFF subsystem, 0xFF node or component).
pub(crate) fn addressed(dest: As4Id, id: As4Id) -> bool {
    (dest.subsystem == 0xFFFF || dest.subsystem == id.subsystem)
        && (dest.node == 0xFF || dest.node == id.node)
        && (dest.component == 0xFF || dest.component == id.component)
}

impl<E: std::fmt::Debug + Send + 'static, A: PeerAddr> As4Endpoint<A> for As4Node<E, A> {
    fn handle(&mut self, now: Instant, from: A, messages: Vec<As4Message>) -> Vec<As4Message> {
        let mut replies = Vec::new();
        for m in messages {
            self.stats.received += 1;
            self.learn_peer(m.source, from);
            let Some(msg) = self.decode(&m) else {
                continue;
            };
            let mut any = false;
            for i in 0..self.components.len() {
                if !addressed(m.destination, self.components[i].id()) {
                    continue;
                }
                any = true;
                let c = &mut self.components[i];
                let source = c.id();
                let out = c.handle(now, m.source, &msg, &mut self.env);
                let (here, elsewhere): (Vec<_>, Vec<_>) = out
                    .into_iter()
                    .partition(|o| o.to == m.source || self.peer(o.to) == Some(from));
                for o in here {
                    if let Some(mut r) = self.encode(source, &o) {
                        if o.to == m.source {
                            r.priority = m.priority;
                        }
                        self.stats.sent += 1;
                        replies.push(r);
                    }
                }
                self.queue(now, source, elsewhere);
            }
            if !any {
                self.stats.no_destination += 1;
                tracing::debug!(to = %m.destination, from = %m.source, "no such component here");
            }
        }
        replies
    }

    fn handle_timeout(&mut self, now: Instant) -> Vec<As4Send<A>> {
        for i in 0..self.components.len() {
            let c = &mut self.components[i];
            if c.poll_timeout().is_some_and(|t| t <= now) {
                let out = c.handle_timeout(now, &mut self.env);
                let source = c.id();
                self.queue(now, source, out);
            }
        }
        self.take_pending()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.components
            .iter()
            .filter_map(|c| c.poll_timeout())
            .chain(self.pending_since)
            .min()
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.set_utc(now, utc);
    }
}
