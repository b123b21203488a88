//! What the browser tests share: headless Chromium ([`super::chromium`]), the
//! demo's simulated vehicle and a console beside it on loopback, and small probes of the
//! page.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
use fantoccini::{Client, Locator};
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
    vehicle_xy_of(c, 1).await
}

/// Where the page draws subsystem `subsystem`'s vehicle (x m east, y m north).
pub async fn vehicle_xy_of(c: &Client, subsystem: u8) -> Option<(f64, f64)> {
    let v = js(
        c,
        &format!("const g = document.getElementById('vehicle-{subsystem}'); return g ? [Number(g.dataset.x), Number(g.dataset.y)] : null;"),
    )
    .await;
    Some((v[0].as_f64()?, v[1].as_f64()?))
}

/// Clicks the element `id` (the test fails when it is not there).
pub async fn click(c: &Client, id: &str) {
    c.find(Locator::Id(id))
        .await
        .unwrap_or_else(|e| panic!("#{id}: {e}"))
        .click()
        .await
        .unwrap_or_else(|e| panic!("click #{id}: {e}"));
}

/// Types `text` into the input `id`, replacing what it held.
pub async fn set_input(c: &Client, id: &str, text: &str) {
    let e = c.find(Locator::Id(id)).await.expect(id);
    e.clear().await.expect("clear");
    e.send_keys(text).await.expect("type");
}

/// Clicks the map at (x m east, y m north) with a real pointer.
pub async fn click_map(c: &Client, x: f64, y: f64) {
    let p = js(c, &format!("return ocu.worldToClient({x}, {y});")).await;
    let (px, py) = (p["x"].as_f64().unwrap(), p["y"].as_f64().unwrap());
    let actions = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x: px.round() as _,
            y: py.round() as _,
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    c.perform_actions(actions).await.expect("pointer actions");
}

/// The vehicle's speed as the page shows it, m/s.
pub async fn speed(c: &Client) -> Option<f64> {
    js(
        c,
        "return Number(document.getElementById('veh-speed').dataset.speed);",
    )
    .await
    .as_f64()
}

/// The text of the element `id`, if it is there.
pub async fn text(c: &Client, id: &str) -> Option<String> {
    c.find(Locator::Id(id)).await.ok()?.text().await.ok()
}
