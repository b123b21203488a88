//! The core messages the runtime handles itself, dispatched in one place
//! ([`Component::core_message`]), and those of them this module carries out: core state
//! commands, authority, component control, emergency and time. Service connections
//! are carried out in [`connections`](super::connections), events in
//! [`events`](super::events).

use super::events::EventSetup;
use super::{
    Behaviour, Component, Controller, CoreState, CoreTransition, Interface, Refusal, Refused,
};
use crate::messages::*;
use crate::{Address, Header, MessageSet};

impl<B: Behaviour> Component<B> {
    /// Handles a core message; `None` when `msg` is not one.
    pub(super) fn core_message(
        &mut self,
        header: &Header,
        original: &<B::Interface as Interface>::Messages,
    ) -> Option<Result<(), Refusal>> {
        let msg = original.standard()?;
        let source = header.source;
        let controlled = |c: &Self| {
            if c.rt.may_command(source) {
                Ok(())
            } else {
                Err(Refusal::NotController)
            }
        };
        let transition = |c: &mut Self, t: CoreTransition| -> Result<(), Refusal> {
            controlled(c)?;
            c.rt.set_state(t)
                .map(|_| ())
                .map_err(|_| Refusal::State(c.rt.state))
        };
        let r = match msg {
            Message::SetComponentAuthority(m) => controlled(self).map(|()| {
                self.rt.authority = m.authority_code;
            }),
            Message::Shutdown(_) => transition(self, CoreTransition::Shutdown),
            Message::Standby(_) => transition(self, CoreTransition::Standby),
            Message::Resume(_) => transition(self, CoreTransition::Resume),
            Message::Reset(_) => transition(self, CoreTransition::Reset),
            Message::SetEmergency(_) => {
                self.set_emergency(source);
                Ok(())
            }
            Message::ClearEmergency(_) => self.clear_emergency(source),
            Message::SetTime(m) => controlled(self).and_then(|()| {
                let now = self.rt.now;
                let time = m.time_stamp.as_ref().map(Into::into);
                let date = m.date_stamp.as_ref().map(Into::into);
                if self.rt.clock.apply(now, time, date).is_ok() {
                    Ok(())
                } else {
                    Err(Refusal::Vendor(Refused::Invalid(
                        "Set Time carries an impossible date or time".into(),
                    )))
                }
            }),
            Message::RequestComponentControl(m) => {
                self.request_control(source, m.authority_code);
                Ok(())
            }
            Message::ReleaseComponentControl(_) => match self.rt.controller {
                Some(c) if c.address == source => {
                    self.rt.controller = None;
                    Ok(())
                }
                _ => Err(Refusal::NotController),
            },
            Message::ConfirmComponentControl(m) => {
                let held = &mut self.rt.held_control;
                if m.response_code == ControlResponse::ControlAccepted {
                    if !held.iter().any(|(a, _)| *a == source) && held.len() < 64 {
                        held.push((source, None));
                    }
                } else {
                    held.retain(|(a, _)| *a != source);
                }
                return Some(self.pass_on(header, original));
            }
            Message::RejectComponentControl(_) => {
                self.rt.held_control.retain(|(a, _)| *a != source);
                return Some(self.pass_on(header, original));
            }
            Message::ReportComponentStatus(m) => {
                // Kept for the components this one controls (a driver resumes its output
                // when it reports Standby); the behaviour sees every report as before.
                let state = CoreState::from_wire(m.primary_status_code);
                match self.rt.held_control.iter_mut().find(|(a, _)| *a == source) {
                    Some((_, s)) => *s = state,
                    None => return None,
                }
                return Some(self.pass_on(header, original));
            }
            Message::ReportComponentControl(m) => {
                // A component this one controls that names another controller, or none,
                // is no longer controlled by it: it restarted (a new process knows
                // nothing of the old grant) or let control go without a word. Control
                // is then asked for again (`ControlKeeper`). The behaviour sees the
                // report as before.
                let controller =
                    Address::new(m.subsystem_id, m.node_id, m.component_id, m.instance_id);
                if controller != self.rt.address {
                    self.rt.held_control.retain(|(a, _)| *a != source);
                }
                return None;
            }
            Message::CreateServiceConnection(m) => {
                self.create_sc(source, m);
                Ok(())
            }
            Message::ActivateServiceConnection(m) => self.sc_set_active(
                source,
                m.service_connection_command_code,
                m.instance_id,
                true,
            ),
            Message::SuspendServiceConnection(m) => self.sc_set_active(
                source,
                m.service_connection_command_code,
                m.instance_id,
                false,
            ),
            Message::TerminateServiceConnection(m) => {
                self.terminate_sc(source, m);
                Ok(())
            }
            Message::ConfirmServiceConnection(m) => {
                self.confirm_sc(self.rt.now, source, m);
                return Some(self.pass_on(header, original));
            }
            Message::CreateEvent(m) => {
                self.create_event(source, m.request_id, EventSetup::from_create(m), None);
                Ok(())
            }
            Message::UpdateEvent(m) => {
                self.create_event(
                    source,
                    m.request_id,
                    EventSetup::from_update(m),
                    Some(m.event_id),
                );
                Ok(())
            }
            Message::CancelEvent(m) => {
                self.cancel_event(source, m);
                Ok(())
            }
            Message::QueryIdentification(q) if q.query_field != QueryLevel::Component => {
                return None;
            }
            m => {
                let reply = self.core_report(m)?;
                self.rt.send(source, reply, false, 0);
                Ok(())
            }
        };
        Some(r)
    }

    /// Hands a core message the runtime has already acted on to the behaviour too
    /// (replies to requests the component made).
    fn pass_on(
        &mut self,
        header: &Header,
        msg: &<B::Interface as Interface>::Messages,
    ) -> Result<(), Refusal> {
        let _ = header;
        let r = self.behaviour.handle(
            &mut super::Context {
                rt: &mut self.rt,
                _i: std::marker::PhantomData,
            },
            msg,
        );
        match r {
            Ok(_) | Err(Refused::Unsupported) => Ok(()),
            Err(e) => Err(Refusal::Vendor(e)),
        }
    }

    fn set_emergency(&mut self, source: Address) {
        let c = &mut self.rt;
        if !c.emergencies.contains(&source) {
            if c.emergencies.len() < c.config.max_emergency_senders {
                c.emergencies.push(source);
            } else {
                c.stats.emergency_overflow += 1;
            }
        }
        tracing::warn!(component = <B::Interface as Interface>::NAME, address = %c.address, source = %source, "emergency set");
        if c.set_state(CoreTransition::SetEmergency).is_err() {
            c.stats.wrong_state += 1;
        }
    }

    /// Clear Emergency: ends `source`'s emergency. A sender that set none is counted;
    /// while another sender's emergency stands, it is refused (NAKed, with the reason),
    /// since only the component that set an emergency may clear it.
    fn clear_emergency(&mut self, source: Address) -> Result<(), Refusal> {
        let c = &mut self.rt;
        let before = c.emergencies.len();
        c.emergencies.retain(|a| *a != source);
        if c.emergencies.len() == before {
            c.stats.foreign_clear_emergency += 1;
            return if c.emergencies.is_empty() {
                Ok(())
            } else {
                Err(Refusal::ForeignClear(c.emergencies.clone()))
            };
        }
        if c.emergencies.is_empty() && c.state == CoreState::Emergency {
            let _ = c.set_state(CoreTransition::ClearEmergency);
        }
        Ok(())
    }

    /// Request Component Control (docs/wire.md §5.3, plus the own-authority check).
    fn request_control(&mut self, source: Address, authority: u8) {
        let c = &mut self.rt;
        let confirm =
            |r: ControlResponse| -> Message { ConfirmComponentControl { response_code: r }.into() };
        if c.state == CoreState::Shutdown {
            c.send(source, confirm(ControlResponse::NotAvailable), false, 0);
            return;
        }
        if authority < c.authority {
            c.send(
                source,
                confirm(ControlResponse::InsufficientAuthority),
                false,
                0,
            );
            return;
        }
        match c.controller {
            None => {
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(cur) if cur.address == source => {
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(cur) if authority > cur.authority => {
                c.send(cur.address, RejectComponentControl {}.into(), false, 0);
                c.displaced = Some((cur.address, c.now));
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(_) => c.send(source, RejectComponentControl {}.into(), false, 0),
        }
    }
}
