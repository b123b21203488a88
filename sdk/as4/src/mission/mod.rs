//! The Mission Spooler (Mission Spooling Service Set, AS6062,
//! `urn:jaus:jss:missionSpooler:MissionSpooler` 1.0), served natively on its generated
//! machines (`defs/mission_spooling_services.yaml`): [`MissionSpoolerService`], a
//! service any AS-4 component hosts (`As4Component::with_service`). It stores a mission
//! from the controlling client and runs it by sending each of its messages to its
//! destination as a Core v1.1 command event.
//!
//! # A mission
//!
//! Spool Mission gives a mission id and a tree of tasks: the `tasks` list, task 0 the
//! root, each task naming its children by index in the list; a task is a list of
//! messages, each a uid, a destination (32-bit JAUS address), the message (its message
//! ID and body) and whether it blocks. Taken only from the controlling client (the
//! machine's `isControllingClient`) in `Init` (no mission stored), and only a mission
//! that validates (`isMissionValid`, [`plan`]): child indices in range, no cycle, every
//! task but the root the child of exactly one task (each reached once from the root),
//! unique task ids and message uids, every embedded message at least 2 bytes, no
//! broadcast destination, and within the bounds of [`SpoolerConfig`] (tasks, messages,
//! bytes per message). A refusal is counted ([`SpoolerStats::refused`]) and logged
//! naming the message, the field (`tasks[2].child_tasks[0]`) and the sender; nothing is
//! answered (the set has no refusal message).
//!
//! **Run order**: a task's messages in their order, then its children depth first, in
//! the order the task lists them. Run Mission starts at the beginning, or at the task
//! or message it names (those before are skipped: status Aborted, no error); it is
//! refused (`isRunValid`) for another mission id, a task or message unknown or already
//! sent.
//!
//! # Running
//!
//! Each message goes to its destination inside **Create Command Event** (request id,
//! maximum allowed duration = [`SpoolerConfig::command_timeout`] in seconds, the
//! message's bytes). The destination answers Confirm Event Request (request id → event
//! id), then **Command Event** (event id, Successful or Unsuccessful) when the command
//! completes; or Reject Event Request. A **blocking** message holds the mission in
//! `Blocked`: nothing further is sent until its Command Event, its rejection or its
//! command timeout (no answer: Unsuccessful). A non-blocking message goes and the next
//! follows at once; its outcome is recorded when it comes (or at its timeout). The
//! mission finishes when every message has an outcome: Report Mission Status
//! (Finished; secondary status Internal Failure when a message did not succeed) to
//! the client that spooled it, which also gets the status of each message as it ends.
//!
//! **Control of the destinations.** A destination takes commands only from its
//! controlling client, so before the first message to a destination the spooler sends
//! it Request Control ([`SpoolerConfig::authority`], never above the authority of the
//! client controlling the spooler) and keeps the message (and any
//! further ones for it, in order) until Confirm Control (Control Accepted). A refusal, a
//! Reject Control, or no answer within [`SpoolerConfig::control_timeout`] ends those
//! messages (Unsuccessful; status Aborted, Lost Component Control) and **aborts the
//! mission** (the machine's `ControlRefused`: Report Mission Status Aborted, Lost
//! Component Control): a mission that cannot command one of its vehicles does not go on
//! with the others. Once granted, the spooler asks the destination Query Timeout; a
//! destination whose control lapses (a timeout above 0) is sent Request Control again
//! every half of it. When the mission has nothing left for a destination (every message
//! for it ended), Release Control; and for all of them when the mission ends or is
//! aborted.
//!
//! **Pause, resume, abort, edits** are the machine's transitions: Pause Mission (a task
//! named or not, the mission pauses: the machine has one Paused state) from Running or
//! Blocked; what went out stays with its destination and its outcome is still recorded.
//! Resume Mission and Run Mission go on. Abort Mission from Pending, Running or Paused
//! (not Blocked, as the JSIDL has it: pause first) forgets the mission, releases the
//! destinations, reports Aborted. Remove/Insert Messages and Remove/Insert Mission Task
//! change only what was not sent yet (the messages sent must stay the first of the run
//! order): in Running and Blocked the machine's `isUpdateValid` refuses the others; in
//! Paused the action checks and logs them. Insert Mission Task puts the new task (which
//! brings no children) beside the task named when `new_parent_task_id` is that task's
//! parent, or over it (the task named becomes its child) when it is the new task's id
//! with Before. Remove Mission Task's `promoted_children` are task ids.
//!
//! **Control of the spooler.** The Core answers Request and Release Control for the
//! whole component; the spooler's machine follows it. When a client takes control with a
//! mission stored, the machine goes to `Pending` (the JSIDL's `isMissionSpooled()`
//! transition), raised as `ControlRegained`; control changing hands pauses a running
//! mission. A release holds the mission where it is (no message is sent while not
//! controlled; outcomes still recorded). An emergency of the spooler's component holds
//! it too (the machine follows the Core into Controlled.NotAvailable; reported Paused);
//! once cleared, the mission waits in Pending for Run or Resume Mission.
//!
//! **Queries**, any client, any state: Query Mission Status (the mission, a task or a
//! message; without a mission id the stored mission or the last ended; an unknown one
//! is not answered), Query Mission Plan (the root task with its messages not yet sent,
//! and its children's indices; empty once ended), Query Stored Missions (the one stored
//! and the [`SpoolerConfig::max_missions`] last ended, with their creators), Query
//! Spooling Preferences (a message count: the bound on messages).
//!
//! **Delegation** to another spooler (the set's `client_of` itself, `spoolNextMessage`)
//! is not served: `isSpoolerPresent` is false, so every message, a Spool Mission too,
//! goes to its destination as a command event, and pause and abort are not forwarded.
//!
//! Sans-IO: time is the Core's (`Cx::now`), timeouts come from
//! [`Service::poll_timeout`]; no thread, no clock of its own; bounded (missions,
//! messages, request ids per destination, raised events per call); nothing panics on
//! bytes from the network.

mod plan;
mod spooler;
#[cfg(test)]
mod tests;

use std::fmt;
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

pub use plan::{address_of, id_of, Bounds, Plan, Refusal};
pub use spooler::{Outcome, SpoolerStats};

use crate::core::machine::Host;
use crate::messages::services::mission_spooler as generated;
use crate::messages::ComponentState;
use crate::outgoing::receive_of;
use crate::service::{Cx, Handled, Request, Service, ServiceId};
use spooler::{Raise, Spooler};

/// The Core's state under which the spooler's own states are.
const AVAILABLE: &str = "Receiving.Ready.Controlled.Available";
/// Internal events run after one trigger at most.
const MAX_RAISED: usize = 64;

/// The Mission Spooler's settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpoolerConfig {
    /// What a mission may hold.
    pub bounds: Bounds,
    /// Missions remembered after they ended (for their status), the oldest forgotten
    /// first, besides the one stored.
    pub max_missions: usize,
    /// The authority with which the spooler asks its destinations for control.
    pub authority: u8,
    /// How long a destination has to answer Request Control.
    pub control_timeout: Duration,
    /// How long a command has to complete (its Command Event); also the command
    /// event's maximum allowed duration.
    pub command_timeout: Duration,
}

impl Default for SpoolerConfig {
    /// 256 tasks, 1024 messages of at most 4096 bytes, 8 missions remembered,
    /// authority 100, 5 s for control, 60 s per command.
    fn default() -> Self {
        Self {
            bounds: Bounds {
                max_tasks: 256,
                max_messages: 1024,
                max_message_bytes: 4096,
            },
            max_missions: 8,
            authority: 100,
            control_timeout: Duration::from_secs(5),
            command_timeout: Duration::from_secs(60),
        }
    }
}

/// The Mission Spooler service on its generated machines (see the module's
/// documentation), hosted by any AS-4 component. Written out rather than the generated
/// `Hosted` adapter because it has timers ([`Service::poll_timeout`]) and raises its
/// machine's internal events.
pub struct MissionSpoolerService {
    imp: Spooler,
    machines: generated::Machines,
    /// The component's controller when last seen.
    controller: Option<As4Id>,
}

impl fmt::Debug for MissionSpoolerService {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MissionSpoolerService")
            .field("state", &self.state())
            .field("stats", &self.imp.stats)
            .finish_non_exhaustive()
    }
}

impl MissionSpoolerService {
    /// The service with `config`, no mission stored, its machines not started (they
    /// follow the Core's at the first call).
    pub fn new(config: SpoolerConfig) -> Self {
        Self {
            imp: Spooler::new(config),
            machines: generated::Machines::new(),
            controller: None,
        }
    }

    /// Its settings.
    pub fn config(&self) -> &SpoolerConfig {
        &self.imp.config
    }

    /// Its counters.
    pub fn stats(&self) -> SpoolerStats {
        self.imp.stats
    }

    /// The machine's state (`Receiving.Ready.Controlled.Available.Running`).
    pub fn state(&self) -> &'static str {
        self.machines.state("ReceiveFSM").unwrap_or("")
    }

    /// How message `uid` of the mission stored (or the last ended) ended, once it did.
    pub fn outcome(&self, uid: u16) -> Option<Outcome> {
        self.imp.outcome(uid)
    }

    /// The destinations the spooler controls now.
    pub fn controlled(&self) -> Vec<As4Id> {
        self.imp.controlled()
    }

    /// Missions held: the one stored and those remembered.
    pub fn missions(&self) -> usize {
        self.imp.stored()
    }

    /// Runs `trigger`, then the internal events it raised.
    fn run(&mut self, core: &mut Host<'_>, trigger: &generated::Trigger<'_>) -> bool {
        self.imp.path = self.state();
        self.imp.client_authority = core.current_authority();
        let taken = self.machines.handle(&mut self.imp, core, trigger);
        self.drain(core);
        taken
    }

    /// Runs the internal events raised, in order (at most [`MAX_RAISED`]).
    fn drain(&mut self, core: &mut Host<'_>) {
        use generated::Trigger as T;
        for _ in 0..MAX_RAISED {
            let Some(r) = self.imp.raised.pop_front() else {
                return;
            };
            let t = match r {
                Raise::NextMessage => T::NextMessage {},
                Raise::MissionCompleted => T::MissionCompleted {},
                Raise::Unblocked => T::Unblocked {},
                Raise::ControlRefused => T::ControlRefused {},
                Raise::ControlRegained => T::ControlRegained {},
            };
            self.imp.path = self.state();
            self.machines.handle(&mut self.imp, core, &t);
        }
        if !self.imp.raised.is_empty() {
            tracing::warn!(
                left = self.imp.raised.len(),
                "Mission Spooler: more than {MAX_RAISED} internal events in one call; the rest dropped"
            );
            self.imp.raised.clear();
        }
    }

    /// Follows the Core's machine (at `core_state`, `controller` in control), raising
    /// `ControlRegained` when it comes into Controlled.Available or control changes
    /// hands there.
    fn follow(&mut self, core: &mut Host<'_>, core_state: &'static str, controller: Option<As4Id>) {
        let was_in = self.state().starts_with(AVAILABLE);
        self.machines.follow(&mut self.imp, core_state);
        let is_in = self.state().starts_with(AVAILABLE);
        let handed = was_in && self.controller.is_some() && controller != self.controller;
        self.controller = controller;
        if is_in && (!was_in || handed) {
            self.imp.regained();
            self.drain(core);
        }
    }

    /// What the machines sent, out with the component's output (the first message to
    /// `reply_to` returned instead).
    fn flush<E>(&mut self, cx: &mut Cx<'_, E>, reply_to: Option<As4Id>) -> Option<crate::Message> {
        let mut reply = None;
        for o in self.imp.outbox.take() {
            if reply.is_none() && Some(o.to) == reply_to {
                reply = Some(o.message);
            } else {
                cx.send(o);
            }
        }
        reply
    }

    /// Follows the Core and runs what time or a change brought, at `cx.now`.
    fn settle<E>(&mut self, cx: &mut Cx<'_, E>, expire: bool) {
        self.imp.now = Some(cx.now);
        let (state, controller, now) = (cx.core_state(), cx.controller, cx.now);
        cx.with_core(|core| {
            self.follow(core, state, controller);
            if expire && self.imp.expire(now) {
                self.run(core, &generated::Trigger::Timeout {});
            } else {
                self.drain(core);
            }
        });
        self.flush(cx, None);
    }
}

impl<E: 'static> Service<E> for MissionSpoolerService {
    fn id(&self) -> ServiceId {
        ServiceId::new(generated::URI, generated::VERSION.0, generated::VERSION.1)
    }

    fn receives(&self, code: CommandCode) -> bool {
        generated::RECEIVES.contains(&code)
    }

    fn needs_control(&self, _code: CommandCode) -> bool {
        // The machines decide (`isControllingClient`).
        false
    }

    fn needs_ready(&self, _code: CommandCode) -> bool {
        false
    }

    fn handle(&mut self, cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled {
        self.imp.now = Some(request.now);
        self.imp.from = Some(request.from);
        let transport = receive_of(request.from);
        let Some(trigger) = generated::Trigger::received(request.message, &transport) else {
            return Handled::NotMine;
        };
        let (state, controller) = (cx.core_state(), cx.controller);
        let taken = cx.with_core(|core| {
            self.follow(core, state, controller);
            self.run(core, &trigger)
        });
        if !taken {
            self.imp.explain(request.message, request.from);
        }
        let reply = self.flush(cx, Some(request.from));
        if taken {
            reply.map_or(Handled::Done, Handled::Reply)
        } else {
            Handled::Refused(format!(
                "{}: no transition for {} in state {}",
                generated::URI,
                request.message.name(),
                self.state()
            ))
        }
    }

    fn state_changed(&mut self, cx: &mut Cx<'_, E>, _from: ComponentState, _to: ComponentState) {
        self.settle(cx, false);
    }

    fn controller_changed(&mut self, cx: &mut Cx<'_, E>, _controller: Option<As4Id>) {
        self.settle(cx, false);
    }

    fn tick(&mut self, cx: &mut Cx<'_, E>) {
        self.settle(cx, true);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.imp.next_deadline()
    }
}
