//! The message log: every message the console's System Commander sent or received, as
//! decoded JSON, numbered, at most [`LOG_MAX`] kept (the oldest go; the count of what went
//! is kept).

use std::collections::VecDeque;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

use jaus::messages::Message;
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::net::Framing;
use jaus::wire::AckNak;
use jaus::{Address, MessageSet};
use serde::Serialize;

/// Entries kept.
pub const LOG_MAX: usize = 2_000;

/// One logged message.
#[derive(Debug, Clone, Serialize)]
pub struct Entry {
    /// Running number (from 1).
    pub seq: u64,
    /// Milliseconds since the Unix epoch.
    pub unix_ms: u64,
    /// `"rx"` (received by the console) or `"tx"` (sent).
    pub dir: &'static str,
    /// Source address.
    pub src: String,
    /// Destination address.
    pub dst: String,
    /// Message name (`ACK`/`NAK` of a message for acknowledgements).
    pub name: String,
    /// The message's fields as JSON (null for acknowledgements and undecodable bodies).
    pub fields: serde_json::Value,
    /// Why the body did not decode, when it did not; or the NAK.
    pub error: Option<String>,
}

/// The log (see the module documentation).
#[derive(Debug)]
pub struct MessageLog {
    me: Address,
    framing: Framing,
    reassembler: Reassembler,
    entries: VecDeque<Entry>,
    seq: u64,
    /// Whether heartbeats are logged (off: they would crowd everything else out).
    pub heartbeats: bool,
}

impl MessageLog {
    /// The log of the component at `me`, reading datagrams framed with `framing`.
    pub fn new(me: Address, framing: Framing) -> Self {
        Self {
            me,
            framing,
            reassembler: Reassembler::new(ReassemblyLimits::default()),
            entries: VecDeque::new(),
            seq: 0,
            heartbeats: false,
        }
    }

    /// Takes a datagram the node received (`received`) or sent; logs it when it is a
    /// message to or from the console's component.
    pub fn see(&mut self, now: Instant, received: bool, datagram: &[u8]) {
        let Ok((header, body)) = self.framing.packet(datagram) else {
            return;
        };
        let mine = if received {
            header.destination.matches(&self.me) && header.source != self.me
        } else {
            header.source == self.me
        };
        if !mine {
            return;
        }
        let code = header.command_code;
        let (name, fields, error) = if matches!(header.ack_nak, AckNak::Ack | AckNak::Nak) {
            let of = Message::info(code).map_or_else(|| code.to_string(), |i| i.name.to_string());
            let nak = header.ack_nak == AckNak::Nak;
            (
                format!("{} of {of}", if nak { "NAK" } else { "ACK" }),
                serde_json::Value::Null,
                nak.then(|| format!("{} refused {of}", header.source)),
            )
        } else {
            let Some((header, body)) = self.reassembler.message(now, &header, body) else {
                return;
            };
            match Message::decode(header.command_code, &body) {
                Ok(m) => {
                    if !self.heartbeats && matches!(m, Message::ReportHeartbeatPulse(_)) {
                        return;
                    }
                    let v = serde_json::to_value(&m).unwrap_or(serde_json::Value::Null);
                    let fields = v.get("fields").cloned().unwrap_or(serde_json::Value::Null);
                    (m.name().to_string(), fields, None)
                }
                Err(e) => (
                    header.command_code.to_string(),
                    serde_json::Value::Null,
                    Some(e.to_string()),
                ),
            }
        };
        self.seq += 1;
        if self.entries.len() >= LOG_MAX {
            self.entries.pop_front();
        }
        self.entries.push_back(Entry {
            seq: self.seq,
            unix_ms: SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_millis() as u64),
            dir: if received { "rx" } else { "tx" },
            src: header.source.to_string(),
            dst: header.destination.to_string(),
            name,
            fields,
            error,
        });
    }

    /// The last message's number (0: none yet).
    pub fn seq(&self) -> u64 {
        self.seq
    }

    /// Entries after number `after`, at most `max` (the newest of them).
    pub fn since(&self, after: u64, max: usize) -> Vec<Entry> {
        let newer = self.entries.iter().filter(|e| e.seq > after);
        let n = newer.clone().count();
        newer.skip(n.saturating_sub(max)).cloned().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use jaus::codec::Encode;
    use jaus::messages::{QueryComponentStatus, ReportComponentStatus};
    use jaus::{Header, JausMessage};

    fn datagram(header: Header, body: &[u8]) -> Vec<u8> {
        let mut d = Vec::new();
        Framing::Judp.write_packet(&mut d, &header, body).unwrap();
        d
    }

    #[test]
    fn logs_what_the_console_sends_and_receives_and_nothing_else() {
        let me = Address::new(200, 1, 40, 1);
        let pd = Address::new(1, 1, 33, 1);
        let mut log = MessageLog::new(me, Framing::Judp);
        let t = Instant::now();
        let q = QueryComponentStatus {};
        log.see(
            t,
            false,
            &datagram(
                Header::new(QueryComponentStatus::CODE, pd, me),
                &q.to_bytes().unwrap(),
            ),
        );
        let r = ReportComponentStatus::default();
        log.see(
            t,
            true,
            &datagram(
                Header::new(ReportComponentStatus::CODE, me, pd),
                &r.to_bytes().unwrap(),
            ),
        );
        // Not the console's.
        let other = Address::new(1, 1, 42, 1);
        log.see(
            t,
            true,
            &datagram(
                Header::new(ReportComponentStatus::CODE, other, pd),
                &r.to_bytes().unwrap(),
            ),
        );
        let mut nak = Header::new(ReportComponentStatus::CODE, me, pd);
        nak.ack_nak = AckNak::Nak;
        log.see(t, true, &datagram(nak, &[]));
        // Garbage.
        log.see(t, true, &[1, 2, 3]);
        let all = log.since(0, 100);
        assert_eq!(all.len(), 3, "{all:?}");
        assert_eq!(
            (all[0].dir, all[0].name.as_str()),
            ("tx", "QueryComponentStatus")
        );
        assert_eq!(all[1].name, "ReportComponentStatus");
        assert!(
            all[1].fields.get("primary_status_code").is_some(),
            "{:?}",
            all[1].fields
        );
        assert!(all[2].name.starts_with("NAK"), "{}", all[2].name);
        assert!(all[2].error.is_some());
        assert_eq!(log.since(2, 100).len(), 1);
        assert_eq!(log.since(0, 1)[0].seq, 3);
    }
}
