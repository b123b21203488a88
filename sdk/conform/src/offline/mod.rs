//! Judging recorded traffic (`jaus conform --from-pcap FILE`): the same report as a live
//! run, from the packets of a capture, without sending anything.
//!
//! Sans-IO: the caller (the CLI reads pcap and pcapng files) hands the datagrams in
//! file order as [`Record`]s, their framing removed, to a [`Judge`]; [`Judge::finish`]
//! gives the [`RunReport`], one [`ComponentReport`] per component seen, whose
//! findings name the packet numbers (1-based frame numbers of the file, as Wireshark
//! shows them).
//!
//! | Check | Level | What |
//! |---|---|---|
//! | [`ids::MALFORMED`] | required | every RA 3.3 packet decodes (header, data size, body) |
//! | [`ids::QUERY`] | required | Query Identification, Query Services and Query Component Status are answered by the component asked, to the asker, within the window |
//! | [`ids::QUERY_OTHER`] | advisory | every other query is answered the same way |
//! | [`ids::ACKNAK`] | required | a packet asking for an acknowledgement gets an ACK or NAK from its receiver within the window |
//! | [`ids::OUTSIDER`] | required | a state command (Standby, Resume, Shutdown, Reset) from a client not in control of a controlled component is not followed by a Report Component Status showing its effect |
//! | [`ids::OUTSIDER_ACK`] | advisory | a command from a client not in control is not acknowledged with ACK |
//! | [`ids::AS4_MALFORMED`] | required | every AS5669A datagram and the AS-4 messages it carries decode |
//! | [`ids::AS4_QUERY`] | required | AS-4 Query Identification, Query Services and Query Status are answered |
//! | [`ids::AS4_QUERY_OTHER`] | advisory | every other AS-4 query is answered |
//!
//! ```
//! use std::time::Duration;
//! use jaus_conform::offline::{judge, Carrier, Options, Record};
//!
//! let record = Record {
//!     number: 1,
//!     time: Duration::ZERO,
//!     src: "10.0.0.1:3794".parse().unwrap(),
//!     dst: "10.0.0.2:3794".parse().unwrap(),
//!     carrier: Carrier::Ra33,
//!     payload: vec![1, 2, 3], // not a JAUS packet
//! };
//! let run = judge([record], &Options::default(), "example");
//! assert!(!run.passed());
//! assert!(run.components[0].outcomes[0].detail.contains("packet 1"));
//! ```

mod as4;
mod outsider;
mod pairs;
mod ra33;
mod report;

use std::collections::{BTreeMap, BTreeSet};
use std::net::SocketAddr;
use std::time::Duration;

use jaus::net::as5669a::As4Id;
use jaus::Address;

use crate::check::Rule;
use crate::engine::{ComponentReport, RunReport};

/// The check ids of an offline judgement.
pub mod ids {
    /// Every RA 3.3 packet decodes.
    pub const MALFORMED: &str = "offline.packet.malformed";
    /// The core queries are answered.
    pub const QUERY: &str = "offline.query.answered";
    /// Every other query is answered.
    pub const QUERY_OTHER: &str = "offline.query.answered.other";
    /// Acknowledgements asked for are given.
    pub const ACKNAK: &str = "offline.acknak.answered";
    /// State commands from a client not in control have no effect.
    pub const OUTSIDER: &str = "offline.control.outsider";
    /// Commands from a client not in control are not acknowledged with ACK.
    pub const OUTSIDER_ACK: &str = "offline.control.outsider.ack";
    /// Every AS5669A datagram decodes.
    pub const AS4_MALFORMED: &str = "offline.as4.packet.malformed";
    /// The core AS-4 queries are answered.
    pub const AS4_QUERY: &str = "offline.as4.query.answered";
    /// Every other AS-4 query is answered.
    pub const AS4_QUERY_OTHER: &str = "offline.as4.query.answered.other";
}

/// The rules the offline checks cite, in this tool's words.
pub mod rules {
    use crate::check::Rule;

    /// Packets decode.
    pub const WELL_FORMED: Rule = Rule {
        id: "offline.packet",
        source: "Part 1 §3 (header); the message definitions",
        text: "A packet has a 16-byte header of version 2 whose data size is the number of bytes that follow, and a body that decodes as the message its command code names.",
    };
    /// Queries are answered.
    pub const ANSWERED: Rule = Rule {
        id: "offline.query",
        source: "Part 1 §3.3 (query/report pairs)",
        text: "A component sent a query answers its sender with the query's report (query code + 0x2000, or the definitions' pairing) within the answer window.",
    };
    /// Acknowledgements.
    pub const ACKNAK: Rule = Rule {
        id: "offline.acknak",
        source: "Part 1 §3.2 (ACK/NAK)",
        text: "A packet whose header asks for an acknowledgement is answered by its receiver with a packet of the same command code whose header carries ACK or NAK, within the answer window.",
    };
    /// Controller-only commands.
    pub const OUTSIDER: Rule = Rule {
        id: "offline.control",
        source: "Part 1 §4.4 (component control)",
        text: "A component under control carries out commands from its controller only: a state command from another client leaves its state as it was (Set and Clear Emergency are accepted from anyone).",
    };
    /// AS-4 transport and messages.
    pub const AS4: Rule = Rule {
        id: "offline.as4",
        source: "AS5669A; AS5710A",
        text: "An AS5669A datagram is version 2 followed by whole transport messages; an AS-4 message decodes as the message its ID names; a query is answered with its report by the component asked, within the answer window.",
    };
}

/// How the payload of a [`Record`] is carried.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Carrier {
    /// An RA 3.3 packet (header and body), its framing (JUDP, OPC) removed.
    Ra33,
    /// A whole AS5669A datagram (version byte 2 first).
    As5669a,
    /// A datagram whose framing could not be removed: the reason (the payload is the
    /// datagram as captured).
    Unframed(String),
}

/// One datagram of a capture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Record {
    /// Its frame number in the file, from 1.
    pub number: u64,
    /// When it was seen (since 1970-01-01 UTC, or any fixed origin).
    pub time: Duration,
    /// Sender's socket.
    pub src: SocketAddr,
    /// Receiver's socket.
    pub dst: SocketAddr,
    /// What the payload is.
    pub carrier: Carrier,
    /// The payload (see [`Carrier`]).
    pub payload: Vec<u8>,
}

/// How the judge decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// How long an answer (report, ACK/NAK, a state change) may take.
    pub window: Duration,
    /// The most requests (queries, acknowledgements asked for, commands watched)
    /// tracked at once, of each kind; beyond it they are counted, not judged.
    pub max_outstanding: usize,
}

impl Default for Options {
    /// A one-second window; 10 000 requests of each kind at once.
    fn default() -> Self {
        Options {
            window: Duration::from_secs(1),
            max_outstanding: 10_000,
        }
    }
}

/// Who a finding is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Who {
    /// An RA 3.3 component.
    Ra33(Address),
    /// An AS-4 component.
    As4(As4Id),
    /// A sender whose packet named no component (the header did not decode); `true`
    /// for an AS5669A datagram.
    Socket(SocketAddr, bool),
}

impl std::fmt::Display for Who {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Who::Ra33(a) => write!(f, "{a}"),
            Who::As4(id) => write!(f, "{id} (AS-4)"),
            Who::Socket(s, _) => write!(f, "{s}"),
        }
    }
}

/// A packet that did not decode.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Bad {
    pub number: u64,
    pub time: Duration,
    pub error: String,
    pub to: String,
}

/// What was seen of one sender.
#[derive(Debug, Default)]
pub(crate) struct Seen {
    /// Packets (messages) that decoded.
    pub decoded: u64,
    /// Those that did not (up to [`pairs::LIST_CAP`]).
    pub malformed: Vec<Bad>,
    /// Those beyond the list.
    pub malformed_more: u64,
    /// Codes the definitions do not know (kept raw, not malformed).
    pub unknown: BTreeSet<u16>,
    /// Pieces of multi-packet messages (not decoded alone).
    pub pieces: u64,
    /// Its Report Identification text.
    pub identification: Option<String>,
}

impl Seen {
    fn bad(&mut self, b: Bad) {
        if self.malformed.len() < pairs::LIST_CAP {
            self.malformed.push(b);
        } else {
            self.malformed_more += 1;
        }
    }
}

/// The judge: fed the records of a capture in order, it gives the report.
#[derive(Debug)]
pub struct Judge {
    opts: Options,
    seen: BTreeMap<Who, Seen>,
    ra33: ra33::Ra33,
    as4: as4::As4,
    first: Option<Duration>,
    last: Duration,
    records: u64,
}

impl Judge {
    /// A judge with `opts`, nothing seen yet.
    pub fn new(opts: Options) -> Self {
        Judge {
            opts,
            seen: BTreeMap::new(),
            ra33: ra33::Ra33::new(opts),
            as4: as4::As4::new(opts),
            first: None,
            last: Duration::ZERO,
            records: 0,
        }
    }

    /// Judges the next datagram of the capture.
    pub fn push(&mut self, r: &Record) {
        self.records += 1;
        self.first.get_or_insert(r.time);
        self.last = self.last.max(r.time);
        match &r.carrier {
            Carrier::Ra33 => self.ra33.push(r, &mut self.seen),
            Carrier::As5669a => self.as4.push(r, &mut self.seen),
            Carrier::Unframed(why) => {
                self.seen
                    .entry(Who::Socket(r.src, false))
                    .or_default()
                    .bad(Bad {
                        number: r.number,
                        time: r.time,
                        error: format!("framing: {why}"),
                        to: r.dst.to_string(),
                    })
            }
        }
    }

    /// The report: per component seen, its checks (packets decoded, queries answered,
    /// acknowledgements given, commands from clients not in control); `source` names
    /// the capture in the report.
    pub fn finish(mut self, source: &str) -> RunReport {
        self.ra33.finish(self.last);
        self.as4.finish(self.last);
        let origin = self.first.unwrap_or_default();
        let mut b = report::Builder::new(origin, self.opts);
        let components: Vec<ComponentReport> = b.components(&self.seen, &self.ra33, &self.as4);
        RunReport {
            tool: format!("jaus conform --from-pcap {}", env!("CARGO_PKG_VERSION")),
            peer: format!("{source} ({} datagrams)", self.records),
            components,
            // Requests not tracked are no packets the tester failed to keep: see
            // [`Judge::dropped`].
            tester_dropped: 0,
        }
    }

    /// Requests (queries, acknowledgements asked for, commands watched) not judged
    /// because [`Options::max_outstanding`] of their kind were waiting at once.
    pub fn dropped(&self) -> u64 {
        self.ra33.dropped() + self.as4.dropped()
    }
}

/// Judges `records` (in file order) with `opts`; `source` names the capture.
pub fn judge(records: impl IntoIterator<Item = Record>, opts: &Options, source: &str) -> RunReport {
    let mut j = Judge::new(*opts);
    for r in records {
        j.push(&r);
    }
    j.finish(source)
}

/// The rule a check id cites, its title and whether it is required.
pub(crate) fn describe(id: &str) -> (&'static str, Rule, bool) {
    match id {
        ids::MALFORMED => ("Every packet decodes", rules::WELL_FORMED, true),
        ids::QUERY => ("Core queries are answered", rules::ANSWERED, true),
        ids::QUERY_OTHER => ("Other queries are answered", rules::ANSWERED, false),
        ids::ACKNAK => ("Acknowledgements asked for are given", rules::ACKNAK, true),
        ids::OUTSIDER => (
            "State commands from a client not in control have no effect",
            rules::OUTSIDER,
            true,
        ),
        ids::OUTSIDER_ACK => (
            "Commands from a client not in control are not acknowledged",
            rules::OUTSIDER,
            false,
        ),
        ids::AS4_MALFORMED => ("Every AS5669A datagram decodes", rules::AS4, true),
        ids::AS4_QUERY => ("Core AS-4 queries are answered", rules::AS4, true),
        _ => ("Other AS-4 queries are answered", rules::AS4, false),
    }
}

/// "packets 3, 7, 9 (and 12 more)" of `numbers`, at most 20 named.
pub(crate) fn packet_list(numbers: &[u64], more: u64) -> String {
    let shown: Vec<String> = numbers.iter().take(20).map(|n| n.to_string()).collect();
    let rest = (numbers.len().saturating_sub(20)) as u64 + more;
    format!(
        "{} {}{}",
        if numbers.len() as u64 + more == 1 {
            "packet"
        } else {
            "packets"
        },
        shown.join(", "),
        if rest > 0 {
            format!(" (and {rest} more)")
        } else {
            String::new()
        }
    )
}
