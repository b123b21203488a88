//! The RA 3.3 side of the judge: decodes each packet with the SDK's header and message
//! codecs, pairs queries with reports and acknowledgement requests with their ACK or
//! NAK, and follows component control ([`super::outsider`]).

use std::collections::BTreeMap;
use std::time::Duration;

use jaus::messages::Message;
use jaus::wire::{AckNak, DataFlag, MessageClass};
use jaus::{Address, CommandCode, Header, JausMessage, MessageInfo, PacketRef};

use super::outsider::Outsider;
use super::pairs::{Pairs, Pending};
use super::{Bad, Options, Record, Seen, Who};

/// The RA 3.3 state of the judge.
#[derive(Debug)]
pub(crate) struct Ra33 {
    /// Queries waiting for their report.
    pub queries: Pairs<Address>,
    /// Packets waiting for their ACK or NAK.
    pub acks: Pairs<Address>,
    /// Component control and the outsiders' commands.
    pub outsider: Outsider,
}

/// The name of code `code` in the definitions (`0xD123` when unknown).
pub(crate) fn name_of(code: u16) -> String {
    MessageInfo::of(CommandCode(code)).map_or_else(|| format!("{code:#06X}"), |i| i.name.into())
}

/// Whether `a` names several components (255 at a level).
fn broadcast(a: Address) -> bool {
    [a.subsystem, a.node, a.component, a.instance].contains(&Address::BROADCAST)
}

/// The report answering query `query`: the definitions' pairing, else the complement
/// rule (query + 0x2000).
pub(crate) fn report_of(catalogue: &[MessageInfo], query: CommandCode) -> Option<u16> {
    let info = catalogue.iter().find(|m| m.code == query);
    info.and_then(|i| i.report)
        .and_then(|name| catalogue.iter().find(|m| m.name == name))
        .map(|m| m.code.0)
        .or_else(|| query.complement().map(|c| c.0))
}

/// Whether `msg` asks for a value its definition does not name (no answer is due).
fn out_of_range(msg: &Message) -> bool {
    use jaus::messages::QueryLevel;
    matches!(msg, Message::QueryIdentification(q) if matches!(q.query_field, QueryLevel::Unknown(_)))
}

/// Whether Part 1 requires every component to answer `code`.
fn core_query(code: CommandCode) -> bool {
    use jaus::messages::{QueryComponentStatus, QueryIdentification, QueryServices};
    [
        QueryIdentification::CODE,
        QueryServices::CODE,
        QueryComponentStatus::CODE,
    ]
    .contains(&code)
}

impl Ra33 {
    pub fn new(opts: Options) -> Self {
        Ra33 {
            queries: Pairs::new(opts.max_outstanding, opts.window),
            acks: Pairs::new(opts.max_outstanding, opts.window),
            outsider: Outsider::new(opts.window, opts.max_outstanding),
        }
    }

    /// Requests and commands not tracked (a bound was reached).
    pub fn dropped(&self) -> u64 {
        self.queries.dropped + self.acks.dropped + self.outsider.dropped
    }

    /// Judges one RA 3.3 packet.
    pub fn push(&mut self, r: &Record, seen: &mut BTreeMap<Who, Seen>) {
        self.queries.expire(r.time);
        self.acks.expire(r.time);
        self.outsider.expire(r.time, false);
        let bad = |error: String, to: String| Bad {
            number: r.number,
            time: r.time,
            error,
            to,
        };
        let h = match Header::parse(&r.payload) {
            Ok(h) => h,
            Err(e) => {
                let to = r.dst.to_string();
                seen.entry(Who::Socket(r.src, false))
                    .or_default()
                    .bad(bad(format!("header: {e}"), to));
                return;
            }
        };
        let code = h.command_code;
        let s = seen.entry(Who::Ra33(h.source)).or_default();
        let what = || {
            format!(
                "{} ({code}) from {} to {}",
                name_of(code.0),
                h.source,
                h.destination
            )
        };
        if h.version != Header::VERSION_3_3 {
            let e = format!("{}: header version {} (RA 3.3 is 2)", what(), h.version);
            s.bad(bad(e, h.destination.to_string()));
            return;
        }
        let body = match PacketRef::parse(&r.payload) {
            Ok(p) => p.body,
            Err(e) => {
                s.bad(bad(format!("{}: {e}", what()), h.destination.to_string()));
                return;
            }
        };
        if h.ack_nak.is_answer() {
            s.decoded += 1;
            let nak = h.ack_nak == AckNak::Nak;
            self.acks
                .answer(h.destination, h.source, code.0, r.time, nak);
            self.outsider.answer(r.number, r.time, &h);
            return;
        }
        let pending = Pending {
            number: r.number,
            time: r.time,
            code: code.0,
            asker: h.source,
        };
        if h.ack_nak == AckNak::Request && !broadcast(h.destination) {
            self.acks.ask(h.destination, code.0, pending, true);
        }
        if h.data_flag != DataFlag::Single {
            s.pieces += 1;
            // A report in several packets (an image) answers its query when its first
            // packet leaves; its body is not reassembled here.
            if h.data_flag == DataFlag::First && code.class() == MessageClass::Inform {
                self.queries
                    .answer(h.destination, h.source, code.0, r.time, false);
            }
            return;
        }
        let msg = match Message::decode(code, body) {
            Ok(m) => m,
            Err(e) => {
                s.bad(bad(format!("{}: {e}", what()), h.destination.to_string()));
                return;
            }
        };
        s.decoded += 1;
        match &msg {
            Message::Raw(_) => {
                s.unknown.insert(code.0);
            }
            Message::ReportIdentification(id) => {
                let text = id.identification.trim_end_matches('\0').trim();
                s.identification = Some(text.chars().take(80).collect());
            }
            _ => {}
        }
        match code.class() {
            // Query Identification for a level no level has (the live check
            // `robust.out-of-range` sends one) has no report to expect.
            MessageClass::Query if !broadcast(h.destination) && !out_of_range(&msg) => {
                if let Some(report) = report_of(jaus::messages::MESSAGES, code) {
                    self.queries
                        .ask(h.destination, report, pending, core_query(code));
                }
            }
            MessageClass::Inform => {
                self.queries
                    .answer(h.destination, h.source, code.0, r.time, false);
            }
            _ => {}
        }
        self.outsider.message(r.number, r.time, &h, &msg);
    }

    /// The capture ended at `end`.
    pub fn finish(&mut self, end: Duration) {
        self.queries.finish(end);
        self.acks.finish(end);
        self.outsider.expire(end, true);
    }
}
