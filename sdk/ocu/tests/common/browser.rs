//! What the browser tests share: headless Chromium ([`super::chromium`]), the
//! demo's simulated vehicle and a console beside it on loopback, and small probes of the
//! page.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use fantoccini::Client;
use jaus::net::{udp, NodeConfig};
use jaus_ocu::{Bound, ConsoleOptions};
use serde_json::Value;

// Not every test file uses all three.
#[allow(unused_imports)]
pub use super::chromium::{js, wait_for, Browser};

/// The demo's vehicle on a node of its own (subsystem 1), as `jaus node` hosts it.
pub fn vehicle(socket: UdpSocket, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut node = jaus_sim::demo::vehicle_node(Instant::now(), NodeConfig::default(), 1, 1)
            .expect("the vehicle's components");
        udp::run_on(&mut node, &socket, &stop, None, |_| {}).expect("the vehicle's node");
    })
}

/// The demo's vehicle and a console (subsystem 200, `options` otherwise) that has it as
/// its peer, each on a thread.
pub struct Rig {
    pub bound: Bound,
    stop: Arc<AtomicBool>,
    threads: Vec<std::thread::JoinHandle<()>>,
}

impl Rig {
    pub fn start(options: ConsoleOptions) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let vsock = UdpSocket::bind("127.0.0.1:0").unwrap();
        let vaddr = vsock.local_addr().unwrap();
        let vthread = vehicle(vsock, stop.clone());
        let options = ConsoleOptions {
            node: NodeConfig {
                subsystem: 200,
                node: 1,
                peers: vec![vaddr],
                ..NodeConfig::default()
            },
            http: SocketAddr::from(([127, 0, 0, 1], 0)),
            ..options
        };
        let (tx, rx) = mpsc::channel::<Bound>();
        let cstop = stop.clone();
        let cthread = std::thread::spawn(move || {
            jaus_ocu::run(&options, &cstop, |b| {
                let _ = tx.send(b);
            })
            .expect("the console")
        });
        let bound = rx
            .recv_timeout(Duration::from_secs(10))
            .expect("the console is up");
        Self {
            bound,
            stop,
            threads: vec![cthread, vthread],
        }
    }

    /// Stops both and waits for them (a panic of either fails the test).
    pub fn finish(mut self) {
        self.stop.store(true, Ordering::Relaxed);
        for t in self.threads.drain(..) {
            t.join().unwrap();
        }
    }
}

impl Drop for Rig {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

/// A keyed GET of the console's API.
pub fn get(bound: &Bound, path: &str) -> Value {
    use std::io::{Read, Write};
    let mut s = std::net::TcpStream::connect(bound.http).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {}\r\nX-Jaus-Key: {}\r\nConnection: close\r\n\r\n",
        bound.http, bound.key
    )
    .unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    serde_json::from_str(body).unwrap_or_else(|e| panic!("{path}: {e}: {text}"))
}

pub async fn vehicle_xy(c: &Client) -> Option<(f64, f64)> {
    let v = js(
        c,
        "const g = document.getElementById('vehicle-1'); return g ? [Number(g.dataset.x), Number(g.dataset.y)] : null;",
    )
    .await;
    Some((v[0].as_f64()?, v[1].as_f64()?))
}
