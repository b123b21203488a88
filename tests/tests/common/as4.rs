//! An AS-4 client of a node's gateway, on the simulated network: the node (its RA 3.3
//! components) behind the gateway at 1.1.60.1 presenting subsystem 1, our `As4Client`
//! beside it, messages sent by value and answers decoded.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Client, As4Id, As4Message};
use jaus::net::Node;
use jaus::Address;
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::messages::{ControlConfirmation, NodeServicesQuery, QueryServices, RequestControl};
use jaus_as4::Message;
use jaus_sim::network::{LinkModel, SimNet};

/// The client's AS-4 id.
pub const ME: As4Id = As4Id::new(42, 1, 1);

/// The node with its gateway, the client, on SimNet.
pub struct As4Rig {
    /// The network (run it to let time pass).
    pub net: SimNet,
    /// The client's index on `net`.
    pub client: usize,
    /// The node's index on `net` (a [`DualNode`]).
    pub node: usize,
    /// The gateway's AS-4 component.
    pub target: As4Id,
}

impl As4Rig {
    /// `node` behind a gateway (AS-4 component `target`, named `name`), after `settle`
    /// (its components come up, the gateway finds them).
    pub fn new(t0: Instant, node: Node, target: As4Id, name: &str, settle: Duration) -> Self {
        Self::hosting(t0, node, Vec::new(), target, name, settle)
    }

    /// [`new`](Self::new), the gateway's component hosting `native` services too
    /// (`DualNode::with_service`).
    pub fn hosting(
        t0: Instant,
        node: Node,
        native: jaus_node::As4Native,
        target: As4Id,
        name: &str,
        settle: Duration,
    ) -> Self {
        let config = GatewayConfig::new(target, Address::new(1, 1, 60, 1), 1, name);
        Self::configured(t0, node, native, config, settle)
    }

    /// [`hosting`](Self::hosting) with the gateway's whole `config` (its AS-4 id the
    /// target).
    pub fn configured(
        t0: Instant,
        node: Node,
        native: jaus_node::As4Native,
        config: GatewayConfig,
        settle: Duration,
    ) -> Self {
        let mut net = SimNet::new(t0, LinkModel::default(), 11);
        let target = config.as4;
        let mut dual = DualNode::new(node, config).expect("gateway");
        for s in native {
            dual = dual.with_service(s);
        }
        let node = net.add(dual);
        let client = net.add(As4Client::<SocketAddr>::default());
        net.run_for(settle);
        As4Rig {
            net,
            client,
            node,
            target,
        }
    }

    /// Sends `m` to the gateway's component, runs the network for `wait`, returns what
    /// came back.
    pub fn ask(&mut self, m: impl Into<Message>, wait: Duration) -> Vec<Message> {
        let m: Message = m.into();
        let body = m.body().to_bytes().expect("encodes");
        let to = SimNet::addr(self.node);
        let c = self.net.get_mut::<As4Client>(self.client).expect("client");
        c.send(to, &[As4Message::new(m.code().0, self.target, ME, body)]);
        self.net.run_for(wait);
        let c = self.net.get_mut::<As4Client>(self.client).expect("client");
        c.take()
            .into_iter()
            .map(|(_, a)| {
                Message::decode(jaus::CommandCode(a.message_id), &a.body).expect("decodes")
            })
            .collect()
    }

    /// The one answer to `m` within `wait`.
    pub fn one_within(&mut self, m: impl Into<Message>, wait: Duration) -> Message {
        let got = self.ask(m, wait);
        assert_eq!(got.len(), 1, "one answer expected, got {got:?}");
        got.into_iter().next().expect("one")
    }

    /// The one answer to `m` within 300 ms.
    pub fn one(&mut self, m: impl Into<Message>) -> Message {
        self.one_within(m, Duration::from_millis(300))
    }

    /// Messages the gateway's AS-4 component refused (a guard said no).
    pub fn refused(&self) -> u64 {
        self.dual()
            .gateway()
            .component()
            .expect("the gateway's component")
            .stats()
            .refused
    }

    /// The node and its gateway.
    pub fn dual(&self) -> &DualNode {
        self.net.get::<DualNode>(self.node).expect("node")
    }

    /// Node 1.1 with the demo vehicle's components (its local waypoint driver among
    /// them) but the one at `without` (for a test to add its own in its place), and
    /// the vehicle's model.
    pub fn demo_vehicle_node(
        t0: Instant,
        without: Option<Address>,
    ) -> (Node, jaus_sim::SimVehicle) {
        let opts = jaus_sim::demo::Options {
            local_waypoint_driver: true,
            ..Default::default()
        };
        let (parts, vehicle) = jaus_sim::demo::vehicle_at(t0, &opts, 1, 1);
        let config = jaus::net::NodeConfig {
            subsystem: 1,
            node: 1,
            ..jaus::net::NodeConfig::default()
        };
        let mut node = Node::new(config, t0);
        for p in parts.into_iter().filter(|p| Some(p.address()) != without) {
            node.add_boxed(p).expect("a demo component");
        }
        (node, vehicle)
    }

    /// The demo vehicle (node 1.1) behind its gateway as AS-4 component 1.1.1, settled
    /// for 3 s (the gateway has found its components).
    pub fn demo_vehicle() -> Self {
        let t0 = Instant::now();
        let node =
            jaus_sim::demo::vehicle_node(t0, jaus::net::NodeConfig::default(), 1, 1).unwrap();
        As4Rig::new(
            t0,
            node,
            As4Id::new(1, 1, 1),
            "demo vehicle",
            Duration::from_secs(3),
        )
    }

    /// The URIs of every service Report Services lists for the gateway's subsystem.
    pub fn service_uris(&mut self) -> Vec<String> {
        let Message::ReportServices(s) = self.one_within(
            QueryServices {
                nodes: vec![NodeServicesQuery {
                    node_id: 255,
                    component_ids: vec![255],
                }],
            },
            Duration::from_millis(500),
        ) else {
            panic!("no Report Services");
        };
        s.nodes
            .iter()
            .flat_map(|n| &n.components)
            .flat_map(|c| &c.services)
            .map(|s| s.uri.clone())
            .collect()
    }

    /// Requests control (authority 5) and checks it is accepted.
    pub fn take_control(&mut self) {
        let Message::ConfirmControl(c) = self.one_within(
            RequestControl { authority_code: 5 },
            Duration::from_millis(500),
        ) else {
            panic!("no Confirm Control");
        };
        assert_eq!(c.response_code, ControlConfirmation::ControlAccepted);
    }
}
