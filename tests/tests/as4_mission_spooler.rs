//! A mission spooled through AS-4 runs: on the simulated network, an AS-4 client takes
//! control of a node's Mission Spooler (`jaus_as4::mission::MissionSpoolerService` on
//! its own AS-4 component), spools a mission of three commands for a destination on
//! another node, runs it and queries its status until Finished; the destination got
//! the commands in run order, each inside a Create Command Event, under the spooler's
//! control, which it released at the end.
//!
//! The destination is this test's own small AS-4 endpoint ([`Destination`]): it grants
//! control, and answers each Create Command Event with Confirm Event Request and a
//! Command Event Successful, as a component with Core v1.1 command events does. To run
//! the same mission against the demo vehicle once its components answer command events,
//! replace [`destination`] with the vehicle's node (`As4Rig::demo_vehicle_node` behind a
//! `DualNode`, AS-4 id 1.1.1) and read what it did from the vehicle instead of the log.

use std::net::SocketAddr;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Client, As4Config, As4Endpoint, As4Id, As4Message, As4Mux};
use jaus::net::{Node, NodeConfig};
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::messages::{
    CommandEvent, CommandResult, ConfirmControl, ConfirmEventRequest, ControlConfirmation,
    ControlRejection, MessageBlocking, MissionState, MissionStatusLevel, MissionTask,
    QueryMissionStatus, QueryStoredMissions, RejectControl, ReportTimeout, RequestControl, Resume,
    RunMission, SetTravelSpeed, SpoolMission, SpooledMessage, Standby,
};
use jaus_as4::mission::{address_of, MissionSpoolerService, SpoolerConfig};
use jaus_as4::node::As4Node;
use jaus_as4::{embedded, Message};
use jaus_as4::{Element, ExecuteList, QueryLocalPose, SetElement, SetLocalPose, SetLocalWaypoint};
use jaus_sim::network::{LinkModel, SimNet};

/// The client's AS-4 id.
const ME: As4Id = As4Id::new(42, 1, 1);
/// The spooler's AS-4 component.
const SPOOLER: As4Id = As4Id::new(1, 1, 5);

/// What the destination saw.
#[derive(Debug, Default)]
struct Log {
    /// The commands it ran (their names), in order, with whether the sender controlled it.
    commands: Vec<(String, bool)>,
    /// Control requests and releases, by sender.
    controllers: Vec<(As4Id, bool)>,
}

/// A small AS-4 component of this test's own: Access Control (grants anyone, no
/// timeout) and Core v1.1 command events (every command Successful).
#[derive(Debug)]
struct Destination {
    id: As4Id,
    controller: Option<As4Id>,
    next_event: u8,
    log: Arc<Mutex<Log>>,
}

impl Destination {
    fn answer(&mut self, from: As4Id, m: Message) -> Vec<Message> {
        let mut log = self.log.lock().unwrap();
        match m {
            Message::RequestControl(_) => {
                self.controller = Some(from);
                log.controllers.push((from, true));
                vec![ConfirmControl {
                    response_code: ControlConfirmation::ControlAccepted,
                }
                .into()]
            }
            Message::ReleaseControl(_) => {
                self.controller = None;
                log.controllers.push((from, false));
                vec![RejectControl {
                    response_code: ControlRejection::ControlReleased,
                }
                .into()]
            }
            Message::QueryTimeout(_) => vec![ReportTimeout { timeout: 0 }.into()],
            Message::CreateCommandEvent(c) => {
                let name = embedded::decode(&c.command_message)
                    .map(|m| m.name().to_string())
                    .unwrap_or_else(|e| format!("undecodable: {e}"));
                log.commands.push((name, self.controller == Some(from)));
                self.next_event = self.next_event.wrapping_add(1);
                let event_id = self.next_event;
                vec![
                    ConfirmEventRequest {
                        request_id: c.request_id,
                        event_id,
                        confirmed_periodic_rate: 0.0,
                    }
                    .into(),
                    CommandEvent {
                        event_id,
                        command_result: CommandResult::Successful,
                    }
                    .into(),
                ]
            }
            _ => Vec::new(),
        }
    }
}

impl As4Endpoint<SocketAddr> for Destination {
    fn handle(
        &mut self,
        _now: Instant,
        _from: SocketAddr,
        messages: Vec<As4Message>,
    ) -> Vec<As4Message> {
        let mut out = Vec::new();
        for m in messages {
            let Ok(msg) = Message::decode(jaus::CommandCode(m.message_id), &m.body) else {
                continue;
            };
            for a in self.answer(m.source, msg) {
                let body = a.body().to_bytes().expect("encodes");
                out.push(As4Message::new(a.code().0, m.source, self.id, body));
            }
        }
        out
    }

    fn serves(&self, destination: As4Id) -> bool {
        destination == self.id
    }
}

/// Adds the destination to `net`: its slot, its AS-4 id and what it saw.
fn destination(net: &mut SimNet, t0: Instant) -> (usize, As4Id, Arc<Mutex<Log>>) {
    let id = As4Id::new(2, 1, 1);
    let log = Arc::new(Mutex::new(Log::default()));
    let ra33 = Node::new(
        NodeConfig {
            subsystem: 2,
            node: 1,
            ..NodeConfig::default()
        },
        t0,
    );
    let d = Destination {
        id,
        controller: None,
        next_event: 0,
        log: log.clone(),
    };
    let slot = net.add(As4Mux::new(ra33, d, As4Config::default()));
    (slot, id, log)
}

/// A message of the mission.
fn spooled(uid: u16, to: As4Id, m: Message, blocking: bool) -> SpooledMessage {
    SpooledMessage {
        uid,
        destination_id: address_of(to),
        jaus_message: embedded::encode(&m).expect("encodes"),
        blocking: if blocking {
            MessageBlocking::Blocking
        } else {
            MessageBlocking::NonBlocking
        },
    }
}

struct Rig {
    net: SimNet,
    spooler: usize,
    client: usize,
}

impl Rig {
    fn ask(&mut self, m: impl Into<Message>, wait: Duration) -> Vec<Message> {
        self.ask_of(SPOOLER, m, wait)
    }

    /// `m` to AS-4 component `target` of the spooler's node.
    fn ask_of(&mut self, target: As4Id, m: impl Into<Message>, wait: Duration) -> Vec<Message> {
        let m: Message = m.into();
        let body = m.body().to_bytes().expect("encodes");
        let to = SimNet::addr(self.spooler);
        let c = self.net.get_mut::<As4Client>(self.client).expect("client");
        c.send(to, &[As4Message::new(m.code().0, target, ME, body)]);
        self.net.run_for(wait);
        let c = self.net.get_mut::<As4Client>(self.client).expect("client");
        c.take()
            .into_iter()
            .map(|(_, a)| {
                Message::decode(jaus::CommandCode(a.message_id), &a.body).expect("decodes")
            })
            .collect()
    }
}

#[test]
fn a_mission_spooled_through_as4_runs_on_its_destination() {
    let t0 = Instant::now();
    let mut net = SimNet::new(t0, LinkModel::default(), 5);
    let (dest_slot, dest, log) = destination(&mut net, t0);

    // The spooler's node: its own AS-4 component, knowing where the destination is.
    let spooler_node = {
        let component = As4Component::new(SPOOLER, CoreConfig::named("mission spooler"))
            .with_service(MissionSpoolerService::new(SpoolerConfig {
                command_timeout: Duration::from_secs(5),
                ..SpoolerConfig::default()
            }));
        let mut node: As4Node<()> = As4Node::new(()).with_component(component);
        node.learn_peer(dest, SimNet::addr(dest_slot));
        let ra33 = Node::new(
            NodeConfig {
                subsystem: 1,
                node: 1,
                ..NodeConfig::default()
            },
            t0,
        );
        As4Mux::new(ra33, node, As4Config::default())
    };
    let spooler = net.add(spooler_node);
    let client = net.add(As4Client::<SocketAddr>::default());
    let mut rig = Rig {
        net,
        spooler,
        client,
    };
    rig.net.run_for(Duration::from_millis(200));

    let wait = Duration::from_millis(300);
    let got = rig.ask(RequestControl { authority_code: 10 }, wait);
    assert!(
        got.iter().any(|m| matches!(m, Message::ConfirmControl(c)
            if c.response_code == ControlConfirmation::ControlAccepted)),
        "{got:?}"
    );
    // Root: Resume (blocking); its child: Set Travel Speed (not blocking), Standby
    // (blocking). Run order: Resume, Set Travel Speed, Standby.
    let mission = SpoolMission {
        mission_id: 77,
        source_id: address_of(ME),
        tasks: vec![
            MissionTask {
                task_id: 1,
                messages: vec![spooled(1, dest, Resume {}.into(), true)],
                child_tasks: vec![1],
            },
            MissionTask {
                task_id: 2,
                messages: vec![
                    spooled(2, dest, SetTravelSpeed { speed: 1.5 }.into(), false),
                    spooled(3, dest, Standby {}.into(), true),
                ],
                child_tasks: vec![],
            },
        ],
    };
    rig.ask(mission, wait);
    let got = rig.ask(QueryStoredMissions {}, wait);
    assert!(
        got.iter()
            .any(|m| matches!(m, Message::ReportStoredMissions(s)
            if s.missions.len() == 1 && s.missions[0].mission_id == 77)),
        "{got:?}"
    );
    rig.ask(RunMission::default(), wait);

    // Query the status until Finished.
    let mut finished = false;
    for _ in 0..20 {
        let got = rig.ask(
            QueryMissionStatus {
                mission_id: Some(77),
                ..Default::default()
            },
            wait,
        );
        let status = got.iter().find_map(|m| match m {
            Message::ReportMissionStatus(s) if s.level == MissionStatusLevel::Mission => {
                Some(s.status)
            }
            _ => None,
        });
        if status == Some(MissionState::Finished) {
            finished = true;
            break;
        }
    }
    assert!(
        finished,
        "the mission did not finish: {:?}",
        log.lock().unwrap()
    );

    let log = log.lock().unwrap();
    assert_eq!(
        log.commands,
        vec![
            ("Resume".to_string(), true),
            ("SetTravelSpeed".to_string(), true),
            ("Standby".to_string(), true),
        ]
    );
    // Control taken before the first command, released after the last.
    assert_eq!(log.controllers, vec![(SPOOLER, true), (SPOOLER, false)]);
    // Each message is Finished.
    drop(log);
    for uid in 1..=3 {
        let got = rig.ask(
            QueryMissionStatus {
                mission_id: Some(77),
                message_uid: Some(uid),
                ..Default::default()
            },
            wait,
        );
        assert!(
            got.iter()
                .any(|m| matches!(m, Message::ReportMissionStatus(s)
                if s.id == uid && s.status == MissionState::Finished)),
            "message {uid}: {got:?}"
        );
    }
}

/// A node file hosting the demo vehicle behind its gateway (1.1.1) and a Mission
/// Spooler (`as4: { mission_spooler: … }`, component 1.1.5) on the same socket: a mission
/// spooled through AS-4 drives the simulated vehicle. Its messages (Resume, the local
/// frame, a waypoint list and a blocking Execute List) go to the gateway's component
/// through the node's own socket, each inside a Core v1.1 Create Command Event, under
/// the spooler's control; Execute List's Command Event comes when the vehicle has driven
/// the list, so the mission finishes then, and the vehicle is at the last waypoint; the
/// spooler released control of it.
#[test]
fn a_node_files_spooler_commands_the_vehicle_on_its_own_node() {
    use jaus_as4::gateway::DualNode;
    use jaus_node::NodeFile;

    let dir = std::env::temp_dir().join(format!("jaus-as4-spooler-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("vehicle.yaml");
    // Slot 0 of the simulated network is 10.0.0.1:3794.
    std::fs::write(
        &path,
        "subsystem: 1\nnode: 1\nbind: 10.0.0.1:3794\nhost: [vehicle]\nas4:\n  name: demo vehicle\n  mission_spooler: { command_timeout: 60 }\n",
    )
    .unwrap();
    let file = NodeFile::load(&path).unwrap();
    let t0 = Instant::now();
    let (node, native) = file.build_node_and_as4(&path, t0).unwrap();
    let mut dual = DualNode::new(node, file.as4_config().unwrap()).expect("gateway");
    for s in native {
        dual = dual.with_service(s);
    }
    let spooler = file.as4_mission_spooler(&path).unwrap().expect("a spooler");
    let dual = dual.with_endpoint(spooler);
    let mut net = SimNet::new(t0, LinkModel::default(), 9);
    let slot = net.add(dual);
    assert_eq!(SimNet::addr(slot), file.bind);
    let client = net.add(As4Client::<SocketAddr>::default());
    let mut rig = Rig {
        net,
        spooler: slot,
        client,
    };
    rig.net.run_for(Duration::from_secs(3));
    let vehicle = As4Id::new(1, 1, 1);
    let wait = Duration::from_millis(300);

    rig.ask(RequestControl { authority_code: 10 }, wait);
    let pose = SetLocalPose {
        x: Some(0.0),
        y: Some(0.0),
        yaw: Some(0.0),
        ..Default::default()
    };
    let waypoint = |x: f64, y: f64| -> Message {
        SetLocalWaypoint {
            x,
            y,
            waypoint_tolerance: Some(0.5),
            ..Default::default()
        }
        .into()
    };
    let list = SetElement {
        request_id: 1,
        elements: vec![
            Element::holding(1, 0, 2, &waypoint(4.0, 0.0)).expect("element"),
            Element::holding(2, 1, 0, &waypoint(4.0, 3.0)).expect("element"),
        ],
    };
    let execute = ExecuteList {
        speed: 1.5,
        element_uid: Some(1),
    };
    let mission = SpoolMission {
        mission_id: 5,
        source_id: address_of(ME),
        tasks: vec![MissionTask {
            task_id: 1,
            messages: vec![
                spooled(1, vehicle, Resume {}.into(), true),
                spooled(2, vehicle, pose.into(), true),
                spooled(3, vehicle, list.into(), true),
                spooled(4, vehicle, execute.into(), true),
            ],
            child_tasks: vec![],
        }],
    };
    rig.ask(mission, wait);
    rig.ask(RunMission::default(), wait);
    let mut end = None;
    for _ in 0..60 {
        let got = rig.ask(
            QueryMissionStatus {
                mission_id: Some(5),
                message_uid: Some(4),
                ..Default::default()
            },
            Duration::from_millis(500),
        );
        end = got.iter().find_map(|m| match m {
            Message::ReportMissionStatus(s)
                if matches!(s.status, MissionState::Finished | MissionState::Aborted) =>
            {
                Some(s.status)
            }
            _ => None,
        });
        if end.is_some() {
            break;
        }
    }
    let end = end.expect("Execute List ended");
    assert_eq!(end, MissionState::Finished, "Execute List");
    let dual = rig.net.get::<DualNode>(slot).expect("node");
    let component = dual.gateway().component().expect("the gateway's component");
    assert_eq!(component.controller(), None, "control released");
    // Where the simulated vehicle is, in the frame the mission set.
    let got = rig.ask_of(
        vehicle,
        QueryLocalPose {
            presence_vector: 0x0003,
        },
        wait,
    );
    let Some(Message::ReportLocalPose(p)) = got.first() else {
        panic!("no Report Local Pose: {got:?}");
    };
    let (x, y) = (p.x.expect("x"), p.y.expect("y"));
    assert!(
        (x - 4.0).hypot(y - 3.0) < 1.0,
        "the vehicle ended at ({x:.2}, {y:.2})"
    );
    let got = rig.ask(
        QueryMissionStatus {
            mission_id: Some(5),
            ..Default::default()
        },
        wait,
    );
    assert!(
        got.iter()
            .any(|m| matches!(m, Message::ReportMissionStatus(s)
            if s.level == MissionStatusLevel::Mission && s.status == MissionState::Finished)),
        "{got:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
