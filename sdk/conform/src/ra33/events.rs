//! Events and time: a periodic event on Report Component Status (create, confirm with
//! the request's id, Event messages at the confirmed rate carrying the report, listed by
//! Query Events, cancelled), an every-change event seeing the controller's Standby and
//! Resume, and Query Time against the tester's clock.

use std::time::Duration;

use jaus::messages::{
    CancelEvent, ComponentState, CreateEvent, EventResponseCode, EventType, Message, QueryEvents,
    QueryTime, ReportTime,
};
use jaus::{Address, CommandCode};

use super::Ra33Voice;
use crate::check::Verdict;
use crate::session::Incoming;

use crate::engine::Found;

/// Report Component Status, the report every component has.
const REPORT: u16 = 0x4002;
/// Event, Confirm Event Request, Reject Event Request.
const EVENT: u16 = 0x41F1;
const CONFIRM: u16 = 0x01F3;
const REJECT: u16 = 0x01F4;
/// The periodic rate asked for, Hz.
const RATE: f64 = 10.0;
/// The request ids the tester uses (a target echoing 0 is caught).
const CREATE_ID: u8 = 0x5A;
const CANCEL_ID: u8 = 0x5B;
/// Most a clock may differ from the tester's before the time check fails.
const CLOCK_SLACK: Duration = Duration::from_secs(60);

/// How a Create or Cancel Event was answered.
enum Answer {
    Confirmed {
        request_id: u8,
        event_id: u8,
        rate: Option<f64>,
        response: EventResponseCode,
    },
    Rejected(String),
}

impl Ra33Voice<'_> {
    /// Sends an event request from `from` and waits for its Confirm or Reject.
    fn event_request(&mut self, from: Address, msg: Message) -> Option<Answer> {
        self.send(from, &msg, false);
        let target = self.target;
        let p = self.wait_for(self.opts.wait, |p| {
            p.header.source == target
                && p.header.destination == from
                && matches!(p.header.command_code.0, CONFIRM | REJECT)
        })?;
        Some(
            match Message::decode_known(p.header.command_code, &p.body) {
                Ok(Message::ConfirmEventRequest(c)) => Answer::Confirmed {
                    request_id: c.request_id,
                    event_id: c.event_id,
                    rate: c.confirmed_update_rate,
                    response: c.response_code,
                },
                Ok(Message::RejectEventRequest(r)) => Answer::Rejected(format!(
                    "Reject Event Request {:?}{}",
                    r.response_code,
                    r.error_message
                        .map(|m| format!(": {m}"))
                        .unwrap_or_default()
                )),
                _ => Answer::Rejected("an answer that does not decode".into()),
            },
        )
    }

    /// Event messages of event `id` arriving at `voice` within `window`: how many, and
    /// the core states their reports carried (None for a report that did not decode).
    fn watch_events(
        &mut self,
        voice: Address,
        id: u8,
        window: Duration,
    ) -> Vec<Option<ComponentState>> {
        let deadline = self.session.now() + window;
        let target = self.target;
        let mine = |p: &Incoming| {
            p.header.source == target
                && p.header.destination == voice
                && p.header.command_code.0 == EVENT
        };
        let mut seen = Vec::new();
        while let Some(p) = self.next(deadline) {
            if !mine(&p) {
                continue;
            }
            if let Ok(Message::Event(e)) = Message::decode_known(CommandCode(EVENT), &p.body) {
                if e.event_id != id {
                    continue;
                }
                seen.push(match e.report_message_decoded() {
                    Ok(Message::ReportComponentStatus(r)) if e.report_message_code == REPORT => {
                        Some(r.primary_status_code)
                    }
                    _ => None,
                });
            }
        }
        seen
    }

    fn create(&mut self, from: Address, event_type: EventType) -> Result<(u8, f64), Found> {
        let create = CreateEvent {
            request_id: CREATE_ID,
            report_message_code: REPORT,
            event_type,
            requested_minimum_rate: (event_type == EventType::Periodic).then_some(1.0),
            requested_update_rate: (event_type == EventType::Periodic).then_some(RATE),
            query_message: Some(Vec::new()),
            ..CreateEvent::default()
        };
        match self.event_request(from, create.into()) {
            None => Err((
                Verdict::Fail,
                format!(
                    "no Confirm or Reject Event Request within {:?}",
                    self.opts.wait
                ),
            )),
            Some(Answer::Rejected(why)) => Err((
                Verdict::Fail,
                format!("{event_type:?} event on Report Component Status refused: {why}"),
            )),
            Some(Answer::Confirmed {
                response,
                request_id,
                ..
            }) if response != EventResponseCode::Successful || request_id != CREATE_ID => {
                Err((
                    Verdict::Fail,
                    format!(
                        "confirmed with response {response:?} and request id {request_id} (sent {CREATE_ID})"
                    ),
                ))
            }
            Some(Answer::Confirmed { event_id, rate, .. }) => Ok((event_id, rate.unwrap_or(RATE))),
        }
    }

    /// Cancels event `id`; a problem, if any.
    fn cancel(&mut self, from: Address, id: u8) -> Option<String> {
        let cancel = CancelEvent {
            request_id: CANCEL_ID,
            message_code: Some(REPORT),
            event_id: Some(id),
        };
        match self.event_request(from, cancel.into()) {
            Some(Answer::Confirmed {
                response: EventResponseCode::Successful,
                ..
            }) => None,
            Some(Answer::Confirmed { response, .. }) => {
                Some(format!("Cancel Event confirmed with {response:?}"))
            }
            Some(Answer::Rejected(why)) => Some(format!("Cancel Event refused: {why}")),
            None => Some(format!(
                "no answer to Cancel Event within {:?}",
                self.opts.wait
            )),
        }
    }

    pub(super) fn event_periodic(&mut self) -> Found {
        let o = self.voices.outsider;
        let (id, rate) = match self.create(o, EventType::Periodic) {
            Ok(x) => x,
            Err(found) => return found,
        };
        let window = (self.opts.settle * 5).max(Duration::from_millis(500));
        let expected = ((rate * window.as_secs_f64() * 0.5).floor() as usize).max(1);
        let mut problems = Vec::new();
        let seen = self.watch_events(o, id, window);
        if seen.len() < expected {
            problems.push(format!(
                "{} Event messages in {window:?} at a confirmed {rate:.2} Hz (at least {expected} expected)",
                seen.len()
            ));
        }
        if seen.iter().any(Option::is_none) {
            problems.push("an Event's report is not a Report Component Status".into());
        }
        let listed = match self.ask(
            o,
            QueryEvents {
                event_id: Some(id),
                ..QueryEvents::default()
            }
            .into(),
        ) {
            Some(Message::ReportEvents(r)) => r
                .events
                .iter()
                .any(|e| e.message_code == REPORT && e.event_id.is_none_or(|i| i == id)),
            _ => false,
        };
        if !listed {
            problems.push(format!("Query Events does not list event {id}"));
        }
        if let Some(p) = self.cancel(o, id) {
            problems.push(p);
        }
        self.drain(self.opts.settle);
        let after = self.watch_events(o, id, window).len();
        if after > 1 {
            problems.push(format!("{after} Event messages after Cancel Event"));
        }
        if problems.is_empty() {
            (
                Verdict::Pass,
                format!(
                    "event {id} confirmed at {rate:.2} Hz: {} Event messages in {window:?}, listed by Query Events, none after Cancel Event",
                    seen.len()
                ),
            )
        } else {
            (Verdict::Fail, problems.join("; "))
        }
    }

    pub(super) fn event_every_change(&mut self) -> Found {
        if let Err(e) = self.prepare(Some(ComponentState::Ready)) {
            return (Verdict::Inconclusive, e);
        }
        let o = self.voices.outsider;
        let (id, _) = match self.create(o, EventType::EveryChange) {
            Ok(x) => x,
            Err(found) => return found,
        };
        // Whatever the event sends first (some providers send the current value).
        self.watch_events(o, id, self.opts.settle);
        let c = self.voices.controller;
        let mut problems = Vec::new();
        for want in [ComponentState::Standby, ComponentState::Ready] {
            let msg: Message = match want {
                ComponentState::Standby => jaus::messages::Standby {}.into(),
                _ => jaus::messages::Resume {}.into(),
            };
            self.send(c, &msg, false);
            let seen = self.watch_events(o, id, self.opts.settle.max(Duration::from_millis(300)));
            if !seen.contains(&Some(want)) {
                problems.push(format!(
                    "no Event carrying {want:?} after the controller's {} (events seen: {seen:?})",
                    msg.name()
                ));
            }
        }
        if let Some(p) = self.cancel(o, id) {
            problems.push(p);
        }
        if problems.is_empty() {
            (
                Verdict::Pass,
                format!("event {id} reported the change to Standby and back to Ready"),
            )
        } else {
            (Verdict::Fail, problems.join("; "))
        }
    }

    pub(super) fn time(&mut self) -> Found {
        let q = QueryTime {
            presence_vector: 0b11,
        };
        let Some(Message::ReportTime(r)) = self.ask(self.voices.outsider, q.into()) else {
            return (
                Verdict::Fail,
                format!("no answer to Query Time within {:?}", self.opts.wait),
            );
        };
        let ReportTime {
            time_stamp: Some(t),
            date_stamp,
        } = r
        else {
            return (
                Verdict::Inconclusive,
                "Report Time has no time stamp: the component does not know the time of day (nothing to compare)".into(),
            );
        };
        let mine = self.session.utc().as_secs() % 86_400;
        let theirs = u64::from(t.hour) * 3600 + u64::from(t.minute) * 60 + u64::from(t.second);
        let off = mine.abs_diff(theirs).min(86_400 - mine.abs_diff(theirs));
        let text = format!(
            "{:02}:{:02}:{:02}.{:03} UTC, {off} s from the tester's clock{}",
            t.hour,
            t.minute,
            t.second,
            t.millisecond,
            if date_stamp.is_some() {
                ""
            } else {
                "; no date stamp"
            }
        );
        if off > CLOCK_SLACK.as_secs() || t.hour > 23 || t.minute > 59 || t.second > 59 {
            (Verdict::Fail, text)
        } else {
            (Verdict::Pass, text)
        }
    }
}
