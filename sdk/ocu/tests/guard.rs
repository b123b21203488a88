//! The console's web server against the requests a hostile web page, a DNS-rebinding
//! name or a tool without the key would send, over plain HTTP: each is refused with a
//! 4xx and its reason, counted, and nothing is executed (the station shows no notice);
//! the page's own requests (its origin, the key, JSON) still work.

mod common;

use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use common::{request, ws_upgrade, Console};
use jaus_ocu::ConsoleOptions;
use serde_json::Value;

fn console() -> Console {
    common::console(ConsoleOptions {
        http: SocketAddr::from(([127, 0, 0, 1], 0)),
        ..ConsoleOptions::default()
    })
}

/// What a request is, its headers, the status expected.
type Case<'a> = (&'a str, Vec<(&'a str, &'a str)>, u16);

const EMERGENCY: &str = r#"{"op":"emergency","subsystem":1}"#;

impl Console {
    fn host(&self) -> String {
        self.bound.http.to_string()
    }

    fn origin(&self) -> String {
        format!("http://{}", self.bound.http)
    }

    fn get_json(&self, path: &str) -> Value {
        let host = self.host();
        let a = request(
            self.bound.http,
            "GET",
            path,
            &[("Host", &host), ("X-Jaus-Key", &self.bound.key)],
            "",
        );
        assert_eq!(a.status, 200, "{path}: {a:?}");
        serde_json::from_str(&a.body).unwrap()
    }

    /// Notices the station has issued so far (after the node thread had time to run
    /// anything queued).
    fn notices(&self) -> u64 {
        std::thread::sleep(Duration::from_millis(300));
        self.get_json("/api/view")["notice_count"].as_u64().unwrap()
    }

    fn refused(&self) -> u64 {
        self.get_json("/api/stats")["refused"].as_u64().unwrap()
    }
}

#[test]
fn cross_origin_commands_are_refused_and_not_executed() {
    let c = console();
    let (host, origin, key) = (c.host(), c.origin(), c.bound.key.clone());
    let to = c.bound.http;
    let cookie = format!("jaus_ocu_{}={key}", to.port());
    let cases: Vec<Case<'_>> = vec![
        // The report of the issue: a "simple" cross-site request, no key.
        (
            "text/plain from evil.example",
            vec![
                ("Host", &host),
                ("Origin", "http://evil.example"),
                ("Content-Type", "text/plain"),
            ],
            403,
        ),
        // Even with the cookie (another port of 127.0.0.1 is the same site, so a browser
        // would send it): the origin is not the page's.
        (
            "JSON from another port, with the cookie",
            vec![
                ("Host", &host),
                ("Origin", "http://127.0.0.1:1"),
                ("Content-Type", "application/json"),
                ("Cookie", &cookie),
            ],
            403,
        ),
        // A form (urlencoded or text/plain) from the page's own origin, with the key.
        (
            "form post",
            vec![
                ("Host", &host),
                ("Origin", &origin),
                ("Content-Type", "application/x-www-form-urlencoded"),
                ("Cookie", &cookie),
            ],
            415,
        ),
        // DNS rebinding: the attacker's name resolved to 127.0.0.1, so the browser's
        // Origin and Host agree, and the cookie is not sent (another site).
        (
            "rebinding name",
            vec![
                ("Host", "rebind.evil.example"),
                ("Origin", "http://rebind.evil.example"),
                ("Content-Type", "application/json"),
            ],
            403,
        ),
        (
            "no key at all",
            vec![("Host", &host), ("Content-Type", "application/json")],
            401,
        ),
        (
            "wrong key",
            vec![
                ("Host", &host),
                ("Content-Type", "application/json"),
                ("X-Jaus-Key", "00000000000000000000000000000000"),
            ],
            401,
        ),
    ];
    let mut refused = 0;
    for (what, headers, status) in &cases {
        let a = request(to, "POST", "/api/command", headers, EMERGENCY);
        assert_eq!(a.status, *status, "{what}: {a:?}");
        assert!(a.body.starts_with("refused: "), "{what}: {}", a.body);
        refused += 1;
    }
    // The view and the stats need the key too.
    for path in ["/api/view", "/api/stats"] {
        let a = request(to, "GET", path, &[("Host", &host)], "");
        assert_eq!(a.status, 401, "{path}");
        refused += 1;
    }
    assert_eq!(c.notices(), 0, "a refused command was executed");
    assert_eq!(c.refused(), refused);

    // The page's own request works: same origin, the key, JSON.
    let a = request(
        to,
        "POST",
        "/api/command",
        &[
            ("Host", &host),
            ("Origin", &origin),
            ("Content-Type", "application/json"),
            ("Cookie", &cookie),
        ],
        EMERGENCY,
    );
    assert_eq!(a.status, 202, "{a:?}");
    let deadline = Instant::now() + Duration::from_secs(5);
    while c.notices() == 0 {
        assert!(Instant::now() < deadline, "the page's command was not run");
    }
}

#[test]
fn websocket_upgrades_need_the_pages_origin_and_the_key() {
    let c = console();
    let (host, origin, key) = (c.host(), c.origin(), c.bound.key.clone());
    let cookie = format!("jaus_ocu_{}={key}", c.bound.http.port());
    let refused = [
        (
            vec![
                ("Origin", "http://evil.example"),
                ("Cookie", cookie.as_str()),
            ],
            403,
        ),
        (vec![("Origin", origin.as_str())], 401),
        (vec![("Origin", "null"), ("Cookie", cookie.as_str())], 403),
    ];
    for (extra, status) in &refused {
        let a = request(c.bound.http, "GET", "/ws", &ws_upgrade(&host, extra), "");
        assert_eq!(a.status, *status, "{extra:?}: {a:?}");
    }
    let rebinding = request(
        c.bound.http,
        "GET",
        "/ws",
        &ws_upgrade(
            "attacker.example:80",
            &[("Origin", "http://attacker.example"), ("Cookie", &cookie)],
        ),
        "",
    );
    assert_eq!(rebinding.status, 403);
    let ok = request(
        c.bound.http,
        "GET",
        "/ws",
        &ws_upgrade(&host, &[("Origin", &origin), ("Cookie", &cookie)]),
        "",
    );
    assert_eq!(ok.status, 101, "{ok:?}");
    assert_eq!(c.refused(), 4);
}

#[test]
fn the_printed_address_sets_the_cookie_and_the_page_needs_it() {
    let c = console();
    let host = c.host();
    let url = c.bound.url();
    let path = url.split_once(&host).unwrap().1;
    assert!(path.starts_with("/?key="), "{url}");
    let a = request(c.bound.http, "GET", path, &[("Host", &host)], "");
    assert_eq!(a.status, 303, "{a:?}");
    assert_eq!(a.header("location"), Some("/"));
    let set = a.header("set-cookie").unwrap();
    assert!(set.starts_with(&format!("jaus_ocu_{}={}", c.bound.http.port(), c.bound.key)));
    assert!(
        set.contains("SameSite=Strict") && set.contains("HttpOnly"),
        "{set}"
    );
    let cookie = set.split(';').next().unwrap();
    let page = request(
        c.bound.http,
        "GET",
        "/",
        &[("Host", &host), ("Cookie", cookie)],
        "",
    );
    assert_eq!(page.status, 200);
    assert!(page.body.contains("<html"), "the page");
    // Without the cookie, or with a wrong key in the address: a refusal that says what
    // to open.
    let bare = request(c.bound.http, "GET", "/", &[("Host", &host)], "");
    assert_eq!(bare.status, 401);
    assert!(bare.body.contains("printed at start-up"), "{}", bare.body);
    let wrong = request(c.bound.http, "GET", "/?key=nope", &[("Host", &host)], "");
    assert_eq!(wrong.status, 401);
    // The static files need only the Host; a rebinding name gets nothing at all.
    let js = request(c.bound.http, "GET", "/app.js", &[("Host", &host)], "");
    assert_eq!(js.status, 200);
    let rebound = request(
        c.bound.http,
        "GET",
        path,
        &[("Host", "evil.example:80")],
        "",
    );
    assert_eq!(rebound.status, 403);
    assert!(rebound.header("set-cookie").is_none());
}

#[test]
fn a_key_given_by_the_operator_must_be_sound() {
    let options = ConsoleOptions {
        http: SocketAddr::from(([127, 0, 0, 1], 0)),
        key: Some("short".into()),
        ..ConsoleOptions::default()
    };
    let stop = AtomicBool::new(true);
    let e = jaus_ocu::run(&options, &stop, |_| {}).unwrap_err();
    assert!(e.to_string().contains("at least 16 characters"), "{e}");
}
