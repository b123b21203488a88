//! A JAUS vehicle in ROS 2 (vehicle mode): the other direction of the crate. Any JAUS
//! vehicle on the network (the SDK's or OpenJAUS 3.3's) is found in the system tree by
//! its Part 1 component ids and appears on the ROS 2 side as
//!
//! | ROS 2 topic | type | JAUS |
//! | --- | --- | --- |
//! | `odom`, published | `nav_msgs/Odometry` | Report Local Pose (41) + Report Velocity State (42) |
//! | `fix`, published | `sensor_msgs/NavSatFix` | Report Global Pose (38) |
//! | `jaus/status`, published | `std_msgs/String` | Report Component Status / Control of each |
//! | `cmd_vel`, read | `geometry_msgs/Twist` | Set Wrench Effort to the Primitive Driver (33) under control |
//! | `goal_pose`, read | `geometry_msgs/PoseStamped` | Set Local (or Global) Waypoint, Set Travel Speed, Resume |
//!
//! The JAUS side is a System Commander component ([`VehicleClient`]) on a node of the
//! bridge's own; the decisions are the sans-IO [`core`]; the ROS side is a thread of
//! its own. Run the node with the SDK's transports and call [`VehicleLink::step`] after
//! every event (it hands the system tree to the component):
//!
//! ```no_run
//! use std::time::Instant;
//! use jaus::net::NodeConfig;
//!
//! let mut config = jaus_ros2::Ros2Config::default();
//! config.vehicle.subsystem = Some(1);
//! let peers = vec!["127.0.0.1:3794".parse().unwrap()];
//! let node_config = NodeConfig { subsystem: 30, node: 1, peers, ..NodeConfig::default() };
//! let (mut node, mut link) = jaus_ros2::vehicle_node(&config, node_config, Instant::now())?;
//! let socket = std::net::UdpSocket::bind("127.0.0.1:0").unwrap();
//! let stop = std::sync::atomic::AtomicBool::new(false);
//! jaus::net::udp::run_on(&mut node, &socket, &stop, None, |n| link.step(n)).unwrap();
//! # Ok::<(), jaus_ros2::Ros2Error>(())
//! ```

pub mod client;
pub mod core;
mod ros;
mod shared;

use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::component::Config;
use jaus::components::system_commander;
use jaus::net::{Node, NodeConfig};
use jaus::Address;

pub use client::VehicleClient;
pub use shared::{ComponentStatus, VehicleEvent, VehicleStats};

use crate::config::Ros2Config;
use crate::error::Ros2Error;
use shared::{vlock, VShared};

/// The component id and instance of the bridge's JAUS client (a System Commander).
pub const CLIENT_ID: u8 = system_commander::ID;

/// The running vehicle bridge: the ROS 2 thread and what it shares with the JAUS
/// component. Dropping it stops the ROS 2 node (the vehicle's own command timeout then
/// stops it: the bridge sends nothing more).
#[derive(Debug)]
pub struct VehicleLink {
    shared: Arc<Mutex<VShared>>,
    thread: Option<JoinHandle<()>>,
    me: Address,
    tree_version: Option<u64>,
}

impl VehicleLink {
    /// The bridge's JAUS address.
    pub fn address(&self) -> Address {
        self.me
    }

    /// Hands the node's system tree to the component when it changed; call it after
    /// every event of the node's I/O loop (`run_on`'s `on_tick`).
    pub fn step(&mut self, node: &mut Node) {
        let v = node.tree_version();
        if self.tree_version == Some(v) {
            return;
        }
        self.tree_version = Some(v);
        vlock(&self.shared).tree = node.tree().components();
    }

    /// Counters.
    pub fn stats(&self) -> VehicleStats {
        vlock(&self.shared).stats
    }

    /// Takes the events so far, oldest first.
    pub fn events(&self) -> Vec<VehicleEvent> {
        vlock(&self.shared).events.drain(..).collect()
    }

    /// The components whose control the bridge holds.
    pub fn held(&self) -> Vec<Address> {
        vlock(&self.shared).held.clone()
    }

    /// The last status and controller each of the vehicle's components reported.
    pub fn status(&self) -> Vec<(Address, ComponentStatus)> {
        vlock(&self.shared)
            .status
            .iter()
            .map(|(a, s)| (*a, *s))
            .collect()
    }

    /// The latest `jaus/status` text.
    pub fn status_text(&self) -> String {
        vlock(&self.shared).status_text()
    }

    /// `cmd_vel` taken from DDS → its first Set Wrench Effort queued on the JAUS node,
    /// for the latest commands (at most 1024).
    pub fn latencies(&self) -> Vec<Duration> {
        vlock(&self.shared).latencies.iter().copied().collect()
    }

    /// Stops the ROS 2 node (as dropping does).
    pub fn stop(mut self) {
        self.shut();
    }

    fn shut(&mut self) {
        vlock(&self.shared).stop = true;
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

impl Drop for VehicleLink {
    fn drop(&mut self) {
        self.shut();
    }
}

/// A JAUS node presenting the vehicle of `config.vehicle.subsystem` in ROS 2: starts
/// the ROS 2 side (a ROS 2 node on DDS domain `config.domain_id`) and hosts the
/// [`VehicleClient`] at `node_config`'s subsystem.node.40.1 (authority
/// `config.vehicle.authority`, tick 10 ms). `node_config.peers` must reach the
/// vehicle's node (or a node that routes to it).
pub fn vehicle_node(
    config: &Ros2Config,
    node_config: NodeConfig,
    t0: Instant,
) -> Result<(Node, VehicleLink), Ros2Error> {
    config.validate()?;
    let subsystem = config.vehicle.subsystem.ok_or_else(|| {
        Ros2Error::Config("vehicle mode needs vehicle.subsystem (--vehicle SUBSYSTEM)".into())
    })?;
    let me = Address::new(node_config.subsystem, node_config.node, CLIENT_ID, 1);
    if subsystem == node_config.subsystem {
        return Err(Ros2Error::Config(format!(
            "the bridge's subsystem {subsystem} is the vehicle's: give the bridge a subsystem of its own"
        )));
    }
    let shared = Arc::new(Mutex::new(VShared::default()));
    let (ready_tx, ready_rx) = std::sync::mpsc::sync_channel(1);
    let thread_shared = shared.clone();
    let ros_config = config.clone();
    let thread = std::thread::Builder::new()
        .name("jaus-ros2-vehicle".into())
        .spawn(move || {
            let side = match ros::VehicleRos::open(&ros_config) {
                Ok(side) => {
                    let _ = ready_tx.send(Ok(()));
                    side
                }
                Err(e) => {
                    let _ = ready_tx.send(Err(e));
                    return;
                }
            };
            side.run(&ros_config, &thread_shared);
        })
        .map_err(|e| Ros2Error::Dds(format!("cannot start the ROS 2 thread: {e}")))?;
    match ready_rx.recv() {
        Ok(Ok(())) => {}
        Ok(Err(e)) => return Err(e),
        Err(_) => {
            return Err(Ros2Error::Dds(
                "the ROS 2 thread ended during set-up".into(),
            ))
        }
    }
    let link = VehicleLink {
        shared: shared.clone(),
        thread: Some(thread),
        me,
        tree_version: None,
    };
    let client = VehicleClient::new(subsystem, config.vehicle, config.effort, shared);
    let mut component_config: Config = node_config.component.clone();
    component_config.authority = config.vehicle.authority;
    component_config.tick = Duration::from_millis(10);
    component_config.identification = Some("jaus-ros2 vehicle bridge".into());
    let mut node = Node::new(node_config, t0);
    node.add(system_commander::component(
        me,
        client,
        component_config,
        t0,
    ))
    .map_err(|e| Ros2Error::Jaus(e.to_string()))?;
    Ok((node, link))
}
