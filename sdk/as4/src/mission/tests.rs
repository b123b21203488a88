//! The spooler in a component, against scripted destinations: the test answers Confirm
//! Control, Confirm Event Request and Command Event by hand.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

use super::*;
use crate::component::{As4Component, Outgoing};
use crate::core::CoreConfig;
use crate::messages::{
    AbortMission, CommandEvent, CommandResult, ConfirmControl, ConfirmEventRequest,
    ControlConfirmation, CreateCommandEvent, InsertMessages, Message, MessageBlocking,
    MessageInsertPosition, MissionState, MissionStatusLevel, MissionStatusReason, MissionTask,
    PauseMission, QueryMissionPlan, QueryMissionStatus, QueryStoredMissions, RejectEventRequest,
    ReleaseControl, RemoveMessages, ReportMissionStatus, ReportTimeout, RequestControl, Resume,
    ResumeMission, RunMission, SpoolMission, SpooledMessage,
};

const SPOOLER: As4Id = As4Id::new(1, 1, 5);
const CLIENT: As4Id = As4Id::new(42, 1, 1);
const OTHER: As4Id = As4Id::new(43, 1, 1);
const D: As4Id = As4Id::new(1, 1, 6);
const E: As4Id = As4Id::new(1, 1, 7);

fn msg(uid: u16, to: As4Id, blocking: bool) -> SpooledMessage {
    SpooledMessage {
        uid,
        destination_id: address_of(to),
        jaus_message: crate::embedded::encode(&Resume {}.into()).unwrap(),
        blocking: if blocking {
            MessageBlocking::Blocking
        } else {
            MessageBlocking::NonBlocking
        },
    }
}

fn task(id: u16, messages: Vec<SpooledMessage>, children: Vec<u16>) -> MissionTask {
    MissionTask {
        task_id: id,
        messages,
        child_tasks: children,
    }
}

fn mission(id: u16, tasks: Vec<MissionTask>) -> SpoolMission {
    SpoolMission {
        mission_id: id,
        source_id: address_of(CLIENT),
        tasks,
    }
}

/// The spooler shared with the test, which reads its state between calls.
#[derive(Debug, Clone)]
struct Shared(Arc<Mutex<MissionSpoolerService>>);

impl Shared {
    fn get(&self) -> MutexGuard<'_, MissionSpoolerService> {
        self.0.lock().unwrap()
    }
}

impl Service<()> for Shared {
    fn id(&self) -> ServiceId {
        Service::<()>::id(&*self.get())
    }
    fn receives(&self, code: CommandCode) -> bool {
        Service::<()>::receives(&*self.get(), code)
    }
    fn needs_control(&self, code: CommandCode) -> bool {
        Service::<()>::needs_control(&*self.get(), code)
    }
    fn needs_ready(&self, code: CommandCode) -> bool {
        Service::<()>::needs_ready(&*self.get(), code)
    }
    fn handle(&mut self, cx: &mut Cx<'_, ()>, request: &Request<'_>) -> Handled {
        self.get().handle(cx, request)
    }
    fn state_changed(&mut self, cx: &mut Cx<'_, ()>, from: ComponentState, to: ComponentState) {
        self.get().state_changed(cx, from, to)
    }
    fn controller_changed(&mut self, cx: &mut Cx<'_, ()>, controller: Option<As4Id>) {
        self.get().controller_changed(cx, controller)
    }
    fn tick(&mut self, cx: &mut Cx<'_, ()>) {
        self.get().tick(cx)
    }
    fn poll_timeout(&self) -> Option<Instant> {
        Service::<()>::poll_timeout(&*self.get())
    }
}

struct Rig {
    c: As4Component<()>,
    s: Shared,
    t: Instant,
    next_event: u8,
}

impl Rig {
    fn new(config: SpoolerConfig) -> Self {
        let s = Shared(Arc::new(Mutex::new(MissionSpoolerService::new(config))));
        let c = As4Component::new(SPOOLER, CoreConfig::named("spooler")).with_service(s.clone());
        Self {
            c,
            s,
            t: Instant::now(),
            next_event: 1,
        }
    }

    fn send(&mut self, from: As4Id, m: impl Into<Message>) -> Vec<Outgoing> {
        self.c.handle(self.t, from, &m.into(), &mut ())
    }

    fn advance(&mut self, d: Duration) -> Vec<Outgoing> {
        let end = self.t + d;
        let mut out = Vec::new();
        while let Some(due) = self.c.poll_timeout().filter(|t| *t <= end) {
            self.t = due.max(self.t);
            out.extend(self.c.handle_timeout(self.t, &mut ()));
        }
        self.t = end;
        out
    }

    fn spooler(&self) -> MutexGuard<'_, MissionSpoolerService> {
        self.s.get()
    }

    fn state(&self) -> String {
        self.spooler().state().to_string()
    }

    /// Control of the spooler, a mission stored.
    fn controlled_with(&mut self, m: SpoolMission) {
        let out = self.send(CLIENT, RequestControl { authority_code: 10 });
        assert!(matches!(out[0].message, Message::ConfirmControl(_)));
        self.send(CLIENT, m);
    }

    fn run(&mut self) -> Vec<Outgoing> {
        self.send(CLIENT, RunMission::default())
    }

    /// `dest` grants control: the commands waiting for it.
    fn grant(&mut self, dest: As4Id) -> Vec<Outgoing> {
        self.send(
            dest,
            ConfirmControl {
                response_code: ControlConfirmation::ControlAccepted,
            },
        )
    }

    /// `dest` confirms the command event of `request`: its event id.
    fn confirm(&mut self, dest: As4Id, request: &CreateCommandEvent) -> u8 {
        let event_id = self.next_event;
        self.next_event += 1;
        let out = self.send(
            dest,
            ConfirmEventRequest {
                request_id: request.request_id,
                event_id,
                confirmed_periodic_rate: 0.0,
            },
        );
        assert!(out.is_empty(), "{out:?}");
        event_id
    }

    fn complete(&mut self, dest: As4Id, event_id: u8, ok: bool) -> Vec<Outgoing> {
        self.send(
            dest,
            CommandEvent {
                event_id,
                command_result: if ok {
                    CommandResult::Successful
                } else {
                    CommandResult::Unsuccessful
                },
            },
        )
    }

    fn status(&mut self, q: QueryMissionStatus) -> Option<ReportMissionStatus> {
        self.send(OTHER, q)
            .into_iter()
            .find_map(|o| match o.message {
                Message::ReportMissionStatus(r) => Some(r),
                _ => None,
            })
    }

    fn mission_status(&mut self) -> (MissionState, MissionStatusReason) {
        let r = self
            .status(QueryMissionStatus::default())
            .expect("a status");
        (r.status, r.secondary_status)
    }
}

/// The Create Command Events in `out` for `to`.
fn commands(out: &[Outgoing], to: As4Id) -> Vec<CreateCommandEvent> {
    out.iter()
        .filter(|o| o.to == to)
        .filter_map(|o| match &o.message {
            Message::CreateCommandEvent(c) => Some(c.clone()),
            _ => None,
        })
        .collect()
}

fn has(out: &[Outgoing], to: As4Id, f: impl Fn(&Message) -> bool) -> bool {
    out.iter().any(|o| o.to == to && f(&o.message))
}

#[test]
fn a_blocking_message_holds_the_next_until_its_command_event() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        7,
        vec![task(1, vec![msg(10, D, true), msg(11, D, false)], vec![])],
    ));
    assert!(r.state().contains("Pending"), "{}", r.state());
    let out = r.run();
    // Control of the destination first, nothing else; asked at the controlling client's
    // authority (10), not the spooler's configured 100: the spooler lends no authority.
    assert!(has(
        &out,
        D,
        |m| matches!(m, Message::RequestControl(c) if c.authority_code == 10)
    ));
    assert!(commands(&out, D).is_empty());
    assert!(r.state().contains("Blocked"), "{}", r.state());
    let out = r.grant(D);
    assert!(has(&out, D, |m| matches!(m, Message::QueryTimeout(_))));
    let c = commands(&out, D);
    assert_eq!(c.len(), 1, "only the blocking message");
    assert_eq!(c[0].command_message, msg(10, D, true).jaus_message);
    assert_eq!(c[0].maximum_allowed_duration, 60);
    let e = r.confirm(D, &c[0]);
    assert_eq!(
        r.mission_status(),
        (MissionState::Blocked, MissionStatusReason::NoError)
    );
    let out = r.complete(D, e, true);
    let c2 = commands(&out, D);
    assert_eq!(c2.len(), 1, "the next goes once the blocking one is done");
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.level == MissionStatusLevel::Message && s.id == 10 && s.status == MissionState::Finished)
    ));
    let e2 = r.confirm(D, &c2[0]);
    let out = r.complete(D, e2, true);
    assert!(has(&out, D, |m| matches!(m, Message::ReleaseControl(_))));
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.level == MissionStatusLevel::Mission && s.status == MissionState::Finished)
    ));
    assert_eq!(
        r.mission_status(),
        (MissionState::Finished, MissionStatusReason::NoError)
    );
    assert!(r.state().contains("Init"), "{}", r.state());
    assert_eq!(r.spooler().outcome(11), Some(Outcome::Successful));
}

#[test]
fn non_blocking_messages_go_on_at_once_each_destination_controlled_first() {
    let mut r = Rig::new(SpoolerConfig::default());
    // Root (D), child task (E, then D): run order 20, 21, 22.
    r.controlled_with(mission(
        1,
        vec![
            task(1, vec![msg(20, D, false)], vec![1]),
            task(2, vec![msg(21, E, false), msg(22, D, false)], vec![]),
        ],
    ));
    let out = r.run();
    assert!(has(&out, D, |m| matches!(m, Message::RequestControl(_))));
    assert!(has(&out, E, |m| matches!(m, Message::RequestControl(_))));
    assert!(r.state().contains("Running"), "{}", r.state());
    // E first: its message goes; D's two go in order when D grants.
    let ce = commands(&r.grant(E), E);
    assert_eq!(ce.len(), 1);
    let cd = commands(&r.grant(D), D);
    assert_eq!(cd.len(), 2);
    assert!(cd[0].request_id != cd[1].request_id);
    let (e0, e1, e2) = (
        r.confirm(E, &ce[0]),
        r.confirm(D, &cd[0]),
        r.confirm(D, &cd[1]),
    );
    // Outcomes in any order; the same event id from two destinations is told apart.
    let out = r.complete(E, e0, false);
    assert!(has(&out, E, |m| matches!(m, Message::ReleaseControl(_))));
    r.complete(D, e2, true);
    assert_eq!(r.mission_status().0, MissionState::Running);
    let out = r.complete(D, e1, true);
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.status == MissionState::Finished && s.secondary_status == MissionStatusReason::InternalFailure)
    ));
    assert_eq!(r.spooler().outcome(21), Some(Outcome::Unsuccessful));
    let s = r
        .status(QueryMissionStatus {
            mission_id: Some(1),
            message_uid: Some(21),
            ..Default::default()
        })
        .unwrap();
    assert_eq!(
        (s.status, s.level),
        (MissionState::Aborted, MissionStatusLevel::Message)
    );
}

#[test]
fn pause_resume_and_abort() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        3,
        vec![task(
            1,
            vec![msg(1, D, true), msg(2, D, false), msg(3, D, true)],
            vec![],
        )],
    ));
    r.run();
    let c = commands(&r.grant(D), D);
    let e = r.confirm(D, &c[0]);
    let out = r.send(CLIENT, PauseMission::default());
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s) if s.status == MissionState::Paused)
    ));
    assert_eq!(r.mission_status().0, MissionState::Paused);
    // The blocking message completes while paused: recorded, nothing further sent.
    let out = r.complete(D, e, true);
    assert!(commands(&out, D).is_empty());
    assert_eq!(r.spooler().outcome(1), Some(Outcome::Successful));
    // Resumed: back to Blocked, unblocked, on with message 2 and 3 (blocking).
    let out = r.send(CLIENT, ResumeMission { mission_id: 3 });
    let c = commands(&out, D);
    assert_eq!(c.len(), 2, "{out:?}");
    assert!(r.state().contains("Blocked"), "{}", r.state());
    // Abort is not taken while Blocked (the JSIDL's): pause, then abort.
    let before = r.c.stats().refused;
    r.send(CLIENT, AbortMission { mission_id: 3 });
    assert_eq!(r.c.stats().refused, before + 1);
    r.send(CLIENT, PauseMission::default());
    let out = r.send(CLIENT, AbortMission { mission_id: 3 });
    assert!(has(&out, D, |m| matches!(m, Message::ReleaseControl(_))));
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s) if s.status == MissionState::Aborted)
    ));
    assert!(r.state().contains("Init"), "{}", r.state());
    assert_eq!(r.mission_status().0, MissionState::Aborted);
    // Events of the aborted mission are ignored.
    r.complete(D, 99, true);
    assert!(r.spooler().controlled().is_empty());
}

#[test]
fn nothing_is_taken_without_control_of_the_spooler() {
    let mut r = Rig::new(SpoolerConfig::default());
    let m = mission(1, vec![task(1, vec![msg(1, D, false)], vec![])]);
    assert!(r.send(OTHER, m.clone()).is_empty());
    assert_eq!(r.spooler().missions(), 0);
    r.controlled_with(m);
    assert!(r.send(OTHER, RunMission::default()).is_empty());
    assert!(r.state().contains("Pending"));
    assert!(r.c.stats().refused >= 2);
    // Queries answer anyone.
    let out = r.send(OTHER, QueryStoredMissions {});
    assert!(matches!(&out[0].message, Message::ReportStoredMissions(s) if s.missions.len() == 1));
    // Released with a mission stored, then taken again: it waits in Pending.
    r.send(CLIENT, ReleaseControl {});
    assert!(r.state().contains("NotControlled"), "{}", r.state());
    r.send(CLIENT, RequestControl { authority_code: 10 });
    assert!(r.state().contains("Pending"), "{}", r.state());
}

#[test]
fn bad_missions_are_refused_with_the_field() {
    let b = SpoolerConfig::default().bounds;
    let refused = |tasks: Vec<MissionTask>| Plan::new(tasks, &b).unwrap_err().field;
    assert_eq!(refused(vec![]), "tasks");
    assert_eq!(
        refused(vec![task(1, vec![], vec![5])]),
        "tasks[0].child_tasks[0]"
    );
    // A cycle beside the root.
    assert_eq!(
        refused(vec![
            task(1, vec![], vec![]),
            task(2, vec![], vec![2]),
            task(3, vec![], vec![1])
        ]),
        "tasks[1]"
    );
    assert_eq!(
        refused(vec![task(1, vec![], vec![1, 1]), task(2, vec![], vec![])]),
        "tasks[0].child_tasks[1]"
    );
    assert_eq!(
        refused(vec![task(
            1,
            vec![msg(1, D, false), msg(1, E, false)],
            vec![]
        )]),
        "tasks[0].messages[1].uid"
    );
    let mut short = msg(1, D, false);
    short.jaus_message = vec![1];
    assert_eq!(
        refused(vec![task(1, vec![short], vec![])]),
        "tasks[0].messages[0].jaus_message"
    );
    assert_eq!(
        refused(vec![task(
            1,
            vec![msg(1, As4Id::new(1, 1, 0xFF), false)],
            vec![]
        )]),
        "tasks[0].messages[0].destination_id"
    );
    // Through the service: counted, not stored.
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(1, vec![task(1, vec![], vec![3])]));
    assert!(r.state().contains("Init"), "{}", r.state());
    assert_eq!(r.spooler().stats().refused, 1);
}

#[test]
fn bounds_refuse_what_does_not_fit() {
    let mut config = SpoolerConfig::default();
    config.bounds.max_messages = 2;
    config.bounds.max_tasks = 2;
    let mut r = Rig::new(config);
    let three = vec![task(
        1,
        vec![msg(1, D, false), msg(2, D, false), msg(3, D, false)],
        vec![],
    )];
    assert_eq!(
        Plan::new(three.clone(), &config.bounds).unwrap_err().field,
        "tasks"
    );
    r.controlled_with(mission(1, three));
    assert_eq!(r.spooler().stats().refused, 1);
    r.send(
        CLIENT,
        mission(
            2,
            vec![task(1, vec![msg(1, D, false), msg(2, D, false)], vec![])],
        ),
    );
    assert!(r.state().contains("Pending"));
    // An insertion past the bound is refused too (Paused: the action checks).
    r.send(CLIENT, RunMission::default());
    r.send(CLIENT, PauseMission::default());
    r.send(
        CLIENT,
        InsertMessages {
            mission_id: 2,
            task_id: 1,
            uid: 2,
            insert_location: MessageInsertPosition::AfterUid,
            messages: vec![msg(9, D, false)],
        },
    );
    assert_eq!(r.spooler().stats().refused, 2);
    assert_eq!(
        r.spooler().config().bounds.max_messages,
        2,
        "preferences: {:?}",
        r.spooler()
    );
}

#[test]
fn a_destination_that_refuses_control_aborts_the_mission() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        4,
        vec![task(1, vec![msg(1, D, false), msg(2, E, false)], vec![])],
    ));
    r.run();
    let out = r.send(
        D,
        ConfirmControl {
            response_code: ControlConfirmation::InsufficientAuthority,
        },
    );
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.status == MissionState::Aborted && s.secondary_status == MissionStatusReason::LostComponentControl)
    ));
    assert!(has(&out, E, |m| matches!(m, Message::ReleaseControl(_))));
    assert_eq!(r.spooler().outcome(1), Some(Outcome::NoControl));
    assert!(r.state().contains("Init"), "{}", r.state());
    assert_eq!(
        r.mission_status(),
        (
            MissionState::Aborted,
            MissionStatusReason::LostComponentControl
        )
    );
}

#[test]
fn a_destination_that_never_answers_times_out() {
    let config = SpoolerConfig {
        control_timeout: Duration::from_secs(2),
        command_timeout: Duration::from_secs(10),
        ..SpoolerConfig::default()
    };
    let mut r = Rig::new(config);
    r.controlled_with(mission(
        5,
        vec![task(1, vec![msg(1, D, true), msg(2, D, false)], vec![])],
    ));
    r.run();
    let c = commands(&r.grant(D), D);
    assert_eq!(c[0].maximum_allowed_duration, 10);
    // No Confirm Event Request, no Command Event: after 10 s, Unsuccessful, and on.
    let out = r.advance(Duration::from_secs(9));
    assert!(commands(&out, D).is_empty());
    let out = r.advance(Duration::from_secs(2));
    assert_eq!(r.spooler().outcome(1), Some(Outcome::NoAnswer));
    let c = commands(&out, D);
    assert_eq!(c.len(), 1, "{out:?}");
    // A rejection ends the last: the mission finishes, with the failure said.
    let out = r.send(
        D,
        RejectEventRequest {
            request_id: c[0].request_id,
            response_code: None,
            error_message: Some("no".into()),
        },
    );
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.level == MissionStatusLevel::Mission && s.status == MissionState::Finished
            && s.secondary_status == MissionStatusReason::InternalFailure)
    ));
    // A destination that never answers Request Control: aborted after 2 s.
    r.send(
        CLIENT,
        mission(6, vec![task(1, vec![msg(1, E, false)], vec![])]),
    );
    r.run();
    let out = r.advance(Duration::from_secs(3));
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s)
        if s.status == MissionState::Aborted)
    ));
    assert_eq!(r.spooler().outcome(1), Some(Outcome::NoControl));
}

#[test]
fn control_of_a_destination_is_kept_alive_within_its_timeout() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(8, vec![task(1, vec![msg(1, D, true)], vec![])]));
    r.run();
    r.grant(D);
    r.send(D, ReportTimeout { timeout: 4 });
    let out = r.advance(Duration::from_millis(2100));
    assert!(
        has(&out, D, |m| matches!(m, Message::RequestControl(_))),
        "{out:?}"
    );
    let out = r.advance(Duration::from_millis(2000));
    assert!(
        has(&out, D, |m| matches!(m, Message::RequestControl(_))),
        "{out:?}"
    );
    // Its answer to the renewal changes nothing.
    assert!(commands(&r.grant(D), D).is_empty());
    assert_eq!(r.spooler().controlled(), vec![D]);
}

#[test]
fn edits_change_only_what_was_not_sent() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        9,
        vec![task(
            1,
            vec![msg(1, D, true), msg(2, D, false), msg(3, D, false)],
            vec![],
        )],
    ));
    r.run();
    r.grant(D);
    let refused = r.spooler().stats().refused;
    // Message 1 went: removing it is refused (Blocked: isUpdateValid).
    r.send(
        CLIENT,
        RemoveMessages {
            mission_id: 9,
            task_id: 1,
            uids: vec![1],
        },
    );
    assert_eq!(r.spooler().stats().refused, refused + 1);
    r.send(
        CLIENT,
        RemoveMessages {
            mission_id: 9,
            task_id: 1,
            uids: vec![2],
        },
    );
    let plan = r.send(OTHER, QueryMissionPlan { mission_id: 9 });
    let Message::ReportMissionPlan(p) = &plan[0].message else {
        panic!("{plan:?}")
    };
    let left: Vec<u16> = p.task.messages.iter().map(|m| m.uid).collect();
    assert_eq!(left, vec![3]);
    // Inserted before 3, it runs before it.
    r.send(
        CLIENT,
        InsertMessages {
            mission_id: 9,
            task_id: 1,
            uid: 3,
            insert_location: MessageInsertPosition::BeforeUid,
            messages: vec![msg(5, D, false)],
        },
    );
    let plan = r.send(OTHER, QueryMissionPlan { mission_id: 9 });
    let Message::ReportMissionPlan(p) = &plan[0].message else {
        panic!()
    };
    assert_eq!(
        p.task.messages.iter().map(|m| m.uid).collect::<Vec<_>>(),
        vec![5, 3]
    );
}

#[test]
fn control_of_the_spooler_changing_hands_pauses_the_mission() {
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        2,
        vec![task(1, vec![msg(1, D, true), msg(2, D, false)], vec![])],
    ));
    r.run();
    r.grant(D);
    assert!(r.state().contains("Blocked"), "{}", r.state());
    // A client of higher authority takes control: the mission pauses.
    let out = r.send(OTHER, RequestControl { authority_code: 50 });
    assert!(has(&out, OTHER, |m| matches!(
        m,
        Message::ConfirmControl(_)
    )));
    assert!(r.state().contains("Paused"), "{}", r.state());
    assert!(has(
        &out,
        CLIENT,
        |m| matches!(m, Message::ReportMissionStatus(s) if s.status == MissionState::Paused)
    ));
    // The new controller resumes it.
    r.send(OTHER, ResumeMission { mission_id: 2 });
    assert!(r.state().contains("Blocked"), "{}", r.state());
}

#[test]
fn an_emergency_holds_the_mission_until_it_is_cleared_and_resumed() {
    use crate::messages::{ClearEmergency, EmergencyCode, SetEmergency};
    let mut r = Rig::new(SpoolerConfig::default());
    r.controlled_with(mission(
        6,
        vec![task(1, vec![msg(1, D, true), msg(2, D, false)], vec![])],
    ));
    r.run();
    let c = commands(&r.grant(D), D);
    let e = r.confirm(D, &c[0]);
    r.send(
        CLIENT,
        SetEmergency {
            emergency_code: EmergencyCode::Stop,
        },
    );
    assert!(r.state().contains("NotAvailable"), "{}", r.state());
    assert_eq!(r.mission_status().0, MissionState::Paused);
    // The command ends meanwhile: recorded, nothing sent.
    let out = r.complete(D, e, true);
    assert!(commands(&out, D).is_empty());
    r.advance(Duration::from_secs(10));
    r.send(
        CLIENT,
        ClearEmergency {
            emergency_code: EmergencyCode::Stop,
        },
    );
    assert!(r.state().contains("Pending"), "{}", r.state());
    let out = r.send(CLIENT, ResumeMission { mission_id: 6 });
    assert_eq!(commands(&out, D).len(), 1, "{out:?}");
}

#[test]
fn run_order_is_a_tasks_messages_then_its_children_depth_first() {
    let b = SpoolerConfig::default().bounds;
    let p = Plan::new(
        vec![
            task(1, vec![msg(1, D, false)], vec![2, 1]),
            task(2, vec![msg(2, D, false)], vec![3]),
            task(3, vec![msg(3, D, false)], vec![]),
            task(4, vec![msg(4, D, false)], vec![]),
        ],
        &b,
    )
    .unwrap();
    let uids: Vec<u16> = p
        .run_order()
        .into_iter()
        .map(|x| p.message(x).unwrap().uid)
        .collect();
    assert_eq!(uids, vec![1, 3, 2, 4]);
}

#[test]
fn destinations_are_asked_at_the_lower_of_the_configured_and_the_clients_authority() {
    let mut s = super::spooler::Spooler::new(SpoolerConfig::default());
    assert_eq!(SpoolerConfig::default().authority, 100);
    s.client_authority = 200;
    assert_eq!(
        s.request_authority(),
        100,
        "never above the configured authority"
    );
    s.client_authority = 10;
    assert_eq!(s.request_authority(), 10, "never above the client's");
}
