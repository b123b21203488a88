//! The RA 3.3 ↔ AS-4 gateway over the simulated network: an AS-4 client (ours: an
//! `As4Client` on SimNet) drives the demo's RA 3.3 vehicle, hosted by a node that answers
//! both generations on one socket (`jaus_as4::gateway::DualNode`), to its waypoints
//! through the AS-4 Local Waypoint List Driver, and the vehicle must actually arrive
//! (its pose from the simulated vehicle, not from the gateway).

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::as5669a::{As4Client, As4Id, As4Message};
use jaus::net::NodeConfig;
use jaus::{Address, JausMessage};
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::{
    ComponentState, ControlConfirmation, DeleteElement, Element, ExecuteList, Message,
    NodeServicesQuery, QueryActiveElement, QueryControl, QueryGlobalPathSegment, QueryGlobalPose,
    QueryLocalPathSegment, QueryLocalPose, QueryServices, QueryStatus, QueryTravelSpeed,
    QueryVelocityState, RequestControl, Resume, SetElement, SetGlobalPathSegment,
    SetLocalPathSegment, SetLocalPose, SetLocalWaypoint, Standby,
};
use jaus_sim::network::{LinkModel, SimNet};

const ME: As4Id = As4Id::new(42, 1, 1);
const VEHICLE: As4Id = As4Id::new(1, 1, 1);

struct Judge {
    net: SimNet,
    client: usize,
    vehicle: usize,
}

impl Judge {
    fn new() -> Self {
        let t0 = Instant::now();
        let node = jaus_sim::demo::vehicle_node(t0, NodeConfig::default(), 1, 1).unwrap();
        Self::with_node(t0, node)
    }

    /// The gateway in front of `node` (subsystem 1, node 1), as the node's component 60.
    fn with_node(t0: Instant, node: jaus::net::Node) -> Self {
        let mut net = SimNet::new(t0, LinkModel::default(), 7);
        let config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "demo vehicle");
        let vehicle = net.add(DualNode::new(node, config).unwrap());
        let client = net.add(As4Client::<SocketAddr>::default());
        // The vehicle's node settles (its components come up, the gateway finds them).
        net.run_for(Duration::from_secs(2));
        Judge {
            net,
            client,
            vehicle,
        }
    }

    fn send(&mut self, m: impl Into<Message>) {
        let m: Message = m.into();
        let body = m.body().to_bytes().unwrap();
        let to = SimNet::addr(self.vehicle);
        let c = self.net.get_mut::<As4Client>(self.client).unwrap();
        c.send(to, &[As4Message::new(m.code().0, VEHICLE, ME, body)]);
    }

    /// Sends `m`, runs the network for `wait`, returns what came back (decoded).
    fn ask(&mut self, m: impl Into<Message>, wait: Duration) -> Vec<Message> {
        self.send(m);
        self.net.run_for(wait);
        let c = self.net.get_mut::<As4Client>(self.client).unwrap();
        c.take()
            .into_iter()
            .map(|(_, a)| Message::decode(jaus::CommandCode(a.message_id), &a.body).unwrap())
            .collect()
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        let got = self.ask(m, Duration::from_millis(300));
        assert_eq!(got.len(), 1, "one answer expected, got {got:?}");
        got.into_iter().next().unwrap()
    }

    /// The vehicle's speed as the RA 3.3 velocity state sensor last reported it to the
    /// gateway.
    fn true_speed(&self) -> f64 {
        let dual = self.net.get::<DualNode>(self.vehicle).unwrap();
        let g = dual.gateway();
        let vss = g.node().env().targets().velocity_state_sensor.unwrap();
        match g
            .node()
            .env()
            .latest(vss, jaus::messages::ReportVelocityState::CODE)
        {
            Some((_, jaus::messages::Message::ReportVelocityState(r))) => r
                .velocity_x
                .unwrap_or(0.0)
                .hypot(r.velocity_y.unwrap_or(0.0)),
            _ => 0.0,
        }
    }
}

fn waypoint(x: f64, y: f64) -> Message {
    SetLocalWaypoint {
        x,
        y,
        waypoint_tolerance: Some(0.5),
        ..Default::default()
    }
    .into()
}

#[test]
fn an_as4_client_drives_the_ra33_vehicle_through_the_gateway_to_its_waypoints() {
    let mut j = Judge::new();
    // The gateway is an RA 3.3 component of the node too, named in the system tree.
    let dual = j.net.get::<DualNode>(j.vehicle).unwrap();
    let info = dual
        .node()
        .tree()
        .component(Address::new(1, 1, 60, 1))
        .cloned();
    assert_eq!(
        info.and_then(|c| c.name).as_deref(),
        Some(jaus_as4::gateway::ra33::IDENTIFICATION)
    );

    // Discovery: the Mobility services of the RA 3.3 components the node hosts.
    let Message::ReportServices(r) = j.one(QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    }) else {
        panic!("Report Services expected")
    };
    let uris: Vec<&str> = r
        .nodes
        .iter()
        .flat_map(|n| &n.components)
        .flat_map(|c| &c.services)
        .map(|s| s.uri.as_str())
        .collect();
    for want in [
        "urn:jaus:jss:core:AccessControl",
        "urn:jaus:jss:core:Management",
        "urn:jaus:jss:core:ListManager",
        "urn:jaus:jss:mobility:VelocityStateSensor",
        "urn:jaus:jss:mobility:LocalPoseSensor",
        "urn:jaus:jss:mobility:GlobalPoseSensor",
        "urn:jaus:jss:mobility:PrimitiveDriver",
        "urn:jaus:jss:mobility:LocalWaypointListDriver",
        "urn:jaus:jss:mobility:GlobalWaypointListDriver",
    ] {
        assert!(uris.contains(&want), "{want} not in {uris:?}");
    }

    // Control, then Ready.
    let Message::ConfirmControl(c) = j.one(RequestControl { authority_code: 10 }) else {
        panic!("Confirm Control expected")
    };
    assert_eq!(c.response_code, ControlConfirmation::ControlAccepted);
    let Message::ReportControl(rc) = j.one(QueryControl {}) else {
        panic!("Report Control expected")
    };
    assert_eq!(
        (
            rc.controller.subsystem_id,
            rc.controller.node_id,
            rc.controller.component_id
        ),
        (42, 1, 1)
    );
    assert!(j.ask(Resume {}, Duration::from_millis(500)).is_empty());
    let Message::ReportStatus(s) = j.one(QueryStatus {}) else {
        panic!("Report Status expected")
    };
    assert_eq!(s.status, ComponentState::Ready);

    // The AS-4 local frame: the vehicle is at (10, 20) facing +X.
    assert!(j
        .ask(
            SetLocalPose {
                x: Some(10.0),
                y: Some(20.0),
                yaw: Some(0.0),
                ..Default::default()
            },
            Duration::from_millis(300)
        )
        .is_empty());
    let Message::ReportLocalPose(p) = j.one(QueryLocalPose {
        presence_vector: 0x0043,
    }) else {
        panic!("Report Local Pose expected")
    };
    assert!(
        (p.x.unwrap() - 10.0).abs() < 0.05 && (p.y.unwrap() - 20.0).abs() < 0.05,
        "{p:?}"
    );
    assert!(
        p.z.is_none() && p.time_stamp.is_none(),
        "only x, y, yaw asked for: {p:?}"
    );

    // Two waypoints in the AS-4 frame, 4 m ahead then 3 m to the left of that.
    let elements = vec![
        Element::holding(1, 0, 2, &waypoint(14.0, 20.0)).unwrap(),
        Element::holding(2, 1, 0, &waypoint(14.0, 23.0)).unwrap(),
    ];
    let Message::ConfirmElementRequest(ok) = j.one(SetElement {
        request_id: 5,
        elements,
    }) else {
        panic!("Confirm Element Request expected")
    };
    assert_eq!(ok.request_id, 5);
    // Nothing moves before Execute List.
    j.net.run_for(Duration::from_secs(1));
    assert!(j.true_speed() < 0.01, "moving before Execute List");

    assert!(j
        .ask(
            ExecuteList {
                speed: 1.0,
                element_uid: Some(1),
            },
            Duration::from_millis(300)
        )
        .is_empty());
    let mut active = Vec::new();
    for _ in 0..120 {
        let Message::ReportActiveElement(a) = j.one(QueryActiveElement {}) else {
            panic!("Report Active Element expected")
        };
        active.push(a.element_uid);
        if a.element_uid == 0 {
            break;
        }
        j.net.run_for(Duration::from_millis(500));
    }
    assert_eq!(active.first(), Some(&1), "{active:?}");
    assert!(
        active.contains(&2),
        "the second element was never active: {active:?}"
    );
    assert_eq!(
        active.last(),
        Some(&0),
        "the list did not finish: {active:?}"
    );

    // Where the vehicle really is, in the AS-4 frame.
    let Message::ReportLocalPose(p) = j.one(QueryLocalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Local Pose expected")
    };
    let (x, y) = (p.x.unwrap(), p.y.unwrap());
    assert!(
        (x - 14.0).hypot(y - 23.0) < 1.0,
        "ended at ({x:.2}, {y:.2})"
    );
    let Message::ReportVelocityState(v) = j.one(QueryVelocityState {
        presence_vector: 0x0140,
    }) else {
        panic!("Report Velocity State expected")
    };
    assert!(v.yaw_rate.is_some() && v.velocity_x.is_none(), "{v:?}");

    // Standby stops the RA 3.3 drivers too.
    assert!(j.ask(Standby {}, Duration::from_millis(500)).is_empty());
    let Message::ReportStatus(s) = j.one(QueryStatus {}) else {
        panic!("Report Status expected")
    };
    assert_eq!(s.status, ComponentState::Standby);
}

impl Judge {
    /// Control, Resume: the AS-4 component Ready.
    fn take_and_resume(&mut self) {
        let Message::ConfirmControl(c) = self.one(RequestControl { authority_code: 10 }) else {
            panic!("Confirm Control expected")
        };
        assert_eq!(c.response_code, ControlConfirmation::ControlAccepted);
        assert!(self.ask(Resume {}, Duration::from_millis(500)).is_empty());
    }

    /// Executes the list from UID 1 at `speed` and follows Query Active Element every
    /// 500 ms until it is 0; `each` sees each element as it becomes active (and may ask
    /// more: the element has just begun, it is still active).
    fn drive(&mut self, speed: f64, mut each: impl FnMut(&mut Self, u16)) -> Vec<u16> {
        assert!(self
            .ask(
                ExecuteList {
                    speed,
                    element_uid: Some(1),
                },
                Duration::from_millis(300)
            )
            .is_empty());
        let mut active = Vec::new();
        for _ in 0..120 {
            let Message::ReportActiveElement(a) = self.one(QueryActiveElement {}) else {
                panic!("Report Active Element expected")
            };
            active.push(a.element_uid);
            if a.element_uid == 0 {
                break;
            }
            if active.len() < 2 || active[active.len() - 2] != a.element_uid {
                each(self, a.element_uid);
            }
            self.net.run_for(Duration::from_millis(500));
        }
        active
    }
}

fn local_segment(p1: (f64, f64), p2: (f64, f64), w1: f64) -> SetLocalPathSegment {
    SetLocalPathSegment {
        p1_x: p1.0,
        p1_y: p1.1,
        p2_x: p2.0,
        p2_y: p2.1,
        weighting_factor: w1,
        path_tolerance: Some(0.5),
        ..Default::default()
    }
}

#[test]
fn an_as4_client_drives_the_ra33_vehicle_along_path_segments_through_the_gateway() {
    // RUST_LOG=jaus_as4=debug shows what crosses.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .with_test_writer()
        .try_init();
    let mut j = Judge::new();
    let Message::ReportServices(r) = j.one(QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    }) else {
        panic!("Report Services expected")
    };
    let uris: Vec<&str> = r
        .nodes
        .iter()
        .flat_map(|n| &n.components)
        .flat_map(|c| &c.services)
        .map(|s| s.uri.as_str())
        .collect();
    for want in [
        "urn:jaus:jss:mobility:LocalPathSegmentDriver",
        "urn:jaus:jss:mobility:GlobalPathSegmentDriver",
    ] {
        assert!(uris.contains(&want), "{want} not in {uris:?}");
    }
    j.take_and_resume();

    // The AS-4 local frame: the vehicle (facing RA 3.3 +X) at (10, 20) facing +Y, so
    // that every point crosses a rotation on its way to the RA 3.3 driver.
    let quarter = std::f64::consts::FRAC_PI_2;
    assert!(j
        .ask(
            SetLocalPose {
                x: Some(10.0),
                y: Some(20.0),
                yaw: Some(quarter),
                ..Default::default()
            },
            Duration::from_millis(300)
        )
        .is_empty());

    // 4 m straight ahead, then a left curve through (10, 27) to (7, 27).
    let segments = [
        local_segment((10.0, 22.0), (10.0, 24.0), 0.0),
        local_segment((10.0, 27.0), (7.0, 27.0), 1.0),
    ];
    let elements = vec![
        Element::holding(1, 0, 2, &segments[0].clone().into()).unwrap(),
        Element::holding(2, 1, 0, &segments[1].clone().into()).unwrap(),
    ];
    let Message::ConfirmElementRequest(ok) = j.one(SetElement {
        request_id: 7,
        elements,
    }) else {
        panic!("Confirm Element Request expected")
    };
    assert_eq!(ok.request_id, 7);
    j.net.run_for(Duration::from_secs(1));
    assert!(j.true_speed() < 0.01, "moving before Execute List");

    let mut answered = Vec::new();
    let active = j.drive(1.0, |j, uid| {
        // The active element's segment, as the client set it (AS-4 frame).
        let Message::ReportLocalPathSegment(r) = j.one(QueryLocalPathSegment {
            presence_vector: 0x07,
        }) else {
            panic!("Report Local Path Segment expected")
        };
        let want = &segments[usize::from(uid) - 1];
        assert!(
            (r.p2_x - want.p2_x).abs() < 1e-3
                && (r.p2_y - want.p2_y).abs() < 1e-3
                && (r.p1_x - want.p1_x).abs() < 1e-3
                && (r.weighting_factor - want.weighting_factor).abs() < 1e-2
                && r.path_tolerance.is_some(),
            "element {uid}: {r:?}"
        );
        answered.push(uid);
    });
    assert_eq!(active.first(), Some(&1), "{active:?}");
    assert!(
        active.contains(&2),
        "the second element was never active: {active:?}"
    );
    assert_eq!(
        active.last(),
        Some(&0),
        "the list did not finish: {active:?}"
    );
    assert!(
        answered.contains(&1) && answered.contains(&2),
        "{answered:?}"
    );
    let Message::ReportLocalPose(p) = j.one(QueryLocalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Local Pose expected")
    };
    let (x, y) = (p.x.unwrap(), p.y.unwrap());
    assert!((x - 7.0).hypot(y - 27.0) < 1.0, "ended at ({x:.2}, {y:.2})");
    eprintln!("local segments: active {active:?}, ended at ({x:.2}, {y:.2})");

    // One global segment, 6 m north of where the vehicle is now, straight.
    let Message::ReportGlobalPose(g) = j.one(QueryGlobalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Global Pose expected")
    };
    let (lat, lon) = (g.latitude.unwrap(), g.longitude.unwrap());
    let north = (6.0 / 6_371_000.0_f64).to_degrees();
    let segment: Message = SetGlobalPathSegment {
        p1_latitude: lat + north / 2.0,
        p1_longitude: lon,
        p2_latitude: lat + north,
        p2_longitude: lon,
        weighting_factor: 0.0,
        ..Default::default()
    }
    .into();
    assert!(matches!(
        j.one(DeleteElement {
            request_id: 8,
            element_uids: vec![jaus_as4::core::lists::DELETE_ALL],
        }),
        Message::ConfirmElementRequest(_)
    ));
    assert!(matches!(
        j.one(SetElement {
            request_id: 9,
            elements: vec![Element::holding(1, 0, 0, &segment).unwrap()],
        }),
        Message::ConfirmElementRequest(_)
    ));
    let active = j.drive(1.0, |j, _| {
        let Message::ReportGlobalPathSegment(r) =
            j.one(QueryGlobalPathSegment { presence_vector: 0 })
        else {
            panic!("Report Global Path Segment expected")
        };
        assert!((r.p2_latitude - (lat + north)).abs() < 1e-6, "{r:?}");
    });
    assert_eq!(active.first(), Some(&1), "{active:?}");
    assert_eq!(active.last(), Some(&0), "{active:?}");
    let Message::ReportGlobalPose(g) = j.one(QueryGlobalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Global Pose expected")
    };
    let off = (g.latitude.unwrap() - (lat + north)).to_radians() * 6_371_000.0;
    let east = (g.longitude.unwrap() - lon).to_radians() * 6_371_000.0 * lat.to_radians().cos();
    assert!(
        off.hypot(east) < 1.0,
        "ended {off:.2} m north, {east:.2} m east of P2"
    );

    // The same segment run again, left mid-way by Standby: the exit action of Ready
    // (`resetTravelSpeed`, run as the driver's machine follows the Core out of Ready)
    // ends the run: no active element, travel speed 0. A segment 6 m further north.
    let further: Message = SetGlobalPathSegment {
        p1_latitude: lat + north * 1.5,
        p1_longitude: lon,
        p2_latitude: lat + north * 2.0,
        p2_longitude: lon,
        weighting_factor: 0.0,
        ..Default::default()
    }
    .into();
    assert!(matches!(
        j.one(DeleteElement {
            request_id: 10,
            element_uids: vec![jaus_as4::core::lists::DELETE_ALL],
        }),
        Message::ConfirmElementRequest(_)
    ));
    assert!(matches!(
        j.one(SetElement {
            request_id: 11,
            elements: vec![Element::holding(1, 0, 0, &further).unwrap()],
        }),
        Message::ConfirmElementRequest(_)
    ));
    assert!(j
        .ask(
            ExecuteList {
                speed: 1.0,
                element_uid: Some(1),
            },
            Duration::from_millis(300)
        )
        .is_empty());
    let Message::ReportActiveElement(a) = j.one(QueryActiveElement {}) else {
        panic!("Report Active Element expected")
    };
    assert_eq!(a.element_uid, 1, "the run did not start");
    let Message::ReportTravelSpeed(v) = j.one(QueryTravelSpeed {}) else {
        panic!("Report Travel Speed expected")
    };
    assert!((v.speed - 1.0).abs() < 0.01, "{v:?}");
    assert!(j.ask(Standby {}, Duration::from_millis(300)).is_empty());
    let Message::ReportActiveElement(a) = j.one(QueryActiveElement {}) else {
        panic!("Report Active Element expected")
    };
    assert_eq!(a.element_uid, 0, "Standby left the run going");
    let Message::ReportTravelSpeed(v) = j.one(QueryTravelSpeed {}) else {
        panic!("Report Travel Speed expected")
    };
    assert_eq!(v.speed, 0.0);
}

/// The services listed by Report Services.
fn service_uris(j: &mut Judge) -> Vec<String> {
    let Message::ReportServices(r) = j.one(QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    }) else {
        panic!("Report Services expected")
    };
    r.nodes
        .iter()
        .flat_map(|n| &n.components)
        .flat_map(|c| &c.services)
        .map(|s| s.uri.clone())
        .collect()
}

#[test]
fn a_subsystem_with_only_global_services_gets_local_ones_over_them() {
    // As OpenJAUS 3.3's vehicle simulator: a Global Pose Sensor and a Global Waypoint
    // Driver, no Local Pose Sensor, no Local Waypoint Driver.
    let t0 = Instant::now();
    let mut node = jaus::net::Node::new(
        NodeConfig {
            subsystem: 1,
            node: 1,
            ..NodeConfig::default()
        },
        t0,
    );
    let mut host = jaus_node::host::Host::new(1, 1, t0);
    for name in [
        "primitive_driver",
        "global_pose_sensor",
        "velocity_state_sensor",
        "global_waypoint_driver",
    ] {
        let stock = jaus_node::host::Stock::by_name(name).unwrap();
        node.add_boxed(host.build(&jaus_node::host::Host::entry(stock)).unwrap())
            .unwrap();
    }
    let mut j = Judge::with_node(t0, node);
    let uris = service_uris(&mut j);
    for want in [
        "urn:jaus:jss:mobility:LocalPoseSensor",
        "urn:jaus:jss:mobility:LocalWaypointListDriver",
        "urn:jaus:jss:mobility:GlobalPoseSensor",
        "urn:jaus:jss:mobility:GlobalWaypointListDriver",
    ] {
        assert_eq!(
            uris.iter().filter(|u| *u == want).count(),
            1,
            "{want} once in {uris:?}"
        );
    }
    j.take_and_resume();
    // The local frame is placed: the vehicle at (10, 20) facing +X.
    assert!(j
        .ask(
            SetLocalPose {
                x: Some(10.0),
                y: Some(20.0),
                yaw: Some(0.0),
                ..Default::default()
            },
            Duration::from_millis(300)
        )
        .is_empty());
    let Message::ReportLocalPose(p) = j.one(QueryLocalPose {
        presence_vector: 0x0043,
    }) else {
        panic!("Report Local Pose expected")
    };
    assert!(
        (p.x.unwrap() - 10.0).abs() < 0.05 && (p.y.unwrap() - 20.0).abs() < 0.05,
        "{p:?}"
    );
    let Message::ReportGlobalPose(g0) = j.one(QueryGlobalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Global Pose expected")
    };
    // Two local waypoints: 6 m ahead, then 4 m to the left of that.
    let elements = vec![
        Element::holding(1, 0, 2, &waypoint(16.0, 20.0)).unwrap(),
        Element::holding(2, 1, 0, &waypoint(16.0, 24.0)).unwrap(),
    ];
    let Message::ConfirmElementRequest(ok) = j.one(SetElement {
        request_id: 9,
        elements,
    }) else {
        panic!("Confirm Element Request expected")
    };
    assert_eq!(ok.request_id, 9);
    let active = j.drive(1.5, |_, _| {});
    assert_eq!(active.first(), Some(&1), "{active:?}");
    assert!(active.contains(&2), "{active:?}");
    assert_eq!(active.last(), Some(&0), "{active:?}");
    // Where the vehicle is, in the AS-4 frame and in degrees: 6 m and 4 m from where it
    // started, which the global pose shows as well (the frame is not just a relabelling).
    let Message::ReportLocalPose(p) = j.one(QueryLocalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Local Pose expected")
    };
    let (x, y) = (p.x.unwrap(), p.y.unwrap());
    assert!(
        (x - 16.0).hypot(y - 24.0) < 1.0,
        "ended at ({x:.2}, {y:.2})"
    );
    let Message::ReportGlobalPose(g1) = j.one(QueryGlobalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Global Pose expected")
    };
    let frame = jaus::stock::geo::LocalFrame::new(g0.latitude.unwrap(), g0.longitude.unwrap(), 0.0);
    let moved = frame.to_local(g1.latitude.unwrap(), g1.longitude.unwrap());
    assert!(
        (moved.norm() - 6f64.hypot(4.0)).abs() < 1.0,
        "moved {moved:?} on the globe"
    );
}

/// An RA 3.3 Primitive Driver that never answers Query Wrench Effort (OpenJAUS 3.3's)
/// until told to: it counts the queries it receives, and answers Query Identification
/// and Query Services like any component.
#[derive(Debug)]
struct Mute {
    me: Address,
    answers: bool,
    queried: Vec<Instant>,
    out: std::collections::VecDeque<jaus::component::Outgoing>,
}

impl Mute {
    fn new(me: Address) -> Self {
        Self {
            me,
            answers: false,
            queried: Vec::new(),
            out: std::collections::VecDeque::new(),
        }
    }

    fn reply(&mut self, to: Address, m: jaus::messages::Message) {
        self.out.push_back(jaus::component::Outgoing {
            header: jaus::wire::Header::new(m.code(), to, self.me),
            name: m.name(),
            body: m.to_bytes(),
        });
    }
}

impl jaus::component::Endpoint for Mute {
    fn address(&self) -> Address {
        self.me
    }

    fn handle(&mut self, now: Instant, header: &jaus::wire::Header, body: &[u8]) {
        use jaus::messages as ra;
        let Ok(m) = ra::Message::decode(header.command_code, body) else {
            return;
        };
        let to = header.source;
        match m {
            ra::Message::QueryWrenchEffort(_) => {
                self.queried.push(now);
                if self.answers {
                    self.reply(to, ra::ReportWrenchEffort::default().into());
                }
            }
            ra::Message::QueryIdentification(q) => self.reply(
                to,
                ra::ReportIdentification {
                    query_type: q.query_field,
                    authority: 0,
                    identification_type: 0,
                    identification: "mute primitive driver".into(),
                }
                .into(),
            ),
            ra::Message::QueryServices(_) => self.reply(
                to,
                ra::ReportServices {
                    services: vec![ra::JausService {
                        service_type: 33,
                        input_commands: vec![],
                        output_commands: vec![],
                    }],
                }
                .into(),
            ),
            _ => {}
        }
    }

    fn handle_timeout(&mut self, _now: Instant) {}

    fn poll_transmit(&mut self) -> Option<jaus::component::Outgoing> {
        self.out.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        None
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

const GATEWAY_RA33: Address = Address::new(1, 1, 60, 1);
const MUTE: Address = Address::new(1, 1, 33, 1);

fn mute(j: &Judge) -> &Mute {
    j.net
        .get::<DualNode>(j.vehicle)
        .unwrap()
        .node()
        .get::<Mute>(MUTE)
        .unwrap()
}

fn ra33_stats(j: &Judge) -> jaus_as4::ra33::Ra33Stats {
    let dual = j.net.get::<DualNode>(j.vehicle).unwrap();
    dual.gateway().node().env().stats()
}

#[test]
fn a_query_never_answered_is_asked_less_and_less_then_no_more_until_answered() {
    use jaus_as4::ra33::{BACKOFF_AFTER, GIVE_UP_AFTER};
    let t0 = Instant::now();
    let mut node = jaus::net::Node::new(NodeConfig::default(), t0);
    node.add(Mute::new(MUTE)).unwrap();
    let mut j = Judge::with_node(t0, node);
    // The gateway offers the AS-4 Primitive Driver over it and polls it.
    assert!(service_uris(&mut j).contains(&"urn:jaus:jss:mobility:PrimitiveDriver".to_string()));

    // Ten simulated minutes.
    j.net.run_for(Duration::from_secs(600));
    let polls = mute(&j).queried.clone();
    assert_eq!(polls.len(), GIVE_UP_AFTER as usize, "{polls:?}");
    let gaps: Vec<Duration> = polls.windows(2).map(|w| w[1] - w[0]).collect();
    let period = Duration::from_millis(100);
    // At the period while BACKOFF_AFTER polls are unanswered, then doubling each time.
    let mut want = Vec::new();
    let mut every = period;
    for n in 1..GIVE_UP_AFTER {
        if n > BACKOFF_AFTER {
            every *= 2;
        }
        want.push(every);
    }
    assert_eq!(gaps, want, "the gaps between the polls");
    // All within 13 s of the first (0.1 * 3 + 0.2 + ... + 6.4 = 12.9 s): nothing after.
    assert!(polls[polls.len() - 1] - polls[0] <= Duration::from_millis(12_900));
    let stats = ra33_stats(&j);
    assert_eq!(stats.polls_sent, u64::from(GIVE_UP_AFTER), "{stats:?}");
    assert_eq!(
        stats.polls_unanswered,
        u64::from(GIVE_UP_AFTER),
        "{stats:?}"
    );
    assert_eq!(stats.polls_given_up, 1, "{stats:?}");
    assert_eq!(stats.polls_resumed, 0, "{stats:?}");
    let dual = j.net.get::<DualNode>(j.vehicle).unwrap();
    assert_eq!(
        dual.gateway().node().env().polls_given_up(),
        vec![(MUTE, jaus::messages::QueryWrenchEffort::CODE)]
    );

    // The driver answers after all: it reports its efforts once (unasked), and answers
    // every query from now on.
    let now = j.net.now();
    let dual = j.net.get_mut::<DualNode>(j.vehicle).unwrap();
    dual.node_mut().get_mut::<Mute>(MUTE).unwrap().answers = true;
    let report: jaus::messages::Message = jaus::messages::ReportWrenchEffort::default().into();
    dual.node_mut().send(
        now,
        jaus::wire::Header::new(report.code(), GATEWAY_RA33, MUTE),
        report.to_bytes().unwrap(),
    );
    j.net.run_for(Duration::from_secs(10));
    let resumed = &mute(&j).queried[GIVE_UP_AFTER as usize..];
    // Polled at the period again for 10 s: 100 polls, give or take the edges.
    assert!(
        (99..=101).contains(&resumed.len()),
        "{} polls in 10 s after the answer",
        resumed.len()
    );
    assert!(
        resumed.windows(2).all(|w| w[1] - w[0] == period),
        "{resumed:?}"
    );
    let stats = ra33_stats(&j);
    assert_eq!(stats.polls_given_up, 1, "{stats:?}");
    assert_eq!(stats.polls_resumed, 1, "{stats:?}");
    assert_eq!(
        stats.polls_sent,
        u64::from(GIVE_UP_AFTER) + resumed.len() as u64
    );
    assert_eq!(
        stats.polls_unanswered,
        u64::from(GIVE_UP_AFTER),
        "{stats:?}"
    );
    let dual = j.net.get::<DualNode>(j.vehicle).unwrap();
    assert!(dual.gateway().node().env().polls_given_up().is_empty());
}

#[test]
fn the_gateways_ra33_component_answers_query_services() {
    use jaus::component::local::Probe;
    use jaus::messages as ra;
    let mut j = Judge::new();
    // An RA 3.3 client on another node (as OpenJAUS's node manager across the network).
    let t0 = j.net.now();
    let mut other = jaus::net::Node::new(
        NodeConfig {
            subsystem: 1,
            node: 2,
            peers: vec![SimNet::addr(j.vehicle)],
            ..NodeConfig::default()
        },
        t0,
    );
    let probe = Address::new(1, 2, 200, 1);
    other.add(Probe::new(probe)).unwrap();
    let other = j.net.add(other);
    j.net.run_for(Duration::from_secs(3));
    let now = j.net.now();
    j.net.node_mut(other).unwrap().send(
        now,
        jaus::wire::Header::new(ra::QueryServices::CODE, GATEWAY_RA33, probe),
        Vec::new(),
    );
    j.net.run_for(Duration::from_secs(1));
    let p: &Probe = j.net.node(other).unwrap().get(probe).unwrap();
    let reports: Vec<&ra::ReportServices> = p
        .received()
        .iter()
        .filter(|r| r.header.source == GATEWAY_RA33)
        .filter_map(|r| match &r.message {
            ra::Message::ReportServices(s) => Some(s),
            _ => None,
        })
        .collect();
    assert_eq!(reports.len(), 1, "{:?}", p.received());
    let core = &reports[0].services;
    assert_eq!(core.len(), 1, "{core:?}");
    assert_eq!(core[0].service_type, 0);
    let inputs: Vec<u16> = core[0]
        .input_commands
        .iter()
        .map(|c| c.command_code)
        .collect();
    let outputs: Vec<u16> = core[0]
        .output_commands
        .iter()
        .map(|c| c.command_code)
        .collect();
    for want in [ra::QueryServices::CODE, ra::QueryIdentification::CODE] {
        assert!(inputs.contains(&want.0), "{want:?} not in {inputs:?}");
    }
    // What it polls the vehicle's components with, and the reports that answer them.
    assert!(inputs.contains(&ra::ReportGlobalPose::CODE.0), "{inputs:?}");
    for want in [ra::ReportServices::CODE, ra::QueryGlobalPose::CODE] {
        assert!(outputs.contains(&want.0), "{want:?} not in {outputs:?}");
    }
    // Both node managers list it with the core service: they asked too, and were answered.
    for node in [j.vehicle, other] {
        let tree = match j.net.get::<DualNode>(node) {
            Some(d) => d.node().tree().clone(),
            None => j.net.node(node).unwrap().tree().clone(),
        };
        let info = tree.component(GATEWAY_RA33).cloned().unwrap_or_default();
        assert_eq!(info.services, Some(vec![0]), "{}", tree.render());
        assert!(info.inputs.contains(&ra::QueryServices::CODE.0), "{info:?}");
    }
}
