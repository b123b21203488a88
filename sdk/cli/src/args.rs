//! The command line: the `jaus` subcommands and their options (clap), and the network
//! options the commands that act as a component share.

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "jaus",
    version,
    about = "JAUS RA 3.3 toolkit: message catalogue, packet decoder and encoder, nodes, the simulated-vehicle demo"
)]
pub(crate) struct Cli {
    /// More log output on stderr (-v info, -vv debug, -vvv trace: one line per message
    /// sent and received); default: warnings. `RUST_LOG` (e.g. `jaus::net=trace`)
    /// overrides it when set.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub(crate) verbose: u8,
    /// A vendor's YAML overlay (on the SDK's definitions, as its build loads it), for
    /// `messages`, `decode`, `encode`, `send`, `query` and `watch`: its messages are
    /// encoded from and printed as JSON by name. Repeatable.
    #[arg(long, value_name = "FILE", global = true)]
    pub(crate) spec: Vec<std::path::PathBuf>,
    #[command(subcommand)]
    pub(crate) cmd: Cmd,
}

#[derive(Subcommand)]
pub(crate) enum Cmd {
    /// List the message set: code, name, group, and the report answering each query.
    Messages {
        /// Only this group (e.g. `platform`).
        #[arg(long)]
        group: Option<String>,
        /// One message: its fields with types, units, ranges, presence bits, and an
        /// example JSON line.
        name: Option<String>,
        /// The catalogue as JSON lines, one per message: code (number), name, title,
        /// group, class, report (name or null), experimental.
        #[arg(long)]
        json: bool,
    },
    /// Decode packets given as hex (arguments, or stdin one per line) to JSON lines.
    Decode {
        /// Packets as hex: 16-byte header followed by the body.
        hex: Vec<String>,
        /// Decode the JAUS messages of a capture (pcap or pcapng) instead, multi-packet
        /// messages reassembled; each line also has `t` (s), `src` and `dst`.
        #[arg(long, value_name = "FILE", conflicts_with = "hex")]
        pcap: Option<std::path::PathBuf>,
    },
    /// Send the datagrams of a capture (pcap or pcapng) to a node again, with their
    /// captured timing.
    Replay {
        /// The capture.
        file: std::path::PathBuf,
        /// Where to send them (a node's socket).
        #[arg(long)]
        to: std::net::SocketAddr,
        /// Only the datagrams originally sent to this socket (e.g. what one node received).
        #[arg(long, value_name = "ADDR")]
        only_to: Option<std::net::SocketAddrV4>,
        /// Time scale (2: twice as fast; 0: as fast as possible).
        #[arg(long, default_value_t = 1.0)]
        speed: f64,
        /// Local socket.
        #[arg(long, default_value = "127.0.0.1:0")]
        bind: std::net::SocketAddr,
    },
    /// Encode JSON lines from stdin (the form `decode` prints) to hex packets.
    Encode,
    /// Walk through the SDK: build messages, encode packets, decode them back.
    Tour,
    /// The operator console in the browser: a System Commander on a node of its own
    /// serving a local page (system tree, map with trails, control, emergency stop,
    /// waypoints, missions, message log). `--vehicle` also runs the demo's simulated
    /// vehicle on loopback: `jaus ocu --vehicle`, then open the address it prints.
    Ocu {
        /// A node file (as `jaus node` reads, without `host:`) for the console's node.
        #[arg(long)]
        config: Option<std::path::PathBuf>,
        /// The web server's address (keep it on 127.0.0.1 unless the network is trusted:
        /// the page commands vehicles). Open the address printed at start-up: it carries
        /// the run's key, without which the server refuses everything but its static
        /// files; on any address other than loopback that key is all that keeps others
        /// out, and plain HTTP carries it unencrypted.
        #[arg(long, default_value = "127.0.0.1:8700")]
        http: std::net::SocketAddr,
        /// A DNS name the page may be opened under besides IP addresses and `localhost`
        /// (every other name is refused, against DNS rebinding); repeatable.
        #[arg(long = "allow-host", value_name = "NAME")]
        allow_hosts: Vec<String>,
        /// The console's JAUS socket (without --config).
        #[arg(long, default_value = "127.0.0.1:0")]
        bind: std::net::SocketAddr,
        /// Nodes to talk to (without --config); repeatable.
        #[arg(long = "peer", value_name = "ADDR")]
        peers: Vec<std::net::SocketAddr>,
        /// The console's subsystem id (without --config).
        #[arg(long, default_value_t = 200)]
        subsystem: u8,
        /// The console's node id (without --config).
        #[arg(long, default_value_t = 1)]
        node: u8,
        /// Also run the demo's simulated vehicle (subsystem 1) on loopback.
        #[arg(long)]
        vehicle: bool,
        /// The map's origin in degrees: the point whose metres east and north the map
        /// counts (default: the first position received). Give it with --background so
        /// the image's metres mean the same place on every run; --tiles needs an origin
        /// (this, or the first position) to place tiles.
        #[arg(long, value_name = "LAT,LON", value_parser = jaus_cli::ocu::parse_origin, allow_hyphen_values = true)]
        origin: Option<(f64, f64)>,
        /// A background image under the map (PNG or JPEG; read once at start-up, never
        /// fetched). Placed in the map's frame (metres east, north of the origin) by
        /// --background-bounds, else by its world file beside it (map.png -> map.pgw,
        /// map.jpg -> map.jgw, or .wld: six lines: metres per pixel east, rotation,
        /// rotation, metres per pixel north (negative), then x and y of the centre of the
        /// upper-left pixel).
        #[arg(long, value_name = "PATH")]
        background: Option<std::path::PathBuf>,
        /// Where the background image's outer edges lie: west, south, east, north, in
        /// metres east and north of the map's origin (e.g. -100,-50,100,50).
        #[arg(long, value_name = "X0,Y0,X1,Y1", requires = "background", value_parser = jaus_cli::ocu::parse_bounds, allow_hyphen_values = true)]
        background_bounds: Option<[f64; 4]>,
        /// A local directory of map tiles in the usual z/x/y.png layout (as tile
        /// downloaders and tile servers' caches write; .jpg and .webp too), drawn under
        /// the map by latitude and longitude; nothing is fetched from the network.
        #[arg(long, value_name = "DIR")]
        tiles: Option<std::path::PathBuf>,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// A ROS 2 robot on the JAUS network, with no ROS install: its cmd_vel, odom and
    /// fix topics (DDS) as a Primitive Driver, Local Pose, Velocity State and Global
    /// Pose Sensor on UDP, a watchdog stopping it when the JAUS side loses its
    /// controller or the ROS side goes silent (docs/ros2.md); prints each watchdog event
    /// as a JSON line, the bridge's counters at the end. With --vehicle SUBSYSTEM, the
    /// other direction: a JAUS vehicle in ROS 2 (odom, fix, jaus/status published;
    /// cmd_vel and goal_pose drive it).
    Ros2 {
        #[command(flatten)]
        args: jaus_cli::ros2::Ros2Args,
    },
    /// Run a node from a configuration file (YAML: subsystem, node, bind, framing,
    /// transport, peers, host, as4, as4_vehicles, ros2, ...; `jaus_node::NodeFile`);
    /// prints the system tree whenever it changes. `ros2:` (the keys of `jaus ros2
    /// --config`'s file: domain_id, node_name, namespace, topics, frames, odom_axes,
    /// qos_commands, qos_sensors, effort, watchdog_ms, command_timeout_ms) hosts a ROS 2
    /// robot as this node's Primitive Driver 33.1 (cmd_vel), Global Pose Sensor 38.1
    /// (fix), Local Pose Sensor 41.1 and Velocity State Sensor 42.1 (odom), over DDS
    /// with no ROS install (docs/ros2.md).
    Node {
        /// The configuration file.
        #[arg(long)]
        config: std::path::PathBuf,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
        /// Write every datagram the node receives and sends to this pcapng file
        /// (Wireshark: load the dissector of `jaus-gen wireshark`).
        #[arg(long, value_name = "FILE")]
        capture: Option<std::path::PathBuf>,
    },
    /// Make a node's key and certificate for authenticated QUIC data links: writes
    /// NAME.crt (for the far end's `peer_cert`) and NAME.key (mode 0600; stays on this
    /// node), prints both paths and the certificate's SHA-256 fingerprint. Never
    /// overwrites existing files.
    Keygen {
        /// The node's name (letters, digits, `-`, `_`, `.`): the files' names and the
        /// certificate's subject.
        name: String,
        /// Where to write the files (created if missing).
        #[arg(long, default_value = ".")]
        dir: std::path::PathBuf,
    },
    /// Run stock components as OpenJAUS component processes under an OpenJAUS node
    /// manager (or a `jaus node` with `openjaus_components`): each checks in for its
    /// address on the control socket, then talks raw JAUS on the data socket.
    Attach {
        /// Stock components to run (names as in a node file's `host:`).
        #[arg(long = "host", value_name = "NAME", required = true)]
        host: Vec<String>,
        /// The node manager's control socket.
        #[arg(long, default_value = "127.0.0.1:24627")]
        control: std::net::SocketAddr,
        /// The node manager's data socket.
        #[arg(long, default_value = "127.0.0.1:24629")]
        data: std::net::SocketAddr,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// Test components on the network against Part 1 and the core rules (checks read
    /// from the definitions, --spec overlays included); exits 1 when a required check fails.
    Conform {
        #[command(flatten)]
        net: NetArgs,
        #[command(flatten)]
        args: crate::conform::ConformArgs,
    },
    /// Write a Wireshark/tshark dissector (Lua) generated from the definitions built
    /// into this binary, RA 3.3 and AS-4, with a vendor's (--spec overlay files for RA
    /// 3.3, --as4-spec directories of AS-4 YAML): JUDP, "JAUS01.0" and AS5669A framing,
    /// every field of every message, messages carried inside others, multi-packet
    /// messages reassembled. Load it with `tshark -X lua_script:FILE` or from
    /// Wireshark's plugin folder.
    Wireshark {
        /// The file to write.
        #[arg(long, value_name = "FILE", default_value = "jaus.lua")]
        out: std::path::PathBuf,
        /// Directories of a vendor's AS-4 YAML, loaded on jaus-as4's definitions.
        #[arg(long = "as4-spec", value_name = "DIR")]
        as4_spec: Vec<std::path::PathBuf>,
    },
    /// Drive an AS-4 vehicle (AS5669A): find its component, take control, load a
    /// waypoint list and execute it with its Local or Global Waypoint List Driver,
    /// following the active element and the pose until done; then standby and release.
    As4Drive {
        #[command(flatten)]
        args: jaus_cli::as4_drive::As4DriveArgs,
    },
    /// Query an AS-4 component (AS5669A) by message name, for any definitions:
    /// jaus-as4's, a vendor's YAML on them (--spec) or imported JSIDL (--jsidl); each
    /// message is sent after the previous one was answered; prints every message the
    /// component sends back as a JSON line; exits 1 when one is not answered.
    As4Query {
        #[command(flatten)]
        args: jaus_cli::as4_talk::As4TalkArgs,
    },
    /// Send messages to an AS-4 component by name (as for `as4-query`), optionally under
    /// control (--control AUTHORITY, given back at the end), and print what it sends
    /// back for --wait seconds.
    As4Send {
        #[command(flatten)]
        args: jaus_cli::as4_talk::As4TalkArgs,
    },
    /// Listen for a while and print the system tree seen on the network.
    Discover {
        #[command(flatten)]
        net: NetArgs,
        /// The tree as one JSON document: {"subsystems": [{"id", "name", "nodes": [{"id",
        /// "name", "components": [{"address", "name", "services"}]}]}]}.
        #[arg(long)]
        json: bool,
    },
    /// Send messages in one session (arguments, or JSON lines on stdin as they come),
    /// each after the previous one was answered; prints every message addressed to this
    /// tool as a timestamped JSON line as it arrives. Control taken in the session is
    /// held (heartbeats keep this tool in the system) and given back at the end.
    Send {
        #[command(flatten)]
        net: NetArgs,
        /// Destination (subsystem.node.component.instance) of messages without a header.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// Stay this many seconds after the last message (holding control, printing
        /// what arrives); default: until every message is answered or --wait passed.
        #[arg(long)]
        hold: Option<f64>,
        /// Confirm every command by its effect and print the outcome of each
        /// (acknowledged; confirmed by read-back, for a component that never
        /// acknowledges, by its `readback:` query or Query Component Status; refused; not
        /// confirmed, with what is known); exits 1 when one is not confirmed.
        #[arg(long)]
        confirm: bool,
        /// Messages: {"message": "SetTravelSpeed", "fields": {"speed": 2.0}}; `fields` may
        /// be left out for a message without fields. None: JSON lines from stdin.
        messages: Vec<String>,
    },
    /// Send queries and print their reports; returns as soon as every query is answered
    /// and exits 1 if one was not within --wait.
    Query {
        #[command(flatten)]
        net: NetArgs,
        /// Destination address.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// The queries (as for `send`).
        messages: Vec<String>,
    },
    /// Print every message addressed to this tool as it arrives (timestamped JSON
    /// lines) until interrupted: service connections (--sc), events, replies to the
    /// messages given.
    Watch {
        #[command(flatten)]
        net: NetArgs,
        /// Provider of the service connections, and destination of the messages.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// A service connection to open: REPORT@HZ[:PRESENCE], e.g. ReportGlobalPose@2:0x1ff.
        #[arg(long)]
        sc: Vec<String>,
        /// Stop after this many seconds (default: until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
        /// Also print queries and heartbeats sent to this tool.
        #[arg(long)]
        all: bool,
        /// Messages to send first (as for `send`).
        messages: Vec<String>,
    },
    /// Run a simulated subsystem: an operator takes control, drives a waypoint mission
    /// and the path segments of Part 1 Figures 5-12/5-14; prints arrival times and
    /// cross-track errors per leg and plots the run.
    Demo {
        /// Seed of the sensor noise.
        #[arg(long, default_value_t = 7)]
        seed: u64,
        /// Position noise of the pose sensors (standard deviation, m).
        #[arg(long, default_value_t = 0.02)]
        noise: f64,
        /// Run at wall-clock speed (default: as fast as possible).
        #[arg(long)]
        realtime: bool,
        /// Directory for demo.svg.
        #[arg(long, default_value = "target/demo")]
        out: std::path::PathBuf,
        /// Progress line every this many simulated seconds (0: none).
        #[arg(long, default_value_t = 5.0)]
        progress: f64,
        /// Run only the operator (node 1.2), driving a vehicle hosted by `jaus node`
        /// (`host: [vehicle]`) over UDP.
        #[arg(long)]
        ocu_only: bool,
        /// With --ocu-only: the local socket.
        #[arg(long, default_value = "127.0.0.1:3795")]
        bind: std::net::SocketAddr,
        /// With --ocu-only: the vehicle node's socket.
        #[arg(long, default_value = "127.0.0.1:3794")]
        peer: Vec<std::net::SocketAddr>,
        /// Run the arm instead: the ten manipulator components over a simulated 6-axis
        /// arm and an operator's pick-and-place sequence (pose, joint move, velocity
        /// jog, timed poses); prints each move's time and error and plots arm.svg.
        #[arg(long, conflicts_with = "ocu_only")]
        arm: bool,
        /// Run the vehicle's node and the operator's over a simulated radio that loses
        /// this percentage of datagrams (and delays them 0.2-50 ms, reordering them, and
        /// duplicates 5 %), drawn from --seed; the nodes make their commands arrive
        /// (acknowledged, resent, carried out once) and the counters are printed.
        #[arg(long, value_name = "PCT", conflicts_with_all = ["ocu_only", "arm"], value_parser = percent)]
        loss: Option<f64>,
        /// With --loss: send each command once, as before, to see the difference.
        #[arg(long, requires = "loss")]
        no_retry: bool,
    },
}

/// Network options of the commands that act as a component.
#[derive(clap::Args)]
pub(crate) struct NetArgs {
    /// This tool's own address (a System Commander). On the node of a peer, the tool
    /// joins that node as one of its components; else it runs a node of its own.
    /// Default: S.1.40.1 with S in 200-253 taken from the process id, so that two
    /// sessions at once are two subsystems (OpenJAUS keeps one address per subsystem).
    /// With `conform --as4`: the judge's AS-4 id S.N.C (default 42.1.1).
    #[arg(long, value_parser = me_arg)]
    pub(crate) me: Option<String>,
    /// Local socket (default: port 3794 on an address of its own, e.g. 127.0.0.2:3794,
    /// because JUDP peers answer port 3794 of the sender's address).
    #[arg(long)]
    pub(crate) bind: Option<std::net::SocketAddr>,
    /// auto (join the peer's node when --me is on it), join, or node.
    #[arg(long, default_value = "auto")]
    pub(crate) mode: jaus_client::Mode,
    /// Peer nodes: HOST:PORT (JUDP), tcp://HOST:PORT (JTCP, dialed) or
    /// serial:///dev/DEVICE?baud=N (JSerial; one line); repeatable, one transport.
    #[arg(long, default_value = "127.0.0.1:3794")]
    pub(crate) peer: Vec<jaus::net::PeerUrl>,
    /// Framing: judp or opc.
    #[arg(long, default_value = "judp")]
    pub(crate) framing: String,
    /// Seconds to wait for answers (discover: to listen).
    #[arg(long, default_value_t = 2.0)]
    pub(crate) wait: f64,
    /// Confirm every command by its effect (`send --confirm` sets it).
    #[arg(skip)]
    pub(crate) confirm: bool,
}

impl NetArgs {
    /// The peers of a command that speaks UDP only (`what`, for the error).
    pub(crate) fn udp_peers(&self, what: &str) -> Result<Vec<std::net::SocketAddr>, String> {
        self.peer
            .iter()
            .map(|p| match p {
                jaus::net::PeerUrl::Udp(a) => Ok(*a),
                other => Err(format!("--peer {other}: {what} speaks JUDP over UDP only")),
            })
            .collect()
    }

    pub(crate) fn client(&self) -> Result<jaus_client::Client, String> {
        let framing = match self.framing.as_str() {
            "judp" => jaus::net::Framing::Judp,
            "opc" => jaus::net::Framing::Opc,
            other => return Err(format!("unknown framing `{other}` (judp or opc)")),
        };
        let me = match &self.me {
            Some(m) => m
                .parse::<jaus::Address>()
                .map_err(|_| format!("--me {m}: expected subsystem.node.component.instance"))?,
            None => jaus_client::default_me(),
        };
        let (carrier, peers) = jaus_client::carrier_of(&self.peer)?;
        Ok(jaus_client::Client {
            name: "jaus CLI".into(),
            me,
            bind: self.bind,
            peers,
            carrier,
            framing,
            wait: std::time::Duration::from_secs_f64(self.wait.max(0.0)),
            mode: self.mode,
            confirm: self.confirm,
        })
    }
}

/// `--me`: an RA 3.3 address S.N.C.I, or an AS-4 id S.N.C (`conform --as4`).
fn me_arg(text: &str) -> Result<String, String> {
    if text.parse::<jaus::Address>().is_ok() || text.parse::<jaus::net::as5669a::As4Id>().is_ok() {
        Ok(text.to_string())
    } else {
        Err(format!(
            "`{text}`: expected subsystem.node.component.instance (or an AS-4 id subsystem.node.component with conform --as4)"
        ))
    }
}

/// A percentage, 0 to 100.
fn percent(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|e| format!("`{s}`: {e}"))?;
    if (0.0..=100.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("`{s}`: a percentage is 0 to 100"))
    }
}
