//! The planned check of a command inside a Core v1.1 Create Command Event from a client
//! without control: the component refuses the command event, or confirms it and reports
//! the command Unsuccessful; either way its read-back query shows nothing changed.

use jaus::CommandCode;
use jaus::JausMessage;
use jaus_as4::messages::{
    CommandEvent, CommandResult, ConfirmEventRequest, CreateCommandEvent, Message,
    RejectEventRequest,
};

use super::exec::Runner;
use super::sample;
use crate::engine::{fail, inconclusive as unsure, pass, Found};

const CONFIRM_EVENT: u16 = ConfirmEventRequest::CODE.0;
const REJECT_EVENT: u16 = RejectEventRequest::CODE.0;
const COMMAND_EVENT: u16 = CommandEvent::CODE.0;
/// The longest a command may run, as the check asks it (seconds).
const MAX_DURATION: u32 = 10;

/// What the component answered a Create Command Event with.
enum Outcome {
    /// Reject Event Request for the request.
    Refused(String),
    /// Confirmed under an event id, then a Command Event with this result (or none).
    Confirmed(u8, Option<CommandResult>),
    /// Nothing for the request within the wait.
    Silence,
}

impl Runner<'_> {
    /// Runs [`Step::CommandEvent`](super::Step::CommandEvent).
    pub(super) fn command_event(&mut self, command: &str, readback: &str) -> Found {
        let Some((report, shared)) = self.readback(command, readback) else {
            return unsure(format!(
                "{readback} reads back nothing {command} sets, by the definitions"
            ));
        };
        let (r0, cmd, sent) = match self.nudged(command, readback, &report, &shared) {
            Ok(n) => n,
            Err(e) => return unsure(e),
        };
        if sent.is_empty() {
            return unsure(format!("no value of {command} differs from {readback}'s"));
        }
        let body = match self.defs.schema().encode(&cmd) {
            Ok(b) => b,
            Err(e) => return unsure(format!("{command} does not encode: {e}")),
        };
        let mut command_message = cmd.code.0.to_le_bytes().to_vec();
        command_message.extend_from_slice(&body);
        self.request = self.request.wrapping_add(1);
        let request_id = self.request;
        self.j.send(
            &CreateCommandEvent {
                request_id,
                maximum_allowed_duration: MAX_DURATION,
                command_message,
            }
            .into(),
        );
        let outcome = self.command_event_outcome(request_id);
        let confirmed = self.settle_confirmations();
        let r1 = match self.read(readback, &report) {
            Ok(r) => r,
            Err(e) => return unsure(format!("after: {e}")),
        };
        let moved = sample::moved(&r0.fields, &r1.fields, &sent);
        let what = format!("{command} {}", sample::text(&cmd.fields));
        let wait = self.j.opts.wait.as_secs_f64();
        judge(&outcome, &moved, &confirmed, &what, readback, wait)
    }

    /// Waits for the answer to Create Command Event `request_id`: its refusal, or its
    /// confirmation and then the Command Event of the event id confirmed.
    fn command_event_outcome(&mut self, request_id: u8) -> Outcome {
        let peer = Some(self.j.peer);
        // One answer wait for the confirmation and one for the outcome, whatever else
        // the peer sends meanwhile.
        let deadline = self.j.now() + self.j.opts.wait * 2;
        let mut event_id = None;
        loop {
            let ids: &[u16] = if event_id.is_some() {
                &[COMMAND_EVENT]
            } else {
                &[CONFIRM_EVENT, REJECT_EVENT]
            };
            let left = deadline.saturating_duration_since(self.j.now());
            let arrival = if left.is_zero() {
                None
            } else {
                self.j.wait_for(left, peer, ids)
            };
            let Some(a) = arrival else {
                return event_id.map_or(Outcome::Silence, |id| Outcome::Confirmed(id, None));
            };
            match Message::decode(CommandCode(a.message.message_id), &a.message.body) {
                Ok(Message::RejectEventRequest(r)) if r.request_id == request_id => {
                    let why = r
                        .error_message
                        .clone()
                        .or_else(|| r.response_code.map(|c| format!("{c:?}")))
                        .unwrap_or_default();
                    return Outcome::Refused(why);
                }
                Ok(Message::ConfirmEventRequest(c)) if c.request_id == request_id => {
                    event_id = Some(c.event_id);
                }
                Ok(Message::CommandEvent(e)) if Some(e.event_id) == event_id => {
                    return Outcome::Confirmed(e.event_id, Some(e.command_result));
                }
                // Another request's answer, or one that does not decode: keep waiting
                // until the deadline.
                _ => {}
            }
        }
    }
}

/// The verdict of a command event sent without control: what the component answered
/// (`outcome`), what the read-back shows moved, the confirmations seen meanwhile.
fn judge(
    outcome: &Outcome,
    moved: &[String],
    confirmed: &[String],
    what: &str,
    readback: &str,
    wait: f64,
) -> Found {
    if !moved.is_empty() {
        return fail(format!(
            "carried out without control through a command event: {} by {readback}",
            moved.join("; ")
        ));
    }
    if let Some(c) = confirmed.iter().find(|c| *c != "ConfirmEventRequest") {
        return fail(format!(
            "{c} without control, for a command event of {what}"
        ));
    }
    match outcome {
        Outcome::Refused(why) => pass(format!(
            "Create Command Event of {what} refused ({why}); {readback} unchanged"
        )),
        Outcome::Confirmed(id, Some(CommandResult::Unsuccessful)) => pass(format!(
            "command event {id} of {what} confirmed and reported Unsuccessful; {readback} unchanged"
        )),
        Outcome::Confirmed(id, Some(r)) => fail(format!(
            "command event {id} of {what} from a client without control reported {r:?}"
        )),
        Outcome::Confirmed(id, None) => fail(format!(
            "command event {id} of {what} confirmed, but no Command Event reported its outcome within {wait:.1} s"
        )),
        Outcome::Silence => fail(format!(
            "no answer to Create Command Event within {wait:.1} s (Events v1.1 refuses one it does not run)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Verdict;

    fn verdict(outcome: Outcome, moved: &[&str], confirmed: &[&str]) -> (Verdict, String) {
        let moved: Vec<String> = moved.iter().map(|s| s.to_string()).collect();
        let confirmed: Vec<String> = confirmed.iter().map(|s| s.to_string()).collect();
        judge(
            &outcome,
            &moved,
            &confirmed,
            "SetX {\"x\":1}",
            "QueryX",
            1.0,
        )
    }

    #[test]
    fn refused_or_unsuccessful_and_unchanged_passes() {
        let (v, d) = verdict(Outcome::Refused("MessageNotSupported".into()), &[], &[]);
        assert_eq!(v, Verdict::Pass, "{d}");
        let (v, d) = verdict(
            Outcome::Confirmed(3, Some(CommandResult::Unsuccessful)),
            &[],
            &["ConfirmEventRequest"],
        );
        assert_eq!(v, Verdict::Pass, "{d}");
        assert!(d.contains("reported Unsuccessful"), "{d}");
    }

    #[test]
    fn carried_out_reported_successful_or_silent_fails() {
        let (v, d) = verdict(
            Outcome::Confirmed(3, Some(CommandResult::Unsuccessful)),
            &["x: 0 → 1 (sent 1)"],
            &[],
        );
        assert_eq!(v, Verdict::Fail);
        assert!(d.contains("through a command event"), "{d}");
        let (v, d) = verdict(
            Outcome::Confirmed(3, Some(CommandResult::Successful)),
            &[],
            &[],
        );
        assert_eq!(v, Verdict::Fail);
        assert!(d.contains("reported Successful"), "{d}");
        let (v, d) = verdict(Outcome::Confirmed(3, None), &[], &[]);
        assert_eq!(v, Verdict::Fail);
        assert!(d.contains("no Command Event"), "{d}");
        let (v, _) = verdict(Outcome::Silence, &[], &[]);
        assert_eq!(v, Verdict::Fail);
        let (v, d) = verdict(Outcome::Refused("no".into()), &[], &["ConfirmX"]);
        assert_eq!(v, Verdict::Fail);
        assert!(d.contains("ConfirmX without control"), "{d}");
    }
}
