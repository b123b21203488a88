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

/// (c) A node fed datagrams from several peers at virtual times: the input is a
/// sequence of records `[peer (1), delay ms (1), length (2, LE), bytes]`. The
/// reassembly buffer stays within its bound and the node keeps answering.
pub fn node(data: &[u8]) {
    let t0 = Instant::now();
    let limits = ReassemblyLimits {
        max_message: 64 * 1024,
        per_source: 128 * 1024,
        total: 256 * 1024,
        timeout: Duration::from_millis(500),
    };
    let mut node = Node::new(
        NodeConfig {
            reassembly: limits,
            ..NodeConfig::default()
        },
        t0,
    );
    let mut now = t0;
    let mut rest = data;
    while rest.len() >= 4 {
        let peer = SocketAddr::V4(SocketAddrV4::new(
            Ipv4Addr::new(10, 0, 0, rest[0] % 8),
            3794,
        ));
        now += Duration::from_millis(u64::from(rest[1]));
        let len = usize::from(u16::from_le_bytes([rest[2], rest[3]])).min(rest.len() - 4);
        let datagram = &rest[4..4 + len];
        rest = &rest[4 + len..];
        node.handle_datagram(now, peer, datagram);
        node.handle_timeout(now);
        while node.poll_transmit().is_some() {}
        let (_, buffered) = node.reassembly();
        assert!(
            buffered <= limits.total,
            "reassembly holds {buffered} bytes"
        );
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
/// propulsive effort unless some component holds control of it and it is Ready, and
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
