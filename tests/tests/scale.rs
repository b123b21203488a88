//! Scale by simulation (issue 12 item 6): S subsystems × 4 nodes × 10 components on a
//! lossy simulated network (`jaus_sim::SimNet`): virtual time until every node's system
//! tree holds every component, discovery and heartbeat traffic per node per second once
//! converged, and heap bytes per node (a counting allocator).
//!
//! The table for 10, 50 and 100 subsystems:
//! `cargo test --release -p jaus-tests --test scale -- --ignored --nocapture`.
//! A small case (3 subsystems) runs in the normal suite and checks convergence.

use std::alloc::{GlobalAlloc, Layout, System};
use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::sync::atomic::{AtomicIsize, Ordering};
use std::time::{Duration, Instant};

use jaus::component::Config;
use jaus::components::global_pose_sensor;
use jaus::net::{Node, NodeConfig};
use jaus::stock::hardware::{GlobalPose, GlobalPoseSource};
use jaus::stock::nalgebra::UnitQuaternion;
use jaus::stock::sensors::StockGlobalPoseSensor;
use jaus::Address;
use jaus_sim::{LinkModel, SimNet};

/// Live heap bytes of the whole test process.
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

const NODES: u8 = 4;
const COMPONENTS: u8 = 10;

#[derive(Debug, Clone, Copy)]
struct Fixed;
impl GlobalPoseSource for Fixed {
    fn global_pose(&mut self, _: Instant) -> Option<GlobalPose> {
        Some(GlobalPose {
            latitude: 1.0,
            longitude: 2.0,
            elevation: 0.0,
            attitude: UnitQuaternion::identity(),
            position_rms: 1.0,
        })
    }
}

fn addr(ss: u8, node: u8) -> SocketAddr {
    SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::new(10, 1, ss, node), 3794))
}

struct Row {
    subsystems: u8,
    converged: Option<Duration>,
    datagrams_per_node_s: f64,
    heap_per_node: f64,
}

fn run(subsystems: u8, limit: Duration) -> Row {
    let t0 = Instant::now();
    let heap0 = LIVE.load(Ordering::Relaxed);
    let lossy = LinkModel {
        drop: 0.01,
        duplicate: 0.0,
        min_delay: Duration::from_micros(200),
        max_delay: Duration::from_millis(5),
    };
    let mut net = SimNet::new(t0, lossy, 42);
    let all: Vec<SocketAddr> = (1..=subsystems)
        .flat_map(|ss| (1..=NODES).map(move |n| addr(ss, n)))
        .collect();
    for ss in 1..=subsystems {
        for n in 1..=NODES {
            let me = addr(ss, n);
            let config = NodeConfig {
                subsystem: ss,
                node: n,
                peers: all.iter().copied().filter(|a| *a != me).collect(),
                ..NodeConfig::default()
            };
            let mut node = Node::new(config, t0);
            for i in 1..=COMPONENTS {
                node.add(global_pose_sensor::component(
                    Address::new(ss, n, 38, i),
                    StockGlobalPoseSensor(Fixed),
                    Config::default(),
                    t0,
                ))
                .unwrap();
            }
            net.add_at(me, node);
        }
    }
    let total = usize::from(subsystems) * usize::from(NODES) * (usize::from(COMPONENTS) + 1);
    let slots = usize::from(subsystems) * usize::from(NODES);
    let complete = |net: &SimNet| {
        (0..slots).all(|i| {
            net.node(i)
                .is_some_and(|n| n.tree().components().len() >= total)
        })
    };
    let mut converged = None;
    let step = Duration::from_millis(250);
    let mut t = Duration::ZERO;
    while t < limit {
        net.run_for(step);
        t += step;
        if complete(&net) {
            converged = Some(t);
            break;
        }
    }
    // Steady-state traffic over 5 simulated seconds after convergence.
    let sent = |net: &SimNet| -> u64 {
        (0..slots)
            .filter_map(|i| net.node(i))
            .map(|n| n.stats().sent)
            .sum()
    };
    let before = sent(&net);
    net.run_for(Duration::from_secs(5));
    let after = sent(&net);
    let heap = LIVE.load(Ordering::Relaxed) - heap0;
    Row {
        subsystems,
        converged,
        datagrams_per_node_s: (after - before) as f64 / slots as f64 / 5.0,
        heap_per_node: heap as f64 / slots as f64,
    }
}

fn print(rows: &[Row]) {
    println!("| subsystems | nodes | components | tree complete after (virtual) | datagrams sent per node per s (converged) | heap per node |");
    println!("|---|---|---|---|---|---|");
    for r in rows {
        let nodes = usize::from(r.subsystems) * usize::from(NODES);
        println!(
            "| {} | {} | {} | {} | {:.0} | {:.0} KiB |",
            r.subsystems,
            nodes,
            nodes * usize::from(COMPONENTS),
            r.converged
                .map_or("not within the limit".into(), |d| format!(
                    "{:.2} s",
                    d.as_secs_f64()
                )),
            r.datagrams_per_node_s,
            r.heap_per_node / 1024.0
        );
    }
}

#[test]
fn three_subsystems_converge() {
    let r = run(3, Duration::from_secs(30));
    print(std::slice::from_ref(&r));
    let t = r.converged.expect("every tree complete within 30 s");
    assert!(t <= Duration::from_secs(10), "{t:?}");
}

#[test]
#[ignore = "minutes of CPU: run with --release --ignored --nocapture for the table"]
fn scale_table() {
    let rows: Vec<Row> = [10u8, 50, 100]
        .into_iter()
        .map(|s| run(s, Duration::from_secs(120)))
        .collect();
    print(&rows);
}
