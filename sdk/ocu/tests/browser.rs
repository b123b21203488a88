//! The console end to end in a real headless browser (Debian's `chromium` and
//! `chromium-driver`, driven over WebDriver): against a node hosting the demo's simulated
//! vehicle on loopback, the page refuses a route without control and a malformed speed
//! (visible errors), takes control of the waypoint driver, gets two waypoints clicked on
//! the map, shows the vehicle's marker arriving, drives a path segment through the Global
//! Path Segment Driver, spools a two-move mission to the Mission Spooler and runs it to
//! Finished, stores an obstacle clicked on the map in the world model and draws it, and
//! after the emergency stop shows the vehicle stopped and its state
//! Emergency. A screenshot is saved as
//! `target/ocu/console.png`.
//!
//! Without `chromedriver` the test is skipped with a message, unless
//! `JAUS_REQUIRE_BROWSER` is set (CI installs the packages and sets it).

mod common;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use common::browser::{
    click, click_map, get, js, set_input, speed, text, vehicle_xy, wait_for, Browser, Rig,
};
use fantoccini::{Client, Locator};
use jaus_ocu::{Bound, ConsoleOptions};
use serde_json::{json, Value};

/// A page at `http://{host}:{port}/` (served by a thread of the test) that tries the
/// console's commands; the test checks the attempts failed, nothing was run (no notice,
/// the vehicle not in emergency) and the console counted the refusals.
async fn attack_from(c: &Client, host: &str, bound: &Bound) {
    let target = format!("http://{}", bound.http);
    let emergency = r#"{"op":"emergency","subsystem":1}"#;
    let page = format!(
        r#"<!doctype html><html><body><iframe name="sink"></iframe><script>
const results = {{}};
window.results = results;
const body = '{emergency}';
fetch("{target}/api/command", {{method: "POST", mode: "no-cors", headers: {{"Content-Type": "text/plain"}}, body}})
  .then(() => results.nocors = "sent").catch(() => results.nocors = "failed");
fetch("{target}/api/command", {{method: "POST", headers: {{"Content-Type": "application/json"}}, body}})
  .then(r => results.cors = "status " + r.status).catch(() => results.cors = "blocked");
fetch("{target}/api/view").then(r => r.text()).then(t => results.read = t).catch(() => results.read = "blocked");
const ws = new WebSocket("ws://{http}/ws");
ws.onopen = () => {{ results.ws = "open"; ws.send(body); }};
ws.onclose = () => {{ if (!results.ws) results.ws = "refused"; }};
const f = document.createElement("form");
f.method = "POST"; f.action = "{target}/api/command"; f.enctype = "text/plain"; f.target = "sink";
const i = document.createElement("input"); i.name = body; i.value = ""; f.appendChild(i);
document.body.appendChild(f); f.submit(); results.form = "submitted";
</script></body></html>"#,
        http = bound.http
    );
    let listener = std::net::TcpListener::bind(format!("{host}:0")).unwrap();
    let port = listener.local_addr().unwrap().port();
    std::thread::spawn(move || {
        use std::io::{Read, Write};
        // A handful of requests (the page, a favicon); then the thread ends with the test.
        for stream in listener.incoming().take(4).flatten() {
            let mut stream = stream;
            let mut buf = [0u8; 2048];
            let _ = stream.read(&mut buf);
            let _ = write!(
                stream,
                "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{page}",
                page.len()
            );
        }
    });
    let before = stats(bound)["refused"].as_u64().unwrap();
    c.goto(&format!("http://{host}:{port}/"))
        .await
        .expect("the other page");
    let results = wait_for("the attempts", Duration::from_secs(10), async || {
        let r = js(c, "return window.results;").await;
        ["nocors", "cors", "read", "ws", "form"]
            .iter()
            .all(|k| r.get(k).is_some())
            .then_some(r)
    })
    .await;
    assert_eq!(results["ws"], json!("refused"), "from {host}: {results}");
    assert_eq!(results["cors"], json!("blocked"), "from {host}: {results}");
    assert_eq!(results["read"], json!("blocked"), "from {host}: {results}");
    // The no-cors fetch and the form were sent (a browser cannot be stopped from
    // sending them) and refused by the server, as were the view and the WebSocket; the
    // JSON fetch never left the browser (its preflight is not granted).
    let refused = wait_for("the refusals counted", Duration::from_secs(5), async || {
        let n = stats(bound)["refused"].as_u64().unwrap();
        (n >= before + 4).then_some(n)
    })
    .await;
    tokio::time::sleep(Duration::from_millis(500)).await;
    let view = get(bound, "/api/view");
    assert_eq!(
        view["notice_count"],
        json!(0),
        "from {host}: a refused command ran: {view}"
    );
    assert_eq!(
        view["subsystems"][0]["emergency"],
        json!(false),
        "from {host}"
    );
    eprintln!(
        "browser test: from http://{host}:{port}/: {results}; {} refused",
        refused - before
    );
}

fn stats(bound: &Bound) -> Value {
    get(bound, "/api/stats")
}

async fn notices(c: &Client) -> Vec<String> {
    let v = js(
        c,
        "return [...document.querySelectorAll('#notices li.error')].map(e => e.textContent);",
    )
    .await;
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(|s| s.as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default()
}

async fn set_speed(c: &Client, text: &str) {
    set_input(c, "speed", text).await;
}

/// Clicks the map at (`x`, `y`) m and waits until the page has the point in its draft.
/// The map's automatic view may move between reading where the point is and the click
/// (a new pose redraws it), so a click that added nothing is made again, up to 5 times;
/// the failure names the element that took the click.
async fn add_point(c: &Client, x: f64, y: f64) {
    for _ in 0..5 {
        let before = js(c, "return ocu.draft.length;")
            .await
            .as_u64()
            .unwrap_or(0);
        click_map(c, x, y).await;
        for _ in 0..10 {
            if js(c, "return ocu.draft.length;")
                .await
                .as_u64()
                .unwrap_or(0)
                > before
            {
                return;
            }
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
    }
    let hit = js(
        c,
        &format!(
            "const p = ocu.worldToClient({x}, {y}); const e = document.elementFromPoint(p.x, p.y); \
             return [p.x, p.y, e ? e.tagName + '#' + e.id : null];"
        ),
    )
    .await;
    panic!(
        "5 clicks at ({x:.1}, {y:.1}) m added no point to the draft (the click's target: {hit})"
    );
}

/// Selects `address` in the driver list and takes control of it with `authority`.
async fn take(c: &Client, address: &str, authority: &str) {
    c.find(Locator::Id("driver"))
        .await
        .expect("#driver")
        .select_by_value(address)
        .await
        .unwrap_or_else(|e| panic!("select {address}: {e}"));
    set_input(c, "authority", authority).await;
    click(c, "take").await;
    held(c, address).await;
}

/// Waits until the page says control of `address`, the selected component, is held. The
/// line names the component it speaks of: until the page has drawn the new selection it
/// still shows the previous one's control (a "held" that is not this one's).
async fn held(c: &Client, address: &str) {
    wait_for(
        "control of the selected component",
        Duration::from_secs(10),
        async || {
            let line = js(
                c,
                "const e = document.getElementById('driver-control'); \
                 return [e.dataset.address || '', e.textContent];",
            )
            .await;
            (line[0] == address && line[1] == "held").then_some(())
        },
    )
    .await;
}

/// Waits until the vehicle stands within a metre of `to`.
async fn arrive(c: &Client, what: &str, to: (f64, f64)) -> (f64, f64) {
    wait_for(what, Duration::from_secs(60), async || {
        let (x, y) = vehicle_xy(c).await?;
        let still = speed(c).await.is_some_and(|s| s < 0.1);
        ((x - to.0).hypot(y - to.1) < 1.0 && still).then_some((x, y))
    })
    .await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_drives_the_simulated_vehicle_and_stops_it() {
    // The vehicle's and the console's log, shown by the harness when the test fails.
    let _ = tracing_subscriber::fmt()
        .with_env_filter("info")
        .with_test_writer()
        .try_init();
    let Some(browser) = Browser::start().await else {
        return;
    };
    let rig = Rig::start(ConsoleOptions::default());
    let bound = rig.bound.clone();
    let c = browser.client.clone();
    // The address `jaus ocu` prints: it carries the key, which becomes the page's cookie.
    c.goto(&bound.url()).await.expect("the page");

    // The vehicle appears with its waypoint driver.
    wait_for(
        "the vehicle on the map",
        Duration::from_secs(20),
        async || vehicle_xy(&c).await,
    )
    .await;
    wait_for("the waypoint driver", Duration::from_secs(20), async || {
        (js(&c, "return document.getElementById('driver').value;").await == json!("1.1.45.1"))
            .then_some(())
    })
    .await;

    // Pages of other origins try the console's commands (a no-cors fetch, a JSON fetch, a
    // form, a WebSocket): one on another site (localhost), one on another port of the
    // same site (127.0.0.1, which gets the cookie). Nothing gets through.
    for host in ["localhost", "127.0.0.1"] {
        attack_from(&c, host, &bound).await;
    }
    c.goto(&format!("http://{}/", bound.http))
        .await
        .expect("the page again, with its cookie");
    let start = wait_for(
        "the vehicle on the map again",
        Duration::from_secs(20),
        async || vehicle_xy(&c).await,
    )
    .await;

    // A route without control: refused, visibly.
    add_point(&c, start.0 + 3.0, start.1 + 3.0).await;
    click(&c, "drive").await;
    wait_for("the no-control error", Duration::from_secs(5), async || {
        notices(&c)
            .await
            .into_iter()
            .find(|n| n.contains("needs control"))
    })
    .await;

    // Take control.
    click(&c, "take").await;
    held(&c, "1.1.45.1").await;

    // A malformed speed: refused, visibly, naming the field.
    set_speed(&c, "fast").await;
    add_point(&c, start.0 + 3.0, start.1 + 3.0).await;
    click(&c, "drive").await;
    wait_for("the bad-speed error", Duration::from_secs(5), async || {
        notices(&c).await.into_iter().find(|n| n.contains("speed"))
    })
    .await;
    set_speed(&c, "2.0").await;

    // Two waypoints clicked on the map, then driven.
    let targets = [
        (start.0 + 6.0, start.1 + 4.0),
        (start.0 + 12.0, start.1 - 2.0),
    ];
    for (x, y) in targets {
        add_point(&c, x, y).await;
    }
    let draft = js(&c, "return ocu.draft.map(p => [p.x, p.y]);").await;
    let draft: Vec<(f64, f64)> = draft
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    assert_eq!(draft.len(), 2, "two waypoints clicked: {draft:?}");
    for (d, t) in draft.iter().zip(targets) {
        assert!(
            (d.0 - t.0).hypot(d.1 - t.1) < 0.5,
            "clicked {d:?}, meant {t:?}"
        );
    }
    click(&c, "drive").await;
    let t_drive = Instant::now();
    let last = targets[1];
    let arrived = arrive(&c, "the vehicle's arrival", last).await;
    let drive_s = t_drive.elapsed().as_secs_f64();
    // It went through the first waypoint on the way.
    let trail = js(&c, "return ocu.trails.get(1);").await;
    let closest = trail
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|p| Some((p[0].as_f64()?, p[1].as_f64()?)))
        .map(|p| (p.0 - targets[0].0).hypot(p.1 - targets[0].1))
        .fold(f64::INFINITY, f64::min);
    assert!(
        closest < 1.0,
        "the trail passes {closest:.2} m from waypoint 1"
    );

    // A path segment through the Global Path Segment Driver.
    take(&c, "1.1.47.1", "5").await;
    let end = (start.0 + 6.0, start.1 - 8.0);
    add_point(&c, end.0, end.1).await;
    click(&c, "drive-path").await;
    arrive(&c, "the end of the path segment", end).await;

    // A mission of two moves spooled to the Mission Spooler (authority 200) and run.
    take(&c, "1.1.36.1", "200").await;
    let moves = [
        (start.0 + 2.0, start.1 - 8.0),
        (start.0 + 2.0, start.1 - 3.0),
    ];
    for (x, y) in moves {
        add_point(&c, x, y).await;
    }
    click(&c, "spool").await;
    wait_for("the mission spooled", Duration::from_secs(10), async || {
        let t = text(&c, "mission-status").await?;
        t.starts_with("mission").then_some(())
    })
    .await;
    click(&c, "m-run").await;
    wait_for(
        "the mission finished",
        Duration::from_secs(60),
        async || {
            let t = text(&c, "mission-status").await?;
            t.contains("Finished").then_some(())
        },
    )
    .await;
    arrive(&c, "the mission's last move", moves[1]).await;
    // Left to itself, the map keeps the whole trail in view, with a scale bar.
    let seen = js(
        &c,
        "const r = document.getElementById('map').getBoundingClientRect(); \
         const t = ocu.trails.get(1) || []; \
         const out = t.filter(p => { const q = ocu.worldToClient(p[0], p[1]); \
           return q.x < r.left - 1 || q.x > r.right + 1 || q.y < r.top - 1 || q.y > r.bottom + 1; }); \
         return [t.length, out.length, document.getElementById('scale-text').textContent];",
    )
    .await;
    assert!(seen[0].as_u64().unwrap() > 50, "a trail: {seen}");
    assert_eq!(seen[1], json!(0), "trail points off the map: {seen}");
    let scale = seen[2].as_str().unwrap();
    assert!(
        scale.ends_with(" m") && scale.trim_end_matches(" m").parse::<f64>().is_ok(),
        "{scale}"
    );
    // An obstacle stored in the world model from the map, drawn once the store lists it.
    let rock = (start.0 + 15.0, start.1 + 5.0);
    set_input(&c, "obstacle-radius", "0.8").await;
    click_map(&c, rock.0, rock.1).await;
    click(&c, "obstacle").await;
    wait_for("the obstacle on the map", Duration::from_secs(10), async || {
        let objects = js(&c, "return ocu.view.subsystems[0].objects.map(o => [o.points[0][0], o.points[0][1], o.buffer]);").await;
        objects.as_array()?.iter().find_map(|o| {
            let (x, y, r) = (o[0].as_f64()?, o[1].as_f64()?, o[2].as_f64()?);
            ((x - rock.0).hypot(y - rock.1) < 0.5 && (r - 0.8).abs() < 1e-3).then_some(())
        })
    })
    .await;
    // Back to the waypoint driver for the rest.
    take(&c, "1.1.45.1", "5").await;

    // Moving again (back to the start), then the emergency stop.
    add_point(&c, start.0, start.1).await;
    click(&c, "drive").await;
    let until = Instant::now() + Duration::from_secs(20);
    while !speed(&c).await.is_some_and(|s| s > 0.3) {
        assert!(
            Instant::now() < until,
            "timed out waiting for the vehicle moving; the console's view: {}",
            get(&bound, "/api/view")
        );
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    click(&c, "estop-all").await;
    let t_stop = Instant::now();
    wait_for("state Emergency", Duration::from_secs(5), async || {
        let s = text(&c, "veh-state").await?;
        s.contains("Emergency").then_some(())
    })
    .await;
    wait_for("the vehicle stopped", Duration::from_secs(10), async || {
        speed(&c).await.filter(|s| *s < 0.05)
    })
    .await;
    let stopped_s = t_stop.elapsed().as_secs_f64();
    let at_stop = vehicle_xy(&c).await.unwrap();
    tokio::time::sleep(Duration::from_secs(2)).await;
    let later = vehicle_xy(&c).await.unwrap();
    assert!(
        (later.0 - at_stop.0).hypot(later.1 - at_stop.1) < 0.2,
        "still moving after the emergency stop: {at_stop:?} -> {later:?}"
    );
    // The marker shows the emergency; the page is live, not stale.
    let class = js(
        &c,
        "return document.getElementById('vehicle-1').getAttribute('class');",
    )
    .await;
    assert!(class.as_str().unwrap().contains("emergency"), "{class}");
    let link = c
        .find(Locator::Id("link"))
        .await
        .unwrap()
        .text()
        .await
        .unwrap();
    assert!(link.starts_with("live"), "{link}");

    let png = c.screenshot().await.expect("a screenshot");
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/ocu");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("console.png"), &png).unwrap();
    let lat = js(&c, "const l = ocu.stats.latencies.slice().sort((a, b) => a - b); return [l.length, l[Math.floor(l.length / 2)], l[Math.floor(l.length * 0.95)], l[l.length - 1]];").await;
    eprintln!(
        "browser test: arrived at {arrived:?} {drive_s:.1} s after Drive; stopped {stopped_s:.1} s after the emergency stop; pose received -> drawn (n, median, p95, max ms): {lat}; screenshot {}",
        dir.join("console.png").display()
    );
    let _ = c.close().await;
    rig.finish();
}
