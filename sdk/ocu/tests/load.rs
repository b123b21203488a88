//! Page update latency against a console that is already running (ignored by default; the
//! measurement of docs/performance.md "Operator console"): opens `OCU_URL` (the address
//! `jaus ocu` printed, with its key) in headless
//! Chromium for `OCU_SECONDS` (default 30) and prints, for every pose the console
//! received, the time until the page had drawn it (the console stamps each pose with its
//! arrival; the page records when it drew it), and the views drawn per second.
//!
//! ```text
//! OCU_URL='http://127.0.0.1:8720/?key=…' cargo test --release -p jaus-ocu --test load -- --ignored --nocapture
//! ```

use std::time::Duration;

use fantoccini::ClientBuilder;
use serde_json::json;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
#[ignore = "needs a running console (OCU_URL) and chromedriver"]
async fn page_latency_against_a_running_console() {
    let url = std::env::var("OCU_URL").expect("OCU_URL: the console's page");
    let seconds: u64 = std::env::var("OCU_SECONDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30);
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .unwrap()
        .port();
    let mut driver = std::process::Command::new("chromedriver")
        .arg(format!("--port={port}"))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("chromedriver");
    let mut caps = serde_json::Map::new();
    caps.insert(
        "goog:chromeOptions".into(),
        json!({"binary": "/usr/bin/chromium", "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1500,1000"]}),
    );
    let connector = hyper_util::client::legacy::connect::HttpConnector::new();
    let mut client = None;
    for _ in 0..100 {
        if let Ok(c) = ClientBuilder::new(connector.clone())
            .capabilities(caps.clone())
            .connect(&format!("http://127.0.0.1:{port}"))
            .await
        {
            client = Some(c);
            break;
        }
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    let c = client.expect("a WebDriver session");
    c.goto(&url).await.unwrap();
    tokio::time::sleep(Duration::from_secs(3)).await;
    c.execute(
        "ocu.stats.latencies = []; ocu.stats.draw = []; ocu.stats.push = []; ocu.stats.frames = 0;",
        vec![],
    )
    .await
    .unwrap();
    tokio::time::sleep(Duration::from_secs(seconds)).await;
    let r = c
        .execute(
            "const l = ocu.stats.latencies.slice().sort((a, b) => a - b);
             const q = (f) => l[Math.min(l.length - 1, Math.floor(l.length * f))];
             return {n: l.length, median: q(0.5), p95: q(0.95), p99: q(0.99), max: l[l.length - 1],
                     draw_median: ocu.stats.draw.slice().sort((a, b) => a - b)[Math.floor(ocu.stats.draw.length / 2)],
                     push_median: ocu.stats.push.slice().sort((a, b) => a - b)[Math.floor(ocu.stats.push.length / 2)],
                     frames: ocu.stats.frames, vehicles: ocu.view.subsystems.filter(s => s.pose).length};",
            vec![],
        )
        .await
        .unwrap();
    println!("page over {seconds} s: {r}");
    let _ = c.close().await;
    let _ = driver.kill();
    let _ = driver.wait();
}
