//! Headless Chromium through `chromedriver` (WebDriver) for browser tests, with nothing
//! of the console in it: the console's browser tests use it through `browser.rs`, and
//! `jaus conform`'s report test (sdk/conform/tests/report_browser.rs) includes this file
//! by path, so both drive the same browser the same way.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use fantoccini::{Client, ClientBuilder};
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

pub async fn js(c: &Client, script: &str) -> Value {
    c.execute(script, vec![]).await.expect(script)
}
