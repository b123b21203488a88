//! The AS-4 side of the judge: decodes each AS5669A datagram
//! ([`jaus::net::as5669a::parse_datagram`]) and each whole message it carries
//! ([`jaus_as4::Message::decode`]), and pairs AS-4 queries with their reports by the
//! AS-4 catalogue ([`jaus_as4::MESSAGES`]).

use std::collections::BTreeMap;
use std::time::Duration;

use jaus::net::as5669a::{parse_datagram, As4Id, As4Message, DataControl};
use jaus::wire::MessageClass;
use jaus::{CommandCode, JausMessage};

use super::pairs::{Pairs, Pending};
use super::ra33::report_of;
use super::{Bad, Options, Record, Seen, Who};

/// The AS-4 state of the judge.
#[derive(Debug)]
pub(crate) struct As4 {
    /// Queries waiting for their report.
    pub queries: Pairs<As4Id>,
}

/// The name of AS-4 message `id` (`0xD123` when unknown).
pub(crate) fn name_of(id: u16) -> String {
    jaus_as4::MESSAGES
        .iter()
        .find(|m| m.code.0 == id)
        .map_or_else(|| format!("{id:#06X}"), |m| m.name.into())
}

/// Whether every AS-4 component is expected to answer `code` (Discovery, Management).
fn core_query(code: CommandCode) -> bool {
    use jaus_as4::messages::{QueryIdentification, QueryServices, QueryStatus};
    [
        QueryIdentification::CODE,
        QueryServices::CODE,
        QueryStatus::CODE,
    ]
    .contains(&code)
}

impl As4 {
    pub fn new(opts: Options) -> Self {
        As4 {
            queries: Pairs::new(opts.max_outstanding, opts.window),
        }
    }

    /// Queries not tracked (the bound was reached).
    pub fn dropped(&self) -> u64 {
        self.queries.dropped
    }

    /// Judges one AS5669A datagram.
    pub fn push(&mut self, r: &Record, seen: &mut BTreeMap<Who, Seen>) {
        self.queries.expire(r.time);
        let bad = |error: String, to: String| Bad {
            number: r.number,
            time: r.time,
            error,
            to,
        };
        let packets = match parse_datagram(&r.payload) {
            Ok(p) => p,
            Err(e) => {
                seen.entry(Who::Socket(r.src, true))
                    .or_default()
                    .bad(bad(format!("AS5669A datagram: {e}"), r.dst.to_string()));
                return;
            }
        };
        for p in packets {
            let (from, to) = (p.header.source, p.header.destination);
            let s = seen.entry(Who::As4(from)).or_default();
            if p.header.ack_nak.is_answer() {
                s.decoded += 1;
                continue;
            }
            if p.header.data_control != DataControl::Single {
                s.pieces += 1;
                continue;
            }
            let Some(m) = As4Message::from_packet(p) else {
                s.bad(bad(
                    "a message without its two-byte message ID".into(),
                    to.to_string(),
                ));
                continue;
            };
            let code = CommandCode(m.message_id);
            if let Err(e) = jaus_as4::Message::decode(code, &m.body) {
                let e = format!("{} ({code}) from {from} to {to}: {e}", name_of(code.0));
                s.bad(bad(e, to.to_string()));
                continue;
            }
            s.decoded += 1;
            let info = jaus_as4::MESSAGES.iter().find(|i| i.code == code);
            let Some(info) = info else {
                s.unknown.insert(code.0);
                continue;
            };
            match info.class {
                MessageClass::Query if !to.is_broadcast() => {
                    if let Some(report) = report_of(jaus_as4::MESSAGES, code) {
                        let pending = Pending {
                            number: r.number,
                            time: r.time,
                            code: code.0,
                            asker: from,
                        };
                        self.queries.ask(to, report, pending, core_query(code));
                    }
                }
                MessageClass::Inform => {
                    self.queries.answer(to, from, code.0, r.time, false);
                }
                _ => {}
            }
        }
    }

    /// The capture ended at `end`.
    pub fn finish(&mut self, end: Duration) {
        self.queries.finish(end);
    }
}
