//! The Communicator's cost and the simulated radio's figures (issue 14):
//!
//! * `communicator/forward`: the sans-IO CPU cost of one packet from a component of
//!   subsystem 1 to a component of subsystem 2 through both nodes and both
//!   communicators (route → gateway → per-link queue → radio end → far radio end →
//!   routed as received → delivered), on an instantaneous radio; criterion's time per
//!   iteration is the cost per forwarded packet (its inverse the messages/s one core
//!   forwards), its throughput the bytes/s.
//! * printed first, on the virtual clock: messages/s, bytes/s, latency (mean, p99) and
//!   drops through a 1 Mbit/s, 20 ms radio, under a light load and a saturating one.
//!
//! `cargo bench -p jaus-sim --bench communicator`

use std::any::Any;
use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use jaus::component::{Config, Endpoint, Outgoing};
use jaus::net::{Node, NodeConfig};
use jaus::stock::communicator::{CommunicatorConfig, CommunicatorEndpoint, StockCommunicator};
use jaus::{Address, CommandCode, Header};
use jaus_sim::network::{LinkModel, SimNet};
use jaus_sim::radio::{radio_pair, Radio, RadioParams};

const FROM: Address = Address::new(1, 1, 200, 1);
const TO: Address = Address::new(2, 1, 200, 1);
/// Report Global Pose's code: any code routes the same way.
const CODE: CommandCode = CommandCode(0x4402);

/// Counts the messages from `FROM` and keeps their arrival times (up to a bound).
struct Sink {
    address: Address,
    count: u64,
    /// (the message's index from its first 4 bytes, arrival time)
    times: Vec<(u32, Instant)>,
}

impl Endpoint for Sink {
    fn address(&self) -> Address {
        self.address
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        // Only the benchmark's messages (not the node manager's heartbeats).
        if header.source != FROM {
            return;
        }
        self.count += 1;
        if let (Some(b), true) = (body.get(..4), self.times.len() < 1_000_000) {
            let k = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            self.times.push((k, now));
        }
    }
    fn handle_timeout(&mut self, _now: Instant) {}
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        None
    }
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

fn subsystem(ss: u8, link: Radio, t0: Instant) -> Node {
    let comm = Address::new(ss, 1, 35, 1);
    let config = NodeConfig {
        subsystem: ss,
        node: 1,
        communicator: Some(comm),
        ..NodeConfig::default()
    };
    let mut node = Node::new(config, t0);
    let comm_config = CommunicatorConfig {
        max_queue: 1024,
        ..CommunicatorConfig::default()
    };
    if let Ok(stock) = StockCommunicator::new(vec![link], comm_config, t0) {
        let _ = node.add(CommunicatorEndpoint::new(
            comm,
            stock,
            Config::default(),
            t0,
        ));
    }
    let sink = Address::new(ss, 1, 200, 1);
    let _ = node.add(Sink {
        address: sink,
        count: 0,
        times: Vec::new(),
    });
    node
}

fn pair(params: RadioParams, t0: Instant) -> (Node, Node) {
    let (a, b, _) = radio_pair(1, params);
    (subsystem(1, a, t0), subsystem(2, b, t0))
}

/// Sends `count` messages of `body` bytes, one every `interval`, through a radio with
/// `params` on the virtual clock; prints messages/s, bytes/s, latency and drops.
fn link_model_run(label: &str, params: RadioParams, body: usize, interval: Duration, count: u32) {
    let t0 = Instant::now();
    let (n1, n2) = pair(params, t0);
    let mut net = SimNet::new(t0, LinkModel::default(), 1);
    net.add(n1);
    net.add(n2);
    // Let both sides start (initialisation, first heartbeats).
    net.run_for(Duration::from_secs(2));
    let mut sent_at = Vec::with_capacity(count as usize);
    let start = net.now();
    for k in 0..count {
        let now = net.now();
        let mut payload = vec![0x5Au8; body.max(4)];
        payload[..4].copy_from_slice(&k.to_le_bytes());
        if let Some(n) = net.node_mut(0) {
            n.send(now, Header::new(CODE, TO, FROM), payload);
        }
        sent_at.push(now);
        net.run_for(interval);
    }
    let end_of_sending = net.now();
    net.run_for(Duration::from_secs(10));
    let Some(sink) = net.node(1).and_then(|n| n.get::<Sink>(TO)) else {
        return;
    };
    let dropped = net
        .node(0)
        .and_then(|n| n.get::<CommunicatorEndpoint<Radio>>(Address::new(1, 1, 35, 1)))
        .and_then(|g| g.communicator().link_stats(1))
        .map_or(0, |s| s.dropped_queue_full);
    let delivered = sink.times.len();
    let last = sink.times.last().map_or(start, |t| t.1);
    let span = last.duration_since(start).as_secs_f64().max(1e-9);
    let rate = delivered as f64 / span;
    let packet = body + 16;
    let mut line = format!(
        "{label}: offered {:.0} msg/s of {packet} B for {:.1} s; delivered {delivered}/{count} = {rate:.0} msg/s, {:.0} B/s ({:.0} kbit/s), dropped (queue full) {dropped}",
        1.0 / interval.as_secs_f64(),
        end_of_sending.duration_since(start).as_secs_f64(),
        rate * packet as f64,
        rate * packet as f64 * 8.0 / 1000.0,
    );
    {
        let mut lat: Vec<f64> = sink
            .times
            .iter()
            .filter_map(|(k, r)| {
                let s: &Instant = sent_at.get(*k as usize)?;
                Some(r.duration_since(*s).as_secs_f64() * 1e3)
            })
            .collect();
        lat.sort_by(f64::total_cmp);
        let mean = lat.iter().sum::<f64>() / lat.len().max(1) as f64;
        let p99 = lat
            .get((lat.len() * 99 / 100).min(lat.len().saturating_sub(1)))
            .copied()
            .unwrap_or(0.0);
        line += &format!("; latency mean {mean:.2} ms, p99 {p99:.2} ms");
    }
    eprintln!("{line}");
}

fn link_model_report() {
    let radio = RadioParams {
        latency: Duration::from_millis(20),
        bandwidth_bps: 1_000_000,
        queue_frames: 64,
        ..RadioParams::default()
    };
    eprintln!("communicator over the simulated radio (1 Mbit/s, 20 ms one way, virtual clock):");
    link_model_run("  light", radio, 100, Duration::from_millis(10), 1_000);
    link_model_run(
        "  half load",
        radio,
        500,
        Duration::from_micros(8_500),
        1_000,
    );
    link_model_run(
        "  saturating",
        radio,
        500,
        Duration::from_micros(500),
        4_000,
    );
}

fn bench(c: &mut Criterion) {
    link_model_report();
    let mut g = c.benchmark_group("communicator");
    for body in [64usize, 4080] {
        let t0 = Instant::now();
        // An instantaneous radio: the cost is the nodes' and the communicators'.
        let params = RadioParams {
            latency: Duration::ZERO,
            bandwidth_bps: 0,
            ..RadioParams::default()
        };
        let (mut n1, mut n2) = pair(params, t0);
        let now = t0 + Duration::from_millis(1);
        n1.handle_timeout(now);
        n2.handle_timeout(now);
        let payload = vec![0x5Au8; body];
        g.throughput(Throughput::Bytes((body + 16) as u64));
        g.bench_function(format!("forward/{}B", body + 16), |b| {
            b.iter(|| {
                n1.send(now, Header::new(CODE, TO, FROM), payload.clone());
                n2.handle_timeout(now);
            })
        });
        let got = n2.get::<Sink>(TO).map_or(0, |s| s.count);
        assert!(got > 0, "packets crossed");
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
