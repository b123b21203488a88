//! Processes that run threads end when told (issue 36): `jaus ocu --vehicle` takes an
//! emergency stop through the page's API, shows the vehicle in Emergency within a second
//! (the simulated vehicle's thread logs then), and exits at `--seconds` and on SIGINT;
//! `jaus node` with OpenJAUS component sockets (receiver threads that log at -vv) exits
//! on both too. Before the fix the CLI held stderr's lock for its whole run, so the first
//! line another thread logged blocked it forever and the process never ended.

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use common::{free_port, jaus_bin};
use serde_json::Value;

/// A process (killed if the test fails before it ended) whose stderr is read as it
/// comes (a full pipe would block the process's logging: not the bug under test).
struct Proc(Child, std::sync::Arc<std::sync::Mutex<String>>);

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

impl Proc {
    fn new(mut child: Child) -> Self {
        let text = std::sync::Arc::new(std::sync::Mutex::new(String::new()));
        if let Some(mut e) = child.stderr.take() {
            let t = text.clone();
            std::thread::spawn(move || {
                let mut buf = [0u8; 4096];
                while let Ok(n) = e.read(&mut buf) {
                    if n == 0 {
                        break;
                    }
                    t.lock()
                        .unwrap()
                        .push_str(&String::from_utf8_lossy(&buf[..n]));
                }
            });
        }
        Proc(child, text)
    }

    /// Waits up to `limit` for the process to end.
    fn exit_within(&mut self, limit: Duration) -> Option<ExitStatus> {
        let until = Instant::now() + limit;
        while Instant::now() < until {
            if let Some(s) = self.0.try_wait().unwrap() {
                return Some(s);
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        None
    }

    fn interrupt(&self) {
        let ok = Command::new("kill")
            .args(["-INT", &self.0.id().to_string()])
            .status()
            .unwrap();
        assert!(ok.success());
    }

    /// What the process wrote to stderr so far (all of it once it ended: give the
    /// reader a moment).
    fn stderr(&mut self) -> String {
        std::thread::sleep(Duration::from_millis(100));
        self.1.lock().unwrap().clone()
    }
}

/// A keyed request to the console's API; the body of a 2xx, else a panic.
fn api(http: SocketAddr, key: &str, method: &str, path: &str, body: &str) -> String {
    let mut s = TcpStream::connect(http).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: {http}\r\nX-Jaus-Key: {key}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut text = String::new();
    let _ = s.read_to_string(&mut text);
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or((&text, ""));
    assert!(head.starts_with("HTTP/1.1 2"), "{method} {path}: {head}");
    body.to_string()
}

fn vehicle(view: &Value) -> Option<&Value> {
    view["subsystems"].as_array()?.iter().find(|s| s["id"] == 1)
}

/// Starts `jaus ocu --vehicle`, waits for the vehicle's pose, presses the emergency stop
/// through the API and checks the vehicle is shown in Emergency within a second.
fn ocu_with_an_emergency(seconds: u32) -> (Proc, Instant) {
    let port = free_port();
    // (Built first: the clock starts when the process does.)
    let bin = jaus_bin();
    let started = Instant::now();
    let mut p = Proc::new(
        Command::new(bin)
            .args(["-v", "ocu", "--vehicle", "--seconds", &seconds.to_string()])
            .args(["--http", &format!("127.0.0.1:{port}")])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut line = String::new();
    BufReader::new(p.0.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    let key = url.split_once("?key=").unwrap().1.to_string();
    let http: SocketAddr = format!("127.0.0.1:{port}").parse().unwrap();
    let until = Instant::now() + Duration::from_secs(20);
    loop {
        let view: Value = serde_json::from_str(&api(http, &key, "GET", "/api/view", "")).unwrap();
        if vehicle(&view).is_some_and(|v| !v["pose"].is_null()) {
            break;
        }
        assert!(Instant::now() < until, "no vehicle pose: {view}");
        std::thread::sleep(Duration::from_millis(200));
    }
    api(
        http,
        &key,
        "POST",
        "/api/command",
        r#"{"op":"emergency","subsystem":1}"#,
    );
    let pressed = Instant::now();
    loop {
        let view: Value = serde_json::from_str(&api(http, &key, "GET", "/api/view", "")).unwrap();
        if vehicle(&view).is_some_and(|v| v["emergency"] == true) {
            break;
        }
        assert!(
            pressed.elapsed() < Duration::from_secs(1),
            "the vehicle not shown in Emergency within 1 s: {view}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    // The vehicle keeps reporting (it is not stale) after the emergency.
    std::thread::sleep(Duration::from_secs(2));
    let view: Value = serde_json::from_str(&api(http, &key, "GET", "/api/view", "")).unwrap();
    let v = vehicle(&view).expect("the vehicle still in the tree");
    assert_eq!(v["emergency"], true);
    assert_eq!(v["stale"], false, "{v}");
    (p, started)
}

#[test]
fn the_console_with_its_vehicle_exits_at_its_seconds_after_an_emergency_stop() {
    let (mut p, started) = ocu_with_an_emergency(12);
    let status = p
        .exit_within(Duration::from_secs(12 + 10).saturating_sub(started.elapsed()))
        .unwrap_or_else(|| panic!("still running 10 s after --seconds; stderr: {}", p.stderr()));
    let stderr = p.stderr();
    assert!(status.success(), "{status}: {stderr}");
    assert!(
        stderr.contains("Emergency"),
        "the vehicle logged its emergency: {stderr}"
    );
}

#[test]
fn the_console_with_its_vehicle_exits_on_sigint_after_an_emergency_stop() {
    let (mut p, _) = ocu_with_an_emergency(120);
    p.interrupt();
    let status = p
        .exit_within(Duration::from_secs(6))
        .unwrap_or_else(|| panic!("still running 6 s after SIGINT; stderr: {}", p.stderr()));
    assert!(status.success(), "{status}: {}", p.stderr());
}

/// `jaus node` with OpenJAUS's component sockets: one receiver thread per socket, each
/// logging at -vv.
fn node_with_receivers(seconds: Option<u32>) -> Proc {
    let dir = std::env::temp_dir().join(format!("jaus-shutdown-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("node-{}.yaml", seconds.unwrap_or(0)));
    let (udp, control, data) = (free_port(), free_port(), free_port());
    std::fs::write(
        &file,
        format!(
            "subsystem: 7\nnode: 1\nbind: 127.0.0.1:{udp}\nhost: [vehicle]\nopenjaus_components:\n  control: 127.0.0.1:{control}\n  data: 127.0.0.1:{data}\n"
        ),
    )
    .unwrap();
    let mut cmd = Command::new(jaus_bin());
    cmd.args(["-vv", "node", "--config"]).arg(&file);
    if let Some(s) = seconds {
        cmd.args(["--seconds", &s.to_string()]);
    }
    Proc::new(
        cmd.stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap(),
    )
}

#[test]
fn a_node_whose_threads_log_exits_at_its_seconds_and_on_sigint() {
    let mut timed = node_with_receivers(Some(3));
    let status = timed
        .exit_within(Duration::from_secs(13))
        .unwrap_or_else(|| panic!("still running 10 s after --seconds: {}", timed.stderr()));
    let stderr = timed.stderr();
    assert!(status.success(), "{status}: {stderr}");
    assert!(
        stderr.contains("receiving") && stderr.contains("receiver stopped"),
        "the receiver threads logged: {stderr}"
    );

    let mut p = node_with_receivers(None);
    std::thread::sleep(Duration::from_secs(2));
    p.interrupt();
    let status = p
        .exit_within(Duration::from_secs(6))
        .unwrap_or_else(|| panic!("still running 6 s after SIGINT: {}", p.stderr()));
    assert!(status.success(), "{status}: {}", p.stderr());
}
