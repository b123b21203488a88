//! What the browser tests share: headless Chromium through `chromedriver` (WebDriver), the
//! demo's simulated vehicle and a console beside it on loopback, and small probes of the
//! page.

use std::net::{SocketAddr, UdpSocket};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use fantoccini::{Client, ClientBuilder};
use jaus::net::{udp, NodeConfig};
use jaus_ocu::{Bound, ConsoleOptions};
use serde_json::{json, Value};

struct Driver(Child);
impl Drop for Driver {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn chromedriver() -> Option<PathBuf> {
    let p = PathBuf::from("/usr/bin/chromedriver");
    if p.exists() {
        return Some(p);
    }
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("chromedriver"))
            .find(|p| p.exists())
    })
}

fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// Headless Chromium under a `chromedriver` of its own (both end when this is dropped).
pub struct Browser {
    pub client: Client,
    _driver: Driver,
}

impl Browser {
    /// `None` (with a message) when `chromedriver` is not installed, unless
    /// `JAUS_REQUIRE_BROWSER` is set (CI installs the packages and sets it).
    pub async fn start() -> Option<Self> {
        let Some(driver_path) = chromedriver() else {
            assert!(
                std::env::var_os("JAUS_REQUIRE_BROWSER").is_none(),
                "JAUS_REQUIRE_BROWSER is set but chromedriver is not installed"
            );
            eprintln!("skipped: chromedriver not found (apt-get install chromium chromium-driver)");
            return None;
        };
        let port = free_port();
        let driver = Driver(
            Command::new(&driver_path)
                .arg(format!("--port={port}"))
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .expect("chromedriver starts"),
        );
        let mut caps = serde_json::Map::new();
        caps.insert(
            "goog:chromeOptions".into(),
            json!({
                "binary": "/usr/bin/chromium",
                "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1500,1000"]
            }),
        );
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        let client = wait_for("chromedriver", Duration::from_secs(20), async || {
            ClientBuilder::new(connector.clone())
                .capabilities(caps.clone())
                .connect(&format!("http://127.0.0.1:{port}"))
                .await
                .ok()
        })
        .await;
        Some(Self {
            client,
            _driver: driver,
        })
    }
}

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

pub async fn wait_for<T>(
    what: &str,
    timeout: Duration,
    mut probe: impl AsyncFnMut() -> Option<T>,
) -> T {
    let until = Instant::now() + timeout;
    loop {
        if let Some(v) = probe().await {
            return v;
        }
        assert!(Instant::now() < until, "timed out waiting for {what}");
        tokio::time::sleep(Duration::from_millis(100)).await;
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

pub async fn js(c: &Client, script: &str) -> Value {
    c.execute(script, vec![]).await.expect(script)
}

pub async fn vehicle_xy(c: &Client) -> Option<(f64, f64)> {
    let v = js(
        c,
        "const g = document.getElementById('vehicle-1'); return g ? [Number(g.dataset.x), Number(g.dataset.y)] : null;",
    )
    .await;
    Some((v[0].as_f64()?, v[1].as_f64()?))
}
