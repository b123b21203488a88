//! The Core services of one AS-4 component (Core Service Set v1.1, SAE AS5710A),
//! sans-IO: Transport, Events, Access Control, Management, Time, Liveness, Discovery and
//! List Manager. [`Core`] takes each Core message with its sender and the time, and
//! decides the answers (and messages to others, such as the Reject Control of a
//! preempted controller) as values ([`Outgoing`]).
//!
//! Transport, Events, Access Control and Management are decided by their generated state
//! machine (`defs/core_services.yaml`, run through [`machine`]): who gets control, what
//! Resume, Shutdown, Reset or an emergency do in each state, what an event request gets.
//! Time, Liveness, Discovery and the List Manager answer from their modules ([`time`],
//! [`liveness`], [`discovery`], [`lists`]); [`access`], [`management`] and [`events`]
//! keep the data the machine's guards read and its actions change. What needs control:
//!
//! | message | from | in state |
//! |---|---|---|
//! | Request Control, Release Control, Set/Clear Emergency, Create/Update/Cancel Event, Register Services, every query | anyone | any (the machine's rules apply) |
//! | Set Authority, Shutdown, Reset, Standby, Resume | the controller | as the machine says |
//! | Set Time, Set Element, Delete Element | the controller | any |
//! | a message of another service that needs control by the definitions ([`Service::needs_control`](crate::service::Service::needs_control): `is_command`, whatever the code) | the controller | Ready, unless the service says otherwise ([`Service::needs_ready`](crate::service::Service::needs_ready)) |
//!
//! Create and Update Event need the component's other services (their query may be a
//! service's): [`As4Component`](crate::component::As4Component) answers the query first and
//! hands [`Core::handle`] the outcome.

pub mod access;
pub mod discovery;
pub mod events;
pub mod lists;
pub mod liveness;
pub mod machine;
pub mod management;
mod others;
pub mod time;

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

use crate::messages::{self as m, ComponentState, Message};
use crate::outgoing::Outgoing;
use crate::outgoing::ServiceId;

use access::Access;
use discovery::{service_info, Discovery, Identification};
use events::{Events, Rejection};
use lists::Lists;
use machine::{CoreEvent, CoreMachine, Host};
use management::Management;
use time::Time;

/// The id of generated service `$module` (its URI and version in the definitions).
macro_rules! generated_id {
    ($module:ident) => {
        ServiceId::new(
            crate::messages::services::$module::URI,
            crate::messages::services::$module::VERSION.0,
            crate::messages::services::$module::VERSION.1,
        )
    };
}
pub(crate) use generated_id;

/// Transport (`defs/core_services.yaml`).
pub const TRANSPORT: ServiceId = generated_id!(transport);
/// Events.
pub const EVENTS: ServiceId = generated_id!(events);
/// Access Control.
pub const ACCESS_CONTROL: ServiceId = generated_id!(access_control);
/// Management.
pub const MANAGEMENT: ServiceId = generated_id!(management);
/// Time.
pub const TIME: ServiceId = generated_id!(time);
/// Liveness.
pub const LIVENESS: ServiceId = generated_id!(liveness);
/// Discovery.
pub const DISCOVERY: ServiceId = generated_id!(discovery);
/// List Manager.
pub const LIST_MANAGER: ServiceId = generated_id!(list_manager);

/// Settings of the Core services of a component.
#[derive(Debug, Clone, PartialEq)]
pub struct CoreConfig {
    /// Names for Report Identification.
    pub identification: Identification,
    /// Default authority of Access Control: a client needs at least this much to take
    /// control. Default 0.
    pub authority: u8,
    /// Control timeout, seconds (0: control never lapses). The controller must send
    /// Request Control again within it. Default 0: clients that never renew (the IOP
    /// judge's) keep control.
    pub control_timeout: u8,
    /// Event timeout, minutes (0: events never lapse). Default 0.
    pub event_timeout: u8,
    /// Most events at once (at most 255). Default 64.
    pub max_events: usize,
    /// Most list elements. Default 1024.
    pub max_elements: usize,
    /// Most other components in Discovery's registry. Default 64.
    pub max_registrations: usize,
    /// Whether the component offers the List Manager. Default true.
    pub list_manager: bool,
    /// How often every-change events run their query. Default 50 ms (20 Hz).
    pub change_period: Duration,
}

impl CoreConfig {
    /// The defaults, with `name` for the subsystem, node and component.
    pub fn named(name: &str) -> Self {
        Self {
            identification: Identification::named(name),
            authority: 0,
            control_timeout: 0,
            event_timeout: 0,
            max_events: 64,
            max_elements: lists::DEFAULT_MAX_ELEMENTS,
            max_registrations: 64,
            list_manager: true,
            change_period: events::DEFAULT_CHANGE_PERIOD,
        }
    }
}

impl Default for CoreConfig {
    fn default() -> Self {
        Self::named("jaus-as4")
    }
}

/// Why a message was not acted upon (the component logs and counts it).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Refusal {
    /// A message needing control from a client that does not hold it.
    NotController(String),
    /// A command the component's state does not allow.
    NotReady(String),
    /// A bound was reached (events, registrations, emergencies).
    Bounds(String),
    /// Otherwise ignored (nothing to answer, invalid content).
    Ignored(String),
}

/// The Core's data a service generated on the Core's services reaches during one call
/// ([`Cx::with_core`](crate::service::Cx::with_core)).
#[derive(Debug)]
pub(crate) struct CoreParts<'a> {
    pub(crate) access: &'a mut Access,
    pub(crate) management: &'a mut Management,
    pub(crate) events: &'a mut Events,
    /// The Core machine's state path.
    pub(crate) path: &'static str,
}

/// The Core services of one component.
#[derive(Debug, Clone)]
pub struct Core {
    me: As4Id,
    config: CoreConfig,
    access: Access,
    management: Management,
    events: Events,
    time: Time,
    discovery: Discovery,
    lists: Lists,
    machine: Box<dyn CoreMachine>,
    /// The machines of Time, Liveness, Discovery and the List Manager.
    others: others::OtherMachines,
}

impl Core {
    /// The Core services of component `me`, run by the stock machine
    /// (`defs/core_services.yaml`).
    pub fn new(me: As4Id, config: CoreConfig) -> Self {
        Self::with_machine(me, config, machine::stock())
    }

    /// The Core services of component `me`, run by `machine`: a Core generated from a
    /// revised definition ([`core_machine!`](crate::core_machine)).
    pub fn with_machine(me: As4Id, config: CoreConfig, machine: Box<dyn CoreMachine>) -> Self {
        let own = core_services(config.list_manager)
            .iter()
            .map(service_info)
            .collect();
        Self {
            me,
            access: Access::new(config.authority, config.control_timeout),
            management: Management::new(),
            events: Events::new(
                config.max_events,
                config.event_timeout,
                config.change_period,
            ),
            time: Time::default(),
            discovery: Discovery::new(
                me,
                config.identification.clone(),
                own,
                config.max_registrations,
            ),
            lists: Lists::new(config.max_elements),
            machine,
            others: others::OtherMachines::default(),
            config,
        }
    }

    /// The state of the Core's generated machine (Transport, Events, Access Control and
    /// Management merged), by path: `Receiving.Ready.Controlled.Available.Ready`.
    pub fn machine_state(&self) -> &'static str {
        self.machine.path()
    }

    /// Runs `f` with the machines and a host over the services' data; then settles what
    /// the owner does at once (initialisation done, a failure pending after an emergency)
    /// and notes the component's state. What the actions sent, and a bound reached.
    fn run<R>(
        &mut self,
        now: Instant,
        event_query: Option<Result<Message, Rejection>>,
        f: impl FnOnce(&mut dyn CoreMachine, &mut Host<'_>) -> R,
    ) -> (R, Vec<Outgoing>, Option<String>) {
        let mut out = Vec::new();
        let mut host = Host::new(
            now,
            &mut self.access,
            &mut self.management,
            &mut self.events,
            &mut out,
            event_query,
        );
        let r = f(self.machine.as_mut(), &mut host);
        // Bounded: each raise moves the machine out of Init or out of the pending failure.
        for _ in 0..4 {
            host.management().moved(self.machine.path());
            if host.management().state() == ComponentState::Initialize {
                self.machine.raise(&mut host, CoreEvent::Initialized);
            } else if host.management().take_pending_failure() {
                self.machine.raise(&mut host, CoreEvent::Failure);
            } else {
                break;
            }
        }
        let bound = host.take_bound();
        (r, out, bound)
    }

    /// The settings.
    pub fn config(&self) -> &CoreConfig {
        &self.config
    }

    /// The component's state.
    pub fn state(&self) -> ComponentState {
        self.management.state()
    }

    /// The controlling client.
    pub fn controller(&self) -> Option<As4Id> {
        self.access.controller()
    }

    /// Access Control.
    pub fn access(&self) -> &Access {
        &self.access
    }

    /// Management.
    pub fn management(&self) -> &Management {
        &self.management
    }

    /// Events.
    pub fn events(&self) -> &Events {
        &self.events
    }

    /// Events, mutably (Create and Update Event, firing).
    pub fn events_mut(&mut self) -> &mut Events {
        &mut self.events
    }

    /// Time.
    pub fn time(&self) -> &Time {
        &self.time
    }

    /// Time, mutably ([`Time::set_utc`]).
    pub fn time_mut(&mut self) -> &mut Time {
        &mut self.time
    }

    /// Discovery.
    pub fn discovery(&self) -> &Discovery {
        &self.discovery
    }

    /// Discovery, mutably (registrations, own services).
    pub fn discovery_mut(&mut self) -> &mut Discovery {
        &mut self.discovery
    }

    /// The list manager.
    pub fn lists(&self) -> &Lists {
        &self.lists
    }

    /// The list manager and what a service generated on the Core's services uses of
    /// them during one call: their data, run by [`Host`], and the machine's state.
    pub(crate) fn parts(&mut self) -> (&mut Lists, CoreParts<'_>) {
        (
            &mut self.lists,
            CoreParts {
                access: &mut self.access,
                management: &mut self.management,
                events: &mut self.events,
                path: self.machine.path(),
            },
        )
    }

    /// The list manager, mutably.
    pub fn lists_mut(&mut self) -> &mut Lists {
        &mut self.lists
    }

    /// Whether message `code` is one the Core services receive.
    pub fn handles(&self, code: CommandCode) -> bool {
        m::services::management::RECEIVES.contains(&code)
            || others::OtherMachines::takes(code, self.config.list_manager)
    }

    /// The answer of a Core query, as if `from` asked (`None`: not a Core query, or
    /// one the Core does not answer, such as Query Element of an unknown UID).
    pub fn answer_query(&mut self, now: Instant, msg: &Message) -> Option<Message> {
        Some(match msg {
            Message::QueryAuthority(_) => self.access.report_authority().into(),
            Message::QueryTimeout(_) => self.access.report_timeout().into(),
            Message::QueryControl(_) => self.access.report_control().into(),
            Message::QueryStatus(_) => self.management.report().into(),
            Message::QueryTime(q) => self.time.report(now, q).into(),
            Message::QueryEvents(q) => self.events.report(&q.filter).into(),
            Message::QueryEventTimeout(_) => self.events.report_timeout().into(),
            Message::QueryHeartbeatPulse(_) => liveness::heartbeat(),
            Message::QueryIdentification(q) => self.discovery.identify(q.query_type)?.into(),
            Message::QueryConfiguration(q) => self.discovery.configuration(q.query_type)?.into(),
            Message::QuerySubsystemList(_) => self.discovery.subsystems().into(),
            Message::QueryServices(q) => self.discovery.services(q).into(),
            Message::QueryServiceList(q) => self.discovery.service_list(q).into(),
            Message::QueryElement(_)
            | Message::QueryElementList(_)
            | Message::QueryElementCount(_)
                if self.config.list_manager =>
            {
                self.lists.handle(msg)?
            }
            _ => return None,
        })
    }

    /// A Core message from `from`: the messages to send, or why nothing was done.
    /// `event_query` is, for Create and Update Event, the event's query decoded and
    /// answered by the component, or why it is not supported (the query may be any
    /// service's, so the component looks ahead; `None`: decoded here, as unanswered);
    /// for Create Command Event, its command decoded and received by the Core or a
    /// service, or why not. A command event confirmed leaves its command for the
    /// component to run ([`take_command`](Self::take_command)).
    pub fn handle(
        &mut self,
        now: Instant,
        from: As4Id,
        msg: &Message,
        event_query: Option<Result<Message, Rejection>>,
    ) -> Result<Vec<Outgoing>, Refusal> {
        let (taken, out, bound) = self.run(now, event_query, |machine, host| {
            machine.receive(host, msg, from)
        });
        if let Some(b) = bound {
            return Err(Refusal::Bounds(b));
        }
        match taken {
            Some(true) => return Ok(out),
            Some(false) => return Err(self.refusal(from, msg)),
            None => {}
        }
        // Time, Liveness, Discovery and the List Manager: their own machines, following
        // the main one's state.
        let core_state = self.machine.path();
        let list_manager = self.config.list_manager;
        let mut out = Vec::new();
        let mut host = Host::new(
            now,
            &mut self.access,
            &mut self.management,
            &mut self.events,
            &mut out,
            None,
        )
        .with_others(machine::Others {
            time: &mut self.time,
            discovery: &mut self.discovery,
            lists: list_manager.then_some(&mut self.lists),
        });
        let taken = self
            .others
            .receive(&mut host, msg, from, core_state, list_manager);
        let (bound, refused) = (host.take_bound(), host.take_refused());
        if let Some(b) = bound {
            return Err(Refusal::Bounds(b));
        }
        if let Some(why) = refused {
            return Err(Refusal::Ignored(why));
        }
        match taken {
            Some(true) if out.is_empty() && is_query(msg) => {
                Err(Refusal::Ignored("nothing to answer".into()))
            }
            Some(true) => Ok(out),
            Some(false) => Err(self.refusal(from, msg)),
            None => Err(Refusal::Ignored("nothing to answer".into())),
        }
    }

    /// The command of the command event just confirmed, for the component to run as if
    /// its client had sent it and to report with
    /// [`PendingCommand::completed`](events::PendingCommand::completed).
    pub fn take_command(&mut self) -> Option<events::PendingCommand> {
        self.events.take_command()
    }

    /// Why the machine took no transition for `msg` from `from`, as the component counts
    /// it.
    fn refusal(&self, from: As4Id, msg: &Message) -> Refusal {
        let state = self.management.state();
        let controller = self.access.controller();
        if !self.management.available() {
            Refusal::NotReady(format!("{} in state {state:?}", msg.name()))
        } else if controller != Some(from) {
            Refusal::NotController(format!(
                "{} from {from}, not the controller ({})",
                msg.name(),
                controller.map_or_else(|| "none".to_string(), |c| c.to_string())
            ))
        } else {
            Refusal::Ignored(format!(
                "{} refused in machine state {}",
                msg.name(),
                self.machine_state()
            ))
        }
    }

    /// The owner declares a failure: the machine's `Failure` (control ends; during an
    /// emergency, Failure once it is cleared).
    pub fn fail(&mut self, now: Instant) -> Vec<Outgoing> {
        let (_, out, _) = self.run(now, None, |machine, host| {
            machine.raise(host, CoreEvent::Failure)
        });
        out
    }

    /// Time passed: control lapses (the machine's `Timedout` once the controller's
    /// deadline is past), events lapse (the events' reports are the component's job:
    /// [`Events::due`]).
    pub fn handle_timeout(&mut self, now: Instant) -> Vec<Outgoing> {
        let mut out = Vec::new();
        if self.access.deadline().is_some_and(|d| d <= now) {
            let (_, o, _) = self.run(now, None, |machine, host| {
                machine.raise(host, CoreEvent::Timedout)
            });
            out = o;
        }
        out.extend(self.events.expire(now));
        out
    }

    /// When [`handle_timeout`](Self::handle_timeout) or an event is next due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        [self.access.deadline(), self.events.next_timeout()]
            .into_iter()
            .flatten()
            .min()
    }

    /// This component's id.
    pub fn id(&self) -> As4Id {
        self.me
    }
}

/// The Core services a component offers (the List Manager when `list_manager`).
pub fn core_services(list_manager: bool) -> Vec<ServiceId> {
    let mut v = vec![
        TRANSPORT,
        EVENTS,
        ACCESS_CONTROL,
        MANAGEMENT,
        TIME,
        LIVENESS,
        DISCOVERY,
    ];
    if list_manager {
        v.push(LIST_MANAGER);
    }
    v
}

/// Whether `msg` is a query (it names its report in the definitions).
fn is_query(msg: &Message) -> bool {
    let code = msg.code();
    m::MESSAGES
        .iter()
        .any(|i| i.code == code && i.report.is_some())
}
