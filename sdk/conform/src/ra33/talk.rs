//! How the engine talks: messages sent and received through the session, each kept
//! as evidence; queries with their reports, commands with their acknowledgements,
//! control requests with their answers.

use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{
    ClearEmergency, ClearEmergencyCode, ComponentState, ControlResponse, EmergencyCode, Message,
    QueryComponentControl, QueryComponentStatus, RequestComponentControl, Resume, SetEmergency,
    Standby,
};
use jaus::wire::{AckNak, DataFlag};
use jaus::{Address, CommandCode, Header, MessageSet};

use super::Ra33Voice;
use crate::check::Exchange;

use crate::session::Incoming;

/// A packet sent as given, right or wrong.
#[derive(Debug, Clone, Copy)]
pub(super) struct Raw<'b> {
    /// Its command code.
    pub code: CommandCode,
    /// Its body bytes.
    pub body: &'b [u8],
    /// The data size the header announces, when not the body's length.
    pub data_size: Option<u16>,
    /// Its data flag (single, first, normal, last).
    pub flag: DataFlag,
    /// Its sequence number.
    pub sequence: u16,
}

impl<'b> Raw<'b> {
    /// A single packet carrying `body` under `code`.
    pub fn single(code: CommandCode, body: &'b [u8]) -> Self {
        Raw {
            code,
            body,
            data_size: None,
            flag: DataFlag::Single,
            sequence: 0,
        }
    }
}

/// How a control request was answered.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum ControlAnswer {
    /// Confirm Component Control, Control Accepted.
    Accepted,
    /// Confirm Component Control with another code, or Reject Component Control.
    Refused(String),
}

/// A message's fields as JSON (`null` when it has none or they cannot be written).
pub(crate) fn fields_of(m: &Message) -> serde_json::Value {
    serde_json::to_value(m)
        .ok()
        .and_then(|mut v| v.get_mut("fields").map(std::mem::take))
        .unwrap_or(serde_json::Value::Null)
}

impl Ra33Voice<'_> {
    fn t_ms(&self) -> f64 {
        self.evidence.t_ms(self.session.now())
    }

    fn keep(&mut self, e: Exchange) {
        self.evidence.keep(e);
    }

    /// Keeps a packet as evidence.
    pub(super) fn record(&mut self, dir: &'static str, header: &Header, body: &[u8]) {
        let (message, fields) = match header.ack_nak {
            AckNak::Ack | AckNak::Nak => (
                format!(
                    "{} ({})",
                    if header.ack_nak == AckNak::Ack {
                        "ack"
                    } else {
                        "nak"
                    },
                    Message::info(header.command_code).map_or("?", |i| i.name)
                ),
                serde_json::Value::Null,
            ),
            _ => match Message::decode_known(header.command_code, body) {
                Ok(m) => (m.name().to_string(), fields_of(&m)),
                // A message of the loaded definitions the SDK does not have (a vendor
                // overlay's).
                Err(_) if self.schema.by_code(header.command_code).is_some() => {
                    match self.schema.decode(header.command_code, body) {
                        Ok(m) => (
                            m.name.to_string(),
                            serde_json::to_value(&m.fields).unwrap_or_default(),
                        ),
                        Err(e) => (
                            format!("raw {}", header.command_code),
                            serde_json::json!({ "hex": jaus::hex::encode(body), "decode": e.to_string() }),
                        ),
                    }
                }
                Err(e) => (
                    format!("raw {}", header.command_code),
                    serde_json::json!({ "hex": jaus::hex::encode(body), "decode": e.to_string() }),
                ),
            },
        };
        let t_ms = self.t_ms();
        self.keep(Exchange {
            t_ms,
            dir,
            from: header.source.to_string(),
            to: header.destination.to_string(),
            message,
            fields,
        });
    }

    /// Sends `msg` from `from` to the target, asking for an acknowledgement if `ack`.
    pub(super) fn send(&mut self, from: Address, msg: &Message, ack: bool) {
        let Ok(body) = msg.to_bytes() else {
            tracing::warn!(message = msg.name(), "jaus conform: cannot encode");
            return;
        };
        self.send_body(from, msg.code(), body, ack);
    }

    /// Sends `body` under `code` from `from` to the target, asking for an
    /// acknowledgement if `ack`.
    pub(super) fn send_body(&mut self, from: Address, code: CommandCode, body: Vec<u8>, ack: bool) {
        let mut header = Header::new(code, self.target, from);
        if ack {
            header.ack_nak = AckNak::Request;
        }
        header.data_size = body.len() as u16;
        self.record("sent", &header, &body);
        self.session.send(header, body);
    }

    /// Sends a packet exactly as given from `from` to the target: `code`, `body`, the
    /// header's data flag and sequence number, `data_size` overriding the body's length.
    pub(super) fn send_raw(&mut self, from: Address, raw: Raw<'_>) {
        let mut header = Header::new(raw.code, self.target, from);
        header.data_size = raw.data_size.unwrap_or(raw.body.len() as u16);
        header.data_flag = raw.flag;
        header.sequence_number = raw.sequence;
        let t_ms = self.t_ms();
        self.keep(Exchange {
            t_ms,
            dir: "sent",
            from: from.to_string(),
            to: self.target.to_string(),
            message: format!("raw {}", raw.code),
            fields: serde_json::json!({
                "hex": jaus::hex::encode(raw.body),
                "data_size": header.data_size,
                "data_flag": format!("{:?}", raw.flag),
                "sequence_number": raw.sequence,
            }),
        });
        let bytes = crate::memory::packet_bytes(header, raw.body, raw.data_size);
        self.session.send_raw(self.target, bytes);
    }

    /// The next packet by `deadline`, kept as evidence.
    pub(super) fn next(&mut self, deadline: Instant) -> Option<Incoming> {
        let p = self.session.recv(deadline)?;
        self.record("received", &p.header, &p.body);
        Some(p)
    }

    /// Waits `within` for a packet `pred` accepts (every packet is kept as evidence).
    pub(super) fn wait_for(
        &mut self,
        within: Duration,
        mut pred: impl FnMut(&Incoming) -> bool,
    ) -> Option<Incoming> {
        let deadline = self.session.now() + within;
        while let Some(p) = self.next(deadline) {
            if pred(&p) {
                return Some(p);
            }
        }
        None
    }

    /// Takes whatever arrives for `d`.
    pub(super) fn drain(&mut self, d: Duration) {
        let deadline = self.session.now() + d;
        while self.next(deadline).is_some() {}
    }

    /// Sends query `q` from `from` and waits for its report from the target.
    pub(super) fn ask(&mut self, from: Address, q: Message) -> Option<Message> {
        let report = Message::report_of(q.code())?;
        self.send(from, &q, false);
        let target = self.target;
        let p = self.wait_for(self.opts.wait, |p| {
            p.header.source == target
                && p.header.destination == from
                && p.header.command_code == report
                && !matches!(p.header.ack_nak, AckNak::Ack | AckNak::Nak)
        })?;
        Message::decode_known(report, &p.body).ok()
    }

    /// The target's core state, asked by the outsider.
    pub(super) fn status(&mut self) -> Option<ComponentState> {
        match self.ask(self.voices.outsider, QueryComponentStatus {}.into())? {
            Message::ReportComponentStatus(r) => Some(r.primary_status_code),
            _ => None,
        }
    }

    /// Who controls the target: `Some(None)` nobody, `None` not answered.
    pub(super) fn controller(&mut self) -> Option<Option<(Address, u8)>> {
        match self.ask(self.voices.outsider, QueryComponentControl {}.into())? {
            Message::ReportComponentControl(r) => {
                let a = Address::new(r.subsystem_id, r.node_id, r.component_id, r.instance_id);
                Some((a != Address::new(0, 0, 0, 0)).then_some((a, r.authority_code)))
            }
            _ => None,
        }
    }

    /// Asks for control from `voice` at `authority`; the answer, if any came.
    pub(super) fn acquire(&mut self, voice: Address, authority: u8) -> Option<ControlAnswer> {
        self.send(
            voice,
            &RequestComponentControl {
                authority_code: authority,
            }
            .into(),
            false,
        );
        let target = self.target;
        let p = self.wait_for(self.opts.wait, |p| {
            p.header.source == target
                && p.header.destination == voice
                && matches!(p.header.command_code.0, 0x000F | 0x0010)
        })?;
        Some(
            match Message::decode_known(p.header.command_code, &p.body) {
                Ok(Message::ConfirmComponentControl(c))
                    if c.response_code == ControlResponse::ControlAccepted =>
                {
                    ControlAnswer::Accepted
                }
                Ok(Message::ConfirmComponentControl(c)) => ControlAnswer::Refused(format!(
                    "Confirm Component Control {:?}",
                    c.response_code
                )),
                _ => ControlAnswer::Refused("Reject Component Control".into()),
            },
        )
    }

    /// Sends command `msg` from `from` asking for an acknowledgement; the ACK or NAK if
    /// one came within the settle time.
    pub(super) fn command(&mut self, from: Address, msg: &Message) -> Option<AckNak> {
        let body = msg.to_bytes().ok()?;
        self.command_body(from, msg.code(), body)
    }

    /// Sends `body` under command code `code` from `from` asking for an
    /// acknowledgement; the ACK or NAK if one came within the settle time.
    pub(super) fn command_body(
        &mut self,
        from: Address,
        code: CommandCode,
        body: Vec<u8>,
    ) -> Option<AckNak> {
        self.send_body(from, code, body, true);
        let target = self.target;
        let p = self.wait_for(self.opts.settle, |p| {
            p.header.source == target
                && p.header.destination == from
                && p.header.command_code == code
                && matches!(p.header.ack_nak, AckNak::Ack | AckNak::Nak)
        })?;
        Some(p.header.ack_nak)
    }

    /// Takes the target to Ready (Resume) or Standby (Standby) as controller `c`;
    /// whether it got there.
    pub(super) fn set_state(&mut self, c: Address, want: ComponentState) -> bool {
        if self.status() == Some(want) {
            return true;
        }
        let msg: Message = match want {
            ComponentState::Ready => Resume {}.into(),
            ComponentState::Standby => Standby {}.into(),
            _ => return false,
        };
        self.command(c, &msg);
        self.status() == Some(want)
    }

    /// Sends Set Emergency from `from`.
    pub(super) fn set_emergency(&mut self, from: Address) {
        let m = SetEmergency {
            emergency_code: EmergencyCode {
                transition_to_emergency: true,
                ..EmergencyCode::default()
            },
        };
        self.command(from, &m.into());
    }

    /// Sends Clear Emergency from `from`.
    pub(super) fn clear_emergency(&mut self, from: Address) {
        let m = ClearEmergency {
            emergency_code: ClearEmergencyCode {
                clear_emergency: true,
                ..ClearEmergencyCode::default()
            },
        };
        self.command(from, &m.into());
    }

    /// Makes sure the controller voice holds control; `Err` says why not.
    pub(super) fn hold_control(&mut self) -> Result<(), String> {
        let c = self.voices.controller;
        match self.acquire(c, self.authority) {
            Some(ControlAnswer::Accepted) => {
                self.granted = true;
                Ok(())
            }
            Some(ControlAnswer::Refused(why)) => Err(format!("control not granted to {c}: {why}")),
            None => Err(format!(
                "no answer to Request Component Control from {c} within {:?}",
                self.opts.wait
            )),
        }
    }
}
