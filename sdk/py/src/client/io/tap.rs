//! The tap of the client's I/O thread: what arrives for the client, read before the
//! runtime takes it, answers the queries, acknowledgements, control requests and
//! watches Python waits on.

use std::time::Instant;

use jaus::messages::{
    ConfirmComponentControl, ConfirmEventRequest, ConfirmServiceConnection, ControlResponse, Event,
    EventResponseCode, Message, QueryIdentification, QueryServices, RejectEventRequest,
    ReportRefusal, ServiceConnectionResponse,
};
use jaus::wire::AckNak;
use jaus::{Address, CommandCode, Header, JausMessage};

use super::{add, answer, Failure, How, Io, MAX_REASONS};

impl Io {
    /// Reads a datagram for the client before the runtime does.
    pub(super) fn tap(&mut self, now: Instant, datagram: &[u8]) {
        let me = self.client.me;
        let Ok((header, body)) = self.client.framing.packet(datagram) else {
            return;
        };
        if !header.destination.matches(&me) || header.source == me {
            return;
        }
        if matches!(header.ack_nak, AckNak::Ack | AckNak::Nak) {
            self.acknowledged(&header);
            return;
        }
        let Some((header, body)) = self.reassembler.message(now, &header, body) else {
            return;
        };
        add(&self.stats.messages_received);
        let (code, from) = (header.command_code, header.source);
        let mut claimed = code == QueryIdentification::CODE || code == QueryServices::CODE;
        self.known |= claimed;
        match Message::decode(code, &body) {
            Ok(Message::ConfirmComponentControl(c)) => claimed |= self.confirmed(from, &c),
            Ok(Message::RejectComponentControl(_)) => claimed |= self.rejected(from),
            Ok(Message::ConfirmServiceConnection(c)) => claimed |= self.connection(from, &c),
            Ok(Message::ConfirmEventRequest(c)) => claimed |= self.event_confirmed(from, &c),
            Ok(Message::RejectEventRequest(r)) => claimed |= self.event_rejected(from, &r),
            Ok(Message::Event(e)) => claimed |= self.event(from, &e),
            Ok(Message::ReportRefusal(r)) => {
                claimed = true;
                self.refusal(from, &r);
            }
            _ => {}
        }
        // The read-back of a command being confirmed.
        if let Some(checks) = jaus_client::confirm::checks() {
            for (c, _) in &mut self.confirms {
                claimed |= c.message(checks, from, code, &body);
            }
        }
        // The answer to a query.
        if let Some(i) = self
            .queries
            .iter()
            .position(|q| q.answer == code && q.to.matches(&from))
        {
            let q = self.queries.remove(i);
            let r = self.decode(code, &body);
            answer(&q.reply, r.map_err(Failure::new));
            claimed = true;
        }
        // A report of a service connection.
        for w in &self.watches {
            if w.how == How::Connection && w.report == code && w.to.matches(&from) {
                let item = self.decode(code, &body);
                if !w.feed.push(item) {
                    add(&self.stats.reports_dropped);
                }
                claimed = true;
            }
        }
        if !claimed {
            add(&self.stats.unclaimed);
        }
    }

    fn decode(&self, code: CommandCode, body: &[u8]) -> Result<jaus_dynamic::DynMessage, String> {
        self.cat.schema.decode(code, body).map_err(|e| {
            add(&self.stats.decode_errors);
            e.to_string()
        })
    }

    fn acknowledged(&mut self, h: &Header) {
        let nak = h.ack_nak == AckNak::Nak;
        if nak {
            add(&self.stats.naks);
        }
        let reason = self
            .reasons
            .iter()
            .position(|(a, c, _)| *a == h.source && *c == h.command_code)
            .map(|i| self.reasons.remove(i).2);
        if let Some((c, _)) = self
            .confirms
            .iter_mut()
            .find(|(c, _)| c.to.matches(&h.source) && c.code == h.command_code)
        {
            c.ack(nak, reason.as_deref());
        }
        if let Some(i) = self
            .acks
            .iter()
            .position(|a| a.to.matches(&h.source) && a.code == h.command_code)
        {
            let a = self.acks.remove(i);
            let r = if nak {
                Err(Failure::new(format!(
                    "{}: NAK from {}: {}",
                    a.name,
                    h.source,
                    reason
                        .as_deref()
                        .unwrap_or("refused (the receiver gave no reason)")
                )))
            } else {
                Ok(())
            };
            answer(&a.reply, r);
        }
    }

    fn refusal(&mut self, from: Address, r: &ReportRefusal) {
        if let Some((c, _)) = self
            .confirms
            .iter_mut()
            .find(|(c, _)| c.to.matches(&from) && c.code == CommandCode(r.refused_code))
        {
            c.refused(&r.text);
        }
        if self.reasons.len() >= MAX_REASONS {
            self.reasons.remove(0);
        }
        self.reasons
            .push((from, CommandCode(r.refused_code), r.text.clone()));
    }

    fn confirmed(&mut self, from: Address, c: &ConfirmComponentControl) -> bool {
        if c.response_code == ControlResponse::ControlAccepted {
            // Answered once the keeper holds it ([`poll_tool`]).
            return self.keeps.iter().any(|k| k.to == from) || self.kept.contains(&from);
        }
        let Some(i) = self.keeps.iter().position(|k| k.to == from) else {
            return false;
        };
        let k = self.keeps.remove(i);
        let code = format!("{:?}", c.response_code);
        answer(
            &k.reply,
            Err(Failure {
                text: format!(
                    "RequestComponentControl: {from} refused control: Confirm Component Control with response code {code}"
                ),
                response_code: Some(code),
            }),
        );
        self.stop_keeping(from);
        true
    }

    fn rejected(&mut self, from: Address) -> bool {
        if self.kept.contains(&from) {
            // A component of higher authority took it (the keeper still holds it: later
            // rejections answer the keeper's new requests); the keeper asks again.
            let me = self.client.me;
            if self
                .link
                .tool(me)
                .is_some_and(|t| t.behaviour().0.keeper.holds(from))
            {
                add(&self.stats.control_lost);
            }
            return true;
        }
        let Some(i) = self.keeps.iter().position(|k| k.to == from) else {
            return false;
        };
        let k = self.keeps.remove(i);
        answer(
            &k.reply,
            Err(Failure {
                text: format!(
                    "RequestComponentControl: {from} refused control: Reject Component Control (another component holds it with an equal or higher authority)"
                ),
                response_code: Some("Rejected".into()),
            }),
        );
        self.stop_keeping(from);
        true
    }

    fn connection(&mut self, from: Address, c: &ConfirmServiceConnection) -> bool {
        let Some(i) = self.watches.iter().position(|w| {
            w.how == How::Connection
                && w.confirm.is_some()
                && w.to.matches(&from)
                && w.report.0 == c.service_connection_command_code
        }) else {
            return false;
        };
        if c.response_code == ServiceConnectionResponse::Successful {
            if let Some((_, reply)) = self.watches[i].confirm.take() {
                answer(&reply, Ok(()));
            }
        } else {
            let w = self.watches.remove(i);
            let text = format!(
                "CreateServiceConnection: {from} refused the service connection: response code {:?}",
                c.response_code
            );
            self.end_watch(&w, &text);
        }
        true
    }

    fn event_confirmed(&mut self, from: Address, c: &ConfirmEventRequest) -> bool {
        // OpenJAUS answers with request id 0 whatever the request's.
        let Some(w) = self.watches.iter_mut().find(|w| {
            matches!(w.how, How::Event { request, id: None } if request == c.request_id || c.request_id == 0)
                && w.to.matches(&from)
                && w.report.0 == c.message_code
        }) else {
            return false;
        };
        if c.response_code != EventResponseCode::Successful {
            let text = format!(
                "CreateEvent: {from} refused the event: response code {:?}",
                c.response_code
            );
            let id = w.id;
            if let Some(i) = self.watches.iter().position(|w| w.id == id) {
                let w = self.watches.remove(i);
                self.end_watch(&w, &text);
            }
            return true;
        }
        if let How::Event { request, .. } = w.how {
            w.how = How::Event {
                request,
                id: Some(c.event_id),
            };
        }
        if let Some((_, reply)) = w.confirm.take() {
            answer(&reply, Ok(()));
        }
        true
    }

    fn event_rejected(&mut self, from: Address, r: &RejectEventRequest) -> bool {
        let Some(i) = self.watches.iter().position(|w| {
            matches!(w.how, How::Event { request, id: None } if request == r.request_id || r.request_id == 0)
                && w.to.matches(&from)
        }) else {
            return false;
        };
        let mut w = self.watches.remove(i);
        let text = format!(
            "CreateEvent: {from} refused the event: response code {:?}{}",
            r.response_code,
            r.error_message
                .as_deref()
                .map_or(String::new(), |m| format!(" ({m})"))
        );
        // Refused: nothing to cancel.
        w.how = How::Event {
            request: 0,
            id: None,
        };
        if let Some((_, reply)) = w.confirm.take() {
            answer(&reply, Err(Failure::new(text.clone())));
        }
        w.feed.end(&text);
        true
    }

    fn event(&mut self, from: Address, e: &Event) -> bool {
        let Some(w) = self.watches.iter().find(|w| {
            matches!(w.how, How::Event { id: Some(i), .. } if i == e.event_id)
                && w.to.matches(&from)
        }) else {
            return false;
        };
        let item = self.decode(CommandCode(e.report_message_code), &e.report_message);
        if !w.feed.push(item) {
            add(&self.stats.reports_dropped);
        }
        true
    }
}
