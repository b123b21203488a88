//! A node under sustained hostile traffic (issue 17): for a stretch of simulated time,
//! every 10 ms, garbage datagrams, first packets that never finish from many sources,
//! storms of service-connection and event requests and cancellations, and control
//! requests from many components at random authorities, while a legitimate operator
//! queries the node. Checked throughout: reassembly memory within its bound, the
//! sensor's service connections and events within their limits, the process heap not
//! growing once the storm is steady; at the end: every refusal counted, the node still
//! answering, and a legitimate controller still driving the stock Primitive Driver.
//!
//! 60 simulated seconds in the suite; `SOAK_SECONDS=600 cargo test --release -p
//! jaus-tests --test soak -- --nocapture` for a longer run.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicIsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::Probe;
use jaus::component::{Component, Config};
use jaus::components::{global_pose_sensor, primitive_driver};
use jaus::messages::*;
use jaus::net::{Framing, Node, NodeConfig, ReassemblyLimits};
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::stock::hardware::{Actuators, GlobalPose, GlobalPoseSource, Wrench};
use jaus::stock::nalgebra::UnitQuaternion;
use jaus::stock::sensors::StockGlobalPoseSensor;
use jaus::wire::DataFlag;
use jaus::{Address, CommandCode, Header};
use jaus_sim::{LinkModel, SimNet};

struct Counting;
static LIVE: AtomicIsize = AtomicIsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator, which upholds the
// `GlobalAlloc` contract; the counter is only arithmetic on the sizes it was given (the
// default `realloc` goes through these two methods, so it is counted too).
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        LIVE.fetch_add(l.size() as isize, Ordering::Relaxed);
        // SAFETY: same layout as the caller's, per the trait contract.
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        LIVE.fetch_sub(l.size() as isize, Ordering::Relaxed);
        // SAFETY: `p` was allocated by `alloc` above with layout `l`.
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static A: Counting = Counting;

const GPS: Address = Address::new(1, 1, 38, 1);
const PD: Address = Address::new(1, 1, 33, 1);
const OCU: Address = Address::new(1, 2, 40, 1);

#[derive(Clone, Copy)]
struct Fixed;
impl GlobalPoseSource for Fixed {
    fn global_pose(&mut self, _: Instant) -> Option<GlobalPose> {
        Some(GlobalPose {
            latitude: 29.65,
            longitude: -82.32,
            elevation: 0.0,
            attitude: UnitQuaternion::identity(),
            position_rms: 1.0,
        })
    }
}

#[derive(Clone, Default)]
struct Motors(Arc<Mutex<Option<Wrench>>>);
impl Actuators for Motors {
    fn apply(&mut self, _: Instant, w: &Wrench) {
        if let Ok(mut last) = self.0.lock() {
            *last = Some(*w);
        }
    }
}

type Pd = Component<primitive_driver::Dispatch<StockPrimitiveDriver<Motors>>>;
type Gps = Component<global_pose_sensor::Dispatch<StockGlobalPoseSensor<Fixed>>>;

fn packet(msg: &Message, from: Address, to: Address, flag: DataFlag) -> Vec<u8> {
    let body = msg.to_bytes().unwrap();
    let mut h = Header::new(msg.code(), to, from);
    h.data_flag = flag;
    let mut p = h.encode_with_size(body.len()).unwrap().to_vec();
    p.extend_from_slice(&body);
    Framing::Judp.encode(&p)
}

#[test]
fn a_node_holds_under_sustained_hostile_traffic() {
    let seconds: u64 = std::env::var("SOAK_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(60);
    let t0 = Instant::now();
    let limits = ReassemblyLimits {
        per_source: 64 << 10,
        total: 512 << 10,
        ..Default::default()
    };
    let mut net = SimNet::new(t0, LinkModel::default(), 17);
    let victim_cfg = NodeConfig {
        peers: vec![SimNet::addr(1)],
        reassembly: limits,
        ..NodeConfig::default()
    };
    let component = Config::default();
    let (max_sc, max_events) = (component.max_service_connections, component.max_events);
    let mut victim = Node::new(victim_cfg, t0);
    victim
        .add(global_pose_sensor::component(
            GPS,
            StockGlobalPoseSensor(Fixed),
            component.clone(),
            t0,
        ))
        .unwrap();
    let motors = Motors::default();
    victim
        .add(primitive_driver::component(
            PD,
            StockPrimitiveDriver::new(motors.clone(), PrimitiveConfig::default()),
            component,
            t0,
        ))
        .unwrap();
    net.add(victim);
    let mut operator = Node::new(
        NodeConfig {
            subsystem: 1,
            node: 2,
            peers: vec![SimNet::addr(0)],
            ..NodeConfig::default()
        },
        t0,
    );
    operator.add(Probe::new(OCU)).unwrap();
    net.add(operator);
    let attacker = SimNet::addr(2);

    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut rnd = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let mut heap_after_warmup = None;
    let mut max_growth = 0isize;
    for step in 0..seconds * 100 {
        for _ in 0..4 {
            let r = rnd();
            let src = Address::new(3 + (r % 40) as u8, 1, 200, 1 + (r >> 8) as u8 % 4);
            let d = match r % 7 {
                0 => (0..(r >> 16) % 300).map(|_| rnd() as u8).collect(),
                1 => packet(
                    &Message::Raw(jaus::RawMessage {
                        code: CommandCode((r >> 20) as u16),
                        body: vec![0xAB; 4080],
                    }),
                    src,
                    GPS,
                    DataFlag::First,
                ),
                2 => packet(
                    &CreateServiceConnection {
                        service_connection_command_code: 0x4402,
                        requested_periodic_update_rate: ((r >> 12) % 2000) as f64 / 2.0,
                        presence_vector: (r >> 24) as u32,
                    }
                    .into(),
                    src,
                    GPS,
                    DataFlag::Single,
                ),
                3 => packet(
                    &TerminateServiceConnection {
                        service_connection_command_code: 0x4402,
                        instance_id: (r >> 12) as u8 % 4,
                    }
                    .into(),
                    src,
                    GPS,
                    DataFlag::Single,
                ),
                4 => packet(
                    &CreateEvent {
                        request_id: (r >> 12) as u8,
                        event_type: EventType::Periodic,
                        requested_update_rate: Some(((r >> 16) % 50) as f64),
                        report_message_code: 0x4402,
                        ..Default::default()
                    }
                    .into(),
                    src,
                    GPS,
                    DataFlag::Single,
                ),
                5 => packet(
                    &CancelEvent {
                        request_id: (r >> 12) as u8,
                        message_code: Some(0x4402),
                        event_id: Some((r >> 20) as u8),
                    }
                    .into(),
                    src,
                    GPS,
                    DataFlag::Single,
                ),
                _ => packet(
                    &RequestComponentControl {
                        authority_code: (r >> 12) as u8 % 50,
                    }
                    .into(),
                    src,
                    PD,
                    DataFlag::Single,
                ),
            };
            net.inject(0, attacker, d);
        }
        net.run_for(Duration::from_millis(10));
        let v = net.node(0).unwrap();
        let (_, buffered) = v.reassembly();
        assert!(buffered <= limits.total, "{buffered} bytes buffered");
        let gps: &Gps = v.get(GPS).unwrap();
        assert!(gps.service_connections() <= max_sc && gps.events() <= max_events);
        // The operator's probe records what it receives (heartbeats, discovery); empty it
        // so that the heap measures the node, not the test's recorder.
        if step % 100 == 0 {
            if let Some(p) = net.node_mut(1).and_then(|n| n.get_mut::<Probe>(OCU)) {
                p.clear();
            }
        }
        // Heap after 5 simulated seconds of storm, then never more than 1 MiB above it.
        if step == 500 {
            heap_after_warmup = Some(LIVE.load(Ordering::Relaxed));
        }
        if let Some(h) = heap_after_warmup {
            max_growth = max_growth.max(LIVE.load(Ordering::Relaxed) - h);
        }
        if std::env::var_os("SOAK_TRACE").is_some() && step % 6000 == 0 {
            let probe: &Probe = net.node(1).unwrap().get(OCU).unwrap();
            let v = net.node(0).unwrap();
            eprintln!(
                "t {} s heap {} probe {} peers {} sim {:?}",
                step / 100,
                LIVE.load(Ordering::Relaxed),
                probe.received().len(),
                v.peers().len(),
                net.stats()
            );
        }
    }
    assert!(
        max_growth < 1 << 20,
        "heap grew by {max_growth} bytes during the storm"
    );

    // Every refusal is counted.
    let v = net.node(0).unwrap();
    let s = v.stats();
    let (rs, _) = v.reassembly();
    let gps: &Gps = v.get(GPS).unwrap();
    let pd: &Pd = v.get(PD).unwrap();
    assert!(s.bad_framing + s.bad_packet > 0, "{s:?}");
    assert!(rs.over_limit > 0 || rs.timed_out > 0, "{rs:?}");
    assert!(gps.stats().subscriptions_refused > 0, "{:?}", gps.stats());
    println!(
        "{seconds} s: node {s:?}\nreassembly {rs:?}\nGPS {:?}\nPD {:?}\nheap growth after warm-up: {max_growth} bytes",
        gps.stats(),
        pd.stats()
    );

    // Still answering, and a legitimate controller with the highest authority still
    // drives the stock Primitive Driver.
    let send = |net: &mut SimNet, msg: Message, to: Address| {
        let body = msg.to_bytes().unwrap();
        let now = net.now();
        net.node_mut(1)
            .unwrap()
            .send(now, Header::new(msg.code(), to, OCU), body);
    };
    send(&mut net, QueryGlobalPose { presence_vector: 3 }.into(), GPS);
    send(
        &mut net,
        RequestComponentControl {
            authority_code: 255,
        }
        .into(),
        PD,
    );
    net.run_for(Duration::from_millis(200));
    send(&mut net, Resume {}.into(), PD);
    net.run_for(Duration::from_millis(100));
    send(
        &mut net,
        SetWrenchEffort {
            propulsive_linear_effort_x: Some(30.0),
            ..Default::default()
        }
        .into(),
        PD,
    );
    net.run_for(Duration::from_millis(100));
    let probe: &Probe = net.node(1).unwrap().get(OCU).unwrap();
    assert!(probe
        .messages()
        .any(|m| matches!(m, Message::ReportGlobalPose(_))));
    let last = motors.0.lock().unwrap().unwrap_or(Wrench::ZERO);
    assert!((last.linear.x - 30.0).abs() < 0.01, "{last:?}");
}
