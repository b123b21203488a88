//! Two nodes on loopback UDP (one thread and one socket each): query → report round-trip
//! latency (p50/p99, one query outstanding), then routed throughput with a window of
//! outstanding queries (each exchange is two routed messages).
//!
//! `cargo bench -p jaus --bench net`

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::Probe;
use jaus::component::{Config, Refused};
use jaus::components::global_pose_sensor::{self, Ctx, GlobalPoseSensor};
use jaus::messages::{Message, QueryGlobalPose, ReportGlobalPose};
use jaus::net::{udp, Node, NodeConfig};
use jaus::{Address, Header, JausMessage};

const GPS: Address = Address::new(1, 1, 38, 1);
const OCU: Address = Address::new(1, 2, 40, 1);

struct Gps;
impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _c: &mut Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose {
            latitude: Some(29.6),
            longitude: Some(-82.3),
            ..Default::default()
        })
    }
}

fn port() -> SocketAddr {
    UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
}

fn main() {
    let (a, b) = (port(), port());
    let stop = Arc::new(AtomicBool::new(false));
    let t0 = Instant::now();
    // Node 1.1: the sensor.
    let server_stop = stop.clone();
    let server = std::thread::spawn(move || {
        let cfg = NodeConfig {
            subsystem: 1,
            node: 1,
            peers: vec![b],
            ..NodeConfig::default()
        };
        let mut node = Node::new(cfg, t0);
        node.add(global_pose_sensor::component(
            GPS,
            Gps,
            Config::default(),
            t0,
        ))
        .unwrap();
        udp::run(&mut node, a, &server_stop, None, |_| {}).unwrap();
        node.stats()
    });
    // Node 1.2: the operator, measuring.
    let cfg = NodeConfig {
        subsystem: 1,
        node: 2,
        peers: vec![a],
        ..NodeConfig::default()
    };
    let mut node = Node::new(cfg, t0);
    node.add(Probe::new(OCU)).unwrap();
    let query = QueryGlobalPose { presence_vector: 3 }.to_bytes().unwrap();
    let header = Header::new(QueryGlobalPose::CODE, GPS, OCU);

    const WARMUP: usize = 200;
    const RTT_SAMPLES: usize = 5_000;
    const THROUGHPUT_EXCHANGES: usize = 50_000;
    const WINDOW: usize = 32;

    let mut rtts: Vec<Duration> = Vec::with_capacity(RTT_SAMPLES);
    let mut sent_at: Option<Instant> = None;
    let mut seen = 0usize;
    let mut phase = 0; // 0 warm-up + latency, 1 throughput
    let mut outstanding = 0usize;
    let mut done = 0usize;
    let mut tp_start: Option<Instant> = None;
    let mut tp_time = Duration::ZERO;
    let local_stop = AtomicBool::new(false);
    udp::run(
        &mut node,
        b,
        &local_stop,
        Some(Instant::now() + Duration::from_secs(120)),
        |n| {
            let probe = n.get_mut::<Probe>(OCU).unwrap();
            let reports = probe
                .messages()
                .filter(|m| matches!(m, Message::ReportGlobalPose(_)))
                .count();
            probe.clear();
            seen += reports;
            let now = Instant::now();
            if phase == 0 {
                if reports > 0 {
                    if let Some(t) = sent_at.take() {
                        if seen > WARMUP {
                            rtts.push(now - t);
                        }
                    }
                }
                if rtts.len() >= RTT_SAMPLES {
                    phase = 1;
                    tp_start = Some(Instant::now());
                } else if sent_at.is_none() && n.peers().contains_key(&(1, 1)) {
                    sent_at = Some(Instant::now());
                    n.send(Instant::now(), header, query.clone());
                } else if sent_at.is_some_and(|t| now - t > Duration::from_millis(200)) {
                    sent_at = None; // lost: ask again
                }
                return;
            }
            done += reports;
            outstanding = outstanding.saturating_sub(reports);
            if done >= THROUGHPUT_EXCHANGES {
                tp_time = tp_start.map_or(Duration::ZERO, |s| s.elapsed());
                local_stop.store(true, Ordering::Relaxed);
                return;
            }
            while outstanding < WINDOW {
                outstanding += 1;
                n.send(Instant::now(), header, query.clone());
            }
        },
    )
    .unwrap();
    stop.store(true, Ordering::Relaxed);
    let server_stats = server.join().unwrap();
    rtts.sort();
    let pct = |p: f64| rtts[((rtts.len() as f64 - 1.0) * p) as usize];
    println!("loopback UDP, JUDP framing, two nodes (one thread each)");
    println!(
        "query → report round trip ({} samples): p50 {:.1} µs  p99 {:.1} µs  max {:.1} µs",
        rtts.len(),
        pct(0.50).as_secs_f64() * 1e6,
        pct(0.99).as_secs_f64() * 1e6,
        rtts.last().unwrap().as_secs_f64() * 1e6
    );
    let exchanges = done as f64 / tp_time.as_secs_f64();
    println!(
        "throughput (window {WINDOW}): {:.0} query/report exchanges/s = {:.0} routed messages/s ({done} exchanges in {:.2} s)",
        exchanges,
        2.0 * exchanges,
        tp_time.as_secs_f64()
    );
    println!("operator node: {:?}", node.stats());
    println!("sensor node:   {server_stats:?}");
}
