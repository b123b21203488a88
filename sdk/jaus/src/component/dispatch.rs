//! One message through the runtime: the core messages, the refusals (counted, logged,
//! reported), event notifications, the behaviour; and the reports of core queries,
//! answered by the runtime itself.

use std::marker::PhantomData;

use super::refusal::DISPLACED_GRACE;
use super::{
    refusal_report, Behaviour, Component, Context, CoreState, Interface, Refusal, Refused, Set,
};
use crate::messages::*;
use crate::wire::AckNak;
use crate::{Address, CommandCode, Header, MessageSet};

impl<B: Behaviour> Component<B> {
    pub(super) fn refuse(&mut self, header: &Header, msg: &Set<B>, why: Refusal) -> bool {
        let s = &mut self.rt.stats;
        match &why {
            Refusal::NotController => s.not_controller += 1,
            Refusal::State(_) => s.wrong_state += 1,
            Refusal::Vendor(Refused::Unsupported) => s.unsupported += 1,
            Refusal::Vendor(Refused::Invalid(_) | Refused::OutOfRange { .. }) => s.invalid += 1,
            // Counted where it is found.
            Refusal::ForeignClear(_) => {}
        }
        if header.ack_nak == AckNak::Request {
            let report = refusal_report(header.command_code, why.reason(), &why.to_string());
            self.rt.send(header.source, report.into(), false, 0);
        }
        let (component, address, source) = (
            <B::Interface as Interface>::NAME,
            self.rt.address,
            header.source,
        );
        // A command from the controller a higher authority just displaced crossed the
        // Reject Component Control on its way here: normal in JAUS, not a fault.
        let crossed = matches!(why, Refusal::NotController)
            && self.rt.displaced.is_some_and(|(a, t)| {
                a == source && self.rt.now.saturating_duration_since(t) < DISPLACED_GRACE
            });
        if crossed {
            tracing::debug!(component, %address, %source, message = msg.name(),
                "refused: {why} (it lost control to a higher authority; this crossed the Reject Component Control)");
        } else if matches!(why, Refusal::Vendor(Refused::Unsupported)) {
            // Normal when peers probe what a component offers.
            tracing::debug!(component, %address, %source, message = msg.name(), "refused: {why}");
        } else {
            tracing::warn!(component, %address, %source, message = msg.name(), "refused: {why}");
        }
        false
    }

    /// Runs one message; returns whether it was accepted (for ACK/NAK).
    pub(super) fn dispatch(&mut self, header: &Header, msg: &Set<B>) -> bool {
        let source = header.source;
        self.rt.source = Some(source);
        if let Some(r) = self.core_message(header, msg) {
            return match r {
                Ok(()) => true,
                Err(why) => self.refuse(header, msg, why),
            };
        }
        if let Some(Message::Event(ev)) = msg.standard() {
            // An event notification carries a report: handle the report as if it had
            // arrived directly.
            return match Set::<B>::decode(CommandCode(ev.report_message_code), &ev.report_message) {
                Ok(inner) => {
                    let h = Header {
                        command_code: inner.code(),
                        ..*header
                    };
                    self.dispatch(&h, &inner)
                }
                Err(e) => {
                    self.rt.stats.decode_errors += 1;
                    tracing::warn!(
                        component = <B::Interface as Interface>::NAME,
                        source = %source,
                        "event {} carries an undecodable report: {e}",
                        ev.event_id
                    );
                    false
                }
            };
        }
        let state = self.rt.state;
        if state == CoreState::Shutdown {
            return self.refuse(header, msg, Refusal::State(state));
        }
        let code = msg.code();
        if <B::Interface as Interface>::COMMANDS.contains(&code) {
            if !self.rt.may_command(source) {
                return self.refuse(header, msg, Refusal::NotController);
            }
            if !matches!(state, CoreState::Ready | CoreState::Standby) {
                return self.refuse(header, msg, Refusal::State(state));
            }
        }
        let r = self.behaviour.handle(
            &mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            },
            msg,
        );
        match r {
            Ok(Some(reply)) => {
                self.rt.send_set(source, reply, false, 0);
                true
            }
            Ok(None) => true,
            Err(e) => self.refuse(header, msg, Refusal::Vendor(e)),
        }
    }

    /// Answers a query for a service connection or an event: core queries by the
    /// runtime, the others by the behaviour.
    pub(super) fn answer(&mut self, requester: Address, query: &Set<B>) -> Result<Set<B>, Refused> {
        if let Some(r) = query.standard().and_then(|q| self.core_report(q)) {
            return Ok(Set::<B>::from_standard(r));
        }
        let code = query.code();
        let iface_ok = <B::Interface as Interface>::ANY_MESSAGE
            || <B::Interface as Interface>::ACCEPTS.contains(&code);
        if !iface_ok || self.rt.state == CoreState::Shutdown {
            return Err(Refused::Unsupported);
        }
        self.rt.source = Some(requester);
        let r = self.behaviour.handle(
            &mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            },
            query,
        );
        match r {
            Ok(Some(report)) => Ok(report),
            Ok(None) => Err(Refused::Unsupported),
            Err(e) => Err(e),
        }
    }

    /// The report of a core query, answered by the runtime.
    pub(super) fn core_report(&self, query: &Message) -> Option<Message> {
        let c = &self.rt;
        Some(match query {
            Message::QueryComponentAuthority(_) => ReportComponentAuthority {
                authority_code: c.authority,
            }
            .into(),
            Message::QueryComponentStatus(_) => ReportComponentStatus {
                primary_status_code: c.state.to_wire(),
                secondary_status_code: 0,
            }
            .into(),
            Message::QueryComponentControl(_) => {
                let (a, auth) = c
                    .controller
                    .map_or((Address::default(), 0), |k| (k.address, k.authority));
                ReportComponentControl {
                    subsystem_id: a.subsystem,
                    node_id: a.node,
                    component_id: a.component,
                    instance_id: a.instance,
                    authority_code: auth,
                }
                .into()
            }
            Message::QueryTime(q) => {
                let stamps: Option<(TimeStamp, DateStamp)> =
                    c.clock.stamps(c.now).map(|(t, d)| (t.into(), d.into()));
                ReportTime {
                    time_stamp: stamps.filter(|_| q.presence_vector & 1 != 0).map(|s| s.0),
                    date_stamp: stamps.filter(|_| q.presence_vector & 2 != 0).map(|s| s.1),
                }
                .into()
            }
            Message::QueryHeartbeatPulse(_) => ReportHeartbeatPulse {}.into(),
            Message::QueryServices(_) => self.services().into(),
            Message::QueryIdentification(q) if q.query_field == QueryLevel::Component => {
                ReportIdentification {
                    query_type: QueryLevel::Component,
                    authority: c.authority,
                    identification_type: 0,
                    identification: c
                        .config
                        .identification
                        .clone()
                        .unwrap_or_else(|| <B::Interface as Interface>::NAME.to_string()),
                }
                .into()
            }
            Message::QueryEvents(q) => self.rt.events.report(q).into(),
            _ => return None,
        })
    }

    fn services(&self) -> ReportServices {
        let entry = |code: &CommandCode| ServiceCommand {
            command_code: code.0,
            presence_vector: 0,
        };
        let core = JausService {
            service_type: 0,
            input_commands: jaus_core_inputs().iter().map(entry).collect(),
            output_commands: jaus_core_outputs().iter().map(entry).collect(),
        };
        type I<B> = <B as Behaviour>::Interface;
        let inputs: Vec<ServiceCommand> = I::<B>::COMMANDS
            .iter()
            .chain(I::<B>::ACCEPTS)
            .map(entry)
            .collect();
        let outputs: Vec<ServiceCommand> = I::<B>::EMITS
            .iter()
            .copied()
            .chain(
                I::<B>::ACCEPTS
                    .iter()
                    .filter_map(|c| <I<B> as Interface>::Messages::report_of(*c)),
            )
            .map(|c| entry(&c))
            .collect();
        ReportServices {
            services: vec![
                core,
                JausService {
                    service_type: u16::from(I::<B>::ID),
                    input_commands: inputs,
                    output_commands: outputs,
                },
            ],
        }
    }
}

/// The core inputs listed in Report Services (service type 0), as OpenJAUS lists them:
/// the messages the definitions mark `runtime: [handles]` or `[shares]`.
fn jaus_core_inputs() -> &'static [CommandCode] {
    crate::messages::RUNTIME_INPUTS
}

/// The core outputs listed in Report Services: the messages the definitions mark
/// `runtime: [emits]`.
fn jaus_core_outputs() -> &'static [CommandCode] {
    crate::messages::RUNTIME_OUTPUTS
}
