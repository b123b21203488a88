//! The Mission Spooler's own guards and actions ([`Spooler`], the generated
//! `MissionSpooler` trait): the stored mission, what each of its messages became, the
//! destinations it controls. Sans-IO: time is the `now` the shell hands it with each
//! call; what it sends goes into its [`Outbox`]; the internal events its actions raise
//! wait in [`Spooler::raised`] for the shell to run.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use super::plan::{id_of, Bounds, Plan, Refusal};
use super::SpoolerConfig;
use crate::messages::{
    CreateCommandEvent, JausAddress, MessageBlocking, MissionState, MissionStatusLevel,
    MissionStatusReason, ReleaseControl, ReportMissionStatus, RequestControl, RunMission,
};
use crate::service::Outbox;

mod actions;

/// An internal event an action raised, for the shell to run after the trigger.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Raise {
    NextMessage,
    MissionCompleted,
    Unblocked,
    ControlRefused,
    ControlRegained,
}

/// How a message of the mission ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Its Command Event said Successful.
    Successful,
    /// Its Command Event said Unsuccessful.
    Unsuccessful,
    /// The destination answered its Create Command Event with Reject Event Request.
    Rejected,
    /// No Command Event (or rejection) within the command timeout.
    NoAnswer,
    /// The destination refused control, ended it, or did not answer the request.
    NoControl,
    /// Not sent: Run Mission started after it.
    Skipped,
}

impl Outcome {
    /// The state and reason Report Mission Status gives a message that ended so.
    pub fn status(self) -> (MissionState, MissionStatusReason) {
        match self {
            Outcome::Successful => (MissionState::Finished, MissionStatusReason::NoError),
            Outcome::Skipped => (MissionState::Aborted, MissionStatusReason::NoError),
            Outcome::NoControl => (
                MissionState::Aborted,
                MissionStatusReason::LostComponentControl,
            ),
            _ => (MissionState::Aborted, MissionStatusReason::InternalFailure),
        }
    }
}

/// Where a message sent (or being sent) is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stage {
    /// Waits for control of its destination.
    WaitingControl,
    /// Its Create Command Event went out (request id), confirmed with an event id or
    /// not yet; no outcome before `deadline`.
    Out {
        request: u8,
        event: Option<u8>,
        deadline: Option<Instant>,
    },
    /// Ended.
    Done(Outcome),
}

/// A message of the mission that left the plan's "not yet sent" part.
#[derive(Debug, Clone, Copy)]
struct Issued {
    dest: As4Id,
    blocking: bool,
    stage: Stage,
}

/// A mission: the one stored, or one remembered after it ended.
#[derive(Debug, Clone)]
struct Record {
    id: u16,
    source: JausAddress,
    creator: As4Id,
    plan: Plan,
    issued: BTreeMap<u16, Issued>,
    started: bool,
    /// Why it cannot go on (a destination's control lost), once so.
    failure: Option<MissionStatusReason>,
    /// Its final status, once it ended.
    end: Option<(MissionState, MissionStatusReason)>,
}

impl Record {
    fn issued_uids(&self) -> BTreeSet<u16> {
        self.issued.keys().copied().collect()
    }

    /// The next message to send, in run order.
    fn next(&self) -> Option<(u16, As4Id, bool)> {
        if self.failure.is_some() || self.end.is_some() {
            return None;
        }
        self.plan
            .run_order()
            .into_iter()
            .filter_map(|p| self.plan.message(p))
            .find(|m| !self.issued.contains_key(&m.uid))
            .map(|m| {
                (
                    m.uid,
                    id_of(&m.destination_id),
                    m.blocking == MessageBlocking::Blocking,
                )
            })
    }

    /// The blocking message sent whose outcome is awaited.
    fn waited(&self) -> Option<u16> {
        self.issued
            .iter()
            .find(|(_, i)| i.blocking && !matches!(i.stage, Stage::Done(_)))
            .map(|(u, _)| *u)
    }

    /// Every message has its outcome.
    fn complete(&self) -> bool {
        self.next().is_none()
            && self.failure.is_none()
            && self
                .issued
                .values()
                .all(|i| matches!(i.stage, Stage::Done(_)))
    }

    /// Whether anything not ended goes to `d`.
    fn needs(&self, d: As4Id) -> bool {
        if self.failure.is_some() || self.end.is_some() {
            return false;
        }
        self.plan.tasks.iter().flat_map(|t| &t.messages).any(|m| {
            id_of(&m.destination_id) == d
                && self
                    .issued
                    .get(&m.uid)
                    .is_none_or(|i| !matches!(i.stage, Stage::Done(_)))
        })
    }

    /// The message sent to `d` with request id `r`, awaiting confirmation or outcome.
    fn by_request(&self, d: As4Id, r: u8) -> Option<u16> {
        self.issued
            .iter()
            .find(|(_, i)| {
                i.dest == d && matches!(i.stage, Stage::Out { request, .. } if request == r)
            })
            .map(|(u, _)| *u)
    }

    /// The message sent to `d` whose command event is `e`.
    fn by_event(&self, d: As4Id, e: u8) -> Option<u16> {
        self.issued
            .iter()
            .find(|(_, i)| {
                i.dest == d && matches!(i.stage, Stage::Out { event: Some(x), .. } if x == e)
            })
            .map(|(u, _)| *u)
    }

    fn outcome_worst(&self) -> MissionStatusReason {
        if let Some(f) = self.failure {
            return f;
        }
        let bad = self.issued.values().any(|i| {
            matches!(
                i.stage,
                Stage::Done(Outcome::Unsuccessful | Outcome::Rejected | Outcome::NoAnswer)
            )
        });
        if bad {
            MissionStatusReason::InternalFailure
        } else {
            MissionStatusReason::NoError
        }
    }
}

/// A destination the spooler asked for control of, or controls.
#[derive(Debug, Clone, Copy)]
struct Dest {
    held: bool,
    /// No answer to Request Control by then: refused.
    deadline: Option<Instant>,
    /// Request Control again every period (half the destination's control timeout).
    refresh: Option<(Duration, Instant)>,
}

/// Counters of the spooler.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SpoolerStats {
    /// Spool Mission, Run Mission and edits refused (invalid, out of bounds).
    pub refused: u64,
    /// Missions stored.
    pub spooled: u64,
    /// Create Command Events sent.
    pub commands_sent: u64,
    /// Answers (Confirm Control, event answers) matching nothing the spooler awaits.
    pub unmatched_answers: u64,
    /// Messages that ended without a Successful Command Event.
    pub failed_messages: u64,
}

/// The Mission Spooler's own guards and actions (the generated trait's implementation).
#[derive(Debug)]
pub(super) struct Spooler {
    pub(super) config: SpoolerConfig,
    /// The time of the call (set by the shell).
    pub(super) now: Option<Instant>,
    /// The machine's state when the trigger arrived (set by the shell).
    pub(super) path: &'static str,
    /// The sender of the message being handled (set by the shell), for the logs.
    pub(super) from: Option<As4Id>,
    /// The spooler's own current authority (its controlling client's, set by the shell):
    /// destinations are asked for control at no more than this.
    pub(super) client_authority: u8,
    pub(super) outbox: Outbox,
    pub(super) raised: VecDeque<Raise>,
    pub(super) stats: SpoolerStats,
    current: Option<Record>,
    retained: VecDeque<Record>,
    dests: BTreeMap<As4Id, Dest>,
    next_request: u8,
    timer: Option<Instant>,
    /// The message whose status changed last (reportStatusToParent).
    changed: Option<u16>,
}

impl Spooler {
    /// The authority destinations are asked for control with: the configured one, but
    /// never above the controlling client's (a client of low authority cannot command a
    /// destination through the spooler at a higher one).
    pub(super) fn request_authority(&self) -> u8 {
        self.config.authority.min(self.client_authority)
    }

    pub(super) fn new(config: SpoolerConfig) -> Self {
        Self {
            config,
            now: None,
            path: "",
            from: None,
            client_authority: 0,
            outbox: Outbox::new(),
            raised: VecDeque::new(),
            stats: SpoolerStats::default(),
            current: None,
            retained: VecDeque::new(),
            dests: BTreeMap::new(),
            next_request: 0,
            timer: None,
            changed: None,
        }
    }

    fn bounds(&self) -> Bounds {
        self.config.bounds
    }

    fn raise(&mut self, r: Raise) {
        if r == Raise::NextMessage && self.current.as_ref().and_then(Record::waited).is_some() {
            return;
        }
        if !self.raised.contains(&r) && self.raised.len() < 8 {
            self.raised.push_back(r);
        }
    }

    fn after(&self, d: Duration) -> Option<Instant> {
        self.now.and_then(|n| n.checked_add(d))
    }

    /// The missions held: the stored one, then those remembered.
    pub(super) fn stored(&self) -> usize {
        usize::from(self.current.is_some()) + self.retained.len()
    }

    /// Whether the mission stored failed (a destination's control lost).
    pub(super) fn failed(&self) -> bool {
        self.current.as_ref().is_some_and(|r| r.failure.is_some())
    }

    /// The Core's machine came back into Controlled.Available.
    pub(super) fn regained(&mut self) {
        self.raise(Raise::ControlRegained);
        if self.failed() {
            self.raise(Raise::ControlRefused);
        }
    }

    /// Why `message` from `from` was refused, logged and counted (the machine took no
    /// transition for it).
    pub(super) fn explain(&mut self, message: &crate::messages::Message, from: As4Id) {
        use crate::messages::Message as M;
        let issued = self
            .current
            .as_ref()
            .map(Record::issued_uids)
            .unwrap_or_default();
        let b = self.bounds();
        let why: Option<Refusal> = match (message, self.current.as_ref()) {
            (M::SpoolMission(m), _) => Plan::new(m.tasks.clone(), &b).err(),
            (M::RunMission(m), _) => self.run_refusal(m),
            (M::RemoveMessages(m), Some(r)) => self
                .mission_refusal(m.mission_id)
                .or_else(|| r.plan.remove_messages(m, &issued, &b).err()),
            (M::InsertMessages(m), Some(r)) => self
                .mission_refusal(m.mission_id)
                .or_else(|| r.plan.insert_messages(m, &issued, &b).err()),
            (M::RemoveMissionTask(m), Some(r)) => self
                .mission_refusal(m.mission_id)
                .or_else(|| r.plan.remove_task(m, &issued, &b).err()),
            (M::InsertMissionTask(m), Some(r)) => self
                .mission_refusal(m.mission_id)
                .or_else(|| r.plan.insert_task(m, &issued, &b).err()),
            _ => None,
        };
        if let Some(r) = why {
            self.stats.refused += 1;
            tracing::warn!(message = message.name(), %from, field = %r.field, "Mission Spooler refused: {}", r.why);
        }
    }

    fn mission_refusal(&self, id: u16) -> Option<Refusal> {
        match &self.current {
            Some(r) if r.id == id => None,
            Some(r) => Some(Refusal {
                field: "mission_id".into(),
                why: format!("mission {id} is not the one stored ({})", r.id),
            }),
            None => Some(Refusal {
                field: "mission_id".into(),
                why: "no mission stored".into(),
            }),
        }
    }

    fn run_refusal(&self, m: &RunMission) -> Option<Refusal> {
        let r = match &self.current {
            Some(r) => r,
            None => {
                return Some(Refusal {
                    field: "mission_id".into(),
                    why: "no mission stored".into(),
                })
            }
        };
        let refuse = |field: &str, why: String| {
            Some(Refusal {
                field: field.into(),
                why,
            })
        };
        if r.failure.is_some() {
            return refuse(
                "mission_id",
                "the mission lost control of a destination".into(),
            );
        }
        if let Some(id) = m.mission_id {
            if id != r.id {
                return self.mission_refusal(id);
            }
        }
        if let Some(uid) = m.message_uid {
            if r.plan.find(uid).is_none() {
                return refuse("message_uid", format!("no message {uid}"));
            }
            if r.issued.contains_key(&uid) {
                return refuse("message_uid", format!("message {uid} was already sent"));
            }
        } else if let Some(t) = m.task_id {
            let Some(i) = r.plan.task(t) else {
                return refuse("task_id", format!("no task {t}"));
            };
            let first = r.plan.run_order().into_iter().find(|p| p.0 == i);
            if let Some(m) = first.and_then(|p| r.plan.message(p)) {
                if r.issued.contains_key(&m.uid) {
                    return refuse("task_id", format!("task {t} was already started"));
                }
            }
        }
        None
    }

    /// What to do at `now`: requests of control and commands unanswered in time end,
    /// control is asked for again where it lapses; whether the machines' timer
    /// (`setTimer`) is due.
    pub(super) fn expire(&mut self, now: Instant) -> bool {
        self.now = Some(now);
        let late: Vec<As4Id> = self
            .dests
            .iter()
            .filter(|(_, d)| !d.held && d.deadline.is_some_and(|t| t <= now))
            .map(|(k, _)| *k)
            .collect();
        for d in late {
            self.lose(d, "did not answer Request Control in time");
        }
        let authority = self.request_authority();
        let mut refresh = Vec::new();
        for (k, d) in &mut self.dests {
            if let Some((period, at)) = d.refresh {
                if d.held && at <= now {
                    d.refresh = Some((period, now + period));
                    refresh.push(*k);
                }
            }
        }
        for d in refresh {
            self.outbox.send(
                d,
                &RequestControl {
                    authority_code: authority,
                },
            );
        }
        let overdue: Vec<u16> = self
            .current
            .iter()
            .flat_map(|r| r.issued.iter())
            .filter(|(_, i)| matches!(i.stage, Stage::Out { deadline: Some(t), .. } if t <= now))
            .map(|(u, _)| *u)
            .collect();
        for uid in overdue {
            tracing::warn!(uid, "Mission Spooler: no Command Event in time");
            self.finish(uid, Outcome::NoAnswer);
        }
        let due = self.timer.is_some_and(|t| t <= now);
        if due {
            self.timer = None;
        }
        due
    }

    /// When [`expire`](Self::expire) is next due.
    pub(super) fn next_deadline(&self) -> Option<Instant> {
        let dests = self
            .dests
            .values()
            .flat_map(|d| [d.deadline.filter(|_| !d.held), d.refresh.map(|r| r.1)]);
        let out = self
            .current
            .iter()
            .flat_map(|r| r.issued.values())
            .map(|i| match i.stage {
                Stage::Out { deadline, .. } => deadline,
                _ => None,
            });
        dests.chain(out).chain([self.timer]).flatten().min()
    }

    /// Message `uid` ended with `o`: recorded, what it unblocks raised, destinations no
    /// longer needed released.
    fn finish(&mut self, uid: u16, o: Outcome) {
        let Some(r) = self.current.as_mut() else {
            return;
        };
        let Some(i) = r.issued.get_mut(&uid) else {
            return;
        };
        if matches!(i.stage, Stage::Done(_)) {
            return;
        }
        i.stage = Stage::Done(o);
        let blocking = i.blocking;
        if o != Outcome::Successful && o != Outcome::Skipped {
            self.stats.failed_messages += 1;
        }
        self.changed = Some(uid);
        if blocking {
            self.raise(Raise::Unblocked);
            self.raise(Raise::NextMessage);
        }
        self.release_idle();
        if self.current.as_ref().is_some_and(Record::complete) {
            self.raise(Raise::MissionCompleted);
        }
    }

    /// Control of `d` refused or lost: its messages not ended are NoControl, the
    /// mission cannot go on.
    fn lose(&mut self, d: As4Id, why: &str) {
        tracing::warn!(destination = %d, "Mission Spooler: the destination {why}: the mission is aborted");
        self.dests.remove(&d);
        if let Some(r) = self.current.as_mut() {
            let mut ended = 0;
            for i in r.issued.values_mut() {
                if i.dest == d && !matches!(i.stage, Stage::Done(_)) {
                    i.stage = Stage::Done(Outcome::NoControl);
                    ended += 1;
                }
            }
            self.stats.failed_messages += ended;
            if r.end.is_none() {
                r.failure = Some(MissionStatusReason::LostComponentControl);
                self.raise(Raise::ControlRefused);
            }
        }
    }

    /// Releases control of every destination the mission no longer needs.
    fn release_idle(&mut self) {
        let idle: Vec<As4Id> = self
            .dests
            .keys()
            .copied()
            .filter(|d| !self.current.as_ref().is_some_and(|r| r.needs(*d)))
            .collect();
        for d in idle {
            self.dests.remove(&d);
            self.outbox.send(d, &ReleaseControl {});
        }
    }

    /// A request id free for `d`.
    fn request_id(&mut self, d: As4Id) -> Option<u8> {
        for _ in 0..=u8::MAX {
            let id = self.next_request;
            self.next_request = self.next_request.wrapping_add(1);
            if self
                .current
                .as_ref()
                .is_none_or(|r| r.by_request(d, id).is_none())
            {
                return Some(id);
            }
        }
        None
    }

    /// Sends message `uid` to its destination in a Create Command Event.
    fn send_command(&mut self, uid: u16) {
        let Some((dest, bytes)) = self.current.as_ref().and_then(|r| {
            let i = r.issued.get(&uid)?;
            let m = r.plan.message(r.plan.find(uid)?)?;
            Some((i.dest, m.jaus_message.clone()))
        }) else {
            return;
        };
        let Some(request) = self.request_id(dest) else {
            tracing::warn!(uid, destination = %dest, "Mission Spooler: 256 commands await this destination's answer");
            self.finish(uid, Outcome::Rejected);
            return;
        };
        let timeout = self.config.command_timeout;
        let deadline = self.after(timeout);
        if let Some(i) = self.current.as_mut().and_then(|r| r.issued.get_mut(&uid)) {
            i.stage = Stage::Out {
                request,
                event: None,
                deadline,
            };
        }
        self.stats.commands_sent += 1;
        self.outbox.send(
            dest,
            &CreateCommandEvent {
                request_id: request,
                maximum_allowed_duration: u32::try_from(timeout.as_secs()).unwrap_or(u32::MAX),
                command_message: bytes,
            },
        );
    }

    fn record(&self, id: Option<u16>) -> Option<&Record> {
        let current = self.current.iter();
        let old = self.retained.iter().rev();
        match id {
            Some(id) => current.chain(old).find(|r| r.id == id),
            None => current.chain(old).next(),
        }
    }

    fn is_current(&self, r: &Record) -> bool {
        self.current.as_ref().is_some_and(|c| std::ptr::eq(c, r))
    }

    /// The mission's state and reason.
    fn mission_status(&self, r: &Record) -> (MissionState, MissionStatusReason) {
        if let Some(end) = r.end {
            return end;
        }
        let reason = r.failure.unwrap_or(MissionStatusReason::NoError);
        let held = if r.started {
            MissionState::Paused
        } else {
            MissionState::Init
        };
        let p = self.path;
        let state = if !self.is_current(r) {
            MissionState::Aborted
        } else if p.ends_with(".Running") {
            MissionState::Running
        } else if p.ends_with(".Blocked") {
            MissionState::Blocked
        } else if p.ends_with(".Paused") {
            MissionState::Paused
        } else if p.ends_with(".Pausing") {
            // Nothing is delegated: Pausing is where an emergency of the component
            // holds the machine (Controlled.NotAvailable), the mission paused.
            MissionState::Paused
        } else if p.ends_with(".Aborting") {
            MissionState::Aborting
        } else {
            held
        };
        (state, reason)
    }

    fn message_status(r: &Record, uid: u16) -> (MissionState, MissionStatusReason) {
        match r.issued.get(&uid).map(|i| i.stage) {
            None => (MissionState::Init, MissionStatusReason::NoError),
            Some(Stage::Done(o)) => o.status(),
            Some(_) => (MissionState::Running, MissionStatusReason::NoError),
        }
    }

    fn task_status(&self, r: &Record, t: usize) -> (MissionState, MissionStatusReason) {
        let uids: Vec<u16> = r.plan.tasks[t].messages.iter().map(|m| m.uid).collect();
        let states: Vec<_> = uids.iter().map(|u| Self::message_status(r, *u)).collect();
        let ended = |s: &MissionState| matches!(s, MissionState::Finished | MissionState::Aborted);
        if states.iter().all(|(s, _)| ended(s))
            && (r.end.is_some() || !uids.is_empty() || r.started)
        {
            let worst = states
                .iter()
                .map(|(_, w)| *w)
                .find(|w| *w != MissionStatusReason::NoError)
                .unwrap_or(MissionStatusReason::NoError);
            let s = if r.end.is_some_and(|e| e.0 == MissionState::Aborted)
                && states.iter().any(|(s, _)| *s != MissionState::Finished)
            {
                MissionState::Aborted
            } else {
                MissionState::Finished
            };
            return (s, worst);
        }
        if states.iter().all(|(s, _)| *s == MissionState::Init) {
            return (MissionState::Init, MissionStatusReason::NoError);
        }
        match self.mission_status(r) {
            (MissionState::Paused, w) => (MissionState::Paused, w),
            (_, w) => (MissionState::Running, w),
        }
    }

    fn report_to_creator(&mut self, state: MissionState, reason: MissionStatusReason) {
        let Some(r) = self.current.as_ref().or(self.retained.back()) else {
            return;
        };
        let (to, id) = (r.creator, r.id);
        self.outbox.send(
            to,
            &ReportMissionStatus {
                level: MissionStatusLevel::Mission,
                id,
                status: state,
                secondary_status: reason,
            },
        );
    }

    /// The last mission cleared ends as `state`, reported to its creator.
    fn end_last(&mut self, state: MissionState, default: MissionStatusReason) {
        let Some(r) = self.retained.back_mut() else {
            return;
        };
        let reason = match state {
            MissionState::Finished => r.outcome_worst(),
            _ => r.failure.unwrap_or(default),
        };
        r.end = Some((state, reason));
        let (to, id) = (r.creator, r.id);
        self.outbox.send(
            to,
            &ReportMissionStatus {
                level: MissionStatusLevel::Mission,
                id,
                status: state,
                secondary_status: reason,
            },
        );
    }

    /// Applies an edit of the stored mission checked by `f`, or logs why not.
    fn edit(
        &mut self,
        what: &str,
        id: u16,
        f: impl FnOnce(&Plan, &BTreeSet<u16>, &Bounds) -> Result<Plan, Refusal>,
    ) {
        let b = self.bounds();
        let result = match self.mission_refusal(id) {
            Some(r) => Err(r),
            None => match self.current.as_ref() {
                Some(r) => f(&r.plan, &r.issued_uids(), &b),
                None => return,
            },
        };
        match result {
            Ok(plan) => {
                if let Some(r) = self.current.as_mut() {
                    r.plan = plan;
                }
                self.release_idle();
                if self
                    .current
                    .as_ref()
                    .is_some_and(|r| r.started && r.complete())
                {
                    self.raise(Raise::MissionCompleted);
                }
            }
            Err(r) => {
                self.stats.refused += 1;
                let from = self.from.map(|f| f.to_string()).unwrap_or_default();
                tracing::warn!(message = what, %from, field = %r.field, "Mission Spooler refused: {}", r.why);
            }
        }
    }

    /// Test view: the outcome of message `uid` of the mission stored or last ended.
    pub(super) fn outcome(&self, uid: u16) -> Option<Outcome> {
        let r = self.current.as_ref().or(self.retained.back())?;
        match r.issued.get(&uid)?.stage {
            Stage::Done(o) => Some(o),
            _ => None,
        }
    }

    /// The destinations controlled now.
    pub(super) fn controlled(&self) -> Vec<As4Id> {
        self.dests
            .iter()
            .filter(|(_, d)| d.held)
            .map(|(k, _)| *k)
            .collect()
    }
}
