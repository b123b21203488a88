//! The generated state machine of the Core's Transport, Events, Access Control and
//! Management (`defs/core_services.yaml`, generated into
//! [`crate::messages::services`]) at work.
//!
//! [`Host`] holds, for one trigger, the services' data ([`Access`], [`Management`],
//! [`Events`]) and what the actions send; [`core_machine!`](crate::core_machine)
//! implements the guards and actions of the four generated traits on it, and makes the
//! generated `Machines` a [`CoreMachine`], what [`Core`](super::Core) runs. The stock
//! Core is the machine of jaus-as4's own definitions ([`stock`]); a Core regenerated from
//! a revised definition (a `core_services.yaml` edited, or a later revision of the
//! standard with the same guards and actions) is run the same way:
//!
//! ```ignore
//! mod revised {
//!     pub use jaus_as4::messages::*;
//!     pub mod services { include!(concat!(env!("OUT_DIR"), "/services.rs")); }
//! }
//! jaus_as4::core_machine!(revised::services);
//! let core = Core::with_machine(me, config, Box::new(revised::services::management::Machines::new()));
//! ```

use std::fmt;
use std::time::Instant;

use jaus::net::as5669a::As4Id;

use super::access::Access;
use super::discovery::Discovery;
use super::events::{self, Events, Rejection, Setup};
use super::lists::Lists;
use super::management::{Management, MAX_EMERGENCIES};
use super::time::Time;
use crate::messages::{
    ConfirmControl, ControlConfirmation, ControlRejection, EmergencyCode, EventRejection,
    EventType, EventsFilter, Message, RejectControl,
};
use crate::outgoing::Outgoing;

/// The internal events the Core's owner raises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoreEvent {
    /// The controller's deadline passed (Access Control).
    Timedout,
    /// Initialisation is done (Management, in `Init`).
    Initialized,
    /// The owner declares a failure (Management).
    Failure,
}

/// A generated machine of the Core's services (the Management service's `Machines`, with
/// what it inherits), as [`Core`](super::Core) runs it. Implemented by
/// [`core_machine!`](crate::core_machine).
pub trait CoreMachine: fmt::Debug + Send {
    /// Offers a message received from `from`: `None` when the machine does not take
    /// it, else whether a transition was taken.
    fn receive(&mut self, host: &mut Host<'_>, msg: &Message, from: As4Id) -> Option<bool>;
    /// Raises an internal event; whether a transition was taken.
    fn raise(&mut self, host: &mut Host<'_>, event: CoreEvent) -> bool;
    /// The current state's path (`Receiving.Ready.Controlled.Available.Ready`).
    fn path(&self) -> &'static str;
    /// A copy.
    fn boxed_clone(&self) -> Box<dyn CoreMachine>;
}

impl Clone for Box<dyn CoreMachine> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

/// The data of the Core's other services (Time, Discovery, List Manager), lent to a
/// [`Host`] for one call; their machines run in [`super::others`].
#[derive(Debug)]
pub(crate) struct Others<'a> {
    pub(crate) time: &'a mut Time,
    pub(crate) discovery: &'a mut Discovery,
    /// The list manager, when the component offers it.
    pub(crate) lists: Option<&'a mut Lists>,
}

/// The guards and actions of the Core's machine, over the services' data, for one
/// trigger. Its methods are what the generated guards and actions call
/// ([`core_machine!`](crate::core_machine)); the sender is an [`As4Id`].
pub struct Host<'a> {
    now: Instant,
    access: &'a mut Access,
    management: &'a mut Management,
    events: &'a mut Events,
    out: &'a mut Vec<Outgoing>,
    event_query: Option<Result<Message, Rejection>>,
    bound: Option<String>,
    /// The data of the Core's other services (Time, Discovery, List Manager), when the
    /// Core runs their machines ([`super::others`]).
    others: Option<Others<'a>>,
    /// Why an action did not do what was asked (a time out of range), taken by the Core
    /// as a refusal.
    refused: Option<String>,
}

impl fmt::Debug for Host<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Host")
            .field("access", &self.access)
            .field("management", &self.management)
            .finish_non_exhaustive()
    }
}

impl<'a> Host<'a> {
    /// A host at `now` over the services' data, sending into `out`; `event_query` is,
    /// for Create and Update Event, the event's query decoded and answered by the
    /// component, for Create Command Event its command decoded and taken by the
    /// component, or why it is not supported.
    pub(crate) fn new(
        now: Instant,
        access: &'a mut Access,
        management: &'a mut Management,
        events: &'a mut Events,
        out: &'a mut Vec<Outgoing>,
        event_query: Option<Result<Message, Rejection>>,
    ) -> Self {
        Self {
            now,
            access,
            management,
            events,
            out,
            event_query,
            bound: None,
            others: None,
            refused: None,
        }
    }

    /// With the data of the Core's other services.
    pub(crate) fn with_others(mut self, others: Others<'a>) -> Self {
        self.others = Some(others);
        self
    }

    /// The data of the Core's other services, when given.
    pub(crate) fn others(&mut self) -> Option<&mut Others<'a>> {
        self.others.as_mut()
    }

    /// The data of the Core's other services, when given (to read).
    pub(crate) fn others_ref(&self) -> Option<&Others<'a>> {
        self.others.as_ref()
    }

    /// The time of the call.
    pub(crate) fn now(&self) -> Instant {
        self.now
    }

    /// An action could not do what was asked: `why`, taken by the Core as a refusal.
    pub(crate) fn refuse(&mut self, why: String) {
        self.refused = Some(why);
    }

    /// The refusal of an action, taken.
    pub(crate) fn take_refused(&mut self) -> Option<String> {
        self.refused.take()
    }

    /// A bound an action reached (counted as such).
    pub(crate) fn reach_bound(&mut self, why: String) {
        self.bound = Some(why);
    }

    /// Management's data (the component's state is noted there).
    pub(crate) fn management(&mut self) -> &mut Management {
        self.management
    }

    /// A bound an action reached, taken.
    pub(crate) fn take_bound(&mut self) -> Option<String> {
        self.bound.take()
    }

    pub(crate) fn send(&mut self, to: As4Id, message: impl Into<Message>) {
        self.out.push(Outgoing::new(to, message));
    }

    fn confirm(&mut self, to: As4Id, response_code: ControlConfirmation) {
        self.send(to, ConfirmControl { response_code });
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

    // Events.

    /// Guard `isSupported`: the event's query is answered.
    pub fn is_supported(&self) -> bool {
        matches!(self.event_query, Some(Ok(_)))
    }

    /// Create Event from `from` (the query answered): create or update, confirm or
    /// refuse past the bounds.
    pub fn create_event(
        &mut self,
        from: As4Id,
        request_id: u8,
        kind: EventType,
        rate: f64,
        query: &[u8],
    ) {
        let o = match self.setup(request_id, kind, rate, query) {
            Ok(setup) => self.events.create(self.now, from, setup),
            Err(r) => events::reject(from, request_id, r),
        };
        self.out.push(o);
    }

    /// Update Event from `from` of its event `event_id`.
    pub fn update_event(
        &mut self,
        from: As4Id,
        (request_id, event_id): (u8, u8),
        kind: EventType,
        rate: f64,
        query: &[u8],
    ) {
        let o = match self.setup(request_id, kind, rate, query) {
            Ok(setup) => self.events.update(self.now, from, event_id, setup),
            Err(r) => events::reject(from, request_id, r),
        };
        self.out.push(o);
    }

    /// Reject Event Request: the query is not supported (or does not decode).
    pub fn refuse_event(&mut self, from: As4Id, request_id: u8) {
        let r = self.not_supported();
        self.out.push(events::reject(from, request_id, r));
    }

    /// The component's current authority (its controlling client's; the default one
    /// while nobody controls it).
    pub fn current_authority(&self) -> u8 {
        self.access.authority()
    }

    /// Guard `isCommandSupported`: the command event's command is one the component
    /// takes (the component looked ahead).
    pub fn is_command_supported(&self) -> bool {
        matches!(self.event_query, Some(Ok(_)))
    }

    /// Create Command Event from `from`: confirm it and queue its command for the
    /// component to run ([`Events::create_command`]).
    pub fn create_command_event(
        &mut self,
        from: As4Id,
        request_id: u8,
        command: &[u8],
        max_duration: u32,
    ) {
        let o = match self.event_query.take() {
            Some(Ok(c)) => self
                .events
                .create_command(from, request_id, c, max_duration),
            Some(Err(r)) => events::reject(from, request_id, r),
            None => match events::command_of(command) {
                Ok(c) => self
                    .events
                    .create_command(from, request_id, c, max_duration),
                Err(r) => events::reject(from, request_id, r),
            },
        };
        self.out.push(o);
    }

    /// Reject Event Request for a Create Command Event whose command the component does
    /// not take, with why.
    pub fn refuse_command_event(&mut self, from: As4Id, request_id: u8) {
        let r = match self.event_query.take() {
            Some(Err(r)) => r,
            _ => (
                EventRejection::MessageNotSupported,
                "the command is not supported".into(),
            ),
        };
        self.out.push(events::reject(from, request_id, r));
    }

    /// Cancel Event from `from`: confirm, or refuse an event it does not hold.
    pub fn cancel_event(&mut self, from: As4Id, request_id: u8, event_id: u8) {
        let o = self.events.cancel(from, request_id, event_id);
        self.out.push(o);
    }

    /// Report Events to `to`.
    pub fn send_report_events(&mut self, to: As4Id, filter: &EventsFilter) {
        let r = self.events.report(filter);
        self.send(to, r);
    }

    /// Report Event Timeout to `to`.
    pub fn send_report_event_timeout(&mut self, to: As4Id) {
        let r = self.events.report_timeout();
        self.send(to, r);
    }

    // Access Control.

    /// Guard `isAuthorityValid`: within [default, current].
    pub fn is_authority_valid(&self, authority: u8) -> bool {
        self.access.is_valid(authority)
    }

    /// Guard `isControllingClient`.
    pub fn is_controlling_client(&self, from: As4Id) -> bool {
        self.access.controller() == Some(from)
    }

    /// Guard `isCurrentAuthorityLess`: the request's authority exceeds the current one.
    pub fn is_current_authority_less(&self, authority: u8) -> bool {
        self.access.authority() < authority
    }

    /// Guard `isDefaultAuthorityGreater`: the request's authority is below the default.
    pub fn is_default_authority_greater(&self, authority: u8) -> bool {
        self.access.default_authority() > authority
    }

    /// Action `init`: nobody controls, the default authority.
    pub fn init(&mut self) {
        self.access.reset();
    }

    /// Action `storeAddress`: `from` controls.
    pub fn store_address(&mut self, from: As4Id) {
        self.access.store(from);
    }

    /// Action `setAuthority`.
    pub fn set_authority(&mut self, authority: u8) {
        self.access.set_authority(authority);
    }

    /// Action `resetTimer`: control lapses a timeout from now.
    pub fn reset_timer(&mut self) {
        self.access.rearm(self.now);
    }

    /// Confirm Control with `code` to `to`.
    pub fn confirm_control(&mut self, to: As4Id, code: ControlConfirmation) {
        self.confirm(to, code);
    }

    /// Reject Control with `code` to `to`.
    pub fn reject_control(&mut self, to: As4Id, code: ControlRejection) {
        self.reject(to, code);
    }

    /// Action `releaseController`: Reject Control (Control Released) to the controller.
    pub fn release_controller(&mut self) {
        if let Some(c) = self.access.controller() {
            self.reject(c, ControlRejection::ControlReleased);
        }
    }

    /// Report Authority to `to`.
    pub fn send_report_authority(&mut self, to: As4Id) {
        let r = self.access.report_authority();
        self.send(to, r);
    }

    /// Report Control to `to`.
    pub fn send_report_control(&mut self, to: As4Id) {
        let r = self.access.report_control();
        self.send(to, r);
    }

    /// Report Timeout to `to`.
    pub fn send_report_timeout(&mut self, to: As4Id) {
        let r = self.access.report_timeout();
        self.send(to, r);
    }

    // Management.

    /// Guard `isIdStored`: `from` declared emergency `code`.
    pub fn is_id_stored(&self, from: As4Id, code: EmergencyCode) -> bool {
        self.management.is_stored(from, code)
    }

    /// Guard `isLastEmergency`: `from`'s `code` is the only emergency in effect.
    pub fn is_last_emergency(&self, from: As4Id, code: EmergencyCode) -> bool {
        self.management.is_last(from, code)
    }

    /// Action `deleteId`.
    pub fn delete_id(&mut self, from: As4Id, code: EmergencyCode) {
        self.management.delete(from, code);
    }

    /// Action `storeId` (a bound reached is counted by the component).
    pub fn store_id(&mut self, from: As4Id, code: EmergencyCode) {
        if !self.management.store(from, code) {
            self.bound = Some(format!("more than {MAX_EMERGENCIES} emergencies"));
        }
    }

    /// Action `failAfterEmergency`.
    pub fn fail_after_emergency(&mut self) {
        self.management.fail_after_emergency();
    }

    /// Report Status to `to`.
    pub fn send_report_status(&mut self, to: As4Id) {
        let r = self.management.report();
        self.send(to, r);
    }
}

/// Implements the guards and actions of a generated Core (the `services` module of a
/// definition of Transport, Events, Access Control and Management with the guards and
/// actions of `defs/core_services.yaml`) on [`Host`], and [`CoreMachine`] for its
/// Management `Machines`. `$svc` is the path of the generated `services` module, whose
/// parent includes (or re-exports) jaus-as4's messages.
#[macro_export]
macro_rules! core_machine {
    ($($svc:ident)::+) => {
        const _: () = {
            use $crate::core::machine::{CoreEvent, CoreMachine, Host};
            use $crate::messages::*;
            use $($svc)::+ as svc;
            use ::jaus::net::as5669a::As4Id;
            type Receive = svc::transport::event::Receive;

            fn sender(t: &Receive) -> As4Id {
                As4Id::new(t.source.subsystem_id, t.source.node_id, t.source.component_id)
            }

            impl svc::transport::Transport for Host<'_> {}

            impl svc::events::Events for Host<'_> {
                fn is_supported(&self, _: &[svc::Arg<'_>]) -> bool {
                    Host::is_supported(self)
                }
                fn cancel_event(&mut self, m: &CancelEvent, t: &Receive) {
                    Host::cancel_event(self, sender(t), m.request_id, m.event_id)
                }
                fn create_event(&mut self, m: &CreateEvent, t: &Receive) {
                    Host::create_event(self, sender(t), m.request_id, m.event_type, m.requested_periodic_rate, &m.query_message)
                }
                fn update_event(&mut self, m: &UpdateEvent, t: &Receive) {
                    Host::update_event(self, sender(t), (m.request_id, m.event_id), m.event_type, m.requested_periodic_rate, &m.query_message)
                }
                fn refuse_create_event(&mut self, m: &CreateEvent, t: &Receive) {
                    Host::refuse_event(self, sender(t), m.request_id)
                }
                fn refuse_update_event(&mut self, m: &UpdateEvent, t: &Receive) {
                    Host::refuse_event(self, sender(t), m.request_id)
                }
                fn refuse_command_event(&mut self, m: &CreateCommandEvent, t: &Receive) {
                    Host::refuse_command_event(self, sender(t), m.request_id)
                }
                fn is_command_supported(&self, _: &CreateCommandEvent) -> bool {
                    Host::is_command_supported(self)
                }
                fn create_command_event(&mut self, m: &CreateCommandEvent, t: &Receive) {
                    Host::create_command_event(self, sender(t), m.request_id, &m.command_message, m.maximum_allowed_duration)
                }
                fn send_report_events(&mut self, m: &QueryEvents, t: &Receive) {
                    Host::send_report_events(self, sender(t), &m.filter)
                }
                fn send_report_event_timeout(&mut self, t: &Receive) {
                    Host::send_report_event_timeout(self, sender(t))
                }
            }

            impl svc::access_control::AccessControl for Host<'_> {
                fn is_authority_valid(&self, m: &SetAuthority) -> bool {
                    Host::is_authority_valid(self, m.authority_code)
                }
                fn is_controlling_client(&self, t: &Receive) -> bool {
                    Host::is_controlling_client(self, sender(t))
                }
                fn is_current_authority_less(&self, m: &RequestControl) -> bool {
                    Host::is_current_authority_less(self, m.authority_code)
                }
                fn is_default_authority_greater(&self, m: &RequestControl) -> bool {
                    Host::is_default_authority_greater(self, m.authority_code)
                }
                fn init(&mut self) {
                    Host::init(self)
                }
                fn store_address(&mut self, t: &Receive) {
                    Host::store_address(self, sender(t))
                }
                fn set_authority(&mut self, args: &[svc::Arg<'_>]) {
                    for a in args {
                        match a {
                            svc::Arg::RequestControl(m) => Host::set_authority(self, m.authority_code),
                            svc::Arg::SetAuthority(m) => Host::set_authority(self, m.authority_code),
                            _ => {}
                        }
                    }
                }
                fn reset_timer(&mut self) {
                    Host::reset_timer(self)
                }
                fn grant_control(&mut self, t: &Receive) {
                    Host::confirm_control(self, sender(t), ControlConfirmation::ControlAccepted)
                }
                fn refuse_authority(&mut self, t: &Receive) {
                    Host::confirm_control(self, sender(t), ControlConfirmation::InsufficientAuthority)
                }
                fn refuse_not_available(&mut self, t: &Receive) {
                    Host::confirm_control(self, sender(t), ControlConfirmation::NotAvailable)
                }
                fn confirm_release(&mut self, t: &Receive) {
                    Host::reject_control(self, sender(t), ControlRejection::ControlReleased)
                }
                fn reject_not_available(&mut self, t: &Receive) {
                    Host::reject_control(self, sender(t), ControlRejection::NotAvailable)
                }
                fn release_controller(&mut self) {
                    Host::release_controller(self)
                }
                fn send_report_authority(&mut self, t: &Receive) {
                    Host::send_report_authority(self, sender(t))
                }
                fn send_report_control(&mut self, t: &Receive) {
                    Host::send_report_control(self, sender(t))
                }
                fn send_report_timeout(&mut self, t: &Receive) {
                    Host::send_report_timeout(self, sender(t))
                }
            }

            impl svc::management::Management for Host<'_> {
                fn is_id_stored(&self, m: &ClearEmergency, t: &Receive) -> bool {
                    Host::is_id_stored(self, sender(t), m.emergency_code)
                }
                fn is_last_emergency(&self, m: &ClearEmergency, t: &Receive) -> bool {
                    Host::is_last_emergency(self, sender(t), m.emergency_code)
                }
                fn delete_id(&mut self, m: &ClearEmergency, t: &Receive) {
                    Host::delete_id(self, sender(t), m.emergency_code)
                }
                fn store_id(&mut self, m: &SetEmergency, t: &Receive) {
                    Host::store_id(self, sender(t), m.emergency_code)
                }
                fn fail_after_emergency(&mut self) {
                    Host::fail_after_emergency(self)
                }
                fn initialize(&mut self) {
                    // Nothing to wait for: the Core raises Initialized as soon as the
                    // machine is in Init.
                }
                fn send_report_status(&mut self, t: &Receive) {
                    Host::send_report_status(self, sender(t))
                }
            }

            impl CoreMachine for svc::management::Machines {
                fn receive(&mut self, host: &mut Host<'_>, msg: &Message, from: As4Id) -> Option<bool> {
                    let transport = Receive {
                        source: ComponentAddress {
                            subsystem_id: from.subsystem,
                            node_id: from.node,
                            component_id: from.component,
                        },
                    };
                    svc::management::Machines::receive(self, host, msg, &transport)
                }
                fn raise(&mut self, host: &mut Host<'_>, event: CoreEvent) -> bool {
                    let trigger = match event {
                        CoreEvent::Timedout => svc::management::Trigger::Timedout {},
                        CoreEvent::Initialized => svc::management::Trigger::Initialized {},
                        CoreEvent::Failure => svc::management::Trigger::Failure {},
                    };
                    self.handle(host, &trigger)
                }
                fn path(&self) -> &'static str {
                    self.0.iter().next().map_or("", |m| m.path())
                }
                fn boxed_clone(&self) -> Box<dyn CoreMachine> {
                    Box::new(self.clone())
                }
            }
        };
    };
}

/// The stock Core's machine: jaus-as4's own `defs/core_services.yaml`.
pub fn stock() -> Box<dyn CoreMachine> {
    Box::new(crate::messages::services::management::Machines::new())
}

crate::core_machine!(crate::messages::services);
