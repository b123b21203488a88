//! An AS-4 component, sans-IO: the Core services ([`Core`]) and the component's other
//! services ([`Service`]), behind one id.
//!
//! [`As4Component::handle`] takes a decoded message with its sender and the time, and
//! returns what to send ([`Outgoing`]: answers to the sender, and messages to others
//! such as the Reject Control of a preempted controller and Events). Dispatch:
//!
//! 1. Core messages go to the [`Core`], whose generated state machine decides
//!    Transport, Events, Access Control and Management (`defs/core_services.yaml`).
//!    For Create and Update Event the component first runs the event's query through
//!    this dispatch as if the subscriber had sent it: the event is confirmed only when
//!    something answers it. A Create Command Event is confirmed only when its command
//!    is a command that the Core or a service receives; the command then runs through
//!    this dispatch as if the client had sent it (control and state checked as for any
//!    command), and a Command Event tells the client whether it was taken
//!    (`Successful`) or not (`Unsuccessful`).
//! 2. Everything else goes to the services, in the order they were added, to each whose
//!    [`Service::receives`] says yes until one does not answer [`Handled::NotMine`]. A
//!    message that needs control ([`Service::needs_control`]: `is_command` of the
//!    definitions, whatever the code) reaches a service only from the controlling client,
//!    and only while the component is Ready unless [`Service::needs_ready`] says
//!    otherwise.
//!
//! What is refused is counted ([`ComponentStats`]) and logged (`tracing`, debug level)
//! with the message, its sender and the reason. A message ID outside this crate's
//! definitions ([`Message::Raw`], a vendor's) reaches the services whose
//! [`Service::receives`] declares it, and is counted and ignored when none does. Services are told when the state or the
//! controller changes ([`Service::state_changed`], [`Service::controller_changed`]).
//!
//! Time: call [`handle_timeout`](As4Component::handle_timeout) when
//! [`poll_timeout`](As4Component::poll_timeout) is due (control and event lapses,
//! periodic and every-change events, the services' timers), and
//! [`tick`](As4Component::tick) after changing the environment `E` (every service's
//! [`Service::tick`] runs, then the events due).

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use crate::core::discovery::{service_info, Identification};
use crate::core::events;
use crate::core::{core_services, Core, CoreConfig, Refusal};
use crate::messages::{ComponentState, EventRejection, Message, RejectEventRequest, ServiceInfo};
pub use crate::service::Outgoing;
use crate::service::{Cx, Handled, Request, Service, ServiceId};

/// Counters of a component.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ComponentStats {
    /// Messages handed to [`As4Component::handle`].
    pub received: u64,
    /// Messages returned to send (answers, events, messages to others).
    pub sent: u64,
    /// Refused: needs control, and the sender does not hold it.
    pub not_controller: u64,
    /// Refused: the component's state does not allow it (not Ready, an emergency).
    pub not_ready: u64,
    /// Ignored: a message ID this crate does not define.
    pub unknown: u64,
    /// Ignored: a known message that neither the Core nor a service receives.
    pub unhandled: u64,
    /// Refused: a bound was reached (events, registrations, emergencies).
    pub bounds: u64,
    /// Refused otherwise (invalid content, a service's refusal, nothing to answer).
    pub refused: u64,
    /// Events sent.
    pub events_sent: u64,
    /// Event queries nobody answered when due (nothing sent for them).
    pub events_unanswered: u64,
}

// The message catalogue is as large as its largest message (UGV's Report Platform
// Specifications, 456 bytes: 27 optional scaled fields); boxing it would allocate for
// every answer, where moving it costs a copy.
#[allow(clippy::large_enum_variant)]
/// What the services did with a message.
enum Dispatch {
    /// No service takes it.
    Unhandled,
    /// Taken, perhaps with an answer.
    Answered(Option<Message>),
    /// Refused.
    Refused(Refusal),
}

/// One AS-4 component: id, Core services, other services.
#[derive(Debug)]
pub struct As4Component<E> {
    id: As4Id,
    core: Core,
    services: Vec<Box<dyn Service<E>>>,
    stats: ComponentStats,
    /// What services sent besides their replies, for the next output.
    spill: Vec<Outgoing>,
}

impl<E: 'static> As4Component<E> {
    /// Component `id` with the Core services set up by `config` and no other service.
    ///
    /// ```
    /// use jaus::net::as5669a::As4Id;
    /// use jaus_as4::component::As4Component;
    /// use jaus_as4::core::CoreConfig;
    ///
    /// let c: As4Component<()> = As4Component::new(As4Id::new(7, 1, 1), CoreConfig::named("rover"));
    /// assert_eq!(c.state(), jaus_as4::ComponentState::Standby);
    /// ```
    pub fn new(id: As4Id, config: CoreConfig) -> Self {
        Self {
            id,
            core: Core::new(id, config),
            services: Vec::new(),
            stats: ComponentStats::default(),
            spill: Vec::new(),
        }
    }

    /// Component `id` whose Core runs `machine`: the Core generated from a revised
    /// definition of its services ([`core_machine!`](crate::core_machine)).
    pub fn with_machine(
        id: As4Id,
        config: CoreConfig,
        machine: Box<dyn crate::core::machine::CoreMachine>,
    ) -> Self {
        Self {
            id,
            core: Core::with_machine(id, config, machine),
            services: Vec::new(),
            stats: ComponentStats::default(),
            spill: Vec::new(),
        }
    }

    /// With `service` added after the ones already there.
    pub fn with_service(mut self, service: impl Service<E>) -> Self {
        self.add_service(Box::new(service));
        self
    }

    /// Adds `service` after the ones already there (Discovery reports it from now on).
    pub fn add_service(&mut self, service: Box<dyn Service<E>>) {
        self.services.push(service);
        let own = self.service_infos();
        self.core.discovery_mut().set_own(own);
    }

    /// Its id.
    pub fn id(&self) -> As4Id {
        self.id
    }

    /// Its names (Discovery).
    pub fn identification(&self) -> &Identification {
        self.core.discovery().identification()
    }

    /// The Core services.
    pub fn core(&self) -> &Core {
        &self.core
    }

    /// The Core services, mutably.
    pub fn core_mut(&mut self) -> &mut Core {
        &mut self.core
    }

    /// The component's state.
    pub fn state(&self) -> ComponentState {
        self.core.state()
    }

    /// The controlling client.
    pub fn controller(&self) -> Option<As4Id> {
        self.core.controller()
    }

    /// Counters.
    pub fn stats(&self) -> ComponentStats {
        self.stats
    }

    /// Every service it offers: the Core's, then the others in order.
    pub fn service_ids(&self) -> Vec<ServiceId> {
        let mut v = core_services(self.core.config().list_manager);
        v.extend(self.services.iter().map(|s| s.id()));
        v
    }

    /// [`service_ids`](Self::service_ids) as Discovery's records.
    pub fn service_infos(&self) -> Vec<ServiceInfo> {
        self.service_ids().iter().map(service_info).collect()
    }

    /// The services other than the Core's.
    pub fn services(&self) -> impl Iterator<Item = &dyn Service<E>> + '_ {
        self.services.iter().map(|s| s.as_ref())
    }

    /// The wall clock: UTC (since 1970-01-01) is `utc` at `now` (Time's Report Time).
    pub fn set_utc(&mut self, now: Instant, utc: Duration) {
        self.core.time_mut().set_utc(now, utc);
    }

    /// `msg` from `from` at `now`: what to send.
    pub fn handle(
        &mut self,
        now: Instant,
        from: As4Id,
        msg: &Message,
        env: &mut E,
    ) -> Vec<Outgoing> {
        self.stats.received += 1;
        let before = (self.core.state(), self.core.controller());
        let mut out = match msg {
            _ if self.core.handles(msg.code()) => {
                let lookahead = match msg {
                    Message::CreateEvent(c) => {
                        Some(self.lookahead(now, from, &c.query_message, env))
                    }
                    Message::UpdateEvent(u) => {
                        Some(self.lookahead(now, from, &u.query_message, env))
                    }
                    Message::CreateCommandEvent(c) => Some(self.command_taker(&c.command_message)),
                    _ => None,
                };
                match self.core.handle(now, from, msg, lookahead) {
                    Ok(mut out) => {
                        self.count_event_refusals(from, msg, &out);
                        if let Some(pending) = self.core.take_command() {
                            out.extend(self.run_command(now, &pending, env));
                        }
                        out
                    }
                    Err(r) => {
                        self.refuse(from, msg, r);
                        Vec::new()
                    }
                }
            }
            _ => self.offer(now, from, msg, env),
        };
        self.notify(now, before, env);
        out.append(&mut self.spill);
        out.extend(self.finish_commands(now));
        out.extend(self.fire_events(now, env));
        self.stats.sent += out.len() as u64;
        out
    }

    /// Time passed: control and event lapses, events due, services' timers due.
    pub fn handle_timeout(&mut self, now: Instant, env: &mut E) -> Vec<Outgoing> {
        let before = (self.core.state(), self.core.controller());
        let mut out = self.core.handle_timeout(now);
        self.with_services(now, env, |s, cx| {
            if s.poll_timeout().is_some_and(|t| t <= now) {
                s.tick(cx);
            }
        });
        self.notify(now, before, env);
        out.append(&mut self.spill);
        out.extend(self.finish_commands(now));
        out.extend(self.fire_events(now, env));
        self.stats.sent += out.len() as u64;
        out
    }

    /// The environment changed: every service's [`Service::tick`], then the events due
    /// (every-change events notice the change at their next tick).
    pub fn tick(&mut self, now: Instant, env: &mut E) -> Vec<Outgoing> {
        let before = (self.core.state(), self.core.controller());
        self.with_services(now, env, |s, cx| s.tick(cx));
        self.notify(now, before, env);
        let mut out = std::mem::take(&mut self.spill);
        out.extend(self.finish_commands(now));
        out.extend(self.fire_events(now, env));
        self.stats.sent += out.len() as u64;
        out
    }

    /// When [`handle_timeout`](Self::handle_timeout) is next due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.services
            .iter()
            .filter_map(|s| s.poll_timeout())
            .chain(self.core.poll_timeout())
            .min()
    }

    /// The owner declares a failure (Management's Failure state; control ends).
    pub fn fail(&mut self, now: Instant, env: &mut E) -> Vec<Outgoing> {
        let before = (self.core.state(), self.core.controller());
        let mut out = self.core.fail(now);
        self.notify(now, before, env);
        out.append(&mut self.spill);
        self.stats.sent += out.len() as u64;
        out
    }

    fn refuse(&mut self, from: As4Id, msg: &Message, r: Refusal) {
        let (counter, reason) = match r {
            Refusal::NotController(s) => (&mut self.stats.not_controller, s),
            Refusal::NotReady(s) => (&mut self.stats.not_ready, s),
            Refusal::Bounds(s) => (&mut self.stats.bounds, s),
            Refusal::Ignored(s) => (&mut self.stats.refused, s),
        };
        *counter += 1;
        tracing::debug!(message = msg.name(), %from, component = %self.id, "refused: {reason}");
    }

    /// Runs `f` on every service with the call's context; what they send besides their
    /// replies is kept for the component's next output ([`Self::spill`]).
    fn with_services(
        &mut self,
        now: Instant,
        env: &mut E,
        mut f: impl FnMut(&mut dyn Service<E>, &mut Cx<'_, E>),
    ) {
        let (me, state, controller) = (self.id, self.core.state(), self.core.controller());
        let (lists, core) = self.core.parts();
        let mut cx = Cx {
            now,
            me,
            state,
            controller,
            lists,
            env,
            core,
            out: &mut self.spill,
        };
        for s in &mut self.services {
            f(s.as_mut(), &mut cx);
        }
    }

    fn notify(
        &mut self,
        now: Instant,
        (state, controller): (ComponentState, Option<As4Id>),
        env: &mut E,
    ) {
        let (now_state, now_controller) = (self.core.state(), self.core.controller());
        if now_state == state && now_controller == controller {
            return;
        }
        self.with_services(now, env, |s, cx| {
            if now_state != state {
                s.state_changed(cx, state, now_state);
            }
            if now_controller != controller {
                s.controller_changed(cx, now_controller);
            }
        });
    }

    /// Offers `msg` to the services that receive it, in order, until one takes it.
    fn dispatch(&mut self, now: Instant, from: As4Id, msg: &Message, env: &mut E) -> Dispatch {
        let code = msg.code();
        let from_controller = self.core.controller() == Some(from);
        let state = self.core.state();

        let mut decided: Option<Dispatch> = None;
        self.with_services(now, env, |s, cx| {
            if decided.is_some() || !s.receives(code) {
                return;
            }
            let is_command = s.needs_control(code);
            if is_command && !from_controller {
                let why = format!("{} needs control", s.id().uri);
                decided = Some(Dispatch::Refused(Refusal::NotController(why)));
                return;
            }
            if is_command && s.needs_ready(code) && state != ComponentState::Ready {
                let why = format!("{} needs Ready, state {state:?}", s.id().uri);
                decided = Some(Dispatch::Refused(Refusal::NotReady(why)));
                return;
            }
            let request = Request {
                now,
                from,
                message: msg,
                from_controller,
                state,
            };
            decided = match s.handle(cx, &request) {
                Handled::NotMine => None,
                Handled::Done => Some(Dispatch::Answered(None)),
                Handled::Reply(m) => Some(Dispatch::Answered(Some(m))),
                Handled::Refused(r) => Some(Dispatch::Refused(Refusal::Ignored(format!(
                    "{}: {r}",
                    s.id().uri
                )))),
            };
        });
        decided.unwrap_or(Dispatch::Unhandled)
    }

    fn offer(&mut self, now: Instant, from: As4Id, msg: &Message, env: &mut E) -> Vec<Outgoing> {
        match self.dispatch(now, from, msg, env) {
            Dispatch::Answered(reply) => {
                reply.map(|m| Outgoing::new(from, m)).into_iter().collect()
            }
            Dispatch::Unhandled if matches!(msg, Message::Raw(_)) => {
                self.stats.unknown += 1;
                tracing::debug!(id = %format_args!("{:#06X}", msg.code().0), %from, component = %self.id, "a message ID outside the definitions that no service declares: ignored");
                Vec::new()
            }
            Dispatch::Unhandled => {
                self.stats.unhandled += 1;
                tracing::debug!(message = msg.name(), %from, component = %self.id, "no service takes it");
                Vec::new()
            }
            Dispatch::Refused(r) => {
                self.refuse(from, msg, r);
                Vec::new()
            }
        }
    }

    /// The answer of query `q` as if `from` sent it (Core or service).
    fn query(&mut self, now: Instant, q: &Message, from: As4Id, env: &mut E) -> Option<Message> {
        if self.core.handles(q.code()) {
            return self.core.answer_query(now, q);
        }
        match self.dispatch(now, from, q, env) {
            Dispatch::Answered(m) => m,
            _ => None,
        }
    }

    /// The query of a Create or Update Event from `from`, decoded and answered as if
    /// `from` sent it (by the Core or a service), or why it is not supported.
    fn lookahead(
        &mut self,
        now: Instant,
        from: As4Id,
        query_bytes: &[u8],
        env: &mut E,
    ) -> Result<Message, events::Rejection> {
        let query = events::query_of(query_bytes)?;
        if self.query(now, &query, from, env).is_none() {
            let why = format!("nothing answers {}", query.name());
            return Err((EventRejection::MessageNotSupported, why));
        }
        Ok(query)
    }

    /// The command of a Create Command Event, decoded, if it is a command that the Core
    /// or a service receives ([`events::command_of`]; an experimental ID only where the
    /// service receiving it needs control for it), or why not.
    fn command_taker(&self, bytes: &[u8]) -> Result<Message, events::Rejection> {
        let command = events::command_of(bytes)?;
        let code = command.code();
        // An experimental (vendor's) ID is a command when a service receiving it needs
        // control for it.
        let experimental = code.class() == jaus::wire::MessageClass::Experimental;
        let taken = self.core.handles(code)
            || self
                .services
                .iter()
                .any(|s| s.receives(code) && (!experimental || s.needs_control(code)));
        if taken {
            Ok(command)
        } else {
            let why = format!(
                "nothing of the component receives {} ({:#06X}) as a command",
                command.name(),
                code.0
            );
            Err((EventRejection::MessageNotSupported, why))
        }
    }

    /// Runs a confirmed command event's command as if its client had sent it (refusals
    /// counted as for any message), then its Command Event: Successful when the Core or
    /// a service took it.
    fn run_command(
        &mut self,
        now: Instant,
        pending: &events::PendingCommand,
        env: &mut E,
    ) -> Vec<Outgoing> {
        let (from, command) = (pending.client, &pending.command);
        let (mut out, taken) = if self.core.handles(command.code()) {
            match self.core.handle(now, from, command, None) {
                Ok(out) => (out, true),
                Err(r) => {
                    self.refuse(from, command, r);
                    (Vec::new(), false)
                }
            }
        } else {
            match self.dispatch(now, from, command, env) {
                Dispatch::Answered(reply) => {
                    let out = reply.map(|m| Outgoing::new(from, m)).into_iter().collect();
                    (out, true)
                }
                Dispatch::Unhandled => {
                    self.stats.unhandled += 1;
                    tracing::debug!(message = command.name(), %from, component = %self.id, "command event: no service takes it");
                    (Vec::new(), false)
                }
                Dispatch::Refused(r) => {
                    self.refuse(from, command, r);
                    (Vec::new(), false)
                }
            }
        };
        let code = command.code();
        if taken && self.services.iter().any(|s| s.in_progress(code)) {
            tracing::debug!(message = command.name(), %from, component = %self.id, event_id = pending.event_id, "command event running");
            self.core.events_mut().keep_running(now, pending.clone());
        } else {
            tracing::debug!(message = command.name(), %from, component = %self.id, event_id = pending.event_id, taken, "command event completed");
            out.push(pending.completed(taken));
        }
        out
    }

    /// The Command Events of running commands that ended: done, expired, or the
    /// component out of Ready.
    fn finish_commands(&mut self, now: Instant) -> Vec<Outgoing> {
        let ready = self.core.state() == ComponentState::Ready;
        let services = &self.services;
        self.core.events_mut().finish_running(now, ready, |code| {
            services.iter().any(|s| s.in_progress(code))
        })
    }

    /// Counts the Reject Event Requests the Core answered `msg` with (a bound reached,
    /// or otherwise refused) and logs them.
    fn count_event_refusals(&mut self, from: As4Id, msg: &Message, out: &[Outgoing]) {
        for o in out {
            if let Message::RejectEventRequest(RejectEventRequest {
                response_code: Some(code),
                error_message,
                ..
            }) = &o.message
            {
                let reason = error_message.as_deref().unwrap_or_default();
                if *code == EventRejection::ConnectionRefused {
                    self.stats.bounds += 1;
                } else {
                    self.stats.refused += 1;
                }
                tracing::debug!(message = msg.name(), %from, component = %self.id, "event refused: {code:?}: {reason}");
            }
        }
    }

    fn fire_events(&mut self, now: Instant, env: &mut E) -> Vec<Outgoing> {
        let mut out = Vec::new();
        for (id, subscriber, q) in self.core.events().due(now) {
            let report = self.query(now, &q, subscriber, env);
            if report.is_none() {
                self.stats.events_unanswered += 1;
            }
            if let Some(o) = self.core.events_mut().fire(now, id, report.as_ref()) {
                self.stats.events_sent += 1;
                out.push(o);
            }
        }
        out
    }
}
