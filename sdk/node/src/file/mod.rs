//! `jaus node`: a node from a YAML file, its system tree printed when it changes.

use std::net::SocketAddr;
use std::path::Path;
use std::time::Duration;

use jaus::net::{udp, Framing, NodeConfig};

mod as4;
mod build;
pub(crate) mod run;

/// AS-4 services a node file's `host:` entries offer natively, for its gateway.
pub type As4Native = Vec<Box<dyn jaus_as4::service::Service<jaus_as4::gateway::Ra33Side>>>;

/// A node configuration file (YAML).
///
/// ```yaml
/// subsystem: 1
/// node: 1
/// subsystem_name: demo vehicle
/// node_name: vehicle computer
/// bind: 127.0.0.1:3794
/// framing: judp          # or opc ("JAUS01.0")
/// transport: udp         # or tcp (JTCP: `bind` is the listening address, `peers` dialed),
///                        # or serial (JSerial on `serial:`; no bind, no peers)
/// serial: serial:///dev/ttyUSB0?baud=57600   # the line of `transport: serial`
/// peers: [127.0.0.2:3794]
/// host:                  # what the node hosts (see below)
///   - vehicle                                # the demo's whole simulated vehicle
///   - arm                                    # the ten manipulator components, one arm
///   - global_pose_sensor                     # a stock component at instance 1
///   - { component: world_model, instance: 2 }
///   - { component: global_waypoint_driver, output: 1.1.33.1, pose: 1.1.38.1 }
///   - component: communicator                # the gateway to other subsystems
///     links:
///       - { id: 1, udp: { bind: "0.0.0.0:4001", peer: "192.168.1.20:4001" } }
///       - id: 2                                # or authenticated and encrypted:
///         quic: { bind: "0.0.0.0:4002", peer: "192.168.1.20:4002",
///                 cert: keys/vehicle.crt, key: keys/vehicle.key, peer_cert: keys/station.crt }
/// io: { spin_us: 50, batch: 32 }  # optional: how the socket is read (udp::IoOptions)
/// policy:               # optional: who may command (see `PolicyFile`); default open
///   default: query
///   rules: [{ from: 200.*.*.*, may: command, max_authority: 100 }]
/// communicator: 1.2.35.1 # optional: the subsystem's communicator on another node
/// store: vehicle.jstore  # optional: world_model and mission_spooler entries durable
/// ros2: { domain_id: 0 } # optional: a ROS 2 robot on DDS as this node's components
/// ```
///
/// `ros2:` (the keys of `jaus ros2 --config`'s file, `jaus_ros2::Ros2Config`, every one
/// defaulted: `domain_id`, `node_name`, `namespace`, `topics`, `frames`, `odom_axes`,
/// `qos_commands`, `qos_sensors`, `effort`, `watchdog_ms`, `command_timeout_ms`;
/// docs/ros2.md) joins the robot's DDS domain as a ROS 2 node (pure Rust, no ROS
/// install) and hosts the robot as RA 3.3 components of this node: Primitive Driver
/// 33.1 (publishes `cmd_vel`), Global Pose Sensor 38.1 (`fix`), Local Pose Sensor 41.1
/// and Velocity State Sensor 42.1 (`odom`), beside the `host:` entries (none of which
/// may take one of those four addresses; `host: [local_waypoint_driver]` drives the
/// robot through them) and presented to AS-4 clients by `as4:`. Watchdog events are
/// logged; the bridge's counters are the `ros2 stats:` line at the end. Vehicle mode
/// (`vehicle: { subsystem }`) is `jaus ros2 --vehicle`'s, not a node file's.
///
/// `store:` (a file, relative to the node file's directory; created if absent) makes
/// the `world_model` and `mission_spooler` entries of `host:` durable
/// (`jaus_store::Store`): every object created or deleted, metadata set, mission
/// spooled, changed or advanced is committed to it before it is confirmed, and a
/// restarted node reloads them (objects with their ids, missions where they stood,
/// paused until Resume or Run Mission). A store that does not load (a record that
/// does not decode, more than the limits) stops the node with the file, table and key.
/// The demo `vehicle` stays in memory.
///
/// A `host:` entry is `vehicle`, `arm` (the Primitive Manipulator, the three joint sensors
/// and the six manipulator drivers of `jaus_sim::arm_demo::arm_components` over one
/// simulated 6-axis arm) or a stock component by its name in the definitions (`stock:`
/// of a component in `jaus-spec/defs`, `jaus_node::host::Stock::names()`: for example
/// `primitive_driver`, `global_pose_sensor`, `global_waypoint_driver`, `world_model`,
/// `range_sensor`, `joint_position_sensor`, `communicator`; an unknown name's error
/// lists them all), by name or as a map with `component`,
/// `instance` (1), `output` and `pose` (drivers: where the efforts go and which pose
/// sensor they follow; default: this node's 43.1 or 33.1, and 38.1 or 41.1; manipulator
/// drivers: 49.1) and `authority` (0). Those that need hardware share one simulated
/// vehicle, the manipulator components one simulated arm, in an empty world (no
/// obstacles; the vehicle at the origin of the default frame: `jaus_sim::World`).
/// With `as4:`, the gateway's AS-4 component also hosts the AS-4 Illumination service
/// over the `vehicle`'s simulated lamps (RA 3.3 has no lights: `SimLights`), and the
/// AS-4 Range Sensor over the simulated scanner of the first entry with one (`vehicle`
/// or `range_sensor`: the scanner its RA 3.3 Range Sensor reads,
/// `jaus_as4::environment::RangeSensorService`).
///
/// `communicator` (Part 1 §5.2.1, id 35) is the subsystem's gateway to the other
/// subsystems, over real data links: its `links:` (at least one) are each
/// `{ id, udp: { bind, peer, mtu, silence_ms, keepalive_ms, assume_up, poll_ms } }`,
/// a UDP socket bound to `bind` exchanging one datagram per JAUS packet with the far
/// communicator's link socket `peer` (an IP radio modem, a tether; `mtu` 4096 bytes,
/// down after `silence_ms` 3000 of silence, a keep-alive after `keepalive_ms` 1000
/// without sending (0: none), up before anything is heard unless `assume_up: false`,
/// read every `poll_ms` 10: `jaus::net::udp::link::UdpLinkConfig`), or
/// `{ id, quic: { bind, peer, cert, key, peer_cert, mtu, silence_ms, keepalive_ms } }`,
/// a QUIC connection between `bind` and the far end's `peer`, authenticated both ways
/// by pinned certificates and encrypted (`jaus_quic::QuicLink`: this node presents
/// `cert` and `key`, made by `jaus keygen`, and accepts only `peer_cert`, the far end's
/// certificate; paths relative to the node file's directory; `mtu` 4096, down after
/// `silence_ms` 3000 of silence, a QUIC keep-alive after `keepalive_ms` 1000, or a
/// third of `silence_ms` if that is less). A node hosting
/// one sends every message for another subsystem through it and takes those from
/// other subsystems only from it (`NodeConfig::communicator`); the other nodes of the
/// subsystem name it with `communicator:`. At most one per node.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeFile {
    /// Subsystem id.
    pub subsystem: u8,
    /// Node id.
    pub node: u8,
    /// Subsystem name.
    #[serde(default)]
    pub subsystem_name: Option<String>,
    /// Node name.
    #[serde(default)]
    pub node_name: Option<String>,
    /// Local address and port: the UDP socket, or with `transport: tcp` the listening
    /// address (required but with `transport: serial`).
    #[serde(default = "no_bind")]
    pub bind: SocketAddr,
    /// Framing.
    #[serde(default)]
    pub framing: Framing,
    /// The carrier: `udp` (JUDP, the default) or `tcp` (JTCP: the node listens on
    /// `bind`, dials every `peers` address and keeps it connected, redialing with
    /// backoff; RA 3.3 and `as4:` alike; no multicast, no OpenJAUS component sockets).
    #[serde(default)]
    pub transport: TransportFile,
    /// The line of `transport: serial` (`serial:///dev/ttyUSB0?baud=57600`): JSerial,
    /// point to point, the far end its only peer.
    #[serde(default)]
    pub serial: Option<jaus::net::PeerUrl>,
    /// Peers sent broadcasts and messages to nodes not yet located.
    #[serde(default)]
    pub peers: Vec<SocketAddr>,
    /// What to host.
    #[serde(default)]
    pub host: Vec<HostItem>,
    /// Heartbeat period, ms.
    #[serde(default)]
    pub heartbeat_ms: Option<u64>,
    /// Node timeout, ms.
    #[serde(default)]
    pub node_timeout_ms: Option<u64>,
    /// Multicast discovery (off without it).
    #[serde(default)]
    pub multicast: Option<MulticastFile>,
    /// Serve OpenJAUS component processes over their local interface
    /// (`openjaus_components: {}` for OpenJAUS's ports 24627 and 24629 on 127.0.0.1).
    #[serde(default)]
    pub openjaus_components: Option<OjComponentsFile>,
    /// How the node reads its socket (`udp::IoOptions`; defaults when absent).
    #[serde(default)]
    pub io: Option<IoFile>,
    /// The subsystem's Communicator when another node hosts it
    /// (`subsystem.node.component.instance`): messages for other subsystems go to that
    /// node (`NodeConfig::communicator`). A node hosting one needs none.
    #[serde(default)]
    pub communicator: Option<String>,
    /// The node's access policy (`jaus::net::Policy`; open without it).
    #[serde(default)]
    pub policy: Option<crate::policy_file::PolicyFile>,
    /// The durable store of the hosted world models and mission spoolers (relative to
    /// the node file's directory); in memory without it.
    #[serde(default)]
    pub store: Option<std::path::PathBuf>,
    /// Commands that arrive (docs/wire.md §1.7): `reliable: {}` makes the commands the
    /// hosted components send to other nodes (and the AS-4 side's, to AS-4 vehicles)
    /// ask for an acknowledgement and be resent until answered, one at a time per
    /// component, in order (see [`ReliableFile`]). Off without it: sent once.
    #[serde(default)]
    pub reliable: Option<ReliableFile>,
    /// AS-4 clients too: an AS-4 component on the same socket (AS5669A) presenting RA
    /// 3.3 components as AS-4 services (see [`As4File`]).
    #[serde(default)]
    pub as4: Option<As4File>,
    /// AS-4 vehicles this node presents as RA 3.3 components (an AS-4 client of each,
    /// on the node's own socket; see [`As4VehicleFile`]).
    #[serde(default)]
    pub as4_vehicles: Vec<As4VehicleFile>,
    /// A ROS 2 robot hosted on this node (crate `jaus-ros2`, docs/ros2.md): the keys of
    /// [`jaus_ros2::Ros2Config`] (robot mode only).
    #[serde(default)]
    pub ros2: Option<jaus_ros2::Ros2Config>,
}

/// `reliable:` of a node file: how hard commands are tried (`jaus::net::reliable`).
///
/// ```yaml
/// reliable: {}                  # the defaults below
/// reliable:
///   first_timeout_ms: 200       # wait for the first copy's acknowledgement
///   max_timeout_ms: 1600        # the wait doubles up to this
///   attempts: 6                 # copies in all (about 6 s with the defaults)
///   retry_unknown: true         # false: one copy to a peer never heard acknowledging
///                               #   (peers that may be OpenJAUS 3.3, which carries
///                               #   out every copy)
/// ```
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReliableFile {
    /// Wait for the first copy's acknowledgement, ms. Default 200.
    #[serde(default)]
    pub first_timeout_ms: Option<u64>,
    /// Longest wait between copies, ms. Default 1600.
    #[serde(default)]
    pub max_timeout_ms: Option<u64>,
    /// Copies sent in all. Default 6.
    #[serde(default)]
    pub attempts: Option<u32>,
    /// Whether a peer never heard acknowledging is sent more than one copy. Default
    /// true (`RetryPolicy::retry_unknown`).
    #[serde(default)]
    pub retry_unknown: Option<bool>,
}

impl ReliableFile {
    /// The policy it describes (bounded: at least 10 ms, one copy).
    pub fn policy(&self) -> jaus::net::reliable::RetryPolicy {
        let d = jaus::net::reliable::RetryPolicy::default();
        let first = self
            .first_timeout_ms
            .map_or(d.first_timeout, |ms| Duration::from_millis(ms.max(10)));
        jaus::net::reliable::RetryPolicy {
            first_timeout: first,
            max_timeout: self
                .max_timeout_ms
                .map_or(d.max_timeout, Duration::from_millis)
                .max(first),
            max_attempts: self.attempts.map_or(d.max_attempts, |n| n.clamp(1, 100)),
            retry_unknown: self.retry_unknown.unwrap_or(d.retry_unknown),
            ..d
        }
    }
}

/// One entry of `as4_vehicles:` of a node file: an AS-4 vehicle presented as RA 3.3
/// components of this node (`jaus_as4::proxy`), so that RA 3.3 clients (`jaus ocu
/// --peer` this node) see and drive it. The node is an AS-4 client of the vehicle on
/// its own socket (AS5669A beside RA 3.3; with `as4:` too, the socket serves both
/// directions: each AS-4 message goes to the side its destination id names). The
/// components take the standard ids of Part 1 on this node: Velocity State Sensor 42,
/// Local Pose Sensor 41, Global Pose Sensor 38, Primitive Driver 33, Local Waypoint
/// Driver 46, Global Waypoint Driver 45, Global Path Segment Driver 47, Local Path
/// Segment Driver 48 (at `instance`), over the vehicle's AS-4 Mobility services found
/// by Discovery. An RA 3.3 client's control of a driver is granted once the node holds
/// AS-4 control of the vehicle; Resume, Standby and emergencies cross over; waypoints
/// (or path segments) and a travel speed become an AS-4 list executed at that speed. The console expects one vehicle per RA 3.3 subsystem: present each
/// vehicle on a node of its own subsystem.
///
/// ```yaml
/// subsystem: 2
/// node: 1
/// bind: 0.0.0.0:3794
/// as4_vehicles:
///   - peer: 192.168.1.20:3794   # the vehicle's AS5669A address (required)
///     id: 1.1.1                 # its AS-4 component (S.N.C), or S.255.255; default:
///                               #   every component at that address (Discovery finds them)
///     proxy_id: 2.1.200         # this node's AS-4 id as the vehicle's client; default
///                               #   subsystem.node.200 (201, … 254 for the next
///                               #   entries: no part 0 or 255)
///     instance: 1               # RA 3.3 instance of the components; default 1, 2, …
///     authority: 200            # with which AS-4 control is requested; default 200
///     services: [global_pose_sensor, velocity_state_sensor, global_waypoint_driver]
///                               # default: all eight (names as above, snake case)
///     frame: { x: 0, y: 0, yaw: 0 }  # the AS-4 local frame in the RA 3.3 one
///                               #   (m, m, rad); default identity
/// ```
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct As4VehicleFile {
    /// The vehicle's AS5669A address.
    pub peer: SocketAddr,
    /// The vehicle's AS-4 id (`S.N.C`; `S.255.255` for a subsystem); default: every
    /// component at `peer`.
    #[serde(default)]
    pub id: Option<String>,
    /// This node's AS-4 id as the vehicle's client (`S.N.C`).
    #[serde(default)]
    pub proxy_id: Option<String>,
    /// RA 3.3 instance of the presented components.
    #[serde(default)]
    pub instance: Option<u8>,
    /// Authority of the AS-4 control requests (default 200).
    #[serde(default)]
    pub authority: Option<u8>,
    /// The presented services (default all eight).
    #[serde(default)]
    pub services: Option<Vec<String>>,
    /// The AS-4 local frame relative to the RA 3.3 one (default identity).
    #[serde(default)]
    pub frame: Option<FrameFile>,
}

/// `frame:` of an `as4_vehicles:` entry: AS-4 local = rotate(yaw) · RA 3.3 local +
/// (x, y).
#[derive(Debug, Clone, Copy, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrameFile {
    /// Metres.
    #[serde(default)]
    pub x: f64,
    /// Metres.
    #[serde(default)]
    pub y: f64,
    /// Radians.
    #[serde(default)]
    pub yaw: f64,
}

/// `as4:` of a node file: the node answers AS-4 clients (AS5669A, JUDP version 2, on
/// the node's own socket) with one AS-4 component presenting RA 3.3 components as the
/// Core and Mobility services (`jaus_as4::gateway`).
///
/// ```yaml
/// as4:
///   subsystem: 1        # AS-4 subsystem id; default: the node's subsystem
///   node: 1             # AS-4 node id; default: the node's id
///   component: 1        # the AS-4 component's id; default 1
///   name: demo vehicle  # Report Identification's name; default: the subsystem name
///   present: 1          # the RA 3.3 subsystem presented; default: this node's subsystem
///   gateway_id: 60      # the gateway's own RA 3.3 component id on this node; default 60
///   authority: 200      # its authority when it takes RA 3.3 control; default 200
///   multicast: 239.255.0.1  # hear AS-4 first contact on this group (the JAUS Tool Set's);
///                           # needs bind 0.0.0.0; nothing is ever sent to it
///   mission_spooler:        # an AS-4 Mission Spooler on its own component (see
///     component: 5          #   MissionSpoolerFile)
///   video:                  # Digital Video over the RA 3.3 Visual Sensor, MJPEG over
///     listen: 127.0.0.1:8090  # HTTP at http://<listen>/video/1 (see video::VideoFile)
///   pan_tilt: { camera: 1, pan_limit: 90, tilt_limit: 30 }  # the camera's mount (deg),
///                           # for the AS-4 pan-tilt services (see PanTiltFile)
/// ```
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct As4File {
    /// AS-4 subsystem id (default: the node's subsystem).
    #[serde(default)]
    pub subsystem: Option<u16>,
    /// AS-4 node id (default: the node's id).
    #[serde(default)]
    pub node: Option<u8>,
    /// The AS-4 component's id (default 1).
    #[serde(default)]
    pub component: Option<u8>,
    /// Its name in Report Identification (default: the subsystem's name).
    #[serde(default)]
    pub name: Option<String>,
    /// The RA 3.3 subsystem whose components it presents (default: this node's).
    #[serde(default)]
    pub present: Option<u8>,
    /// The gateway's RA 3.3 component id on this node (default 60).
    #[serde(default)]
    pub gateway_id: Option<u8>,
    /// Its authority when it requests RA 3.3 control of the drivers (default 200).
    #[serde(default)]
    pub authority: Option<u8>,
    /// A multicast group to hear AS-4 first contact on: the JAUS Tool Set's runtime
    /// sends a message for an id it has not heard from only to its group, 239.255.0.1 on
    /// its port. The node joins it on its socket (which must be bound to 0.0.0.0 to hear
    /// a group) and answers the sender directly; it never sends to the group, RA 3.3
    /// traffic included.
    #[serde(default)]
    pub multicast: Option<std::net::Ipv4Addr>,
    /// An AS-4 Mission Spooler on its own AS-4 component of this node
    /// (`jaus_as4::mission`), beside the gateway's on the same socket.
    #[serde(default)]
    pub mission_spooler: Option<MissionSpoolerFile>,
    /// AS-4 Digital Video over the RA 3.3 Visual Sensor, its frames served as MJPEG over
    /// HTTP ([`crate::video::VideoFile`]); without it, no Digital Video.
    #[serde(default)]
    pub video: Option<crate::video::VideoFile>,
    /// The pan/tilt mount of a camera of the RA 3.3 Visual Sensor, for the AS-4 pan-tilt
    /// services (RA 3.3 gives no mount limits); without it, none.
    #[serde(default)]
    pub pan_tilt: Option<PanTiltFile>,
}

/// `as4: { pan_tilt: … }` of a node file: the mount of a camera of the RA 3.3 Visual
/// Sensor the gateway presents as the AS-4 Pan Tilt Specification, Joint Position
/// Sensor and Joint Position Driver (`jaus_as4::manipulator::pan_tilt`).
///
/// ```yaml
/// as4:
///   pan_tilt: { camera: 1, pan_limit: 90, tilt_limit: 30 }   # degrees, ± each
/// ```
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PanTiltFile {
    /// The camera on the mount (from 1; default 1).
    #[serde(default = "one")]
    pub camera: u8,
    /// The mount pans ± this far, degrees (the RA 3.3 pan axis's 100 %).
    pub pan_limit: f64,
    /// The mount tilts ± this far, degrees (the RA 3.3 tilt axis's 100 %).
    pub tilt_limit: f64,
}

fn one() -> u8 {
    1
}

/// `as4: { mission_spooler: … }` of a node file: an AS-4 component of its own (the
/// gateway's subsystem and node) serving the Mission Spooler
/// (`jaus_as4::mission::MissionSpoolerService`). A component, not a service of the
/// gateway's, because it takes control of the components its missions command: the
/// gateway's among them, which it reaches through the node's own socket (its address
/// is the bind address, 127.0.0.1 for 0.0.0.0). Destinations on other nodes are listed
/// with their address (an AS-4 node knows an id's address once it heard from it).
///
/// ```yaml
/// as4:
///   mission_spooler:
///     component: 5          # its AS-4 component id (default 5; not the gateway's)
///     authority: 100        # with which it asks its destinations for control (default 100; never above the controlling client's)
///     control_timeout: 5    # s a destination has to grant control (default 5)
///     command_timeout: 60   # s a command has to complete (default 60)
///     max_messages: 1024    # messages in a mission at most (default 1024)
///     destinations:         # AS-4 components on other nodes, and where they are
///       - { id: 2.1.1, peer: 10.0.0.2:3794 }
/// ```
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MissionSpoolerFile {
    /// Its AS-4 component id (default 5).
    #[serde(default)]
    pub component: Option<u8>,
    /// The authority with which it asks its destinations for control (default 100).
    #[serde(default)]
    pub authority: Option<u8>,
    /// Seconds a destination has to answer Request Control (default 5).
    #[serde(default)]
    pub control_timeout: Option<f64>,
    /// Seconds a command has to complete (default 60).
    #[serde(default)]
    pub command_timeout: Option<f64>,
    /// Messages in a mission at most (default 1024).
    #[serde(default)]
    pub max_messages: Option<usize>,
    /// AS-4 components on other nodes its missions command, and their addresses.
    #[serde(default)]
    pub destinations: Vec<SpoolerDestinationFile>,
}

/// One of `mission_spooler: { destinations: … }`.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpoolerDestinationFile {
    /// Its AS-4 id (`subsystem.node.component`).
    pub id: String,
    /// Its node's address.
    pub peer: SocketAddr,
}

/// `transport:` of a node file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TransportFile {
    /// JUDP over UDP.
    #[default]
    Udp,
    /// JTCP over TCP (`jaus::net::tcp`).
    Tcp,
    /// JSerial on the `serial:` line (`jaus::net::serial`).
    Serial,
}

/// `bind` when the file gives none (only `transport: serial` may leave it out).
fn no_bind() -> SocketAddr {
    SocketAddr::from(([127, 0, 0, 1], 0))
}

impl NodeFile {
    /// The serial transport of a `transport: serial` file (`path`: the file, for
    /// errors); its far end is `jaus_client::SERIAL_FAR_END`, the node's one peer.
    #[cfg(target_os = "linux")]
    pub fn serial_transport(
        &self,
        path: &Path,
    ) -> Result<jaus::net::serial::SerialTransport<SocketAddr>, String> {
        let Some(jaus::net::PeerUrl::Serial { path: line, baud }) = &self.serial else {
            return Err(format!("{}: no `serial:` line", path.display()));
        };
        jaus::net::serial::SerialTransport::open(
            jaus::net::serial::SerialConfig::new(line, *baud),
            jaus_client::SERIAL_FAR_END,
        )
        .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// The TCP transport of a `transport: tcp` file (`path`: the file, for errors).
    pub fn tcp_transport(&self, path: &Path) -> Result<jaus::net::tcp::TcpTransport, String> {
        jaus::net::tcp::TcpTransport::new(jaus::net::tcp::TcpConfig {
            listen: Some(self.bind),
            peers: self.peers.clone(),
            ..jaus::net::tcp::TcpConfig::default()
        })
        .map_err(|e| format!("{}: transport: tcp: {e}", path.display()))
    }
}

/// `io:` of a node file: how the node waits for and reads datagrams.
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IoFile {
    /// After a datagram, keep reading without blocking for this many microseconds
    /// (0: always block). Default 50.
    #[serde(default)]
    pub spin_us: Option<u64>,
    /// Datagrams read per system call where the OS offers it, 1 to 64. Default 32.
    #[serde(default)]
    pub batch: Option<usize>,
}

impl IoFile {
    /// The options, defaults filled in.
    pub fn options(&self) -> udp::IoOptions {
        let d = udp::IoOptions::default();
        udp::IoOptions {
            spin: self.spin_us.map_or(d.spin, Duration::from_micros),
            batch: self.batch.unwrap_or(d.batch),
        }
    }
}

/// `openjaus_components:` of a node file: the two sockets of OpenJAUS's local component
/// interface (docs/wire.md §8.5).
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OjComponentsFile {
    /// The control socket (check-in, lookups). Default 127.0.0.1:24627.
    #[serde(default)]
    pub control: Option<SocketAddr>,
    /// The data socket (raw JAUS packets). Default 127.0.0.1:24629.
    #[serde(default)]
    pub data: Option<SocketAddr>,
}

impl OjComponentsFile {
    /// The control and data sockets, defaults filled in.
    pub fn sockets(&self) -> (SocketAddr, SocketAddr) {
        let local = |port| SocketAddr::from(([127, 0, 0, 1], port));
        (
            self.control
                .unwrap_or_else(|| local(jaus::net::oj::CONTROL_PORT)),
            self.data.unwrap_or_else(|| local(jaus::net::oj::DATA_PORT)),
        )
    }
}

/// `multicast:` of a node file: broadcasts go to `group` on the node's port, and the
/// node listens to it (docs/wire.md §9.5).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MulticastFile {
    /// The group: 224.1.0.1 is OpenJAUS's subsystem-level group, 225.1.0.1 its node-level
    /// one.
    pub group: std::net::Ipv4Addr,
    /// Time to live of what the node sends to the group. Default 32 (OpenJAUS's
    /// subsystem level).
    #[serde(default)]
    pub ttl: Option<u32>,
    /// Whether the node's own multicasts come back to this host (other nodes on the
    /// same host then hear them). Default false, as OpenJAUS.
    #[serde(default)]
    pub loopback: Option<bool>,
    /// The local interface address to join on. Default 0.0.0.0 (the system's choice).
    /// What the node sends to the group leaves by the route to 224.0.0.0/4.
    #[serde(default)]
    pub interface: Option<std::net::Ipv4Addr>,
}

/// One `host:` entry as written.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(untagged)]
pub enum HostItem {
    /// `vehicle` or a stock component's name.
    Name(String),
    /// A stock component with settings.
    Component {
        /// Its name.
        component: String,
        /// Its instance.
        #[serde(default)]
        instance: Option<u8>,
        /// Where a driver's efforts go (`ss.node.component.instance`).
        #[serde(default)]
        output: Option<String>,
        /// A driver's pose sensor.
        #[serde(default)]
        pose: Option<String>,
        /// Its authority.
        #[serde(default)]
        authority: Option<u8>,
        /// The Communicator's data links (checked field by field when loaded).
        #[serde(default)]
        links: Option<serde_yaml::Value>,
    },
}

/// What a node hosts, checked.
#[derive(Debug, Clone, PartialEq)]
pub enum Hosted {
    /// The demo's simulated vehicle (every component of `jaus_sim::demo::vehicle_at`).
    Vehicle,
    /// The arm demo's ten manipulator components over one simulated arm
    /// (`jaus_sim::arm_demo::arm_components`).
    Arm,
    /// One stock component.
    Stock(crate::host::Entry),
}
impl NodeFile {
    /// Reads and checks a configuration file.
    pub fn load(path: &Path) -> Result<NodeFile, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let f: NodeFile =
            serde_yaml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let index = jaus_spec::location::LocationIndex::build(&text);
        let at = |key: &str| {
            let p = index.find(key);
            format!("{}:{}:{}", path.display(), p.line, p.column)
        };
        for (what, v) in [("subsystem", f.subsystem), ("node", f.node)] {
            if v == 0 || v == 255 {
                return Err(format!("{}: {what} {v} is not in 1..=254", at(what)));
            }
        }
        if let Some(io) = &f.io {
            if io.spin_us.is_some_and(|s| s > 10_000) {
                return Err(format!(
                    "{}: spin_us {} is over 10000 (10 ms of busy waiting per datagram)",
                    at("io.spin_us"),
                    io.spin_us.unwrap_or_default()
                ));
            }
            if let Some(b) = io.batch.filter(|b| !(1..=udp::MAX_BATCH).contains(b)) {
                return Err(format!(
                    "{}: batch {b} is not in 1..={}",
                    at("io.batch"),
                    udp::MAX_BATCH
                ));
            }
        }
        let has_bind = serde_yaml::from_str::<serde_yaml::Value>(&text)
            .ok()
            .is_some_and(|v| v.get("bind").is_some());
        match (f.transport, &f.serial) {
            (TransportFile::Serial, Some(jaus::net::PeerUrl::Serial { .. }))
                if !f.peers.is_empty() =>
            {
                return Err(format!(
                    "{}: a serial line has one far end: `transport: serial` takes no `peers`",
                    at("peers")
                ));
            }
            (TransportFile::Serial, Some(jaus::net::PeerUrl::Serial { .. })) => {}
            (TransportFile::Serial, _) => {
                return Err(format!(
                    "{}: `transport: serial` needs `serial: serial:///dev/DEVICE?baud=N`",
                    at("transport")
                ))
            }
            (_, Some(_)) => {
                return Err(format!(
                    "{}: `serial:` goes with `transport: serial`",
                    at("serial")
                ))
            }
            (_, None) if !has_bind => {
                return Err(format!(
                    "{}: missing `bind` (the node's address: its UDP socket, or its TCP listening address)",
                    path.display()
                ))
            }
            _ => {}
        }
        if f.transport != TransportFile::Udp {
            let udp_only = [
                ("multicast", f.multicast.is_some()),
                ("openjaus_components", f.openjaus_components.is_some()),
                (
                    "as4.multicast",
                    f.as4.as_ref().is_some_and(|a| a.multicast.is_some()),
                ),
                ("framing", f.framing != Framing::Judp),
            ];
            if let Some((key, _)) = udp_only.iter().find(|(_, set)| *set) {
                return Err(format!(
                    "{}: `{key}` is for UDP only; with `transport: {}` the node speaks {} (framing judp)",
                    at(key),
                    if f.transport == TransportFile::Tcp { "tcp" } else { "serial" },
                    if f.transport == TransportFile::Tcp { "JTCP to its peers" } else { "JSerial on its line" },
                ));
            }
        }
        if let Some(m) = f.as4.as_ref().and_then(|a| a.pan_tilt.as_ref()) {
            for (key, v, max) in [
                ("as4.pan_tilt.pan_limit", m.pan_limit, 180.0),
                ("as4.pan_tilt.tilt_limit", m.tilt_limit, 90.0),
            ] {
                if !(v > 0.0 && v <= max) {
                    return Err(format!(
                        "{}: {key} {v} is not in (0, {max}] degrees (± how far the mount turns)",
                        at(key)
                    ));
                }
            }
            if m.camera == 0 {
                return Err(format!(
                    "{}: as4.pan_tilt.camera 0: cameras count from 1",
                    at("as4.pan_tilt.camera")
                ));
            }
        }
        let hosted = f.hosted_at(&at)?;
        f.check_ros2(&hosted, path, &at)?;
        f.communicator_at(&hosted, &at)?;
        f.check_quic_links(path, &at)?;
        if let Some(p) = &f.policy {
            let policy = p.policy(&at)?;
            // AS5669A datagrams reach the gateway, not the RA 3.3 policy, and the gateway
            // commands the RA 3.3 components as a local component: an AS-4 sender would
            // get around what the policy guards.
            if f.as4.is_some() && !policy.is_open() {
                return Err(format!(
                    "{}: as4: the access policy does not cover AS-4 clients: a node with a `policy:` cannot serve `as4:` (any AS-4 sender could command what the policy guards); serve AS-4 from a node without a policy that only trusted networks reach",
                    at("as4")
                ));
            }
        }
        Ok(f)
    }
    /// The node configuration.
    pub fn node_config(&self) -> NodeConfig {
        let mut c = NodeConfig {
            subsystem: self.subsystem,
            node: self.node,
            framing: self.framing,
            peers: if self.transport == TransportFile::Serial {
                vec![jaus_client::SERIAL_FAR_END]
            } else {
                self.peers.clone()
            },
            ..NodeConfig::default()
        };
        if let Some(n) = &self.subsystem_name {
            c.manager.subsystem_name = n.clone();
        }
        c.manager.node_name = self
            .node_name
            .clone()
            .unwrap_or_else(|| format!("node {}.{}", self.subsystem, self.node));
        if let Some(ms) = self.heartbeat_ms {
            c.manager.heartbeat = Duration::from_millis(ms.max(10));
        }
        if let Some(ms) = self.node_timeout_ms {
            c.manager.node_timeout = Duration::from_millis(ms.max(100));
        }
        if let Some(m) = &self.multicast {
            c.multicast = Some(SocketAddr::from((m.group, self.bind.port())));
        }
        c.communicator = self.communicator();
        c.reliable = self.reliable.as_ref().map(ReliableFile::policy);
        // Checked by `load`.
        c.policy = self
            .policy
            .as_ref()
            .and_then(|p| p.policy(&|k| k.to_string()).ok());
        c
    }
}

#[cfg(test)]
mod transport_tests {
    use super::*;

    fn load(yaml: &str) -> Result<NodeFile, String> {
        let dir = std::env::temp_dir().join(format!("jaus-node-transport-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(format!("{}.yaml", yaml.len()));
        std::fs::write(&p, yaml).unwrap();
        NodeFile::load(&p)
    }

    #[test]
    fn reliable_sets_the_retry_policy_of_the_node() {
        let off = load("subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\n").unwrap();
        assert!(off.node_config().reliable.is_none());
        let on = load("subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nreliable: {}\n").unwrap();
        assert_eq!(
            on.node_config().reliable,
            Some(jaus::net::reliable::RetryPolicy::default())
        );
        let tuned = load(
            "subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nreliable: { first_timeout_ms: 50, max_timeout_ms: 20, attempts: 0 }\n",
        )
        .unwrap();
        let p = tuned.node_config().reliable.unwrap();
        assert_eq!(p.first_timeout, Duration::from_millis(50));
        assert_eq!(p.max_timeout, p.first_timeout, "never below the first wait");
        assert_eq!(p.max_attempts, 1, "at least one copy");
        let e =
            load("subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nreliable: { tries: 3 }\n").unwrap_err();
        assert!(e.contains("tries"), "{e}");
    }

    #[test]
    fn transports_are_checked_with_where() {
        let f = load(
            "subsystem: 1\nnode: 1\ntransport: tcp\nbind: 127.0.0.1:0\npeers: [127.0.0.1:9]\n",
        )
        .unwrap();
        assert_eq!(f.transport, TransportFile::Tcp);
        let e = load("subsystem: 1\nnode: 1\ntransport: tcp\nbind: 127.0.0.1:0\nmulticast: { group: 224.1.0.1 }\n")
            .unwrap_err();
        assert!(e.contains("`multicast` is for UDP only"), "{e}");
        let e = load("subsystem: 1\nnode: 1\n").unwrap_err();
        assert!(e.contains("missing `bind`"), "{e}");
        let f = load(
            "subsystem: 1\nnode: 1\ntransport: serial\nserial: serial:///dev/ttyUSB0?baud=9600\n",
        )
        .unwrap();
        assert_eq!(f.node_config().peers, [jaus_client::SERIAL_FAR_END]);
        let e = load("subsystem: 1\nnode: 1\ntransport: serial\n").unwrap_err();
        assert!(
            e.contains("needs `serial: serial:///dev/DEVICE?baud=N`"),
            "{e}"
        );
        let e = load("subsystem: 1\nnode: 1\ntransport: serial\nserial: serial:///dev/x\npeers: [127.0.0.1:9]\n")
            .unwrap_err();
        assert!(e.contains("takes no `peers`"), "{e}");
        let e = load("subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\nserial: serial:///dev/x\n")
            .unwrap_err();
        assert!(e.contains("goes with `transport: serial`"), "{e}");
        let e = load("subsystem: 1\nnode: 1\ntransport: serial\nserial: tcp://127.0.0.1:1\n")
            .unwrap_err();
        assert!(e.contains("needs `serial:"), "{e}");
    }
}
