//! Running a node file: the node on its sockets, its system tree printed when it
//! changes.

use std::io::Write;
use std::net::SocketAddr;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::udp;
use jaus_client::TreePrinter;

use super::*;

/// `jaus node --config FILE [--capture PCAPNG]`: runs a node until interrupted (or for
/// `duration`), printing the system tree when it changed, at most once a second; with
/// `capture`, every datagram it receives and sends is written to that pcapng file.
pub fn node(
    config: &Path,
    duration: Option<Duration>,
    capture: Option<&Path>,
    stop: &AtomicBool,
    out: &mut impl Write,
) -> Result<(), String> {
    let file = NodeFile::load(config)?;
    let t0 = Instant::now();
    let (mut node, native) = file.build_node_and_as4(config, t0)?;
    // Before the first line: the robot's DDS domain joined, its components hosted.
    let ros2 = file.start_ros2(config, &mut node, t0)?;
    let _ = writeln!(
        out,
        "node {} on {} ({:?}), peers {:?}",
        node.address(),
        file.bind,
        file.framing,
        file.peers
    );
    if let Some(p) = file.store_path(config) {
        let _ = writeln!(
            out,
            "store: {} (world model and mission spooler durable)",
            p.display()
        );
    }
    let _ = match node.policy() {
        Some(p) if !p.policy().is_open() => writeln!(out, "access policy: {}", p.policy().describe()),
        _ => writeln!(
            out,
            "access: open (no `policy:`): any sender that reaches this node may command its components and take control of them"
        ),
    };
    if let Some(c) = file.communicator() {
        let links: Vec<String> = file
            .communicator_links()
            .iter()
            .map(|l| format!("link {} {} {} -> {}", l.id(), l.kind(), l.bind(), l.peer()))
            .collect();
        let _ = writeln!(
            out,
            "other subsystems through the communicator {c}{}{}",
            if links.is_empty() { "" } else { ": " },
            links.join(", ")
        );
    }
    if let (Some(r), Some(link)) = (&file.ros2, &ros2) {
        let at = |id| jaus::Address::new(file.subsystem, file.node, id, jaus_ros2::ids::INSTANCE);
        let [cmd_vel, odom, fix] = link.dds_topics();
        let _ = writeln!(
            out,
            "ROS 2 robot on DDS domain {} as node {}/{}: {cmd_vel} from Primitive Driver {}, {odom} to Local Pose Sensor {} and Velocity State Sensor {}, {fix} to Global Pose Sensor {}",
            r.domain_id,
            r.namespace.trim_end_matches('/'),
            r.node_name,
            at(jaus_ros2::ids::PRIMITIVE_DRIVER),
            at(jaus_ros2::ids::LOCAL_POSE_SENSOR),
            at(jaus_ros2::ids::VELOCITY_STATE_SENSOR),
            at(jaus_ros2::ids::GLOBAL_POSE_SENSOR),
        );
        let (scan, camera) = link.sensor_topics();
        if let Some(scan) = scan {
            let _ = writeln!(
                out,
                "ROS 2 lidar: {scan} to Range Sensor {}",
                at(jaus_ros2::ids::RANGE_SENSOR)
            );
        }
        if let Some(camera) = camera {
            let _ = writeln!(
                out,
                "ROS 2 camera: {camera} to Visual Sensor {}",
                at(jaus_ros2::ids::VISUAL_SENSOR)
            );
        }
    }
    let mut as4 = file.as4_config();
    if let Some(gw) = &as4 {
        let _ = writeln!(
            out,
            "AS-4 (AS5669A) on the same socket: component {} presenting subsystem {} (gateway {})",
            gw.as4, gw.present, gw.ra33
        );
    }
    // Digital Video: the gateway's service publishes to the hub, the server serves it.
    let video = match (&mut as4, file.as4.as_ref().and_then(|a| a.video.as_ref())) {
        (Some(gw), Some(v)) => {
            let (hub, limits) = v.hub();
            let server = crate::video::MjpegServer::start(v, hub.clone())
                .map_err(|e| format!("{}: as4.video.listen {}: {e}", config.display(), v.listen))?;
            let _ = writeln!(
                out,
                "AS-4 Digital Video of the RA 3.3 visual sensor: MJPEG at http://{}/video/{}{} while an AS-4 client plays it (at most {} frames/s)",
                server.local_addr(),
                jaus_as4::environment::SENSOR_ID,
                if v.token.is_some() { "?token=…" } else { "" },
                limits.max_frame_rate
            );
            gw.video = Some((hub, limits));
            Some(server)
        }
        _ => None,
    };
    if let (Some(gw), Some(m)) = (
        &as4,
        file.as4.as_ref().and_then(|a| a.mission_spooler.as_ref()),
    ) {
        let _ = writeln!(
            out,
            "AS-4 Mission Spooler: component {}.{}.{}",
            gw.as4.subsystem,
            gw.as4.node,
            m.component.unwrap_or(5)
        );
    }
    let vehicles = file.as4_vehicles(config)?;
    let mut proxies = Vec::new();
    for (v, peer) in vehicles {
        let (me, instance) = (v.me, v.instance);
        let p = jaus_as4::proxy::install(&mut node, v, peer, t0)
            .map_err(|e| format!("{}: as4_vehicles: {e}", config.display()))?;
        let _ = writeln!(
            out,
            "AS-4 vehicle at {peer} presented as RA 3.3 components {}.{}.*.{instance} (AS-4 client {me})",
            file.subsystem, file.node
        );
        proxies.push(p);
    }
    let _ = out.flush();
    let mut printer = TreePrinter::new(Duration::from_secs(1));
    // JTCP: the node listens on `bind` over TCP and dials its peers; no UDP socket.
    let stream = match file.transport {
        TransportFile::Udp => None,
        TransportFile::Tcp => Some(Carrier::Tcp(Box::new(file.tcp_transport(config)?))),
        #[cfg(target_os = "linux")]
        TransportFile::Serial => Some(Carrier::Serial(Box::new(file.serial_transport(config)?))),
        #[cfg(not(target_os = "linux"))]
        TransportFile::Serial => {
            return Err(format!(
                "{}: serial lines are supported on Linux only",
                config.display()
            ))
        }
    };
    // Over TCP the UDP socket is a stand-in that nothing reads (the settings that need
    // it are refused by `load`).
    let udp_bind = if stream.is_some() {
        SocketAddr::from(([127, 0, 0, 1], 0))
    } else {
        file.bind
    };
    let socket = std::net::UdpSocket::bind(udp_bind).map_err(|e| format!("{}: {e}", file.bind))?;
    let local = match &stream {
        Some(Carrier::Tcp(t)) => t.local_addr().unwrap_or(file.bind),
        Some(_) => file.bind,
        None => socket
            .local_addr()
            .map_err(|e| format!("{}: {e}", file.bind))?,
    };
    if let Some(c) = &stream {
        let _ = writeln!(out, "transport: {}", c.describe());
        let _ = out.flush();
    }
    if let Some(m) = &file.multicast {
        let at =
            |e: std::io::Error| format!("{}: multicast group {}: {e}", config.display(), m.group);
        if !m.group.is_multicast() {
            return Err(at(std::io::Error::other("not a multicast address")));
        }
        let interface = m.interface.unwrap_or(std::net::Ipv4Addr::UNSPECIFIED);
        socket.join_multicast_v4(&m.group, &interface).map_err(at)?;
        socket
            .set_multicast_ttl_v4(m.ttl.unwrap_or(32))
            .map_err(at)?;
        socket
            .set_multicast_loop_v4(m.loopback.unwrap_or(false))
            .map_err(at)?;
        let _ = writeln!(
            out,
            "multicast discovery: group {}:{} (ttl {}, interface {interface})",
            m.group,
            local.port(),
            m.ttl.unwrap_or(32)
        );
    }
    if let Some(group) = file.as4.as_ref().and_then(|a| a.multicast) {
        join_as4_group(&socket, local, group)
            .map_err(|e| format!("{}: as4.multicast: {e}", config.display()))?;
        let _ = writeln!(
            out,
            "AS-4 first contact: listening on group {group}:{} (nothing is sent to it)",
            local.port()
        );
    }
    let mut writer = match capture {
        Some(p) => Some(
            jaus_client::capture::CaptureWriter::create(p)
                .map_err(|e| format!("{}: {e}", p.display()))?,
        ),
        None => None,
    };
    let mut capture_error = None;
    let mut last_flush = Instant::now();
    let oj = match &file.openjaus_components {
        Some(o) => {
            let (control, data) = o.sockets();
            let bind = |a: SocketAddr| {
                std::net::UdpSocket::bind(a).map_err(|e| {
                    format!("{}: OpenJAUS component socket {a}: {e}", config.display())
                })
            };
            let pair = (bind(control)?, bind(data)?);
            let _ = writeln!(
                out,
                "OpenJAUS component interface: control {control}, data {data}"
            );
            Some(pair)
        }
        None => None,
    };
    let sockets = udp::NodeSockets {
        network: &socket,
        component_control: oj.as_ref().map(|p| &p.0),
        component_data: oj.as_ref().map(|p| &p.1),
    };
    let io = file.io.clone().unwrap_or_default().options();
    let mut carrier = stream.unwrap_or(Carrier::Udp(sockets, io));
    let until = duration.map(|d| t0 + d);
    let mut show_tree = |n: &jaus::net::Node| {
        if let Some(link) = &ros2 {
            for e in link.events() {
                log_ros2_event(t0, &e);
            }
        }
        let now = Instant::now();
        if let Some(text) = printer.poll(now, n.tree_version(), n.tree()) {
            let _ = writeln!(
                out,
                "--- system tree at {:.1} s\n{text}",
                t0.elapsed().as_secs_f64()
            );
            let _ = out.flush();
        }
    };
    let mut tap = |direction: udp::Direction, peer: SocketAddr, datagram: &[u8]| {
        let Some(w) = writer.as_mut() else {
            return;
        };
        let time = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap_or_default();
        let (src, dst) = match direction {
            udp::Direction::Received => (peer, local),
            udp::Direction::Sent => (local, peer),
        };
        let mut written = w.write(time, src, dst, datagram);
        if written.is_ok() && last_flush.elapsed() >= Duration::from_secs(1) {
            last_flush = Instant::now();
            written = w.flush();
        }
        if let Err(e) = written {
            // Stop capturing; the node keeps running.
            capture_error.get_or_insert(e.to_string());
            writer = None;
        }
    };
    let mut proxies = proxies.into_iter();
    let first_proxy = if as4.is_none() { proxies.next() } else { None };
    // The AS-4 side's counters, taken from the mux before it is unwrapped.
    let mut as4_line: Option<String> = None;
    let as4_transport = jaus::net::as5669a::As4Config {
        reliable: file.reliable.as_ref().map(super::ReliableFile::policy),
        ..jaus::net::as5669a::As4Config::default()
    };
    let result = match (as4, first_proxy) {
        (None, None) => carrier.drive(&mut node, stop, until, |n| show_tree(n), &mut tap),
        (None, Some(first)) => {
            // AS-4 vehicles only: the node is their client on its own socket, each
            // proxy served the messages for its own AS-4 id.
            let mut mux = jaus::net::as5669a::As4Mux::new(node, first, as4_transport);
            for p in proxies {
                mux.add_endpoint(p);
            }
            let r = carrier.drive(&mut mux, stop, until, |m| show_tree(m.inner()), &mut tap);
            as4_line = Some(as4_stats_line(mux.side()));
            node = mux.into_inner();
            r
        }
        (Some(gw), _) => {
            // AS-4 clients on the same socket: version-2 datagrams go to the gateway
            // the node hosts, which finds the presented components in the tree (and
            // to the proxies of `as4_vehicles:`, those for their ids).
            let mut dual = jaus_as4::gateway::DualNode::with_transport(node, gw, as4_transport)
                .map_err(|e| format!("{}: as4: {e}", config.display()))?;
            for p in proxies {
                dual = dual.with_endpoint(p);
            }
            if let Some(spooler) = file.as4_mission_spooler(config)? {
                dual = dual.with_endpoint(spooler);
            }
            for s in native {
                dual = dual.with_service(s);
            }
            let r = carrier.drive(&mut dual, stop, until, |d| show_tree(d.node()), &mut tap);
            as4_line = Some(as4_stats_line(dual.as4()));
            node = dual.into_node();
            r
        }
    }
    .map_err(|e| format!("{}: {e}", file.bind));
    #[cfg(target_os = "linux")]
    if let Carrier::Serial(t) = &carrier {
        let (s, l) = (t.stats(), t.line_stats());
        let _ = writeln!(
            out,
            "serial stats: datagrams_received {} datagrams_sent {} queue_full {} not_carried {} write_errors {} bytes_lost {} packets {} bytes_skipped {} resyncs {} bad_header_checksum {} bad_checksum {} bad_length {} bad_version {} malformed {} abandoned {}",
            s.datagrams_received, s.datagrams_sent, s.queue_full, s.not_carried, s.write_errors, s.bytes_lost, l.frames, l.bytes_skipped, l.resyncs,
            l.bad_header_checksum, l.bad_checksum, l.bad_length, l.bad_version, l.malformed, l.abandoned,
        );
    }
    if let Carrier::Tcp(t) = &carrier {
        let s = t.stats();
        let _ = writeln!(
            out,
            "tcp stats: accepted {} connected {} connect_failures {} closed {} bad_stream {} stalled {} refused {} datagrams_received {} datagrams_sent {} queue_full {} no_connection {} wrong_version {} not_carried {}",
            s.accepted, s.connected, s.connect_failures, s.closed, s.bad_stream, s.stalled, s.refused,
            s.datagrams_received, s.datagrams_sent, s.queue_full, s.no_connection, s.wrong_version, s.not_carried,
        );
    }
    // What the node counted, for whoever watched it run (one line, `key value` pairs).
    let st = node.stats();
    let (reassembly, buffered) = node.reassembly();
    let (mut missed, mut refused) = (0, 0);
    for (_, c) in node.component_stats() {
        missed += c.reports_missed;
        refused += c.not_controller + c.wrong_state + c.invalid;
    }
    let _ = writeln!(
        out,
        "stats: received {} sent {} delivered_local {} bad_framing {} bad_packet {} from_self {} not_for_us {} no_such_component {} outbox_full {} flooded {} reassembly_timed_out {} reassembly_over_limit {} reassembly_buffered {buffered} reports_missed {missed} commands_refused {refused} to_communicator {} from_communicator {} not_via_communicator {} policy_refused {}",
        st.received,
        st.sent,
        st.delivered_local,
        st.bad_framing,
        st.bad_packet,
        st.from_self,
        st.not_for_us,
        st.no_such_component,
        st.outbox_full,
        st.flooded,
        reassembly.timed_out,
        reassembly.over_limit,
        st.to_communicator,
        st.from_communicator,
        st.not_via_communicator,
        st.policy_refused,
    );
    // Commands that arrive: what this node's commands did, and the retransmissions it
    // carried out once (those happen whether or not `reliable:` is set).
    let r = node.reliable_stats();
    if file.reliable.is_some() || r.duplicates_dropped > 0 {
        let _ = writeln!(
            out,
            "reliable stats: tracked {} retried {} acknowledged {} refused {} given_up {} untracked_peer {} untracked_full {} stray_answers {} duplicates_dropped {} answers_repeated {}",
            r.tracked, r.retried, r.acknowledged, r.refused, r.given_up, r.untracked_peer,
            r.untracked_full, r.stray_answers, r.duplicates_dropped, r.answers_repeated,
        );
    }
    if let Some(line) = &as4_line {
        let _ = writeln!(out, "{line}");
    }
    if let Some(v) = video {
        let _ = writeln!(out, "{}", v.stats_line());
    }
    if let Some(link) = ros2 {
        for e in link.events() {
            log_ros2_event(t0, &e);
        }
        let s = link.stats();
        let _ = writeln!(
            out,
            "ros2 stats: odom {} fix {} refused {} foreign_frames {} published {} published_zero {} publish_errors {} superseded {} held {} events_dropped {} scans {} scans_refused {} images {} images_refused {}",
            s.odom, s.fix, s.refused, s.foreign_frames, s.published, s.published_zero,
            s.publish_errors, s.superseded, s.held, s.events_dropped, s.scans,
            s.scans_refused, s.images, s.images_refused,
        );
        // A last zero twist; the ROS 2 node leaves the graph.
        link.stop();
    }
    let _ = out.flush();
    if let (Some(w), Some(p)) = (writer.as_mut(), capture) {
        w.flush().map_err(|e| format!("{}: {e}", p.display()))?;
    }
    if let (Some(e), Some(p)) = (capture_error, capture) {
        return Err(format!("{}: capture stopped: {e}", p.display()));
    }
    result
}

/// A watchdog event of `ros2:` in the log (`t`: seconds since the node started).
fn log_ros2_event(t0: Instant, e: &jaus_ros2::WatchdogEvent) {
    use jaus_ros2::WatchdogEvent;
    let t = |at: &Instant| at.saturating_duration_since(t0).as_secs_f64();
    match e {
        WatchdogEvent::JausStop {
            at,
            controller,
            reason,
        } => match controller {
            Some(c) => tracing::info!(
                t = t(at),
                controller = %c,
                "ros2: robot stopped (zero twist on cmd_vel): {reason}"
            ),
            None => tracing::info!(
                t = t(at),
                "ros2: robot stopped (zero twist on cmd_vel): {reason}"
            ),
        },
        WatchdogEvent::RosSilent { at } => tracing::warn!(
            t = t(at),
            "ros2: no odom within the watchdog time: robot stopped, commands held at zero"
        ),
        WatchdogEvent::RosResumed { at } => {
            tracing::info!(t = t(at), "ros2: odom again: commands pass")
        }
    }
}

/// What carries the node's datagrams: its UDP sockets, or JTCP.
enum Carrier<'a> {
    Udp(udp::NodeSockets<'a>, udp::IoOptions),
    Tcp(Box<jaus::net::tcp::TcpTransport>),
    #[cfg(target_os = "linux")]
    Serial(Box<jaus::net::serial::SerialTransport<SocketAddr>>),
}

impl Carrier<'_> {
    /// Runs `p` on this carrier through the one I/O loop.
    fn drive<P: jaus::net::Participant>(
        &mut self,
        p: &mut P,
        stop: &AtomicBool,
        until: Option<Instant>,
        on_tick: impl FnMut(&mut P),
        tap: impl FnMut(udp::Direction, SocketAddr, &[u8]),
    ) -> std::io::Result<()> {
        match self {
            Carrier::Udp(sockets, io) => udp::run_node(p, *sockets, io, stop, until, on_tick, tap),
            Carrier::Tcp(t) => jaus::net::shell::run(p, t.as_mut(), stop, until, on_tick, tap),
            #[cfg(target_os = "linux")]
            Carrier::Serial(t) => jaus::net::shell::run(p, t.as_mut(), stop, until, on_tick, tap),
        }
    }

    /// What carries the node, for its first lines.
    fn describe(&self) -> String {
        use jaus::net::Transport;
        match self {
            Carrier::Udp(..) => "JUDP".into(),
            Carrier::Tcp(t) => format!("JTCP ({})", t.describe()),
            #[cfg(target_os = "linux")]
            Carrier::Serial(t) => format!("JSerial ({})", t.describe()),
        }
    }
}

/// The AS-4 side's counters as one `as4 stats:` line of `key value` pairs: datagrams,
/// malformed ones, messages, acknowledgements, reassembly drops, messages no endpoint
/// serves, sends dropped.
fn as4_stats_line<A: jaus::net::PeerAddr>(mux: &jaus::net::as5669a::As4Side<A>) -> String {
    let st = mux.stack().stats();
    let (r, buffered) = mux.stack().reassembly();
    format!(
        "as4 stats: datagrams_received {} bad_datagrams {} packets_received {} messages_received {} messages_sent {} acks_sent {} acks_received {} naks_received {} reassembly_timed_out {} reassembly_over_limit {} reassembly_orphans {} reassembly_buffered {buffered} unrouted {} outbox_full {} encode_errors {}",
        st.datagrams_received,
        st.bad_datagrams,
        st.packets_received,
        st.messages_received,
        st.messages_sent,
        st.acks_sent,
        st.acks_received,
        st.naks_received,
        r.timed_out,
        r.over_limit,
        r.orphans,
        mux.unrouted(),
        st.outbox_full,
        st.encode_errors,
    )
}

/// Joins the AS-4 first-contact `group` on the node's socket bound at `local`: only a
/// socket bound to 0.0.0.0 hears a group's datagrams, so any other bind is an error
/// naming the fix. Multicast loop off: the node never sends to the group.
fn join_as4_group(
    socket: &std::net::UdpSocket,
    local: SocketAddr,
    group: std::net::Ipv4Addr,
) -> Result<(), String> {
    if !group.is_multicast() {
        return Err(format!(
            "{group} is not a multicast address (the JAUS Tool Set's group is 239.255.0.1)"
        ));
    }
    if !local.ip().is_unspecified() {
        return Err(format!(
            "the node is bound to {local}, which does not receive datagrams sent to {group}: bind 0.0.0.0:{} to hear the group",
            local.port()
        ));
    }
    socket
        .join_multicast_v4(&group, &std::net::Ipv4Addr::UNSPECIFIED)
        .map_err(|e| format!("joining {group}: {e}"))?;
    socket
        .set_multicast_loop_v4(false)
        .map_err(|e| format!("{group}: {e}"))
}

#[cfg(test)]
mod as4_group_tests {
    use super::join_as4_group;
    use std::net::{Ipv4Addr, SocketAddr, UdpSocket};

    #[test]
    fn a_node_bound_to_one_address_is_told_to_bind_all_and_a_unicast_group_is_refused() {
        let s = UdpSocket::bind("127.0.0.1:0").unwrap();
        let local = s.local_addr().unwrap();
        let e = join_as4_group(&s, local, Ipv4Addr::new(239, 255, 0, 1)).unwrap_err();
        assert!(e.contains("bind 0.0.0.0:"), "{e}");
        let any: SocketAddr = "0.0.0.0:0".parse().unwrap();
        let e = join_as4_group(&s, any, Ipv4Addr::new(10, 0, 0, 1)).unwrap_err();
        assert!(e.contains("not a multicast address"), "{e}");
    }
}
