//! The transport seam: a node runs on any datagram carrier, not only UDP. Two nodes on
//! an in-memory multi-drop "serial bus" whose drops have one-byte addresses, each
//! driven by the one shell loop (`jaus::net::shell::run`) on its own thread, find each
//! other through their node managers' heartbeats and answer a query across the bus;
//! the routing is the same code UDP uses.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{QueryIdentification, QueryLevel};
use jaus::net::shell::{self, Direction};
use jaus::net::{Datagram, Node, NodeConfig, Transport, Via};
use jaus::wire::Header;
use jaus::{Address, JausMessage};

/// One drop of the bus: what others send to it arrives on `inbox`.
struct Drop8 {
    me: u8,
    inbox: Receiver<(u8, Vec<u8>)>,
    others: HashMap<u8, Sender<(u8, Vec<u8>)>>,
}

impl Transport for Drop8 {
    type Addr = u8;

    fn recv<F: FnMut(Via, u8, &[u8])>(&mut self, wait: Duration, mut on: F) -> std::io::Result<()> {
        match self.inbox.recv_timeout(wait) {
            Ok((from, bytes)) => on(Via::Network, from, &bytes),
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(std::io::Error::other("bus gone"))
            }
        }
        Ok(())
    }

    fn send(&mut self, d: &Datagram<u8>) -> std::io::Result<()> {
        let to = self
            .others
            .get(&d.to)
            .ok_or_else(|| std::io::Error::other(format!("no drop {} on the bus", d.to)))?;
        to.send((self.me, d.bytes.clone()))
            .map_err(|_| std::io::Error::other("drop gone"))
    }

    fn describe(&self) -> String {
        format!("bus drop {}", self.me)
    }
}

/// A bus with drops 1 and 2.
fn bus() -> (Drop8, Drop8) {
    let (t1, r1) = mpsc::channel();
    let (t2, r2) = mpsc::channel();
    (
        Drop8 {
            me: 1,
            inbox: r1,
            others: HashMap::from([(2, t2)]),
        },
        Drop8 {
            me: 2,
            inbox: r2,
            others: HashMap::from([(1, t1)]),
        },
    )
}

fn config(node: u8, peer: u8) -> NodeConfig<u8> {
    let mut c = NodeConfig {
        node,
        ..NodeConfig::default()
    }
    .with_peers(vec![peer], None);
    c.manager.heartbeat = Duration::from_millis(100);
    c
}

#[test]
fn two_nodes_on_a_serial_bus_find_each_other_and_answer_across_it() {
    let (d1, d2) = bus();
    let stop = Arc::new(AtomicBool::new(false));
    let until = Some(Instant::now() + Duration::from_secs(20));

    let s2 = stop.clone();
    let far = std::thread::spawn(move || {
        let mut node = Node::new(config(2, 1), Instant::now());
        let mut d2 = d2;
        shell::run(&mut node, &mut d2, &s2, until, |_| {}, |_, _, _| {}).map(|()| node.stats())
    });

    let mut node = Node::new(config(1, 2), Instant::now());
    let mut d1 = d1;
    let far_manager = Address::new(1, 2, 1, 1);
    let mut asked = false;
    let mut frames = Vec::new();
    let result = shell::run(
        &mut node,
        &mut d1,
        &stop,
        until,
        |n| {
            // Once node 2 is in node 1's system tree, node 1's manager asks it who it is.
            if !asked && n.tree().components().contains(&far_manager) {
                let q = QueryIdentification {
                    query_field: QueryLevel::Node,
                };
                let header = Header::new(QueryIdentification::CODE, far_manager, n.address());
                n.send(Instant::now(), header, q.to_bytes().unwrap());
                asked = true;
            }
        },
        |dir, peer, bytes| {
            frames.push((dir, peer, bytes.first().copied()));
            let answered = dir == Direction::Received
                && bytes.len() > 8
                && jaus::net::Framing::Judp
                    .packet(bytes)
                    .is_ok_and(|(h, _)| h.command_code.0 == 0x4B00 && h.source == far_manager);
            if answered {
                stop.store(true, Ordering::Relaxed);
            }
        },
    );
    stop.store(true, Ordering::Relaxed);
    result.expect("node 1's shell");
    let far_stats = far.join().unwrap().expect("node 2's shell");

    assert!(
        asked,
        "node 2 never appeared in node 1's system tree over the bus"
    );
    assert!(
        frames
            .iter()
            .any(|(d, p, _)| *d == Direction::Received && *p == 2),
        "nothing received from drop 2"
    );
    // JUDP framing (its version byte, 1) on the bus, as on UDP.
    assert!(frames.iter().all(|(_, _, v)| *v == Some(1)), "{frames:?}");
    assert!(
        frames.iter().any(|(d, _, _)| *d == Direction::Received)
            && node.stats().delivered_local > 0,
        "{:?}",
        node.stats()
    );
    assert_eq!(node.peers().get(&(1, 2)), Some(&2u8));
    assert!(
        far_stats.received > 0 && far_stats.bad_framing == 0,
        "{far_stats:?}"
    );
}
