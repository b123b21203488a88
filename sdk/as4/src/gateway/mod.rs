//! An RA 3.3 ↔ AS-4 gateway: one AS-4 component whose Mobility services are RA 3.3
//! components, on a node that speaks both generations on one socket.
//!
//! [`Gateway`] is at once an RA 3.3 component of the node (a
//! [`jaus::component::Endpoint`]: it sends queries and commands to the RA 3.3 components
//! it presents and receives their reports) and the AS-4 side of the node's socket (an
//! [`As4Endpoint`]). [`DualNode`] owns it beside the node, as a peer: the node hands it
//! what is routed to its RA 3.3 address as [`jaus::net::NodeEvent`]s and takes what it
//! sends at once ([`jaus::net::Node::handle_companion`]); the AS-4 side of the socket
//! ([`jaus::net::as5669a::As4Side`]) hands it the AS-4 messages. It hosts one
//! [`As4Component`] with the Core services and, for each RA 3.3 component found in the
//! presented subsystem, the matching Mobility service ([`crate::mobility`]), Manipulator
//! services ([`crate::manipulator`], with the pan-tilt services over the Visual Sensor's
//! camera mount when [`GatewayConfig::pan_tilt`] gives it) and Still Image
//! ([`crate::environment`]); the UGV services ([`crate::ugv`]) come once the RA 3.3
//! Primitive Driver has answered what they read.
//!
//! The control and status semantics cross over: while an AS-4 client holds control of
//! the AS-4 component, the gateway holds RA 3.3 control of the drivers (with its own
//! authority); when the AS-4 component goes Ready the drivers are resumed, when it
//! leaves Ready (Standby, Emergency, Shutdown, control lost) they are put in standby and
//! control is released. The presented components may be this node's own (the demo's
//! vehicle: one node answers RA 3.3 and AS-4 clients at once) or another subsystem's
//! (OpenJAUS 3.3's vehicle simulator): the gateway finds them in the node's system
//! tree ([`Gateway::refresh`]).

use std::collections::HashSet;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Endpoint, Outgoing as Ra33Outgoing};
use jaus::net::as5669a::{As4Endpoint, As4Id, As4Message, As4Send};
use jaus::net::{PeerAddr, SystemTree};
use jaus::wire::Header;
use jaus::{Address, JausMessage};

use crate::component::As4Component;
use crate::core::CoreConfig;
use crate::messages::{
    SetGlobalPathSegment, SetGlobalWaypoint, SetLocalPathSegment, SetLocalWaypoint,
};
use crate::mobility::{
    GlobalPathSegmentDriver, GlobalPoseSensor, GlobalWaypointListDriver, LocalPathSegmentDriver,
    LocalPoseSensor, LocalWaypointListDriver, LocalWaypointListDriverOnGlobal, PrimitiveDriver,
    VelocityStateSensor,
};
use crate::node::As4Node;
use crate::ComponentState;

pub mod dual;
pub mod ra33;

pub use crate::ra33::{Ra33Side, Targets};
pub use dual::DualNode;

/// Settings of a [`Gateway`].
#[derive(Debug, Clone)]
pub struct GatewayConfig {
    /// The AS-4 component's id.
    pub as4: As4Id,
    /// Its Core settings (names for Report Identification, authority, timeouts).
    pub core: CoreConfig,
    /// The gateway's RA 3.3 address (a component of the node hosting it).
    pub ra33: Address,
    /// The RA 3.3 subsystem presented.
    pub present: u8,
    /// The authority with which it requests RA 3.3 control of the drivers.
    pub authority: u8,
    /// How often it queries the RA 3.3 sensors. Default 100 ms.
    pub poll_period: Duration,
    /// Where a Digital Video service over the RA 3.3 Visual Sensor publishes its frames,
    /// and its bounds; `None` (the default): no Digital Video (its frames would have
    /// nowhere to go).
    pub video: Option<(
        crate::environment::VideoHub,
        crate::environment::VideoLimits,
    )>,
    /// The pan/tilt mount of a camera of the RA 3.3 Visual Sensor (RA 3.3 does not give
    /// its limits); `None` (the default): no pan-tilt services
    /// ([`crate::manipulator::pan_tilt`]).
    pub pan_tilt: Option<crate::manipulator::PanTiltMount>,
}

impl GatewayConfig {
    /// AS-4 component `as4` presenting RA 3.3 subsystem `present` from RA 3.3 address
    /// `ra33`, the other settings default.
    pub fn new(as4: As4Id, ra33: Address, present: u8, name: &str) -> Self {
        Self {
            as4,
            core: CoreConfig::named(name),
            ra33,
            present,
            authority: 200,
            poll_period: Duration::from_millis(100),
            video: None,
            pan_tilt: None,
        }
    }
}

/// One AS-4 component presenting RA 3.3 components (see the module's documentation).
#[derive(Debug)]
pub struct Gateway<A: PeerAddr = SocketAddr> {
    node: As4Node<Ra33Side, A>,
    as4: As4Id,
    present: u8,
    offered: HashSet<Address>,
    pending: Vec<As4Send<A>>,
    pending_since: Option<Instant>,
    seen: (ComponentState, bool),
    /// The presented components the system tree listed at the last
    /// [`refresh`](Self::refresh) (one that leaves it and comes back is discovered
    /// again: the polls it stopped answering start again).
    in_tree: HashSet<Address>,
    /// The local services offered over the global ones (the subsystem had no Local Pose
    /// Sensor, no Local Waypoint Driver when its global ones were found): a local one
    /// found later is not offered beside them.
    derived: Derived,
    /// The UGV services offered so far (each when its RA 3.3 report first came).
    ugv: crate::ugv::Offered,
    /// Where Digital Video publishes ([`GatewayConfig::video`]).
    video: Option<(
        crate::environment::VideoHub,
        crate::environment::VideoLimits,
    )>,
    /// The camera mount the pan-tilt services drive ([`GatewayConfig::pan_tilt`]).
    pan_tilt: Option<crate::manipulator::PanTiltMount>,
}

/// Which local services a [`Gateway`] derived from global ones.
#[derive(Debug, Default, Clone, Copy)]
struct Derived {
    pose: bool,
    waypoints: bool,
}

impl<A: PeerAddr> Gateway<A> {
    /// A gateway with `config`; its services come as [`refresh`](Self::refresh) finds
    /// the RA 3.3 components.
    pub fn new(config: GatewayConfig) -> Self {
        let side = Ra33Side::new(
            config.ra33,
            Targets::default(),
            config.authority,
            config.poll_period,
        );
        let component = As4Component::new(config.as4, config.core);
        let seen = (component.state(), component.controller().is_some());
        Self {
            node: As4Node::new(side).with_component(component),
            as4: config.as4,
            present: config.present,
            offered: HashSet::new(),
            pending: Vec::new(),
            pending_since: None,
            seen,
            in_tree: HashSet::new(),
            derived: Derived::default(),
            ugv: crate::ugv::Offered::default(),
            video: config.video,
            pan_tilt: config.pan_tilt,
        }
    }

    /// The AS-4 side (its component, peers, counters) and the RA 3.3 side
    /// ([`As4Node::env`]).
    pub fn node(&self) -> &As4Node<Ra33Side, A> {
        &self.node
    }

    /// The AS-4 component.
    pub fn component(&self) -> Option<&As4Component<Ra33Side>> {
        self.node.component(self.as4)
    }

    /// Adds to the AS-4 component a service no RA 3.3 component stands behind, hosted
    /// natively (a [`GeneratedService`](crate::service::GeneratedService) over a
    /// hardware trait, as [`crate::ugv::IlluminationService`]); Report Services lists it
    /// from then on.
    pub fn add_service(&mut self, service: Box<dyn crate::service::Service<Ra33Side>>) {
        if let Some(c) = self.node.component_mut(self.as4) {
            tracing::info!(service = %service.id(), as4 = %self.as4, "AS-4 service hosted natively");
            c.add_service(service);
        }
    }

    /// Looks for the presented subsystem's components in `tree` and offers the service
    /// of each one found for the first time (Report Services lists it from then on). A
    /// presented component that was missing from the tree (or
    /// [forgotten](Endpoint::forget)) and is listed again is discovered again: the RA 3.3
    /// side polls it at the normal rate again ([`Ra33Side::rediscovered`]).
    pub fn refresh(&mut self, now: Instant, tree: &SystemTree) {
        let listed = |t: &Targets| -> HashSet<Address> {
            t.all().filter(|a| tree.component(*a).is_some()).collect()
        };
        let back: Vec<Address> = listed(self.node.env().targets())
            .difference(&self.in_tree)
            .copied()
            .collect();
        for a in back {
            tracing::debug!(gateway = %self.node.env().address(), component = %a, "presented RA 3.3 component listed again");
            self.node.env_mut().rediscovered(now, a);
            crate::ugv::rediscovered(self.node.env_mut(), a, &self.ugv);
        }
        self.offer(now, tree);
        self.in_tree = listed(self.node.env().targets());
    }

    /// Offers the service of each presented component found in `tree` for the first
    /// time.
    fn offer(&mut self, now: Instant, tree: &SystemTree) {
        let found = Targets::of_tree(tree, self.present);
        let mut targets = *self.node.env().targets();
        let new = targets.adopt(&found);
        let vss = new.velocity_state_sensor;
        let lps = new.local_pose_sensor;
        let gps = new.global_pose_sensor;
        let pd = new.primitive_driver;
        let lwd = new.local_waypoint_driver;
        let gwd = new.global_waypoint_driver;
        let lpsd = new.local_path_segment_driver;
        let gpsd = new.global_path_segment_driver;
        // Local services over the global ones where the subsystem has no local ones; a
        // local one found after that is not offered beside them.
        let lps = lps.filter(|_| !self.derived.pose);
        let lwd = lwd.filter(|_| !self.derived.waypoints);
        let derive_pose = gps.filter(|_| targets.local_pose_sensor.is_none());
        let derive_waypoints = gwd.filter(|_| {
            targets.local_waypoint_driver.is_none() && targets.global_pose_sensor.is_some()
        });
        self.derived.pose |= derive_pose.is_some();
        self.derived.waypoints |= derive_waypoints.is_some();
        if new.all().next().is_none() {
            return;
        }
        let env = self.node.env_mut();
        env.set_targets(targets);
        let mut services: Vec<Box<dyn crate::service::Service<Ra33Side>>> = Vec::new();
        if let Some(a) = vss {
            services.push(Box::new(VelocityStateSensor::new(env, now, a)));
        }
        if let Some(a) = lps {
            services.push(Box::new(LocalPoseSensor::new(env, now, a)));
        }
        if let Some(a) = gps {
            services.push(Box::new(GlobalPoseSensor::new(env, now, a)));
        }
        if let Some(a) = derive_pose {
            tracing::info!(global_pose_sensor = %a, "no RA 3.3 Local Pose Sensor: the AS-4 one is derived from the global one");
            services.push(Box::new(LocalPoseSensor::over_global(env, now, a)));
        }
        if let Some(a) = derive_waypoints {
            tracing::info!(global_waypoint_driver = %a, "no RA 3.3 Local Waypoint Driver: the AS-4 Local Waypoint List Driver drives the global one");
            services.push(Box::new(LocalWaypointListDriverOnGlobal::new(a)));
        }
        if let Some(a) = pd {
            services.push(Box::new(PrimitiveDriver::new(env, now, a)));
        }
        if let Some(a) = lwd {
            services.push(Box::new(LocalWaypointListDriver::new(a)));
        }
        if let Some(a) = gwd {
            services.push(Box::new(GlobalWaypointListDriver::new(a)));
        }
        if let Some(a) = lpsd {
            services.push(Box::new(LocalPathSegmentDriver::new(a)));
        }
        if let Some(a) = gpsd {
            services.push(Box::new(GlobalPathSegmentDriver::new(a)));
        }
        services.extend(crate::manipulator::services(env, now, &targets, &new));
        crate::ugv::ask(env, &new);
        services.extend(crate::ugv::found(&new));
        if let Some(a) = new.visual_sensor {
            services.push(Box::new(crate::environment::StillImage::new(a)));
            if let Some(mount) = self.pan_tilt {
                services.extend(crate::manipulator::pan_tilt::services(env, now, a, mount));
            }
            if let Some((hub, limits)) = &self.video {
                services.push(Box::new(crate::environment::DigitalVideo::new(
                    a,
                    hub.clone(),
                    *limits,
                )));
            }
        }
        let Some(c) = self.node.component_mut(self.as4) else {
            return;
        };
        if lwd.is_some() || derive_waypoints.is_some() {
            c.core_mut().lists_mut().support(SetLocalWaypoint::CODE);
        }
        if gwd.is_some() {
            c.core_mut().lists_mut().support(SetGlobalWaypoint::CODE);
        }
        if lpsd.is_some() {
            c.core_mut().lists_mut().support(SetLocalPathSegment::CODE);
        }
        if gpsd.is_some() {
            c.core_mut().lists_mut().support(SetGlobalPathSegment::CODE);
        }
        for (id, code) in crate::manipulator::LIST_ELEMENTS {
            // The manipulator list drivers' elements.
            if services.iter().any(|s| s.id() == id) {
                c.core_mut().lists_mut().support(code);
            }
        }
        for s in services {
            tracing::info!(service = %s.id(), as4 = %self.as4, "AS-4 service offered");
            c.add_service(s);
        }
        self.offered.extend(new.all());
    }

    /// Offers the UGV services whose RA 3.3 report has just come for the first time
    /// ([`crate::ugv::services`]).
    fn offer_late(&mut self, now: Instant) {
        let services = crate::ugv::services(self.node.env_mut(), now, &mut self.ugv);
        if services.is_empty() {
            return;
        }
        let Some(c) = self.node.component_mut(self.as4) else {
            return;
        };
        for s in services {
            tracing::info!(service = %s.id(), as4 = %self.as4, "AS-4 service offered");
            c.add_service(s);
        }
    }

    /// Carries changes of the AS-4 component's controller and state over to the RA 3.3
    /// drivers.
    fn sync(&mut self) {
        let Some(c) = self.node.component(self.as4) else {
            return;
        };
        let now = (c.state(), c.controller().is_some());
        if now == self.seen {
            return;
        }
        self.seen = now;
        let env = self.node.env_mut();
        env.set_controlled(now.1);
        env.set_ready(now.1 && now.0 == ComponentState::Ready);
    }

    fn queue(&mut self, now: Instant, sends: Vec<As4Send<A>>) {
        if !sends.is_empty() {
            self.pending.extend(sends);
            self.pending_since.get_or_insert(now);
        }
    }
}

impl<A: PeerAddr> As4Endpoint<A> for Gateway<A> {
    fn handle(&mut self, now: Instant, from: A, messages: Vec<As4Message>) -> Vec<As4Message> {
        let replies = self.node.handle(now, from, messages);
        self.sync();
        replies
    }

    fn handle_timeout(&mut self, now: Instant) -> Vec<As4Send<A>> {
        let mut out = std::mem::take(&mut self.pending);
        self.pending_since = None;
        if self.node.poll_timeout().is_some_and(|t| t <= now) {
            out.extend(self.node.handle_timeout(now));
        }
        self.sync();
        out
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [self.node.poll_timeout(), self.pending_since]
            .into_iter()
            .flatten()
            .min()
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.node.set_utc(now, utc);
    }

    /// Messages for its AS-4 component (or a broadcast covering it): on a socket shared
    /// with an [`As4Proxy`](crate::proxy::As4Proxy), the proxy's answers are not the
    /// gateway's.
    fn serves(&self, destination: As4Id) -> bool {
        crate::node::addressed(destination, self.as4)
    }
}

impl<A: PeerAddr> Endpoint for Gateway<A> {
    fn address(&self) -> Address {
        self.node.env().address()
    }

    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        match jaus::messages::Message::decode(header.command_code, body) {
            Ok(m) => {
                self.node.env_mut().on_message(now, header.source, m);
                self.offer_late(now);
            }
            Err(e) => {
                tracing::debug!(from = %header.source, "RA 3.3 message to the gateway does not decode: {e}");
                return;
            }
        }
        // The services notice the new report (a list driver's progress, events on
        // change).
        let sends = self.node.poll(now);
        self.queue(now, sends);
        self.sync();
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.node.env_mut().handle_timeout(now);
    }

    /// A component is gone: if it is presented, it is discovered again when the tree
    /// lists it next ([`refresh`](Gateway::refresh)).
    fn forget(&mut self, gone: Address) {
        self.in_tree.remove(&gone);
    }

    /// How a command of the RA 3.3 side ended (the node making commands arrive):
    /// [`Ra33Side::on_settled`].
    fn settled(&mut self, now: Instant, settled: jaus::component::Settled) {
        self.node.env_mut().on_settled(now, settled);
        let sends = self.node.poll(now);
        self.queue(now, sends);
        self.sync();
    }

    fn poll_transmit(&mut self) -> Option<Ra33Outgoing> {
        let (to, m) = self.node.env_mut().poll_transmit()?;
        let me = self.node.env().address();
        Some(Ra33Outgoing {
            header: Header::new(m.code(), to, me),
            name: m.name(),
            body: m.to_bytes(),
        })
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.node.env().poll_timeout()
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.node.set_utc(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use jaus::messages::QueryWrenchEffort;
    use jaus::net::manager::{ComponentInfo, NodeInfo, Subscription, SubsystemInfo};

    use super::*;

    const PD: Address = Address::new(1, 1, 33, 1);

    /// Subsystem 1, node 1, with the Primitive Driver or without.
    fn tree(with_driver: bool, now: Instant) -> SystemTree {
        let mut components = BTreeMap::new();
        components.insert((1, 1), ComponentInfo::default());
        if with_driver {
            components.insert((PD.component, PD.instance), ComponentInfo::default());
        }
        let node = NodeInfo {
            name: None,
            components,
            configured: true,
            last_heard: now,
            subscription: Subscription::None,
            config_asked: None,
        };
        let mut tree = SystemTree::default();
        tree.subsystems.insert(
            1,
            SubsystemInfo {
                name: None,
                nodes: BTreeMap::from([(1, node)]),
            },
        );
        tree
    }

    /// Runs the gateway's RA 3.3 side until nothing is due; the queries sent.
    fn run_out(g: &mut Gateway<SocketAddr>, now: &mut Instant) -> usize {
        let mut sent = 0;
        while let Some(due) = Endpoint::poll_timeout(g) {
            *now = due;
            Endpoint::handle_timeout(g, *now);
            while Endpoint::poll_transmit(g).is_some() {
                sent += 1;
            }
        }
        sent
    }

    #[test]
    fn a_driver_that_leaves_the_tree_and_comes_back_is_polled_again() {
        let config = GatewayConfig::new(As4Id::new(1, 1, 1), Address::new(1, 1, 60, 1), 1, "gw");
        let mut g = Gateway::<SocketAddr>::new(config);
        let t0 = Instant::now();
        g.refresh(t0, &tree(true, t0));
        assert_eq!(g.node().env().targets().primitive_driver, Some(PD));
        let mut now = t0;
        // The polls of its efforts, after the UGV services' three queries (discrete
        // devices, platform specifications, operational data: asked once, polled only
        // once answered).
        assert_eq!(
            run_out(&mut g, &mut now),
            3 + crate::ra33::GIVE_UP_AFTER as usize
        );
        let given_up = vec![(PD, QueryWrenchEffort::CODE)];
        assert_eq!(g.node().env().polls_given_up(), given_up);
        // Still listed: nothing changes.
        g.refresh(now, &tree(true, now));
        assert_eq!(Endpoint::poll_timeout(&g), None);
        // Gone, then back: polled again at once.
        g.refresh(now, &tree(false, now));
        assert_eq!(Endpoint::poll_timeout(&g), None);
        now += Duration::from_secs(60);
        g.refresh(now, &tree(true, now));
        assert!(g.node().env().polls_given_up().is_empty());
        assert_eq!(Endpoint::poll_timeout(&g), Some(now));
        assert_eq!(g.node().env().stats().polls_resumed, 1);
        // Given up again (the three queries asked again with the rediscovery); then
        // forgotten by the node (timed out) and listed again.
        assert_eq!(
            run_out(&mut g, &mut now),
            3 + crate::ra33::GIVE_UP_AFTER as usize
        );
        assert_eq!(g.node().env().polls_given_up(), given_up);
        Endpoint::forget(&mut g, PD);
        g.refresh(now, &tree(true, now));
        assert_eq!(Endpoint::poll_timeout(&g), Some(now));
        let stats = g.node().env().stats();
        assert_eq!(
            (stats.polls_given_up, stats.polls_resumed, stats.polls_sent),
            (2, 2, 2 * u64::from(crate::ra33::GIVE_UP_AFTER))
        );
    }
}
