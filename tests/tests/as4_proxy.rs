//! The other direction of the gateway over the simulated network: an AS-4 vehicle (the
//! demo's vehicle behind our gateway, `DualNode`, RA 3.3 subsystem 1) reached only over
//! AS5669A by a node of RA 3.3 subsystem 2 hosting `jaus_as4::proxy` (its RA 3.3
//! components presenting the vehicle's Mobility services); an RA 3.3 operator (the
//! console's logic, `jaus::stock::commander::Station`, subsystem 200, peered with the
//! proxy node only) takes control of the proxy's Global Waypoint Driver, sends two
//! waypoints with Resume and a speed, and the simulated vehicle must arrive (its pose
//! read on the vehicle's own node). Then an AS-4 client of higher authority takes the
//! vehicle: the operator gets Reject Component Control, and its next request is refused.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::component::Component;
use jaus::component::Config;
use jaus::components::system_commander;
use jaus::net::as5669a::{As4Client, As4Config, As4Id, As4Message, As4Mux};
use jaus::net::{Node, NodeConfig, SystemTree};
use jaus::stock::commander::view::{ComponentView, SystemView};
use jaus::stock::commander::{Command, GeoPoint, Station, StationConfig, TreeInput};
use jaus::{Address, JausMessage};
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::proxy::shared::{lock, SharedRef};
use jaus_as4::proxy::{install, ProxyConfig, ProxyStats, Role};
use jaus_sim::network::{LinkModel, SimNet};

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const PROXY: As4Id = As4Id::new(2, 1, 200);
const RIVAL: As4Id = As4Id::new(42, 1, 1);
const STATION: Address = Address::new(200, 1, 40, 1);
const GWD: Address = Address::new(2, 1, 45, 1);

type Hosted = Component<system_commander::Dispatch<Station>>;

fn tree_input(tree: &SystemTree) -> TreeInput {
    let mut t = TreeInput::default();
    for (ss, s) in &tree.subsystems {
        t.subsystems.insert(*ss, s.name.clone());
        for (n, node) in &s.nodes {
            t.nodes.insert((*ss, *n), node.name.clone());
            for ((c, i), info) in &node.components {
                t.components
                    .insert(Address::new(*ss, *n, *c, *i), info.name.clone());
            }
        }
    }
    t
}

struct Rig {
    net: SimNet,
    vehicle: usize,
    operator: usize,
    rival: usize,
    /// The proxy's shared state (its counters, the latest reports).
    proxy: SharedRef,
}

impl Rig {
    fn new() -> Self {
        let t0 = Instant::now();
        let mut net = SimNet::new(t0, LinkModel::default(), 11);
        let vehicle = net.add(Self::vehicle_node(t0));
        let mut pnode: Node = Node::new(
            NodeConfig {
                subsystem: 2,
                node: 1,
                ..NodeConfig::default()
            },
            t0,
        );
        let proxy = install(
            &mut pnode,
            ProxyConfig::new(PROXY, None),
            SimNet::addr(vehicle),
            t0,
        )
        .unwrap();
        let shared = proxy.shared();
        let p = net.add(As4Mux::new(pnode, proxy, As4Config::default()));
        let mut onode: Node = Node::new(
            NodeConfig {
                subsystem: 200,
                node: 1,
                peers: vec![SimNet::addr(p)],
                ..NodeConfig::default()
            },
            t0,
        );
        onode
            .add(system_commander::component(
                STATION,
                Station::new(StationConfig::default()),
                Config::default(),
                t0,
            ))
            .unwrap();
        let operator = net.add(onode);
        let rival = net.add(As4Client::<SocketAddr>::default());
        Rig {
            net,
            vehicle,
            operator,
            rival,
            proxy: shared,
        }
    }

    /// The vehicle's node: the demo vehicle with its gateway (AS-4 component
    /// `VEHICLE`).
    fn vehicle_node(t0: Instant) -> DualNode {
        Self::vehicle_node_with(t0, |_| {})
    }

    /// [`vehicle_node`](Self::vehicle_node) with its gateway's settings changed by `f`.
    fn vehicle_node_with(t0: Instant, f: impl FnOnce(&mut GatewayConfig)) -> DualNode {
        let node = jaus_sim::demo::vehicle_node(t0, NodeConfig::default(), 1, 1).unwrap();
        let mut config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "demo vehicle");
        f(&mut config);
        DualNode::new(node, config).unwrap()
    }

    /// The proxy's counters.
    fn proxy_stats(&self) -> ProxyStats {
        lock(&self.proxy).stats
    }

    /// The vehicle gateway's AS-4 component's counters (events sent, messages received).
    fn vehicle_stats(&self) -> jaus_as4::component::ComponentStats {
        let dual = self.net.get::<DualNode>(self.vehicle).unwrap();
        dual.gateway().component().unwrap().stats()
    }

    /// How old the proxy's latest Report Velocity State is.
    fn velocity_age(&self) -> Option<Duration> {
        let s = lock(&self.proxy);
        let (t, _) = s.report(
            Role::VelocityStateSensor,
            jaus_as4::messages::ReportVelocityState::CODE,
        )?;
        Some(self.net.now().saturating_duration_since(t))
    }

    /// Runs until the proxy's three sensor events are confirmed and flowing (no sensor
    /// query sent for a second).
    fn until_events_flow(&mut self, limit: Duration) {
        let start = self.net.now();
        loop {
            let before = self.proxy_stats();
            self.net.run_for(Duration::from_secs(1));
            let after = self.proxy_stats();
            if after.sensor_queries == before.sensor_queries
                && after.events_received > before.events_received + 20
            {
                return;
            }
            assert!(
                self.net.now().duration_since(start) < limit,
                "events not flowing within {limit:?}: {after:#?}"
            );
        }
    }

    fn station(&mut self) -> &mut Station {
        let node = self.net.node_mut(self.operator).unwrap();
        let tree = tree_input(node.tree());
        let s = &mut node.get_mut::<Hosted>(STATION).unwrap().behaviour_mut().0;
        s.set_tree(tree);
        s
    }

    /// Runs in steps of 100 ms, the station's tree kept up to date, until `f` of its
    /// view says yes (or `limit` passes).
    fn until<T>(
        &mut self,
        what: &str,
        limit: Duration,
        mut f: impl FnMut(&SystemView, &mut Self) -> Option<T>,
    ) -> T {
        let start = self.net.now();
        loop {
            self.net.run_for(Duration::from_millis(100));
            let now = self.net.now();
            let view = self.station().view(now, Duration::ZERO, false);
            if let Some(t) = f(&view, self) {
                return t;
            }
            assert!(
                now.duration_since(start) < limit,
                "{what}: not within {limit:?}; the driver: {:#?}; notices: {:#?}",
                component(&view, GWD),
                view.notices
            );
        }
    }

    /// The vehicle's true position: its own Global Pose Sensor's latest report, as the
    /// gateway on the vehicle's node received it.
    fn true_position(&self) -> Option<(f64, f64)> {
        let dual = self.net.get::<DualNode>(self.vehicle)?;
        let side = dual.gateway().node().env();
        let gps = side.targets().global_pose_sensor?;
        match side.latest(gps, jaus::messages::ReportGlobalPose::CODE) {
            Some((_, jaus::messages::Message::ReportGlobalPose(p))) => {
                Some((p.latitude?, p.longitude?))
            }
            _ => None,
        }
    }

    fn rival_send(&mut self, m: impl Into<jaus_as4::Message>) {
        let m: jaus_as4::Message = m.into();
        let body = jaus::codec::Encode::to_bytes(m.body()).unwrap();
        let to = SimNet::addr(self.vehicle);
        let c = self.net.get_mut::<As4Client>(self.rival).unwrap();
        c.send(to, &[As4Message::new(m.code().0, VEHICLE, RIVAL, body)]);
    }
}

fn component(view: &SystemView, a: Address) -> Option<&ComponentView> {
    let text = a.to_string();
    view.subsystems
        .iter()
        .flat_map(|s| &s.nodes)
        .flat_map(|n| &n.components)
        .find(|c| c.address == text)
}

/// Metres between two positions (equirectangular; exact enough over metres).
fn metres(a: (f64, f64), b: (f64, f64)) -> f64 {
    let r = 6_371_000.0_f64;
    let north = (b.0 - a.0).to_radians() * r;
    let east = (b.1 - a.1).to_radians() * r * ((a.0 + b.0) / 2.0).to_radians().cos();
    north.hypot(east)
}

/// `from` moved `north` and `east` metres.
fn offset(from: (f64, f64), north: f64, east: f64) -> GeoPoint {
    let r = 6_371_000.0_f64;
    GeoPoint {
        latitude: from.0 + (north / r).to_degrees(),
        longitude: from.1 + (east / (r * from.0.to_radians().cos())).to_degrees(),
    }
}

#[test]
fn an_ra33_operator_drives_an_as4_vehicle_through_the_proxy() {
    // RUST_LOG=jaus_as4=debug shows what crosses.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .with_test_writer()
        .try_init();
    let mut rig = Rig::new();

    // The operator sees the vehicle's services as RA 3.3 components of subsystem 2, and
    // nothing of the vehicle's own RA 3.3 subsystem: only AS5669A crosses.
    let start = rig.until(
        "the proxy's pose at the operator",
        Duration::from_secs(20),
        |v, _| {
            let s = v.subsystems.iter().find(|s| s.id == 2)?;
            let p = s.pose.as_ref()?;
            Some((p.latitude, p.longitude))
        },
    );
    let tree = tree_input(rig.net.node(rig.operator).unwrap().tree());
    for id in [33, 38, 41, 42, 45, 46] {
        assert!(
            tree.components.contains_key(&Address::new(2, 1, id, 1)),
            "2.1.{id}.1 not in {:?}",
            tree.components.keys().collect::<Vec<_>>()
        );
    }
    assert!(
        tree.components.keys().all(|a| a.subsystem != 1),
        "the vehicle's RA 3.3 components are visible: {:?}",
        tree.components.keys().collect::<Vec<_>>()
    );
    let truth = rig.true_position().expect("the vehicle's own pose");
    assert!(
        metres(start, truth) < 0.5,
        "the proxy says {start:?}, the vehicle is at {truth:?}"
    );

    // Control of the proxy's waypoint driver: granted once the proxy holds AS-4 control.
    rig.station()
        .submit(Command::TakeControl {
            target: GWD,
            authority: 5,
        })
        .unwrap();
    rig.until("control of 2.1.45.1", Duration::from_secs(10), |v, _| {
        component(v, GWD).filter(|c| c.held).map(|_| ())
    });

    // Two waypoints, 8 m north then 6 m east of that, at 2 m/s.
    let points = vec![offset(start, 8.0, 0.0), offset(start, 8.0, 6.0)];
    let last = (points[1].latitude, points[1].longitude);
    rig.net.run_for(Duration::from_secs(1));
    let before = rig.true_position().unwrap();
    assert!(metres(start, before) < 0.1, "moving before the route");
    rig.station()
        .submit(Command::Waypoints {
            driver: GWD,
            points: points.clone(),
            speed: 2.0,
        })
        .unwrap();
    let t0 = rig.net.now();
    let mut closest_first = f64::INFINITY;
    rig.until(
        "the vehicle at the last waypoint",
        Duration::from_secs(60),
        |_, r| {
            let here = r.true_position()?;
            closest_first =
                closest_first.min(metres(here, (points[0].latitude, points[0].longitude)));
            (metres(here, last) < 1.0).then_some(())
        },
    );
    let took = rig.net.now().duration_since(t0);
    assert!(
        closest_first < 1.5,
        "passed {closest_first:.2} m from waypoint 1"
    );
    // The list done, the proxy's driver returns to Standby (Part 1).
    rig.until(
        "the proxy's driver in Standby",
        Duration::from_secs(10),
        |v, _| {
            component(v, GWD)
                .and_then(|c| c.state.clone())
                .filter(|s| s == "Standby")
        },
    );
    eprintln!("arrived {took:?} after the route was sent");

    // An AS-4 client of higher authority takes the vehicle: the RA 3.3 operator loses
    // control, and its request again is refused (the proxy cannot get AS-4 control).
    rig.rival_send(jaus_as4::RequestControl {
        authority_code: 250,
    });
    rig.until("control lost", Duration::from_secs(10), |v, _| {
        v.notices
            .iter()
            .any(|n| n.text.contains("2.1.45.1: control taken away"))
            .then_some(())
    });
    rig.until("control refused", Duration::from_secs(15), |v, _| {
        v.notices
            .iter()
            .any(|n| n.text.contains("2.1.45.1: control refused"))
            .then_some(())
    });
    let c = rig.net.get_mut::<As4Client>(rig.rival).unwrap();
    assert!(
        c.take()
            .iter()
            .any(|(_, m)| m.message_id == jaus_as4::ConfirmControl::CODE.0),
        "the rival got no answer"
    );
}

/// The proxy's Global Path Segment Driver.
const GPSD: Address = Address::new(2, 1, 47, 1);

#[test]
fn an_ra33_operator_drives_an_as4_vehicle_along_path_segments_through_the_proxy() {
    let mut rig = Rig::new();
    let start = rig.until(
        "the proxy's pose at the operator",
        Duration::from_secs(20),
        |v, _| {
            let s = v.subsystems.iter().find(|s| s.id == 2)?;
            let p = s.pose.as_ref()?;
            Some((p.latitude, p.longitude))
        },
    );
    let tree = tree_input(rig.net.node(rig.operator).unwrap().tree());
    for id in [47, 48] {
        assert!(
            tree.components.contains_key(&Address::new(2, 1, id, 1)),
            "2.1.{id}.1 not in {:?}",
            tree.components.keys().collect::<Vec<_>>()
        );
    }

    // Control of the proxy's path segment driver: granted once the proxy found the
    // vehicle's AS-4 Global Path Segment Driver and holds AS-4 control.
    rig.station()
        .submit(Command::TakeControl {
            target: GPSD,
            authority: 5,
        })
        .unwrap();
    rig.until("control of 2.1.47.1", Duration::from_secs(10), |v, _| {
        component(v, GPSD).filter(|c| c.held).map(|_| ())
    });

    // Two straight segments, 8 m north then 6 m east of that, at 2 m/s.
    let points = vec![offset(start, 8.0, 0.0), offset(start, 8.0, 6.0)];
    let last = (points[1].latitude, points[1].longitude);
    rig.station()
        .submit(Command::PathSegments {
            driver: GPSD,
            points: points.clone(),
            speed: 2.0,
        })
        .unwrap();
    let t0 = rig.net.now();
    let mut closest_first = f64::INFINITY;
    rig.until(
        "the vehicle at the end of the last segment",
        Duration::from_secs(60),
        |_, r| {
            let here = r.true_position()?;
            closest_first =
                closest_first.min(metres(here, (points[0].latitude, points[0].longitude)));
            (metres(here, last) < 1.0).then_some(())
        },
    );
    let took = rig.net.now().duration_since(t0);
    assert!(
        closest_first < 1.5,
        "passed {closest_first:.2} m from the end of segment 1"
    );
    // The list done, the proxy's driver returns to Standby (Part 1).
    rig.until(
        "the proxy's path segment driver in Standby",
        Duration::from_secs(10),
        |v, _| {
            component(v, GPSD)
                .and_then(|c| c.state.clone())
                .filter(|s| s == "Standby")
        },
    );
    let end = rig.true_position().unwrap();
    eprintln!(
        "path segments: arrived {took:?} after the route was sent, {:.2} m from the end",
        metres(end, last)
    );
}

#[test]
fn the_proxy_gets_the_sensor_reports_by_as4_events_not_by_polling() {
    let mut rig = Rig::new();
    rig.until_events_flow(Duration::from_secs(10));
    let (p0, v0) = (rig.proxy_stats(), rig.vehicle_stats());
    rig.net.run_for(Duration::from_secs(5));
    let (p1, v1) = (rig.proxy_stats(), rig.vehicle_stats());
    let received = p1.events_received - p0.events_received;
    let queries = p1.sensor_queries - p0.sensor_queries;
    let sent = v1.events_sent - v0.events_sent;
    let messages_in = v1.received - v0.received;
    println!(
        "over 5 s: {received} events received, {sent} sent by the vehicle, {queries} sensor \
         queries, {messages_in} messages to the vehicle's component"
    );
    // Three sensors at 10 Hz for 5 s: about 150 Events.
    assert!(received >= 140, "{received} events in 5 s: {p1:#?}");
    assert_eq!(queries, 0, "sensor queries polled while the events run");
    assert!(sent >= received);
    // The proxy's messages to the vehicle are now its status and controller queries
    // (every 500 ms) and the Query Wrench Effort: far fewer than the 150 sensor queries.
    assert!(
        messages_in < 60,
        "{messages_in} messages to the vehicle in 5 s"
    );
    assert_eq!(p1.events_refused, 0);
    assert_eq!(p1.events_malformed, 0);
    assert_eq!(p1.events_lapsed, 0);
    assert!(rig.velocity_age().unwrap() < Duration::from_millis(300));
}

#[test]
fn the_proxy_notices_a_restarted_vehicle_lost_its_events_and_recovers() {
    let mut rig = Rig::new();
    rig.until_events_flow(Duration::from_secs(10));
    let before = rig.proxy_stats();

    // The vehicle restarts (its node replaced in place, same address): its new AS-4
    // component has no events.
    let t = rig.net.now();
    *rig.net.get_mut::<DualNode>(rig.vehicle).unwrap() = Rig::vehicle_node(t);
    assert_eq!(rig.vehicle_stats().events_sent, 0);

    // Silent for 3 periods + 0.5 s: the proxy polls again and the reports flow.
    rig.net.run_for(Duration::from_millis(1500));
    let lapsed = rig.proxy_stats();
    assert_eq!(
        lapsed.events_lapsed - before.events_lapsed,
        3,
        "{lapsed:#?}"
    );
    assert!(rig.velocity_age().unwrap() < Duration::from_millis(500));

    // It creates the events again on the new component: events flow, polling stops.
    rig.until_events_flow(Duration::from_secs(15));
    let after = rig.proxy_stats();
    assert!(rig.vehicle_stats().events_sent > 20);
    assert!(after.events_received > lapsed.events_received);
    assert!(rig.velocity_age().unwrap() < Duration::from_millis(300));
    println!(
        "after the restart: {} sensor queries polled, {} Create Events refused or unanswered",
        after.sensor_queries - before.sensor_queries,
        after.events_refused - before.events_refused
    );
}

#[test]
fn a_vehicle_that_refuses_events_is_polled_instead() {
    let mut rig = Rig::new();
    // Before the proxy has met it, the vehicle becomes one whose AS-4 component takes
    // no events (every Create Event is refused).
    let t = rig.net.now();
    *rig.net.get_mut::<DualNode>(rig.vehicle).unwrap() =
        Rig::vehicle_node_with(t, |c| c.core.max_events = 0);
    rig.net.run_for(Duration::from_secs(4));
    let p0 = rig.proxy_stats();
    rig.net.run_for(Duration::from_secs(5));
    let p1 = rig.proxy_stats();
    let queries = p1.sensor_queries - p0.sensor_queries;
    println!(
        "refusing vehicle: {} Create Events refused, {queries} sensor queries in 5 s",
        p1.events_refused
    );
    // Each of the three sensors refused (and asked again every 5 s), never received.
    assert!(p1.events_refused >= 3, "{p1:#?}");
    assert_eq!(p1.events_received, 0, "{p1:#?}");
    // Polled instead: three sensors at 10 Hz for 5 s, about 150 queries; the reports
    // are fresh.
    assert!(queries >= 140, "{queries} sensor queries in 5 s: {p1:#?}");
    assert!(rig.velocity_age().unwrap() < Duration::from_millis(300));
}
