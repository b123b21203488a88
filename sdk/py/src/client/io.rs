//! The client's I/O thread: the CLI's place in the system (`jaus_client::Client::link`:
//! the peer's node joined, or a node of its own with heartbeats and discovery), its
//! System Commander (service connections, control taken and kept), and a tap that
//! reads what arrives for the client before the runtime does, answering the queries,
//! control requests and watches Python waits on.

use std::net::SocketAddr;
use std::sync::atomic::AtomicU64;
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{CancelEvent, CreateEvent, EventType, Message};
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::wire::{AckNak, MessageClass};
use jaus::{Address, CommandCode, Header};
use jaus_client::catalogue::Catalogue;
use jaus_client::confirm::{self, Check, Confirmation, Confirming, Habit, Habits, Step};
use jaus_client::{flush, flush_seen, Link};

use super::feed::{Cmd, Failure, Feed, Reply, Stats};
use crate::catalog::Catalog;

mod tap;

/// How long commands wait for the system to know the client (as the CLI's session).
const KNOWN_BY: Duration = Duration::from_millis(2500);
/// The longest the loop sleeps in a read: how soon a command from Python goes out.
const POLL: Duration = Duration::from_millis(5);
/// Refusal reasons kept until their NAK comes.
const MAX_REASONS: usize = 64;
/// Commands being confirmed by their effect at once, at most.
const MAX_CONFIRMS: usize = 256;

/// What the thread says once it has taken its place (or could not).
#[derive(Debug, Clone)]
pub(crate) struct Joined {
    pub(crate) local: SocketAddr,
    pub(crate) joined: bool,
}

struct PendingQuery {
    to: Address,
    name: &'static str,
    answer: CommandCode,
    deadline: Instant,
    reply: Reply<jaus_dynamic::DynMessage>,
}

struct PendingAck {
    to: Address,
    code: CommandCode,
    name: &'static str,
    deadline: Instant,
    reply: Reply<()>,
}

struct PendingKeep {
    to: Address,
    deadline: Instant,
    reply: Reply<()>,
}

#[derive(PartialEq, Eq)]
enum How {
    /// A service connection (the runtime's requester keeps it).
    Connection,
    /// An event: its request id, and its id once confirmed.
    Event { request: u8, id: Option<u8> },
}

struct WatchState {
    id: u64,
    to: Address,
    query: CommandCode,
    report: CommandCode,
    how: How,
    feed: Arc<Feed>,
    /// Waiting for the confirmation: (deadline, answer).
    confirm: Option<(Instant, Reply<()>)>,
}

/// The I/O thread's state.
pub(crate) struct Io {
    client: jaus_client::Client,
    cat: Arc<Catalog>,
    codes: Catalogue,
    stats: Arc<Stats>,
    port: jaus_client::Port,
    link: Link,
    reassembler: Reassembler,
    t0: Instant,
    heard: bool,
    known: bool,
    queries: Vec<PendingQuery>,
    acks: Vec<PendingAck>,
    keeps: Vec<PendingKeep>,
    kept: Vec<Address>,
    releases: Vec<Reply<()>>,
    watches: Vec<WatchState>,
    reasons: Vec<(Address, CommandCode, String)>,
    next_request: u8,
    /// Commands being confirmed by their effect, each with its answer.
    confirms: Vec<(Confirming, Reply<Confirmation>)>,
    /// What is known of each component's acknowledgements (for the client's life).
    habits: Habits,
}

fn answer<T>(reply: &Reply<T>, r: Result<T, Failure>) {
    // Python may have stopped waiting (timeout, interrupt): nothing to do then.
    let _ = reply.try_send(r);
}

fn add(c: &AtomicU64) {
    Stats::add(c);
}

impl Io {
    /// Binds, takes the client's place and waits until the peers are heard and the
    /// system knows the client (or `wait` passes).
    pub(crate) fn start(
        client: jaus_client::Client,
        cat: Arc<Catalog>,
        stats: Arc<Stats>,
    ) -> Result<Io, String> {
        let mut port = jaus_client::Port::open(&client.carrier, client.bind, &client.peers)?;
        let t0 = Instant::now();
        let mut link = client.link(&mut port, t0)?;
        if let Some(tool) = link.tool(client.me) {
            // Control is kept (asked for again when lost), never resumed behind
            // Python's back: the script sends Resume when it wants one.
            tool.behaviour_mut().0.keeper =
                jaus::stock::commander::ControlKeeper::new(jaus::stock::commander::KeeperConfig {
                    resume: false,
                    ..Default::default()
                });
        }
        Ok(Io {
            client,
            cat,
            codes: Catalogue::sdk(),
            stats,
            port,
            link,
            reassembler: Reassembler::new(ReassemblyLimits::default()),
            t0,
            heard: false,
            known: false,
            queries: Vec::new(),
            acks: Vec::new(),
            keeps: Vec::new(),
            kept: Vec::new(),
            releases: Vec::new(),
            watches: Vec::new(),
            reasons: Vec::new(),
            next_request: 1,
            confirms: Vec::new(),
            habits: Habits::default(),
        })
    }

    /// The socket and whether the peer's node was joined.
    pub(crate) fn joined(&self) -> Joined {
        Joined {
            local: self
                .port
                .local_addr()
                .unwrap_or_else(|| SocketAddr::from(([0, 0, 0, 0], 0))),
            joined: matches!(self.link, Link::Attached(_)),
        }
    }

    /// Runs the network until the system knows the client: a peer heard and (a node
    /// manager asked for its identification, or 2.5 s passed), within `wait`.
    pub(crate) fn settle(&mut self, wait: Duration) -> Result<(), String> {
        let end = self.t0 + wait;
        loop {
            let now = Instant::now();
            // A node of its own: until the tree lists the components of another node,
            // each with its name (discovery done, as `client.tree()` shows it), or
            // lists one and 2.5 s passed.
            let me = self.client.me;
            let located = match &self.link {
                Link::Node(n) => {
                    let tree = n.tree();
                    let remote: Vec<Address> = tree
                        .components()
                        .into_iter()
                        .filter(|a| (a.subsystem, a.node) != (me.subsystem, me.node))
                        .collect();
                    !remote.is_empty()
                        && (now >= self.t0 + KNOWN_BY
                            || remote
                                .iter()
                                .all(|a| tree.component(*a).is_some_and(|c| c.name.is_some())))
                }
                Link::Attached(_) => true,
            };
            if self.heard && located && (self.known || now >= self.t0 + KNOWN_BY) {
                return Ok(());
            }
            if now >= end {
                let local = self.joined().local;
                return Err(if self.heard {
                    format!("the peers {:?} answered but did not take this client ({}) into their system within {:.1} s", self.client.peers, self.client.me, wait.as_secs_f64())
                } else {
                    jaus_client::silence_hint(&local, &self.client.peers, wait)
                });
            }
            self.turn();
        }
    }

    /// The thread's loop: commands from Python, the network, deadlines; at the end
    /// every watch ended and control given back.
    pub(crate) fn run(mut self, commands: mpsc::Receiver<Cmd>) {
        loop {
            let mut close = false;
            loop {
                match commands.try_recv() {
                    Ok(Cmd::Close) | Err(mpsc::TryRecvError::Disconnected) => {
                        close = true;
                        break;
                    }
                    Ok(cmd) => self.command(cmd),
                    Err(mpsc::TryRecvError::Empty) => break,
                }
            }
            if close {
                break;
            }
            self.expire(Instant::now());
            self.confirm(Instant::now());
            self.turn();
        }
        self.finish();
    }

    /// One turn of the network: a read (at most [`POLL`]), the hosts' timers, the
    /// datagrams they queued.
    ///
    /// One datagram at a time rather than through `jaus::net::shell`: each is shown to
    /// the open confirmations and counted before the node sees it, and between two
    /// turns the thread answers Python's requests.
    fn turn(&mut self) {
        let wake = self
            .link
            .host()
            .poll_timeout()
            .map_or(POLL, |t| t.saturating_duration_since(Instant::now()))
            .clamp(Duration::from_micros(100), POLL);
        let mut buf = [0u8; 8 + 4096 + 64];
        match self.port.recv_from(&mut buf, wake) {
            Ok(None) => {}
            Ok(Some((n, from))) => {
                let now = Instant::now();
                add(&self.stats.datagrams_received);
                if self.client.peers.contains(&from) || matches!(self.link, Link::Attached(_)) {
                    self.heard = true;
                }
                self.tap(now, &buf[..n]);
                self.link.host().handle_datagram(now, from, &buf[..n]);
            }
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock
                        | std::io::ErrorKind::TimedOut
                        | std::io::ErrorKind::ConnectionReset
                ) => {}
            Err(_) => add(&self.stats.send_errors),
        }
        let host = self.link.host();
        let now = Instant::now();
        host.handle_timeout(now);
        let (framing, confirms) = (self.client.framing, &mut self.confirms);
        flush_seen(host, &mut self.port, |d| {
            for (c, _) in confirms.iter_mut() {
                c.leaving(framing, d, now);
            }
        });
        self.poll_tool();
    }

    /// What the tool's component did since: control gained, releases sent.
    fn poll_tool(&mut self) {
        let me = self.client.me;
        let Some(tool) = self.link.tool(me) else {
            return;
        };
        let commander = &tool.behaviour().0;
        let mut i = 0;
        while i < self.keeps.len() {
            if commander.keeper.holds(self.keeps[i].to) {
                let k = self.keeps.remove(i);
                if !self.kept.contains(&k.to) {
                    self.kept.push(k.to);
                }
                answer(&k.reply, Ok(()));
            } else {
                i += 1;
            }
        }
        if commander.release.is_empty() {
            for r in self.releases.drain(..) {
                answer(&r, Ok(()));
            }
        }
    }

    fn send(&mut self, to: Address, code: CommandCode, body: Vec<u8>, ack: bool) {
        let mut header = Header::new(code, to, self.client.me);
        if ack {
            header.ack_nak = AckNak::Request;
        }
        self.link.send(Instant::now(), header, body);
        add(&self.stats.messages_sent);
    }

    fn send_message(&mut self, to: Address, m: Message) {
        match m.to_bytes() {
            Ok(body) => self.send(to, m.code(), body, false),
            Err(_) => add(&self.stats.send_errors),
        }
    }

    fn command(&mut self, cmd: Cmd) {
        let now = Instant::now();
        match cmd {
            Cmd::Send {
                to,
                code,
                name,
                body,
                ack,
                confirm,
            } => {
                // Commands ask for an acknowledgement, as the CLI's do.
                let is_command = self.codes.class_of(code) == MessageClass::Command;
                let confirming = confirm.map(|(wait, reply)| {
                    let check = confirm::checks().map_or_else(
                        || Check::Nothing("the definitions did not load".into()),
                        |c| c.of(code, &body),
                    );
                    let habit = if self.link.acknowledges(to) {
                        self.habits.of(to)
                    } else {
                        Habit::Silent
                    };
                    let c = Confirming::new(to, code, name, check, habit, now, wait);
                    (c, reply)
                });
                if let Some((_, reply)) = &confirming {
                    if self.confirms.len() >= MAX_CONFIRMS {
                        let text = format!("{name}: {MAX_CONFIRMS} commands are being confirmed already; wait for one");
                        answer(reply, Err(Failure::new(text)));
                        return;
                    }
                }
                self.send(
                    to,
                    code,
                    body,
                    is_command || ack.is_some() || confirming.is_some(),
                );
                if let Some(c) = confirming {
                    self.confirms.push(c);
                }
                if let Some((wait, reply)) = ack {
                    self.acks.push(PendingAck {
                        to,
                        code,
                        name,
                        deadline: now + wait,
                        reply,
                    });
                }
            }
            Cmd::Query {
                to,
                code,
                name,
                body,
                answer,
                wait,
                reply,
            } => {
                self.send(to, code, body, false);
                self.queries.push(PendingQuery {
                    to,
                    name,
                    answer,
                    deadline: now + wait,
                    reply,
                });
            }
            Cmd::Keep {
                to,
                authority,
                wait,
                reply,
            } => {
                let me = self.client.me;
                match self.link.tool(me) {
                    Some(t) => {
                        t.behaviour_mut().0.keep.push((to, authority));
                        self.keeps.push(PendingKeep {
                            to,
                            deadline: now + wait,
                            reply,
                        });
                    }
                    None => answer(&reply, Err(Failure::new("the client has no component"))),
                }
            }
            Cmd::Release { to, reply } => {
                let me = self.client.me;
                self.kept.retain(|a| *a != to);
                self.keeps.retain(|k| k.to != to);
                match self.link.tool(me) {
                    Some(t) => {
                        t.behaviour_mut().0.release.push(to);
                        self.releases.push(reply);
                    }
                    None => answer(&reply, Ok(())),
                }
            }
            Cmd::Watch {
                id,
                to,
                query,
                query_body,
                report,
                periodic_hz,
                presence,
                feed,
                wait,
                reply,
            } => {
                let how = match periodic_hz {
                    Some(hz) => {
                        let me = self.client.me;
                        if let Some(t) = self.link.tool(me) {
                            t.behaviour_mut().0.open.push((to, report, hz, presence));
                        }
                        How::Connection
                    }
                    None => {
                        let request = self.next_request;
                        self.next_request = self.next_request.wrapping_add(1).max(1);
                        let create = CreateEvent {
                            request_id: request,
                            report_message_code: report.0,
                            event_type: EventType::EveryChange,
                            query_message: Some(query_body),
                            ..Default::default()
                        };
                        self.send_message(to, create.into());
                        How::Event { request, id: None }
                    }
                };
                self.watches.push(WatchState {
                    id,
                    to,
                    query,
                    report,
                    how,
                    feed,
                    confirm: Some((now + wait, reply)),
                });
            }
            Cmd::Unwatch { id } => {
                if let Some(i) = self.watches.iter().position(|w| w.id == id) {
                    let w = self.watches.remove(i);
                    self.end_watch(&w, "closed");
                }
            }
            Cmd::Tree { reply } => {
                let r = match &self.link {
                    Link::Node(n) => Ok(jaus_client::tree_json(n.tree())),
                    Link::Attached(_) => Err(Failure::new(format!(
                        "this client ({}) joined node {}.{} as one of its components: the system tree is that node's manager's (give the client a `me` on a node of its own, or mode=\"node\")",
                        self.client.me, self.client.me.subsystem, self.client.me.node
                    ))),
                };
                answer(&reply, r);
            }
            Cmd::Close => {}
        }
    }

    /// Ends a watch's service connection or event at the provider, and its feed.
    fn end_watch(&mut self, w: &WatchState, why: &str) {
        match w.how {
            How::Connection => {
                let me = self.client.me;
                if let Some(t) = self.link.tool(me) {
                    t.behaviour_mut().0.close.push((w.to, w.report));
                }
            }
            How::Event { request, id } => {
                let cancel = CancelEvent {
                    request_id: request,
                    message_code: Some(w.query.0),
                    event_id: id,
                };
                if id.is_some() || w.confirm.is_some() {
                    self.send_message(w.to, cancel.into());
                }
            }
        }
        if let Some((_, reply)) = &w.confirm {
            answer(reply, Err(Failure::new(why)));
        }
        w.feed.end(why);
    }

    /// Drives the commands being confirmed: their read-backs asked, their ends
    /// answered (and what they taught of their components remembered).
    fn confirm(&mut self, now: Instant) {
        let mut i = 0;
        while i < self.confirms.len() {
            match self.confirms[i].0.poll(now) {
                Step::Idle => i += 1,
                Step::Ask(code, body) => {
                    let to = self.confirms[i].0.to;
                    self.send(to, code, body, false);
                    i += 1;
                }
                Step::Done(end) => {
                    let (c, reply) = self.confirms.remove(i);
                    if let Some(acks) = c.learnt() {
                        self.habits.learn(c.to, acks);
                    }
                    answer(&reply, Ok(end));
                }
            }
        }
    }

    /// Answers what waited too long.
    fn expire(&mut self, now: Instant) {
        let waited = |d: Instant| now >= d;
        self.queries.retain(|q| {
            if waited(q.deadline) {
                let text = format!("{}: no answer from {} within the time given", q.name, q.to);
                answer(&q.reply, Err(Failure::new(text)));
                false
            } else {
                true
            }
        });
        let link = &self.link;
        self.acks.retain(|a| {
            if waited(a.deadline) {
                let text = no_ack_text(link, a.name, a.to);
                answer(&a.reply, Err(Failure::new(text)));
                false
            } else {
                true
            }
        });
        let mut gave_up = Vec::new();
        self.keeps.retain(|k| {
            if waited(k.deadline) {
                let text = format!(
                    "RequestComponentControl: no answer from {} within the time given",
                    k.to
                );
                answer(&k.reply, Err(Failure::new(text)));
                gave_up.push(k.to);
                false
            } else {
                true
            }
        });
        for to in gave_up {
            self.stop_keeping(to);
        }
        let late: Vec<usize> = (0..self.watches.len())
            .filter(|i| {
                self.watches[*i]
                    .confirm
                    .as_ref()
                    .is_some_and(|(d, _)| waited(*d))
            })
            .collect();
        for i in late.into_iter().rev() {
            let w = self.watches.remove(i);
            let name = self.cat.schema.by_code(w.report).map_or("?", |m| m.name);
            let text = format!(
                "{name} from {}: the {} was not confirmed within the time given",
                w.to,
                if w.how == How::Connection {
                    "service connection"
                } else {
                    "event"
                }
            );
            self.end_watch(&w, &text);
        }
    }

    fn stop_keeping(&mut self, to: Address) {
        let me = self.client.me;
        if let Some(t) = self.link.tool(me) {
            t.behaviour_mut().0.release.push(to);
        }
    }

    /// Ends every watch, gives control back, and sends what that takes.
    fn finish(mut self) {
        let watches: Vec<WatchState> = self.watches.drain(..).collect();
        for w in &watches {
            self.end_watch(w, "the client closed");
        }
        for to in std::mem::take(&mut self.kept) {
            self.stop_keeping(to);
        }
        for k in std::mem::take(&mut self.keeps) {
            answer(&k.reply, Err(Failure::new("the client closed")));
            self.stop_keeping(k.to);
        }
        for q in self.queries.drain(..) {
            answer(&q.reply, Err(Failure::new("the client closed")));
        }
        for a in self.acks.drain(..) {
            answer(&a.reply, Err(Failure::new("the client closed")));
        }
        for (_, reply) in self.confirms.drain(..) {
            answer(&reply, Err(Failure::new("the client closed")));
        }
        // The component's next tick sends the releases and the ends of the service
        // connections (as the CLI's session ends).
        let host = self.link.host();
        host.handle_timeout(Instant::now() + Duration::from_millis(60));
        flush(host, &mut self.port);
        for r in self.releases.drain(..) {
            answer(&r, Ok(()));
        }
    }
}

/// Why a command was not acknowledged in time, with what is known of its component: a
/// component the system tree lists is there, and one that has never acknowledged
/// anything most likely never will (OpenJAUS 3.3's components send no ACK/NAK).
fn no_ack_text(link: &Link, name: &str, to: Address) -> String {
    let node = match link {
        Link::Node(n) => Some(n),
        Link::Attached(_) => None,
    };
    let listed = node.is_some_and(|n| n.tree().component(to).is_some());
    let silent = node.is_some_and(|n| !n.acknowledges(to));
    match (listed, silent) {
        (true, true) => format!(
            "{name}: {to} is in the system but has never acknowledged a command (it let every request for one go unanswered; OpenJAUS 3.3's components never send ACK/NAK): `ack=True` cannot confirm it there; query the value back to see whether it took effect"
        ),
        (true, false) => format!(
            "{name}: {to} is in the system but did not acknowledge within the time given (it may never acknowledge, as OpenJAUS 3.3's components do not; query the value back to see whether it took effect)"
        ),
        _ => format!(
            "{name}: no acknowledgement from {to} within the time given, and the system tree does not list it (is the component there? `client.tree()` lists the system)"
        ),
    }
}
