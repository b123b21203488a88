//! The `jaus demo` main job: a complete simulated subsystem on the in-process bus.
//!
//! Node 1 of subsystem 1 hosts the Primitive Driver, the Reflexive Driver, the Global
//! and Local Pose Sensors, the Velocity State Sensor, the Global Waypoint Driver, the
//! Local and Global Path Segment Drivers, the Range and Visual Sensors, the World Model
//! Vector Knowledge Store, the Mission Spooler and the Subsystem Commander, all over one
//! simulated skid-steer vehicle; the drivers
//! drive through the Reflexive Driver (Part 1 Figures 5-9 and 5-16). An operator (a System
//! Commander on node 2, taking and keeping control through `jaus::stock::commander`)
//! takes control of both drivers, sends a waypoint mission in
//! WGS 84, then the two path segments of Part 1 Figures 5-12 and 5-14, waiting each time
//! for the driver to report Standby (Part 1: back to Standby at the final point). The
//! run reports arrival times and the cross-track error of every leg, measured on the
//! vehicle's true trajectory against the commanded path, and draws both in an SVG.
//!
//! Third phase: the operator stores an obstacle in the World Model Vector Knowledge
//! Store, queries it for objects along its mission (a line region with a clearance
//! buffer), plans a detour waypoint round each object it finds, and hands the mission —
//! blocking moves, a payload action (the horn), a blocking move home — to the
//! subsystem's Subsystem Commander (1.1.32.1, `jaus::stock::commander::subsystem`). The
//! Subsystem Commander takes control of the Mission Spooler, spools the mission to it,
//! runs it, watches it and reports its status back to the operator; the spooler drives
//! the waypoint driver. The world also holds an obstacle nobody
//! stored ([`UNKNOWN_OBSTACLE`], on the way home): the vehicle's Range Sensor detects
//! it and keeps it in the world model (`jaus::stock::environment::map_feed`), so the
//! same query finds it and the vehicle goes round it too. At the start the operator asks
//! the Visual Sensor for an image (the simulated camera's view ahead, both obstacles in
//! it).

use std::time::{Duration, Instant};

use nalgebra::Vector2;

use crate::scanner::Scene;
use crate::vehicle::SimVehicle;
use crate::world::World;
use jaus::component::local::LocalBus;
use jaus::component::Config;
use jaus::components::system_commander;
use jaus::messages::*;
use jaus::stock::geo::LocalFrame;
use jaus::stock::path::Path;

mod measure;
mod operator;
mod plan;
mod vehicle;

use measure::measure;
pub use measure::operator_report;
pub use operator::Operator;
use operator::Step;
pub use vehicle::{operator, vehicle, vehicle_at, vehicle_node, vehicle_with_scanner_at};

/// Addresses of the demo subsystem.
pub mod addr {
    use jaus::components as c;
    use jaus::Address;
    /// Primitive Driver.
    pub const PD: Address = Address::new(1, 1, c::primitive_driver::ID, 1);
    /// Reflexive Driver.
    pub const RD: Address = Address::new(1, 1, c::reflexive_driver::ID, 1);
    /// Global Pose Sensor.
    pub const GPS: Address = Address::new(1, 1, c::global_pose_sensor::ID, 1);
    /// Local Pose Sensor.
    pub const LPS: Address = Address::new(1, 1, c::local_pose_sensor::ID, 1);
    /// Velocity State Sensor.
    pub const VSS: Address = Address::new(1, 1, c::velocity_state_sensor::ID, 1);
    /// Global Waypoint Driver.
    pub const GWD: Address = Address::new(1, 1, c::global_waypoint_driver::ID, 1);
    /// Local Waypoint Driver (not used by the scripted run; what an AS-4 Local Waypoint
    /// List Driver of `jaus node`'s `as4:` option drives).
    pub const LWD: Address = Address::new(1, 1, c::local_waypoint_driver::ID, 1);
    /// Local Path Segment Driver.
    pub const LPSD: Address = Address::new(1, 1, c::local_path_segment_driver::ID, 1);
    /// Global Path Segment Driver (not used by the scripted run; operator stations
    /// such as `jaus ocu` drive path segments in WGS 84 with it).
    pub const GPSD: Address = Address::new(1, 1, c::global_path_segment_driver::ID, 1);
    /// Mission Spooler.
    pub const MS: Address = Address::new(1, 1, c::mission_spooler::ID, 1);
    /// World Model Vector Knowledge Store.
    pub const WM: Address = Address::new(1, 1, c::world_model_vector_knowledge_store::ID, 1);
    /// Range Sensor.
    pub const RS: Address = Address::new(1, 1, c::range_sensor::ID, 1);
    /// Visual Sensor.
    pub const VS: Address = Address::new(1, 1, c::visual_sensor::ID, 1);
    /// Subsystem Commander (it hands the operator's missions to the spooler).
    pub const SC: Address = Address::new(1, 1, c::subsystem_commander::ID, 1);
    /// The operator (System Commander).
    pub const OCU: Address = Address::new(1, 2, c::system_commander::ID, 1);

    /// `a` moved to node `node` of subsystem `ss`.
    pub const fn on(a: Address, ss: u8, node: u8) -> Address {
        Address::new(ss, node, a.component, a.instance)
    }
}

/// Options of a demo run.
#[derive(Debug, Clone)]
pub struct Options {
    /// Seed of the sensor noise.
    pub seed: u64,
    /// Standard deviation of the position noise of the pose sensors, m.
    pub position_noise: f64,
    /// Waypoint travel speed, m/s.
    pub waypoint_speed: f64,
    /// Path-segment travel speed, m/s.
    pub path_speed: f64,
    /// Run at wall-clock speed instead of as fast as possible.
    pub realtime: bool,
    /// Print progress every this much simulated time (`None`: quiet).
    pub progress: Option<Duration>,
    /// Give up after this much simulated time.
    pub timeout: Duration,
    /// Host the Local Waypoint Driver too (what an AS-4 Local Waypoint List Driver
    /// drives; [`vehicle_node`] and `jaus node`'s `vehicle` do). Off in the scripted
    /// run, which does not use it: its pose subscription would shift the seeded noise
    /// the run's figures come from.
    pub local_waypoint_driver: bool,
    /// Run the vehicle's and the operator's nodes over a simulated network impaired as
    /// this says, instead of on one in-process bus ([`Impairment`]).
    pub network: Option<Impairment>,
}

/// A lossy radio between the vehicle's node (1.1) and the operator's (1.2): `loss` of
/// the datagrams lost, one-way delays of 0.2 to 50 ms (so datagrams overtake each
/// other), 5 % duplicated; drawn from `seed`. With `reliable`, both nodes make their
/// commands arrive (`jaus::net::NodeConfig::reliable`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impairment {
    /// Fraction of datagrams lost, 0-1.
    pub loss: f64,
    /// Seed of the network's draws.
    pub seed: u64,
    /// Commands that arrive, on both nodes.
    pub reliable: bool,
}

impl Impairment {
    /// The link model.
    pub fn model(&self) -> crate::network::LinkModel {
        crate::network::LinkModel {
            drop: self.loss.clamp(0.0, 1.0),
            duplicate: 0.05,
            min_delay: Duration::from_micros(200),
            max_delay: Duration::from_millis(50),
        }
    }
}

/// What the network of a run over [`Impairment`] did, and what the nodes' commands did.
#[derive(Debug, Clone, Copy, Default)]
pub struct NetworkReport {
    /// The simulated network's counters.
    pub net: crate::network::SimStats,
    /// Commands of the operator's node.
    pub operator: jaus::net::reliable::ReliableStats,
    /// Commands of the vehicle's node.
    pub vehicle: jaus::net::reliable::ReliableStats,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            seed: 7,
            position_noise: 0.02,
            waypoint_speed: 1.0,
            path_speed: 1.0,
            realtime: false,
            progress: None,
            timeout: Duration::from_secs(300),
            local_waypoint_driver: false,
            network: None,
        }
    }
}

/// The WGS 84 origin of the demo's local frame (x north, y east).
pub const ORIGIN: (f64, f64, f64) = (29.6436, -82.3549, 40.0);

/// The waypoint mission, local metres (sent as WGS 84); it ends at P0 of Figure 5-12,
/// arriving along the direction of P0→P1.
pub const WAYPOINTS: [(f64, f64); 5] = [
    (10.0, 0.0),
    (10.0, -6.0),
    (-3.0, -6.0),
    (-1.0, -1.0),
    (1.0, 2.0),
];

/// The path segments of Part 1 Figures 5-12 and 5-14: (P1, P2, w1); P0 of the first is
/// the vehicle's position, [1, 2, 0].
pub const SEGMENTS: [SegmentDef; 2] = [
    ((3.0, 5.0), (5.0, 1.0), 1.5),
    ((6.0, -1.0), (8.0, -1.0), 2.0),
];

/// A path segment as sent: P1 (x, y), P2 (x, y), w1.
pub type SegmentDef = ((f64, f64), (f64, f64), f64);

/// Named commanded legs.
type Legs = Vec<(String, Path)>;

/// The spooled mission (local metres, sent as WGS 84): a blocking move, a payload action
/// (the horn of the primitive driver's discrete devices), a blocking move home.
pub const MISSION: [(f64, f64); 2] = [(3.0, -4.0), (0.0, 0.0)];

/// An obstacle the operator stores in the world model before the mission: centre
/// (local metres) and radius (the object's region buffer), on the straight line from P4
/// to the first mission point, so the operator's planner must go round it.
pub const OBSTACLE: ((f64, f64), f64) = ((5.5, -2.5), 0.6);

/// An obstacle on the way home that nobody stores: only the Range Sensor's detections
/// put it in the world model. Centre (local metres) and radius.
pub const UNKNOWN_OBSTACLE: ((f64, f64), f64) = ((1.5, -2.0), 0.4);

/// The demo's world as it is: the obstacle the operator stores ([`OBSTACLE`]) and one
/// nobody stores ([`UNKNOWN_OBSTACLE`]).
pub fn scene() -> Scene {
    let circle = |((x, y), r): ((f64, f64), f64)| (Vector2::new(x, y), r);
    Scene {
        circles: vec![circle(OBSTACLE), circle(UNKNOWN_OBSTACLE)],
    }
}

/// The demo's world for a host of stock components (`jaus_node::host::Host::with_world`): its
/// frame's origin ([`ORIGIN`]), its [`scene`] and the arm demo's control period.
pub fn world() -> World {
    World {
        origin: LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2),
        scene: scene(),
        arm_control_period: crate::arm_demo::CONTROL_PERIOD,
    }
}

/// Feature class of the objects the operator stores (the Range Sensor's are class 2).
pub const OPERATOR_CLASS: u16 = 1;

/// Clearance the operator's planner keeps from a stored obstacle's buffer, m.
pub const CLEARANCE: f64 = 0.6;

/// One leg of the run.
#[derive(Debug, Clone, PartialEq)]
pub struct Leg {
    /// "waypoint 2", "path segment 0".
    pub name: String,
    /// Simulated time the leg's end was reached, s (`None`: never).
    pub arrival: Option<f64>,
    /// Cross-track error RMS, m.
    pub xte_rms: f64,
    /// Cross-track error maximum, m.
    pub xte_max: f64,
}

/// What a run measured.
#[derive(Debug, Clone)]
pub struct Report {
    /// Every leg, in order.
    pub legs: Vec<Leg>,
    /// When the waypoint driver returned to Standby, s.
    pub waypoints_done: Option<f64>,
    /// When the path-segment driver returned to Standby, s.
    pub path_done: Option<f64>,
    /// When the spooler reported the mission finished, s.
    pub mission_done: Option<f64>,
    /// When the operator saw the mission's payload action (the horn), s.
    pub horn_at: Option<f64>,
    /// Closest approach of the vehicle to the obstacle's centre during the mission, m
    /// (the obstacle's radius is `OBSTACLE.1`).
    pub obstacle_clearance: f64,
    /// Closest approach to [`UNKNOWN_OBSTACLE`]'s centre during the mission, m.
    pub unknown_clearance: f64,
    /// Objects along the mission the world model returned: (stored by the operator,
    /// detected by the Range Sensor), after merging those that overlap.
    pub objects_found: (usize, usize),
    /// The mission's moves as the operator planned them from the world model.
    pub planned: Vec<(f64, f64)>,
    /// The image the operator received from the Visual Sensor at the start.
    pub image: Option<ReportImage>,
    /// Distance from the final point of each phase when it ended, m.
    pub final_errors: Vec<f64>,
    /// Simulated duration, s.
    pub duration: f64,
    /// Messages delivered on the bus.
    pub messages: u64,
    /// The commanded paths and the driven trajectory (local metres).
    pub commanded: Vec<Vec<Vector2<f64>>>,
    /// The driven trajectory.
    pub trail: Vec<Vector2<f64>>,
}

fn config() -> Config {
    Config {
        utc: Some(Duration::from_secs(1_795_000_000)),
        ..Config::default()
    }
}

/// Builds the demo subsystem on a bus starting at `t0`; returns the bus and the vehicle.
pub fn build(t0: Instant, opts: &Options) -> (LocalBus, SimVehicle) {
    let (parts, vehicle) = vehicle(t0, opts);
    let mut bus = LocalBus::new(t0);
    for p in parts {
        bus.add_boxed(p);
    }
    bus.add(operator(t0, opts));
    (bus, vehicle)
}

/// Progress of the operator: (phase, waypoints done at, path done at, mission done at).
pub fn progress(
    ocu: &Ocu,
) -> (
    &'static str,
    Option<Instant>,
    Option<Instant>,
    Option<Instant>,
) {
    let o = &ocu.behaviour().0;
    (
        phase_name(o.step),
        o.waypoints_done,
        o.path_done,
        o.mission_done,
    )
}

fn phase_name(s: Step) -> &'static str {
    match s {
        Step::TakeControl => "taking control",
        Step::StartWaypoints | Step::Waypoints => "waypoints",
        Step::StartPath | Step::Path => "path segments",
        Step::StartMission | Step::StoreObstacle | Step::PlanMission | Step::Mission => {
            "spooled mission"
        }
        Step::Done => "done",
    }
}

/// The operator component.
pub type Ocu = jaus::component::Component<system_commander::Dispatch<Operator>>;

/// Where a run happens: one in-process bus, or two nodes on a simulated network.
trait Venue {
    fn ocu(&self) -> Option<&Ocu>;
    fn now(&self) -> Instant;
    fn run_for(&mut self, d: Duration);
    fn delivered(&self) -> u64;
}

impl Venue for LocalBus {
    fn ocu(&self) -> Option<&Ocu> {
        self.get::<Ocu>(addr::OCU)
    }
    fn now(&self) -> Instant {
        LocalBus::now(self)
    }
    fn run_for(&mut self, d: Duration) {
        LocalBus::run_for(self, d);
    }
    fn delivered(&self) -> u64 {
        self.stats().delivered
    }
}

/// The vehicle's node and the operator's on a [`SimNet`](crate::network::SimNet).
struct Network {
    net: crate::network::SimNet,
    vehicle: usize,
    operator: usize,
}

impl Network {
    fn build(t0: Instant, opts: &Options, imp: &Impairment) -> Result<(Self, SimVehicle), String> {
        use crate::network::SimNet;
        use jaus::net::{Node, NodeConfig};
        let config = |node: u8, peer: usize| {
            let mut c = NodeConfig {
                subsystem: 1,
                node,
                peers: vec![SimNet::addr(peer)],
                reliable: imp.reliable.then(jaus::net::reliable::RetryPolicy::default),
                ..NodeConfig::default()
            };
            c.manager.node_name = format!("demo node {node}");
            c
        };
        let mut net = SimNet::new(t0, imp.model(), imp.seed);
        let mut vehicle_node = Node::new(config(1, 1), t0);
        let (parts, vehicle) = vehicle_at(t0, opts, 1, 1);
        for p in parts {
            vehicle_node.add_boxed(p).map_err(|e| e.to_string())?;
        }
        let mut operator_node = Node::new(config(2, 0), t0);
        operator_node
            .add(operator(t0, opts))
            .map_err(|e| e.to_string())?;
        let (v, o) = (net.add(vehicle_node), net.add(operator_node));
        Ok((
            Self {
                net,
                vehicle: v,
                operator: o,
            },
            vehicle,
        ))
    }

    fn report(&self) -> NetworkReport {
        let stats = |i| {
            self.net
                .node(i)
                .map(jaus::net::Node::reliable_stats)
                .unwrap_or_default()
        };
        NetworkReport {
            net: self.net.stats(),
            operator: stats(self.operator),
            vehicle: stats(self.vehicle),
        }
    }
}

impl Venue for Network {
    fn ocu(&self) -> Option<&Ocu> {
        self.net.node(self.operator)?.get::<Ocu>(addr::OCU)
    }
    fn now(&self) -> Instant {
        self.net.now()
    }
    fn run_for(&mut self, d: Duration) {
        self.net.run_for(d);
    }
    fn delivered(&self) -> u64 {
        self.net.stats().delivered
    }
}

/// Runs the demo; `print` receives progress lines.
pub fn run(opts: &Options, print: impl FnMut(&str)) -> Result<Report, String> {
    let t0 = Instant::now();
    let (mut bus, vehicle) = build(t0, opts);
    run_in(&mut bus, t0, &vehicle, opts, print)
}

/// Runs the demo over a simulated network impaired as `opts.network` says (a clean
/// one when `None`): the report, and what the network and the nodes' commands did.
pub fn run_over_network(
    opts: &Options,
    print: impl FnMut(&str),
) -> Result<(Report, NetworkReport), String> {
    let t0 = Instant::now();
    let imp = opts.network.unwrap_or(Impairment {
        loss: 0.0,
        seed: opts.seed,
        reliable: true,
    });
    let (mut world, vehicle) = Network::build(t0, opts, &imp)?;
    let report = run_in(&mut world, t0, &vehicle, opts, print);
    let net = world.report();
    report
        .map(|r| (r, net))
        .map_err(|e| format!("{e}; {}", network_summary(&net)))
}

/// One line of what the network and the commands did.
pub fn network_summary(n: &NetworkReport) -> String {
    format!(
        "network: {} datagrams, {} lost, {} duplicated, {} reordered; the operator's commands: {} tracked, {} copies resent, {} acknowledged, {} refused, {} given up; the vehicle's node: {} retransmissions carried out once, {} answers repeated",
        n.net.sent,
        n.net.dropped,
        n.net.duplicated,
        n.net.reordered,
        n.operator.tracked,
        n.operator.retried,
        n.operator.acknowledged,
        n.operator.refused,
        n.operator.given_up,
        n.vehicle.duplicates_dropped,
        n.vehicle.answers_repeated
    )
}

fn run_in(
    bus: &mut impl Venue,
    t0: Instant,
    vehicle: &SimVehicle,
    opts: &Options,
    mut print: impl FnMut(&str),
) -> Result<Report, String> {
    let slice = Duration::from_millis(100);
    let mut next_progress = Duration::ZERO;
    let wall = Instant::now();
    loop {
        let elapsed = bus.now() - t0;
        let (step, done_at, horn_at) = {
            let o = &bus.ocu().ok_or("operator missing")?.behaviour().0;
            (
                o.step,
                [o.waypoints_done, o.path_done, o.mission_done],
                o.horn_at,
            )
        };
        if let Some(every) = opts.progress {
            if elapsed >= next_progress || step == Step::Done {
                next_progress = elapsed + every;
                let v = vehicle.lock();
                let p = v.position();
                print(&format!(
                    "t = {:6.1} s  {:<16} x {:6.2} m  y {:6.2} m  heading {:6.1}°  speed {:4.2} m/s",
                    elapsed.as_secs_f64(),
                    phase_name(step),
                    p.x,
                    p.y,
                    v.yaw().to_degrees(),
                    v.speed()
                ));
            }
        }
        if step == Step::Done {
            let (planned, found, image) = bus
                .ocu()
                .map(|o| {
                    let o = &o.behaviour().0;
                    (o.planned.clone(), o.objects_found, o.image.clone())
                })
                .unwrap_or_default();
            let trail: Vec<(f64, Vector2<f64>)> = vehicle
                .lock()
                .trail()
                .iter()
                .map(|(d, p)| (d.as_secs_f64(), *p))
                .collect();
            let run = ((bus.now() - t0).as_secs_f64(), bus.delivered());
            return Ok(Report {
                image,
                ..measure(t0, &trail, done_at, horn_at, (&planned, found), run)
            });
        }
        if elapsed > opts.timeout {
            return Err(format!(
                "the mission did not finish within {:?} of simulated time (stuck at {step:?})",
                opts.timeout
            ));
        }
        bus.run_for(slice);
        if opts.realtime {
            let target = wall + (bus.now() - t0);
            let now = Instant::now();
            if target > now {
                std::thread::sleep(target - now);
            }
        }
    }
}
