//! One function per fuzz target. Network bytes and user input go in; the functions
//! panic only when an invariant of the SDK is broken.

use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::Message;
use jaus::net::{Node, NodeConfig, ReassemblyLimits};
use jaus::PacketRef;

/// (a) A packet: header parse, decode by command code; whatever decodes re-encodes to
/// a body that decodes again and encodes to the same bytes (a fixed point; values are
/// not compared directly because NaN payloads are not equal to themselves).
pub fn packet(data: &[u8]) {
    let Ok(p) = PacketRef::parse(data) else {
        return;
    };
    let Ok(m) = Message::decode(p.header.command_code, p.body) else {
        return;
    };
    let Ok(once) = m.to_bytes() else {
        // A received value the encoder refuses would be a codec asymmetry, except
        // for scaled values outside their range, which decoding never produces.
        panic!("{} decoded from {:02x?} does not encode", m.name(), p.body);
    };
    let again = Message::decode(m.code(), &once).unwrap_or_else(|e| {
        panic!(
            "{} re-encoded as {once:02x?} does not decode: {e}",
            m.name()
        )
    });
    let twice = again.to_bytes().expect("a decoded message encodes");
    assert_eq!(once, twice, "{}: encoding is not a fixed point", m.name());
}

/// (b) A line of `jaus encode` / `jaus send`: errors are fine, panics are not; a line
/// that encodes decodes back.
pub fn json(data: &[u8]) {
    let Ok(line) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(hex) = jaus::json::encode_line(line) {
        jaus::json::decode_line(&hex)
            .unwrap_or_else(|e| panic!("`{line}` encoded to {hex}, which does not decode: {e}"));
    }
}

/// One step of the node target, drawn from the fuzzer's bytes with `arbitrary`: raw
/// bytes, a well-formed packet with arbitrary header fields and body, a multi-packet
/// message cut into parts sent in an arbitrary order (some lost), or time passing.
#[derive(Debug, arbitrary::Arbitrary)]
pub enum NodeStep {
    /// Any bytes from a peer.
    Garbage {
        /// Which of 8 peers.
        peer: u8,
        /// The datagram.
        bytes: Vec<u8>,
    },
    /// A packet with a consistent data size.
    Packet {
        /// Which of 8 peers.
        peer: u8,
        /// "JAUS01.0" rather than JUDP framing (which the node refuses: counted).
        opc: bool,
        /// Message properties (priority, ACK/NAK, flags, version).
        properties: u16,
        /// Command code.
        code: u16,
        /// Destination (subsystem, node, component, instance).
        dst: (u8, u8, u8, u8),
        /// Source.
        src: (u8, u8, u8, u8),
        /// Data flag (low 4 bits used).
        flag: u8,
        /// Sequence number.
        sequence: u16,
        /// Body.
        body: Vec<u8>,
    },
    /// A message of `parts` packets from one source, sent in `order` (indices modulo
    /// the part count; parts never named are lost).
    Fragments {
        /// Which of 8 peers.
        peer: u8,
        /// Source (subsystem, node, component, instance).
        src: (u8, u8, u8, u8),
        /// Command code.
        code: u16,
        /// Number of packets, 2 to 9.
        parts: u8,
        /// Bytes per packet.
        size: u16,
        /// Send order.
        order: Vec<u8>,
    },
    /// Time passes.
    Wait {
        /// Milliseconds.
        ms: u16,
    },
}

fn peer_of(p: u8) -> SocketAddr {
    SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::new(10, 0, 0, p % 8), 3794))
}

fn address((ss, n, c, i): (u8, u8, u8, u8)) -> jaus::Address {
    jaus::Address::new(ss, n, c, i)
}

/// The node target's access policy (on when the input's first byte is odd): rules of
/// each kind for subsystems the fuzzer reaches easily.
fn fuzz_policy() -> jaus::net::Policy {
    use jaus::net::policy::{Permission, Policy, Rule};
    let rule = |from: &str, may, emergency| Rule {
        from: from.parse().expect("a pattern"),
        may,
        emergency,
    };
    Policy {
        rules: vec![
            rule("0.*.*.*", Permission::Command { max_authority: 7 }, true),
            rule("2.*.*.*", Permission::Query, true),
            rule("3.*.*.*", Permission::None, false),
        ],
        default: Permission::Query,
        default_emergency: true,
    }
}

/// (c) A node (the reassembler behind it, its access policy when the first byte is odd)
/// fed a sequence of [`NodeStep`]s at virtual times: the reassembly buffer stays within
/// its bound, the outbox is always drained, every refusal of the policy is counted
/// once, and nothing panics.
pub fn node(data: &[u8]) {
    use arbitrary::{Arbitrary, Unstructured};
    use jaus::net::Framing;
    use jaus::wire::{DataFlag, Header};
    let t0 = Instant::now();
    let limits = ReassemblyLimits {
        max_message: 64 * 1024,
        per_source: 128 * 1024,
        total: 256 * 1024,
        timeout: Duration::from_millis(500),
    };
    let policy = data.first().is_some_and(|b| b % 2 == 1).then(fuzz_policy);
    let mut node = Node::new(
        NodeConfig {
            reassembly: limits,
            policy,
            ..NodeConfig::default()
        },
        t0,
    );
    let mut now = t0;
    let mut u = Unstructured::new(data);
    let mut steps = 0;
    while !u.is_empty() && steps < 256 {
        steps += 1;
        let Ok(step) = NodeStep::arbitrary(&mut u) else {
            break;
        };
        match step {
            NodeStep::Garbage { peer, bytes } => node.handle_datagram(now, peer_of(peer), &bytes),
            NodeStep::Packet {
                peer,
                opc,
                properties,
                code,
                dst,
                src,
                flag,
                sequence,
                body,
            } => {
                let mut packet = Vec::with_capacity(16 + body.len());
                let size = body.len().min(0x0FFF);
                packet.extend_from_slice(&properties.to_le_bytes());
                packet.extend_from_slice(&code.to_le_bytes());
                packet.extend_from_slice(&[dst.3, dst.2, dst.1, dst.0, src.3, src.2, src.1, src.0]);
                packet.extend_from_slice(
                    &((size as u16) | (u16::from(flag & 0x0F) << 12)).to_le_bytes(),
                );
                packet.extend_from_slice(&sequence.to_le_bytes());
                packet.extend_from_slice(&body[..size]);
                let framing = if opc { Framing::Opc } else { Framing::Judp };
                node.handle_datagram(now, peer_of(peer), &framing.encode(&packet));
            }
            NodeStep::Fragments {
                peer,
                src,
                code,
                parts,
                size,
                order,
            } => {
                let parts = 2 + usize::from(parts % 8);
                let size = usize::from(size % 4081);
                let mut header = Header::new(
                    jaus::CommandCode(code),
                    jaus::Address::new(1, 1, 255, 255),
                    address(src),
                );
                for i in order.iter().map(|o| usize::from(*o) % parts) {
                    header.data_flag = match i {
                        0 => DataFlag::First,
                        i if i + 1 == parts => DataFlag::Last,
                        _ => DataFlag::Normal,
                    };
                    header.sequence_number = i as u16;
                    let body = vec![i as u8; size];
                    if let Ok(h) = header.encode_with_size(size) {
                        let packet = [h.as_slice(), &body].concat();
                        node.handle_datagram(now, peer_of(peer), &Framing::Judp.encode(&packet));
                    }
                }
            }
            NodeStep::Wait { ms } => now += Duration::from_millis(u64::from(ms)),
        }
        node.handle_timeout(now);
        while node.poll_transmit().is_some() {}
        let (_, buffered) = node.reassembly();
        assert!(
            buffered <= limits.total,
            "reassembly holds {buffered} bytes"
        );
        let per_rule: u64 = node.policy().map_or(0, |p| p.counts().iter().sum());
        assert_eq!(node.stats().policy_refused, per_rule);
    }
}

/// (e) The YAML loader and validator: errors with positions, never a panic.
pub fn spec_yaml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = jaus_spec::load_texts(vec![("fuzz.yaml".into(), text.to_string())]);
}

/// (d) The component runtime with stock components (a Primitive Driver over recording
/// actuators, the Mission Spooler, the World Model) on the in-process bus, fed
/// arbitrary messages from four sources: records `[source, destination, code LE16,
/// length, bytes, run ms]`. After every step the driver's actuators carry no
/// propulsive effort unless some component holds control of it and it is Ready, every
/// component serves no more service connections and events than its bounds, and
/// nothing panics.
pub fn runtime(data: &[u8]) {
    use jaus::component::local::LocalBus;
    use jaus::component::{Component, Config, CoreState};
    use jaus::components::{mission_spooler, primitive_driver, world_model_vector_knowledge_store};
    use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
    use jaus::stock::hardware::{Actuators, Wrench};
    use jaus::stock::spooler::{SpoolerConfig, StockMissionSpooler};
    use jaus::stock::world_model::{StockWorldModel, WorldModelConfig};
    use jaus::{Address, CommandCode, RawMessage};
    use std::sync::{Arc, Mutex};

    #[derive(Clone, Default)]
    struct Recorder(Arc<Mutex<Option<Wrench>>>);
    impl Actuators for Recorder {
        fn apply(&mut self, _now: Instant, effort: &Wrench) {
            if let Ok(mut last) = self.0.lock() {
                *last = Some(*effort);
            }
        }
    }
    type Pd = Component<primitive_driver::Dispatch<StockPrimitiveDriver<Recorder>>>;
    type Ms = Component<mission_spooler::Dispatch<StockMissionSpooler>>;
    type Wm = Component<world_model_vector_knowledge_store::Dispatch<StockWorldModel>>;

    const PD: Address = Address::new(1, 1, 33, 1);
    let targets = [PD, Address::new(1, 1, 36, 1), Address::new(1, 1, 61, 1)];
    let sources = [
        Address::new(1, 2, 40, 1),
        Address::new(1, 2, 40, 2),
        Address::new(2, 1, 40, 1),
        Address::new(1, 1, 36, 1),
    ];
    let t0 = Instant::now();
    let recorder = Recorder::default();
    let mut bus = LocalBus::new(t0);
    bus.add(primitive_driver::component(
        PD,
        StockPrimitiveDriver::new(recorder.clone(), PrimitiveConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(mission_spooler::component(
        targets[1],
        StockMissionSpooler::new(SpoolerConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(world_model_vector_knowledge_store::component(
        targets[2],
        StockWorldModel::new(WorldModelConfig::default()),
        Config::default(),
        t0,
    ));
    let mut rest = data;
    while rest.len() >= 6 {
        let from = sources[usize::from(rest[0]) % sources.len()];
        let to = targets[usize::from(rest[1]) % targets.len()];
        let code = CommandCode(u16::from_le_bytes([rest[2], rest[3]]));
        let len = usize::from(rest[4]).min(rest.len() - 6);
        let run = Duration::from_millis(u64::from(rest[5 + len]));
        let body = rest[5..5 + len].to_vec();
        rest = &rest[6 + len..];
        bus.send_set(from, to, &Message::Raw(RawMessage { code, body }));
        bus.run_for(run);
        // Queues within their bounds: service connections and events served by each
        // component (Config's defaults: 32 of each).
        let bounds = Config::default();
        let counts = [
            bus.get::<Pd>(PD)
                .map(|c| (c.service_connections(), c.events())),
            bus.get::<Ms>(targets[1])
                .map(|c| (c.service_connections(), c.events())),
            bus.get::<Wm>(targets[2])
                .map(|c| (c.service_connections(), c.events())),
        ];
        for (sc, ev) in counts.into_iter().flatten() {
            assert!(
                sc <= bounds.max_service_connections && ev <= bounds.max_events,
                "{sc} service connections and {ev} events served"
            );
        }
        let pd: &Pd = bus.get(PD).expect("the driver is on the bus");
        let moving = recorder.0.lock().ok().and_then(|w| *w).is_some_and(|w| {
            w.linear != Wrench::ZERO.linear || w.rotational != Wrench::ZERO.rotational
        });
        if moving {
            assert!(
                pd.controller().is_some() && pd.state() == CoreState::Ready,
                "the actuators move without a controller in Ready: {:?} {:?}",
                pd.controller(),
                pd.state()
            );
        }
    }
}

/// (f) The AS-4 side: the input is a sequence of steps at virtual times, each either a
/// datagram into an AS5669A stack and an AS-4 node hosting a component (its Core on the
/// generated state machine), or a message by code and body decoded with the AS-4
/// definitions and handed to that component from one of three clients (so that the
/// Core's machine sees well-formed messages in any order: control, emergencies, events,
/// lists). Nothing panics, the outbox is drained, and the component's state is always
/// one the machine can be in with the controller it reports.
pub fn as4(data: &[u8]) {
    use jaus::net::as5669a::{As4Config, As4Endpoint, As4Id, As4Stack};
    use jaus_as4::component::As4Component;
    use jaus_as4::core::CoreConfig;
    use jaus_as4::node::As4Node;
    use jaus_as4::ComponentState;

    const ME: As4Id = As4Id::new(7, 1, 1);
    let clients = [
        As4Id::new(42, 1, 1),
        As4Id::new(42, 1, 2),
        As4Id::new(43, 1, 1),
    ];
    let t0 = Instant::now();
    let mut config = CoreConfig::named("fuzz");
    config.authority = data.first().map_or(0, |b| b % 4);
    config.control_timeout = 1;
    let mut direct: As4Component<()> = As4Component::new(ME, config.clone());
    let mut node: As4Node<()> = As4Node::new(()).with_component(As4Component::new(ME, config));
    let mut stack: As4Stack<SocketAddr> = As4Stack::new(As4Config::default());
    let from = SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::new(10, 0, 0, 2), 3794));
    let mut now = t0;
    let mut rest = data.get(1..).unwrap_or_default();
    let mut steps = 0;
    while rest.len() >= 3 && steps < 256 {
        steps += 1;
        let (kind, len) = (rest[0], usize::from(rest[1]));
        let take = len.min(rest.len() - 2);
        let chunk = &rest[2..2 + take];
        rest = &rest[2 + take..];
        now += Duration::from_millis(u64::from(kind >> 2) * 20);
        if kind & 1 == 0 {
            if let Ok(messages) = stack.receive(now, from, chunk) {
                let replies = node.handle(now, from, messages);
                stack.send(from, &replies);
            }
        } else if chunk.len() >= 2 {
            let code = jaus::CommandCode(u16::from_le_bytes([chunk[0], chunk[1]]));
            if let Ok(m) = jaus_as4::Message::decode(code, &chunk[2..]) {
                let client = clients[usize::from(kind >> 1) % clients.len()];
                let _ = direct.handle(now, client, &m, &mut ());
            }
        }
        if node.poll_timeout().is_some_and(|t| t <= now) {
            for s in node.handle_timeout(now) {
                stack.send(s.to, &[s.message]);
            }
        }
        if direct.poll_timeout().is_some_and(|t| t <= now) {
            let _ = direct.handle_timeout(now, &mut ());
        }
        while stack.poll_transmit().is_some() {}
        // Ready only under control; the state is the one the machine's path names.
        let machine = direct.core().machine_state();
        assert_eq!(
            direct.state(),
            jaus_as4::core::management::state_of(machine),
            "state and machine disagree at {machine}"
        );
        if direct.state() == ComponentState::Ready {
            assert!(
                direct.controller().is_some(),
                "Ready without a controller at {machine}"
            );
        }
        assert_eq!(
            direct.controller().is_some(),
            machine.contains(".Controlled"),
            "controller {:?} in machine state {machine}",
            direct.controller()
        );
    }
}

/// Cuts `data` into pieces whose lengths cycle through the bytes of `sizes` (1-64), as a
/// stream's reads would.
fn stream_pieces<'a>(sizes: &'a [u8], mut data: &'a [u8]) -> Vec<&'a [u8]> {
    let mut out = Vec::new();
    let mut i = 0;
    while !data.is_empty() {
        let n = sizes
            .get(i % sizes.len().max(1))
            .map_or(data.len(), |s| usize::from(s % 64) + 1);
        let (piece, rest) = data.split_at(n.min(data.len()));
        out.push(piece);
        data = rest;
        i += 1;
    }
    out
}

/// (g) A JTCP stream (first byte: how reads cut it): the decoder never panics, keeps at
/// most one frame, fails for good once it fails; every datagram it hands on encodes back
/// to a stream that decodes to the same datagrams.
pub fn jtcp(data: &[u8]) {
    use jaus::net::stream::{jtcp::JtcpEncoder, JtcpDecoder};
    let (sizes, stream) = data.split_at(data.len().min(4));
    let mut d = JtcpDecoder::new(1024);
    let mut got = Vec::new();
    let mut failed = None;
    for piece in stream_pieces(sizes, stream) {
        match d.decode(piece, |g| got.push(g.to_vec())) {
            Ok(()) => assert!(failed.is_none(), "read on after {failed:?}"),
            Err(e) => {
                assert!(failed.is_none_or(|f| f == e), "{failed:?} then {e}");
                failed = Some(e);
            }
        }
        assert!(d.pending() <= 1024);
    }
    let mut e = JtcpEncoder::default();
    let mut wire = Vec::new();
    for g in &got {
        e.encode(g, &mut wire).expect("a decoded datagram encodes");
    }
    let mut again = Vec::new();
    JtcpDecoder::new(1024)
        .decode(&wire, |g| again.push(g.to_vec()))
        .expect("re-encoded frames decode");
    assert_eq!(again, got);
}

/// (h) A serial line's bytes (first four: how reads cut them): the JSerial decoder never
/// panics and counts every byte it takes; every datagram it hands on encodes back to a
/// packet that decodes to the same datagram, with nothing skipped.
pub fn jserial(data: &[u8]) {
    use jaus::net::stream::{jserial, JSerialDecoder};
    let (sizes, line) = data.split_at(data.len().min(4));
    let mut d = JSerialDecoder::new(1024);
    let mut got = Vec::new();
    for piece in stream_pieces(sizes, line) {
        d.decode(piece, |g| got.push(g.to_vec()));
    }
    let s = d.stats();
    assert_eq!(s.bytes as usize, line.len());
    assert!(s.bytes_skipped <= s.bytes);
    assert_eq!(s.frames as usize, got.len());
    let mut wire = Vec::new();
    for g in &got {
        jserial::encode_into(g, &mut wire).expect("a decoded datagram encodes");
    }
    let mut again = Vec::new();
    let mut d2 = JSerialDecoder::new(1024);
    d2.decode(&wire, |g| again.push(g.to_vec()));
    assert_eq!(again, got);
    assert_eq!(d2.stats().bytes_skipped, 0);
}
