//! The console drives an AS-4 vehicle, in a real headless browser: the demo's vehicle
//! answers only AS-4 (RA 3.3 subsystem 1 behind the gateway, `jaus_as4::gateway::DualNode`,
//! no RA 3.3 peer), a node of subsystem 2 presents it as RA 3.3 components
//! (`jaus_as4::proxy`, an AS-4 client of the vehicle on its own socket), and the console
//! (subsystem 200) has only that node as its peer. The page lists the proxy's
//! components, takes control of its Global Waypoint Driver (granted once the proxy holds
//! AS-4 control), gets a waypoint clicked on the map and drives the vehicle there; the
//! vehicle's own pose (read on its node) must agree with the page's. A screenshot is saved
//! as `target/ocu/console-as4.png`.
//!
//! Without `chromedriver` the test is skipped with a message, unless
//! `JAUS_REQUIRE_BROWSER` is set.

mod common;

use std::net::{SocketAddr, UdpSocket};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

use common::browser::{
    click, click_map, get, js, set_input, speed, text, vehicle_xy_of, wait_for, Browser,
};
use jaus::net::as5669a::{As4Config, As4Id, As4Mux};
use jaus::net::{udp, Node, NodeConfig};
use jaus::{Address, JausMessage};
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::proxy::{install, ProxyConfig};
use jaus_ocu::{Bound, ConsoleOptions};
use serde_json::{json, Value};

/// The vehicle's true position (latitude, longitude), as its own node last had it.
type Truth = Arc<Mutex<Option<(f64, f64)>>>;

/// The AS-4 vehicle, the proxy node and the console, each on a thread of the test.
struct Rig {
    bound: Bound,
    truth: Truth,
    stop: Arc<AtomicBool>,
    threads: Vec<std::thread::JoinHandle<()>>,
}

impl Rig {
    fn start() -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let truth: Truth = Arc::new(Mutex::new(None));
        let vsock = UdpSocket::bind("127.0.0.1:0").unwrap();
        let vaddr = vsock.local_addr().unwrap();
        let (s, t) = (stop.clone(), truth.clone());
        let vehicle = std::thread::spawn(move || {
            let now = Instant::now();
            let node = jaus_sim::demo::vehicle_node(now, NodeConfig::default(), 1, 1).unwrap();
            let gw = GatewayConfig::new(
                As4Id::new(1, 1, 1),
                Address::new(1, 1, 60, 1),
                1,
                "demo vehicle",
            );
            let mut dual = DualNode::new(node, gw).unwrap();
            udp::run_on(&mut dual, &vsock, &s, None, |d| {
                if let Some(p) = position(d) {
                    *t.lock().unwrap() = Some(p);
                }
            })
            .expect("the AS-4 vehicle");
        });
        let psock = UdpSocket::bind("127.0.0.1:0").unwrap();
        let paddr = psock.local_addr().unwrap();
        let s = stop.clone();
        let proxy = std::thread::spawn(move || {
            let now = Instant::now();
            let config = NodeConfig {
                subsystem: 2,
                node: 1,
                ..NodeConfig::default()
            };
            let mut node: Node = Node::new(config, now);
            let p = install(
                &mut node,
                ProxyConfig::new(As4Id::new(2, 1, 200), None),
                vaddr,
                now,
            )
            .unwrap();
            let mut mux = As4Mux::new(node, p, As4Config::default());
            udp::run_on(&mut mux, &psock, &s, None, |_| {}).expect("the proxy node");
        });
        let options = ConsoleOptions {
            node: NodeConfig {
                subsystem: 200,
                node: 1,
                peers: vec![paddr],
                ..NodeConfig::default()
            },
            http: SocketAddr::from(([127, 0, 0, 1], 0)),
            ..ConsoleOptions::default()
        };
        let (tx, rx) = mpsc::channel::<Bound>();
        let s = stop.clone();
        let console = std::thread::spawn(move || {
            jaus_ocu::run(&options, &s, |b| {
                let _ = tx.send(b);
            })
            .expect("the console")
        });
        let bound = rx
            .recv_timeout(Duration::from_secs(10))
            .expect("the console is up");
        Self {
            bound,
            truth,
            stop,
            threads: vec![console, proxy, vehicle],
        }
    }

    fn finish(mut self) {
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

/// The vehicle's Global Pose Sensor's latest report on its own node.
fn position(d: &DualNode) -> Option<(f64, f64)> {
    let side = d.gateway().node().env();
    let gps = side.targets().global_pose_sensor?;
    match side.latest(gps, jaus::messages::ReportGlobalPose::CODE) {
        Some((_, jaus::messages::Message::ReportGlobalPose(p))) => {
            Some((p.latitude?, p.longitude?))
        }
        _ => None,
    }
}

/// Metres between two positions (equirectangular).
fn metres(a: (f64, f64), b: (f64, f64)) -> f64 {
    let r = 6_371_000.0_f64;
    let north = (b.0 - a.0).to_radians() * r;
    let east = (b.1 - a.1).to_radians() * r * ((a.0 + b.0) / 2.0).to_radians().cos();
    north.hypot(east)
}

/// The view's subsystem 2 (the proxy's).
fn subsystem(view: &Value, id: u64) -> Option<&Value> {
    view["subsystems"]
        .as_array()?
        .iter()
        .find(|s| s["id"] == json!(id))
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_drives_an_as4_vehicle_through_the_proxy() {
    let Some(browser) = Browser::start().await else {
        return;
    };
    let rig = Rig::start();
    let bound = rig.bound.clone();
    let c = browser.client.clone();
    c.goto(&bound.url()).await.expect("the page");

    // The AS-4 vehicle appears as subsystem 2 with its waypoint driver; nothing of its
    // own RA 3.3 subsystem reaches the console.
    let start = wait_for(
        "the AS-4 vehicle on the map",
        Duration::from_secs(30),
        async || vehicle_xy_of(&c, 2).await,
    )
    .await;
    wait_for(
        "the proxy's waypoint driver",
        Duration::from_secs(20),
        async || {
            (js(&c, "return document.getElementById('driver').value;").await == json!("2.1.45.1"))
                .then_some(())
        },
    )
    .await;
    // The API's view (with trails) is published once a second.
    let view = wait_for(
        "subsystem 2 in /api/view",
        Duration::from_secs(5),
        async || {
            let v = get(&bound, "/api/view");
            subsystem(&v, 2).is_some().then_some(v)
        },
    )
    .await;
    let proxy = subsystem(&view, 2).unwrap();
    let listed: Vec<String> = proxy["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|n| n["components"].as_array().unwrap().iter())
        .filter_map(|c| c["address"].as_str().map(String::from))
        .collect();
    for a in ["2.1.38.1", "2.1.42.1", "2.1.45.1", "2.1.33.1"] {
        assert!(listed.iter().any(|l| l == a), "{a} not listed: {listed:?}");
    }
    assert!(
        subsystem(&view, 1).is_none(),
        "the vehicle's RA 3.3 subsystem is visible"
    );

    // Control of the proxy's driver (the proxy takes AS-4 control first).
    set_input(&c, "authority", "5").await;
    click(&c, "take").await;
    wait_for("control held", Duration::from_secs(15), async || {
        (text(&c, "driver-control").await? == "held").then_some(())
    })
    .await;

    // A waypoint 10 m east and 6 m north, at 2 m/s.
    set_input(&c, "speed", "2.0").await;
    let target = (start.0 + 10.0, start.1 + 6.0);
    click_map(&c, target.0, target.1).await;
    click(&c, "drive").await;
    let t_drive = Instant::now();
    let arrived = wait_for(
        "the vehicle's arrival",
        Duration::from_secs(60),
        async || {
            let (x, y) = vehicle_xy_of(&c, 2).await?;
            let still = speed(&c).await.is_some_and(|s| s < 0.1);
            ((x - target.0).hypot(y - target.1) < 1.0 && still).then_some((x, y))
        },
    )
    .await;
    let drive_s = t_drive.elapsed().as_secs_f64();

    // The page's pose (through the proxy) is the vehicle's own.
    let (shown, truth, off) = wait_for(
        "the page's pose and the vehicle's own agreeing",
        Duration::from_secs(5),
        async || {
            let view = get(&bound, "/api/view");
            let pose = &subsystem(&view, 2)?["pose"];
            let shown = (pose["latitude"].as_f64()?, pose["longitude"].as_f64()?);
            let truth = (*rig.truth.lock().unwrap())?;
            let off = metres(shown, truth);
            (off < 0.5).then_some((shown, truth, off))
        },
    )
    .await;
    eprintln!("AS-4 browser test: the page shows {shown:?}, the vehicle is at {truth:?}");

    let png = c.screenshot().await.expect("a screenshot");
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/ocu");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("console-as4.png"), &png).unwrap();
    eprintln!(
        "AS-4 browser test: arrived at {arrived:?} (target {target:?}) {drive_s:.1} s after Drive; page vs vehicle {off:.2} m; screenshot {}",
        dir.join("console-as4.png").display()
    );
    let _ = c.close().await;
    rig.finish();
}
