//! The generated state machine of the Core's Transport, Events, Access Control and
//! Management (`defs/core_services.yaml`, generated into
//! [`crate::messages::services`]) at work: [`Host`] implements the guards and actions of
//! the four generated traits over the services' data ([`Access`], [`Management`],
//! [`Events`]), and the messages they decide go out as [`Outgoing`] values.
//!
//! A host lives for one trigger: [`super::Core`] builds it over its data, offers the
//! trigger to the machines ([`Machines::receive`](crate::messages::services::management::Machines::receive)
//! for a received message, `handle` for an internal event such as `Timedout`) and takes
//! what it sent.

use std::time::Instant;

use jaus::net::as5669a::As4Id;

use super::access::Access;
use super::events::{self, Events, Rejection, Setup};
use super::management::Management;
use crate::messages::services::{access_control, events as ev, management, transport, Arg};
use crate::messages::{
    CancelEvent, ClearEmergency, ComponentAddress, ConfirmControl, ControlConfirmation,
    ControlRejection, CreateCommandEvent, CreateEvent, EventRejection, EventType, Message,
    QueryEvents, RejectControl, RequestControl, SetAuthority, SetEmergency, UpdateEvent,
};
use crate::service::Outgoing;

/// The data of a `Receive` event: the sender as the machine sees it.
pub fn receive_of(from: As4Id) -> transport::event::Receive {
    transport::event::Receive {
        source: ComponentAddress {
            subsystem_id: from.subsystem,
            node_id: from.node,
            component_id: from.component,
        },
    }
}

fn sender(t: &transport::event::Receive) -> As4Id {
    As4Id::new(
        t.source.subsystem_id,
        t.source.node_id,
        t.source.component_id,
    )
}

/// The guards and actions of the Core's machine, over the services' data, for one
/// trigger.
pub(crate) struct Host<'a> {
    /// The time of the trigger.
    pub now: Instant,
    /// Access Control's data.
    pub access: &'a mut Access,
    /// Management's data.
    pub management: &'a mut Management,
    /// Events' subscriptions.
    pub events: &'a mut Events,
    /// What the actions send.
    pub out: &'a mut Vec<Outgoing>,
    /// For a Create or Update Event: its query, decoded and answered by the component,
    /// or why it is not supported (the component looks ahead: the query may be any
    /// service's).
    pub event_query: Option<Result<Message, Rejection>>,
    /// A bound an action reached (the component counts it).
    pub bound: Option<String>,
}

impl Host<'_> {
    fn send(&mut self, to: As4Id, message: impl Into<Message>) {
        self.out.push(Outgoing::new(to, message));
    }

    fn confirm(&mut self, t: &transport::event::Receive, response_code: ControlConfirmation) {
        self.send(sender(t), ConfirmControl { response_code });
    }

    fn reject(&mut self, to: As4Id, response_code: ControlRejection) {
        self.send(to, RejectControl { response_code });
    }

    fn setup<'q>(
        &mut self,
        request_id: u8,
        kind: EventType,
        rate: f64,
        query_bytes: &'q [u8],
    ) -> Result<Setup<'q>, Rejection> {
        let query = match self.event_query.take() {
            Some(Ok(q)) => q,
            Some(Err(r)) => return Err(r),
            None => events::query_of(query_bytes)?,
        };
        Ok(Setup {
            request_id,
            kind,
            rate,
            query_bytes,
            query,
        })
    }

    fn not_supported(&mut self) -> Rejection {
        match self.event_query.take() {
            Some(Err(r)) => r,
            _ => (
                EventRejection::MessageNotSupported,
                "the query is not supported".into(),
            ),
        }
    }
}

impl transport::Transport for Host<'_> {}

impl ev::Events for Host<'_> {
    fn is_supported(&self, _: &[Arg<'_>]) -> bool {
        matches!(self.event_query, Some(Ok(_)))
    }

    fn cancel_event(&mut self, msg: &CancelEvent, t: &transport::event::Receive) {
        let o = self.events.cancel(sender(t), msg.request_id, msg.event_id);
        self.out.push(o);
    }

    fn create_event(&mut self, msg: &CreateEvent, t: &transport::event::Receive) {
        let from = sender(t);
        let o = match self.setup(
            msg.request_id,
            msg.event_type,
            msg.requested_periodic_rate,
            &msg.query_message,
        ) {
            Ok(setup) => self.events.create(self.now, from, setup),
            Err(r) => events::reject(from, msg.request_id, r),
        };
        self.out.push(o);
    }

    fn update_event(&mut self, msg: &UpdateEvent, t: &transport::event::Receive) {
        let from = sender(t);
        let o = match self.setup(
            msg.request_id,
            msg.event_type,
            msg.requested_periodic_rate,
            &msg.query_message,
        ) {
            Ok(setup) => self.events.update(self.now, from, msg.event_id, setup),
            Err(r) => events::reject(from, msg.request_id, r),
        };
        self.out.push(o);
    }

    fn refuse_create_event(&mut self, msg: &CreateEvent, t: &transport::event::Receive) {
        let r = self.not_supported();
        self.out.push(events::reject(sender(t), msg.request_id, r));
    }

    fn refuse_update_event(&mut self, msg: &UpdateEvent, t: &transport::event::Receive) {
        let r = self.not_supported();
        self.out.push(events::reject(sender(t), msg.request_id, r));
    }

    fn refuse_command_event(&mut self, msg: &CreateCommandEvent, t: &transport::event::Receive) {
        let r = (
            EventRejection::MessageNotSupported,
            "command events are not supported".into(),
        );
        self.out.push(events::reject(sender(t), msg.request_id, r));
    }

    fn send_report_events(&mut self, msg: &QueryEvents, t: &transport::event::Receive) {
        let report = self.events.report(&msg.filter);
        self.send(sender(t), report);
    }

    fn send_report_event_timeout(&mut self, t: &transport::event::Receive) {
        let report = self.events.report_timeout();
        self.send(sender(t), report);
    }
}

impl access_control::AccessControl for Host<'_> {
    fn is_authority_valid(&self, msg: &SetAuthority) -> bool {
        self.access.is_valid(msg.authority_code)
    }

    fn is_controlling_client(&self, t: &transport::event::Receive) -> bool {
        self.access.controller() == Some(sender(t))
    }

    fn is_current_authority_less(&self, msg: &RequestControl) -> bool {
        self.access.authority() < msg.authority_code
    }

    fn is_default_authority_greater(&self, msg: &RequestControl) -> bool {
        self.access.default_authority() > msg.authority_code
    }

    fn init(&mut self) {
        self.access.reset();
    }

    fn store_address(&mut self, t: &transport::event::Receive) {
        self.access.store(sender(t));
    }

    fn set_authority(&mut self, args: &[Arg<'_>]) {
        for a in args {
            match a {
                Arg::RequestControl(m) => self.access.set_authority(m.authority_code),
                Arg::SetAuthority(m) => self.access.set_authority(m.authority_code),
                _ => {}
            }
        }
    }

    fn reset_timer(&mut self) {
        self.access.rearm(self.now);
    }

    fn grant_control(&mut self, t: &transport::event::Receive) {
        self.confirm(t, ControlConfirmation::ControlAccepted);
    }

    fn refuse_authority(&mut self, t: &transport::event::Receive) {
        self.confirm(t, ControlConfirmation::InsufficientAuthority);
    }

    fn refuse_not_available(&mut self, t: &transport::event::Receive) {
        self.confirm(t, ControlConfirmation::NotAvailable);
    }

    fn confirm_release(&mut self, t: &transport::event::Receive) {
        self.reject(sender(t), ControlRejection::ControlReleased);
    }

    fn reject_not_available(&mut self, t: &transport::event::Receive) {
        self.reject(sender(t), ControlRejection::NotAvailable);
    }

    fn release_controller(&mut self) {
        if let Some(c) = self.access.controller() {
            self.reject(c, ControlRejection::ControlReleased);
        }
    }

    fn send_report_authority(&mut self, t: &transport::event::Receive) {
        let r = self.access.report_authority();
        self.send(sender(t), r);
    }

    fn send_report_control(&mut self, t: &transport::event::Receive) {
        let r = self.access.report_control();
        self.send(sender(t), r);
    }

    fn send_report_timeout(&mut self, t: &transport::event::Receive) {
        let r = self.access.report_timeout();
        self.send(sender(t), r);
    }
}

impl management::Management for Host<'_> {
    fn is_id_stored(&self, msg: &ClearEmergency, t: &transport::event::Receive) -> bool {
        self.management.is_stored(sender(t), msg.emergency_code)
    }

    fn is_last_emergency(&self, msg: &ClearEmergency, t: &transport::event::Receive) -> bool {
        self.management.is_last(sender(t), msg.emergency_code)
    }

    fn delete_id(&mut self, msg: &ClearEmergency, t: &transport::event::Receive) {
        self.management.delete(sender(t), msg.emergency_code);
    }

    fn store_id(&mut self, msg: &SetEmergency, t: &transport::event::Receive) {
        if !self.management.store(sender(t), msg.emergency_code) {
            self.bound = Some(format!(
                "more than {} emergencies",
                super::management::MAX_EMERGENCIES
            ));
        }
    }

    fn fail_after_emergency(&mut self) {
        self.management.fail_after_emergency();
    }

    fn initialize(&mut self) {
        // Nothing to wait for: the Core raises Initialized as soon as the machine is in
        // Init (`Core::settle`).
    }

    fn send_report_status(&mut self, t: &transport::event::Receive) {
        let r = self.management.report();
        self.send(sender(t), r);
    }
}
