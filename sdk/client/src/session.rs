//! The operator's session (`send`, `query`, `watch`): messages sent in order, each after
//! the previous one was answered, control held and given back.

use std::collections::VecDeque;
use std::io::{BufRead, Write};
use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{Message, ReleaseComponentControl};
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::wire::{AckNak, MessageClass};
use jaus::{Address, CommandCode, Header, JausMessage};

use super::{
    confirm::{self, Check, Confirmation, Confirming, Habit, Habits, Step},
    output::{unix_now, AckLine, RawLine, Tap, Tapped},
    place::{flush, flush_seen, Client, Link},
    port::Port,
};

/// What the session does with its time.
#[derive(Debug, Clone, Default)]
pub struct Script {
    /// Messages to send, in order, each to its destination.
    pub messages: Vec<(Address, Message)>,
    /// Also take messages from standard input (JSON lines), as they come.
    pub stdin: bool,
    /// Service connections to open: (provider, report, rate Hz, presence vector).
    pub service_connections: Vec<(Address, CommandCode, f64, u32)>,
    /// Print incoming query messages and heartbeats too.
    pub all: bool,
    /// End as soon as every message sent is answered (query → its report, command →
    /// ACK or NAK), or `wait` after the last one was sent when some are not.
    pub until_answered: bool,
    /// Stay this long after the last message (holding control, watching): `None` runs
    /// until interrupted.
    pub hold: Option<Duration>,
    /// Default destination of stdin lines without one.
    pub to: Option<Address>,
    /// The messages spoken: the SDK's, and a vendor's overlays (`--spec`).
    pub catalogue: std::sync::Arc<crate::catalogue::Catalogue>,
}

/// What a session saw.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Outcome {
    /// Messages printed.
    pub printed: usize,
    /// Messages sent.
    pub sent: usize,
    /// Sent messages answered (report, ACK or NAK).
    pub answered: usize,
    /// NAKs received.
    pub naks: usize,
    /// Whether anything at all came from a peer.
    pub heard: bool,
    /// Whether the CLI joined the peer's node (else it ran a node of its own).
    pub joined: bool,
    /// Bad input lines.
    pub bad_lines: usize,
    /// Control requests rejected (Reject Component Control received).
    pub rejected: usize,
    /// Commands (sent with an acknowledgement request) that got neither ACK nor NAK,
    /// each with what the system tree says of its destination and what to do.
    pub unacknowledged: Vec<String>,
    /// Refusals received (NAKs), each with its reason when the receiver gave one.
    pub refusals: Vec<String>,
    /// The socket the session used.
    pub local: Option<SocketAddr>,
    /// Another node answers as this tool's node (`--me`'s subsystem and node): the
    /// session stopped.
    pub conflict: Option<String>,
    /// With [`Client::confirm`]: how each command ended (destination, name, outcome),
    /// in the order sent. A command not confirmed is also in `unacknowledged`.
    pub confirmations: Vec<(Address, String, Confirmation)>,
}

impl Client {
    /// Runs one session: takes its place, sends `script`'s messages in order (each
    /// after the previous one was answered, or after a short pause when the receiver
    /// does not acknowledge), opens its service connections, prints every message
    /// addressed to it as a timestamped JSON line as it arrives, and at the end ends
    /// its service connections and gives back the control it took.
    pub fn session(
        &self,
        script: &Script,
        stop: &AtomicBool,
        out: &mut impl Write,
        err: &mut impl Write,
    ) -> Result<Outcome, String> {
        let mut port = Port::open(&self.carrier, self.bind, &self.peers)?;
        let local = port.describe();
        let t0 = Instant::now();
        let mut link = self.link(&mut port, t0)?;
        let mut outcome = Outcome {
            joined: matches!(link, Link::Attached(_)),
            local: port.local_addr(),
            ..Outcome::default()
        };
        // Commands wait until the system knows this tool (a node manager asked for its
        // identification or services): OpenJAUS rejects a controller it cannot find in its
        // system tree. Queries go at once.
        let mut known = false;
        let known_by = Duration::from_millis(2500);
        let mut requested: Vec<Address> = Vec::new();
        let me = self.me;
        let cat = &script.catalogue;
        let lines = script.stdin.then(stdin_reader);
        let mut queue: VecDeque<(Address, Message)> = script.messages.iter().cloned().collect();
        let mut stdin_open = lines.is_some();
        // The message waiting for its answer: (code answering it, destination, deadline).
        let mut pending: Option<(Option<CommandCode>, Address, CommandCode, Instant)> = None;
        let mut last_sent: Option<Instant> = None;
        let mut controlled: Vec<Address> = Vec::new();
        // Commands sent with an acknowledgement request, waiting for their ACK or NAK.
        let mut awaiting_ack: Vec<(Address, CommandCode)> = Vec::new();
        // Reasons given by Report Refusal, until their NAK arrives.
        let mut reasons: Vec<(Address, CommandCode, String)> = Vec::new();
        let mut opened = false;
        // The command being confirmed by its effect (`confirm`), and what is learnt of
        // the components' acknowledgements.
        let mut confirming: Option<Confirming> = None;
        let mut habits = Habits::default();
        let mut tap = Tap {
            me,
            framing: self.framing,
            reassembler: Reassembler::new(ReassemblyLimits::default()),
        };
        let mut done = false;
        let step = Duration::from_millis(500);
        let mut buf = vec![0u8; 8 + 4096 + 64];
        loop {
            let now = Instant::now();
            if stop.load(Ordering::Relaxed) {
                break;
            }
            // Input lines.
            if let Some(rx) = &lines {
                loop {
                    match rx.try_recv() {
                        Ok(line) => {
                            if line.trim().is_empty() {
                                continue;
                            }
                            match cat.parse_message(&line) {
                                Ok((to, m)) => match to.or(script.to) {
                                    Some(to) => queue.push_back((to, m)),
                                    None => {
                                        outcome.bad_lines += 1;
                                        let _ = writeln!(err, "error: {}: no destination (--to, or a header with a destination)", m.name());
                                    }
                                },
                                Err(e) => {
                                    outcome.bad_lines += 1;
                                    let _ = writeln!(err, "error: {e}");
                                }
                            }
                        }
                        Err(mpsc::TryRecvError::Empty) => break,
                        Err(mpsc::TryRecvError::Disconnected) => {
                            stdin_open = false;
                            break;
                        }
                    }
                }
            }
            // The next message, once the previous one is answered or timed out.
            if pending.is_some_and(|p| now >= p.3) {
                pending = None;
            }
            if pending.is_none() && confirming.is_none() {
                if let Some((to, next)) = queue.front() {
                    let waited = now.saturating_duration_since(t0);
                    let ready = (link.reaches(*to) || waited > Duration::from_millis(300))
                        && (known
                            || cat.class_of(next.code()) != MessageClass::Command
                            || waited > known_by);
                    if ready {
                        let Some((to, msg)) = queue.pop_front() else {
                            continue;
                        };
                        let body = msg.to_bytes().map_err(|e| format!("{}: {e}", msg.name()))?;
                        let code = msg.code();
                        let mut header = Header::new(code, to, me);
                        let class = cat.class_of(code);
                        if class == MessageClass::Command {
                            header.ack_nak = AckNak::Request;
                            awaiting_ack.push((to, code));
                        }
                        if matches!(msg, Message::RequestComponentControl(_)) {
                            requested.push(to);
                        }
                        if matches!(msg, Message::ReleaseComponentControl(_)) {
                            controlled.retain(|a| *a != to);
                            requested.retain(|a| *a != to);
                        }
                        let answer = cat.answer_of(code);
                        let wait = if class == MessageClass::Query {
                            self.wait
                        } else {
                            step
                        };
                        if self.confirm && class == MessageClass::Command {
                            let check = confirm::checks().map_or_else(
                                || Check::Nothing("the definitions did not load".into()),
                                |c| c.of(code, &body),
                            );
                            let habit = if link.acknowledges(to) {
                                habits.of(to)
                            } else {
                                Habit::Silent
                            };
                            confirming = Some(Confirming::new(
                                to,
                                code,
                                msg.name(),
                                check,
                                habit,
                                now,
                                self.wait,
                            ));
                        } else {
                            pending = Some((answer, to, code, now + wait));
                        }
                        link.send(now, header, body);
                        outcome.sent += 1;
                        last_sent = Some(now);
                    }
                }
            }
            if !opened && !script.service_connections.is_empty() {
                opened = true;
                if let Some(t) = link.tool(me) {
                    t.behaviour_mut()
                        .0
                        .open
                        .extend(script.service_connections.iter().copied());
                }
            }
            // The command being confirmed: its read-back asked, or its end.
            if let Some(c) = &mut confirming {
                match c.poll(now) {
                    Step::Idle => {}
                    Step::Ask(code, body) => link.send(now, Header::new(code, c.to, me), body),
                    Step::Done(end) => {
                        if let Some(acks) = c.learnt() {
                            habits.learn(c.to, acks);
                        }
                        let (to, code, name) = (c.to, c.code, c.name.clone());
                        confirming = None;
                        if let Some(i) = awaiting_ack
                            .iter()
                            .position(|(a, k)| *a == to && *k == code)
                        {
                            awaiting_ack.remove(i);
                        }
                        let text = format!("{name} to {to}: {end}");
                        let _ = writeln!(err, "{text}");
                        let line = serde_json::json!({
                            "t": now.saturating_duration_since(t0).as_secs_f64(),
                            "utc": unix_now(),
                            "confirm": name,
                            "to": to.to_string(),
                            "outcome": end.outcome(),
                            "detail": end.detail(),
                        });
                        let _ = writeln!(out, "{line}");
                        let _ = out.flush();
                        outcome.printed += 1;
                        match &end {
                            Confirmation::ReadBack(_) => outcome.answered += 1,
                            Confirmation::NotConfirmed(_) => outcome.unacknowledged.push(text),
                            Confirmation::Refused(d)
                                if d.starts_with("Confirm Component Control") =>
                            {
                                outcome.rejected += 1;
                            }
                            _ => {}
                        }
                        outcome.confirmations.push((to, name, end));
                    }
                }
            }
            // Done?
            let idle = queue.is_empty() && pending.is_none() && confirming.is_none() && !stdin_open;
            if idle && !done {
                let since = last_sent.unwrap_or(t0);
                let all_answered = outcome.answered >= outcome.sent;
                let finished = match script.hold {
                    Some(h) => now.saturating_duration_since(since) >= h,
                    None => false,
                } || (script.until_answered
                    && (all_answered || now.saturating_duration_since(since) >= self.wait));
                if finished {
                    done = true;
                }
            }
            if done {
                break;
            }
            // The network, one datagram at a time rather than through
            // `jaus::net::shell`: each datagram is read by the session before the node
            // sees it (an acknowledgement, a confirmation's answer, another node
            // answering as this tool's node ends the session at that datagram), and
            // between two datagrams the session takes the operator's next line.
            let host = link.host();
            let wake = host
                .poll_timeout()
                .map_or(Duration::from_millis(50), |t| {
                    t.saturating_duration_since(Instant::now())
                })
                .clamp(Duration::from_micros(100), Duration::from_millis(50));
            match port.recv_from(&mut buf, wake) {
                Ok(Some((n, from))) => {
                    let now = Instant::now();
                    if self.peers.contains(&from) || matches!(link, Link::Attached(_)) {
                        outcome.heard = true;
                    }
                    if !outcome.joined {
                        if let Some(other) = tap.foreign_twin(&buf[..n]) {
                            let text = format!("another node answers as {}.{} (a message for {other} arrived from {from}); this tool's --me {me} is on that node: use --mode join to join it, or a --me on a node of its own", me.subsystem, me.node);
                            let _ = writeln!(err, "error: {text}");
                            outcome.conflict = Some(text);
                            break;
                        }
                    }
                    if let Some(seen) = tap.see(now, &buf[..n]) {
                        let (t, utc) = ((now - t0).as_secs_f64(), unix_now());
                        match seen {
                            Tapped::Ack(h) => {
                                let name = cat.name_of(h.command_code).unwrap_or("?");
                                if let Some(p) =
                                    pending.filter(|p| p.1 == h.source && p.2 == h.command_code)
                                {
                                    let _ = p;
                                    pending = None;
                                }
                                outcome.answered += 1;
                                if let Some(i) = awaiting_ack
                                    .iter()
                                    .position(|(a, c)| a.matches(&h.source) && *c == h.command_code)
                                {
                                    awaiting_ack.remove(i);
                                }
                                let nak = h.ack_nak == AckNak::Nak;
                                let reason = reasons
                                    .iter()
                                    .position(|(a, c, _)| *a == h.source && *c == h.command_code)
                                    .filter(|_| nak)
                                    .map(|i| reasons.remove(i).2);
                                if let Some(c) = confirming
                                    .as_mut()
                                    .filter(|c| c.to.matches(&h.source) && c.code == h.command_code)
                                {
                                    c.ack(nak, reason.as_deref());
                                }
                                if nak {
                                    outcome.naks += 1;
                                    let text = format!(
                                        "NAK from {} for {name}: {}",
                                        h.source,
                                        reason.as_deref().unwrap_or("refused (the receiver gave no reason: its log may name it)")
                                    );
                                    let _ = writeln!(err, "{text}");
                                    outcome.refusals.push(text);
                                }
                                let line = AckLine {
                                    t,
                                    utc,
                                    header: &h,
                                    acknowledges: name,
                                };
                                let _ = writeln!(
                                    out,
                                    "{}",
                                    serde_json::to_string(&line).unwrap_or_default()
                                );
                                outcome.printed += 1;
                            }
                            Tapped::Packet(p) => {
                                let code = p.header.command_code;
                                let from_addr = p.header.source;
                                match &p.message {
                                    Message::QueryIdentification(_) | Message::QueryServices(_) => {
                                        known = true;
                                    }
                                    Message::ConfirmComponentControl(c)
                                        if c.response_code
                                            == jaus::messages::ControlResponse::ControlAccepted
                                            && requested.contains(&from_addr)
                                            && !controlled.contains(&from_addr) =>
                                    {
                                        controlled.push(from_addr);
                                    }
                                    Message::ReportRefusal(r) => {
                                        if let Some(c) = confirming.as_mut().filter(|c| {
                                            c.to.matches(&from_addr)
                                                && c.code == CommandCode(r.refused_code)
                                        }) {
                                            c.refused(&r.text);
                                        }
                                        // The reason of the NAK that follows.
                                        if reasons.len() >= 64 {
                                            reasons.remove(0);
                                        }
                                        reasons.push((
                                            from_addr,
                                            CommandCode(r.refused_code),
                                            r.text.clone(),
                                        ));
                                    }
                                    Message::RejectComponentControl(_) => {
                                        if requested.contains(&from_addr)
                                            || controlled.contains(&from_addr)
                                        {
                                            outcome.rejected += 1;
                                            let _ = writeln!(err, "control of {from_addr} rejected (or taken by a component of higher authority)");
                                        }
                                        controlled.retain(|a| *a != from_addr);
                                        requested.retain(|a| *a != from_addr);
                                    }
                                    _ => {}
                                }
                                if let (Some(c), Some(checks)) =
                                    (confirming.as_mut(), confirm::checks())
                                {
                                    if let Ok(body) = p.message.to_bytes() {
                                        c.message(checks, from_addr, code, &body);
                                    }
                                }
                                let answer = pending.is_some_and(|q| {
                                    q.0 == Some(code) && q.1.matches(&p.header.source)
                                });
                                if answer {
                                    pending = None;
                                    outcome.answered += 1;
                                }
                                let noise = !answer
                                    && (cat.class_of(code) == MessageClass::Query
                                        || matches!(p.message, Message::ReportHeartbeatPulse(_)));
                                if script.all || !noise {
                                    let _ = writeln!(out, "{}", cat.print_line(t, utc, &p));
                                    outcome.printed += 1;
                                }
                            }
                            Tapped::Raw(h, body, e) => {
                                let line = RawLine {
                                    t,
                                    utc,
                                    header: &h,
                                    error: e,
                                    body: jaus::hex::encode(&body),
                                };
                                let _ = writeln!(
                                    out,
                                    "{}",
                                    serde_json::to_string(&line).unwrap_or_default()
                                );
                                outcome.printed += 1;
                            }
                        }
                        let _ = out.flush();
                    }
                    link.host().handle_datagram(now, from, &buf[..n]);
                }
                Ok(None) => {}
                Err(e) => return Err(format!("{local}: {e}")),
            }
            let host = link.host();
            let now = Instant::now();
            host.handle_timeout(now);
            let framing = self.framing;
            flush_seen(host, &mut port, |d| {
                if let Some(c) = &mut confirming {
                    c.leaving(framing, d, now);
                }
            });
        }
        // Commands nobody acknowledged, with what the system tree says of them.
        for (to, code) in awaiting_ack {
            let name = cat.name_of(code).unwrap_or("?");
            let text = match link.lists(to) {
                Some((false, listed)) => format!(
                    "{name} to {to}: no such component: node {}.{} lists {} (`jaus discover` shows the system)",
                    to.subsystem,
                    to.node,
                    listed.iter().map(ToString::to_string).collect::<Vec<_>>().join(", ")
                ),
                None if !link.reaches(to) => format!(
                    "{name} to {to}: no node {}.{} answered: check the address and --peer (`jaus discover` shows the system)",
                    to.subsystem, to.node
                ),
                _ => format!(
                    "{name} to {to}: no acknowledgement within {:.1} s; the component is there but did not acknowledge (OpenJAUS never does): check the effect with a query",
                    self.wait.as_secs_f64()
                ),
            };
            let _ = writeln!(err, "error: {text}");
            outcome.unacknowledged.push(text);
        }
        // End cleanly: service connections ended, control given back.
        let now = Instant::now();
        if let Some(t) = link.tool(me) {
            let sc: Vec<(Address, CommandCode)> = script
                .service_connections
                .iter()
                .map(|s| (s.0, s.1))
                .collect();
            t.behaviour_mut().0.close.extend(sc);
        }
        for to in controlled {
            if let Ok(body) = (ReleaseComponentControl {}).to_bytes() {
                link.send(
                    now,
                    Header::new(ReleaseComponentControl::CODE, to, me),
                    body,
                );
            }
        }
        let host = link.host();
        host.handle_timeout(now + Duration::from_millis(60));
        flush(host, &mut port);
        Ok(outcome)
    }
}

/// Standard input, line by line, on a thread of its own.
fn stdin_reader() -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
}
