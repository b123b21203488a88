//! Who may use the console's web server: only its own page, opened by someone who holds
//! the run's key.
//!
//! A browser lets any web page send a "simple" cross-site request (a form, a `no-cors`
//! fetch) and open a WebSocket to any address, including 127.0.0.1, and a DNS name of an
//! attacker's can be made to point at 127.0.0.1 (DNS rebinding). So every request that
//! reads the system or commands it passes three checks, and a refusal is a 4xx with its
//! reason, logged and counted, never executed:
//!
//! 1. **Host**: an IP literal or `localhost` (or a name the operator allowed) with the
//!    server's port. A rebinding name is refused.
//! 2. **Origin**: when the browser sends one (it always does for WebSockets and for
//!    cross-origin requests), exactly `http://` + the request's Host. Another port of the
//!    same machine is another origin.
//! 3. **Key**: the run's random key, from the cookie the printed address sets
//!    (`jaus_ocu_PORT`, `HttpOnly; SameSite=Strict`), or an `X-Jaus-Key` header (for
//!    scripts). Commands must also be `Content-Type: application/json`, which no form can
//!    send and no cross-origin fetch can send without a preflight this server never
//!    grants.

use std::net::IpAddr;

use axum::http::{header, HeaderMap, StatusCode};

/// The header a script may carry the key in instead of the cookie.
pub const KEY_HEADER: &str = "x-jaus-key";

/// What a request is for, which decides the checks it passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// The page's static files: Host only.
    Asset,
    /// Reading the view, the stats, opening the WebSocket: Host, Origin, key.
    Read,
    /// A command: Host, Origin, key, JSON.
    Command,
}

/// Why a request was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum Refusal {
    /// The Host header is not this server's.
    #[error("Host `{0}` is not this console's (an IP address or localhost with port {1}, or an allowed name)")]
    Host(String, u16),
    /// The request came from another origin (another site, or another port).
    #[error("Origin `{0}` is not this console's page")]
    Origin(String),
    /// No key, or the wrong key.
    #[error(
        "the console's key is missing or wrong: open the address `jaus ocu` printed at start-up"
    )]
    Key,
    /// A command not sent as JSON.
    #[error("commands must be sent as Content-Type: application/json (got `{0}`)")]
    NotJson(String),
}

impl Refusal {
    /// The HTTP status of the refusal.
    pub fn status(&self) -> StatusCode {
        match self {
            Refusal::Host(..) | Refusal::Origin(_) => StatusCode::FORBIDDEN,
            Refusal::Key => StatusCode::UNAUTHORIZED,
            Refusal::NotJson(_) => StatusCode::UNSUPPORTED_MEDIA_TYPE,
        }
    }
}

/// The checks, for one running console.
#[derive(Debug, Clone)]
pub struct Guard {
    key: String,
    port: u16,
    allowed_hosts: Vec<String>,
}

impl Guard {
    /// A guard for a server on `port` with `key`; `allowed_hosts` are DNS names besides
    /// `localhost` the page may be opened under (e.g. a vehicle laptop's name on a LAN).
    pub fn new(key: String, port: u16, allowed_hosts: Vec<String>) -> Self {
        Self {
            key,
            port,
            allowed_hosts: allowed_hosts
                .into_iter()
                .map(|h| h.to_ascii_lowercase())
                .collect(),
        }
    }

    /// The run's key.
    pub fn key(&self) -> &str {
        &self.key
    }

    /// The cookie that carries the key (ports share cookies, so the name has the port).
    pub fn cookie_name(&self) -> String {
        format!("jaus_ocu_{}", self.port)
    }

    /// The `Set-Cookie` value given to whoever opened the address with the key.
    pub fn set_cookie(&self) -> String {
        format!(
            "{}={}; Path=/; HttpOnly; SameSite=Strict",
            self.cookie_name(),
            self.key
        )
    }

    /// Whether `candidate` is the key (compared in constant time).
    pub fn is_key(&self, candidate: &str) -> bool {
        let (a, b) = (self.key.as_bytes(), candidate.as_bytes());
        a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
    }

    /// Runs the checks `access` needs on a request's headers.
    pub fn check(&self, access: Access, headers: &HeaderMap) -> Result<(), Refusal> {
        let host = self.check_host(headers)?;
        if access == Access::Asset {
            return Ok(());
        }
        if let Some(origin) = headers.get(header::ORIGIN) {
            let origin = origin.to_str().unwrap_or("(not text)");
            if !origin.eq_ignore_ascii_case(&format!("http://{host}")) {
                return Err(Refusal::Origin(origin.to_string()));
            }
        }
        if !self.has_key(headers) {
            return Err(Refusal::Key);
        }
        if access == Access::Command {
            let kind = headers
                .get(header::CONTENT_TYPE)
                .and_then(|v| v.to_str().ok())
                .unwrap_or("");
            let mime = kind.split(';').next().unwrap_or("").trim();
            if !mime.eq_ignore_ascii_case("application/json") {
                return Err(Refusal::NotJson(kind.to_string()));
            }
        }
        Ok(())
    }

    /// Whether the request carries the key (cookie or header).
    pub fn has_key(&self, headers: &HeaderMap) -> bool {
        if headers
            .get(KEY_HEADER)
            .and_then(|v| v.to_str().ok())
            .is_some_and(|k| self.is_key(k))
        {
            return true;
        }
        let name = self.cookie_name();
        headers
            .get_all(header::COOKIE)
            .iter()
            .filter_map(|v| v.to_str().ok())
            .flat_map(|v| v.split(';'))
            .filter_map(|c| c.trim().split_once('='))
            .any(|(n, v)| n == name && self.is_key(v))
    }

    /// The Host header, when it names this server; else the refusal.
    pub fn check_host<'h>(&self, headers: &'h HeaderMap) -> Result<&'h str, Refusal> {
        let raw = headers
            .get(header::HOST)
            .and_then(|v| v.to_str().ok())
            .unwrap_or("");
        let refused = || Refusal::Host(raw.to_string(), self.port);
        let (name, port) = split_host(raw).ok_or_else(refused)?;
        if port != Some(self.port) && !(port.is_none() && self.port == 80) {
            return Err(refused());
        }
        let name = name.to_ascii_lowercase();
        let ip_literal = name
            .strip_prefix('[')
            .and_then(|n| n.strip_suffix(']'))
            .unwrap_or(&name)
            .parse::<IpAddr>()
            .is_ok();
        if ip_literal || name == "localhost" || self.allowed_hosts.contains(&name) {
            Ok(raw)
        } else {
            Err(refused())
        }
    }
}

/// `name[:port]` or `[v6][:port]`; `None` when malformed.
fn split_host(raw: &str) -> Option<(&str, Option<u16>)> {
    if raw.is_empty() {
        return None;
    }
    let (name, port) = if raw.starts_with('[') {
        let end = raw.find(']')?;
        let (name, rest) = raw.split_at(end + 1);
        match rest.strip_prefix(':') {
            Some(p) => (name, Some(p)),
            None if rest.is_empty() => (name, None),
            None => return None,
        }
    } else {
        match raw.rsplit_once(':') {
            Some((n, p)) => (n, Some(p)),
            None => (raw, None),
        }
    };
    let port = match port {
        Some(p) => Some(p.parse().ok()?),
        None => None,
    };
    Some((name, port))
}

/// Whether a key given by the operator is long enough and safe in a URL and a cookie.
pub fn key_is_sound(key: &str) -> bool {
    key.len() >= 16
        && key
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_')
}

/// A new random key: 128 bits from the operating system, as hex.
pub fn new_key() -> std::io::Result<String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes).map_err(std::io::Error::other)?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use axum::http::HeaderValue;

    fn guard() -> Guard {
        Guard::new("k3y".into(), 8700, vec!["rover-ocu.lan".into()])
    }

    fn headers(pairs: &[(&'static str, &str)]) -> HeaderMap {
        let mut h = HeaderMap::new();
        for (n, v) in pairs {
            h.append(*n, HeaderValue::from_str(v).unwrap());
        }
        h
    }

    #[test]
    fn hosts_are_ip_literals_localhost_or_allowed_names_on_the_port() {
        let g = guard();
        for ok in [
            "127.0.0.1:8700",
            "localhost:8700",
            "LOCALHOST:8700",
            "[::1]:8700",
            "10.1.2.3:8700",
            "rover-ocu.lan:8700",
        ] {
            assert!(
                g.check(Access::Asset, &headers(&[("host", ok)])).is_ok(),
                "{ok}"
            );
        }
        for bad in [
            "evil.example:8700",
            "127.0.0.1:8701",
            "127.0.0.1",
            "",
            "127.0.0.1:x",
            "[::1",
            "localhost.evil.example:8700",
        ] {
            assert_eq!(
                g.check(Access::Asset, &headers(&[("host", bad)])),
                Err(Refusal::Host(bad.into(), 8700)),
                "{bad}"
            );
        }
        assert!(g.check(Access::Asset, &HeaderMap::new()).is_err());
    }

    #[test]
    fn origin_must_be_the_pages_own() {
        let g = guard();
        let base = [("host", "127.0.0.1:8700"), ("x-jaus-key", "k3y")];
        assert!(g.check(Access::Read, &headers(&base)).is_ok());
        let mut h = headers(&base);
        h.insert("origin", HeaderValue::from_static("http://127.0.0.1:8700"));
        assert!(g.check(Access::Read, &h).is_ok());
        for bad in [
            "http://evil.example",
            "http://127.0.0.1:9999",
            "http://localhost:8700",
            "https://127.0.0.1:8700",
            "null",
        ] {
            h.insert("origin", HeaderValue::from_str(bad).unwrap());
            assert_eq!(
                g.check(Access::Read, &h),
                Err(Refusal::Origin(bad.into())),
                "{bad}"
            );
            assert_eq!(Refusal::Origin(bad.into()).status(), StatusCode::FORBIDDEN);
        }
    }

    #[test]
    fn the_key_comes_from_the_ports_cookie_or_the_header() {
        let g = guard();
        let host = ("host", "127.0.0.1:8700");
        assert_eq!(g.check(Access::Read, &headers(&[host])), Err(Refusal::Key));
        assert_eq!(
            g.check(Access::Read, &headers(&[host, ("x-jaus-key", "wrong")])),
            Err(Refusal::Key)
        );
        assert_eq!(
            g.check(Access::Read, &headers(&[host, ("x-jaus-key", "k3")])),
            Err(Refusal::Key)
        );
        assert!(g
            .check(
                Access::Read,
                &headers(&[host, ("cookie", "a=b; jaus_ocu_8700=k3y")])
            )
            .is_ok());
        // Another console's cookie (another port) is not this one's.
        assert_eq!(
            g.check(
                Access::Read,
                &headers(&[host, ("cookie", "jaus_ocu_8701=k3y")])
            ),
            Err(Refusal::Key)
        );
        assert!(g.set_cookie().contains("SameSite=Strict"));
        assert!(g.set_cookie().contains("HttpOnly"));
    }

    #[test]
    fn commands_must_be_json() {
        let g = guard();
        let base = [("host", "127.0.0.1:8700"), ("x-jaus-key", "k3y")];
        let mut h = headers(&base);
        assert_eq!(
            g.check(Access::Command, &h),
            Err(Refusal::NotJson(String::new()))
        );
        for bad in [
            "text/plain",
            "application/x-www-form-urlencoded",
            "multipart/form-data",
        ] {
            h.insert("content-type", HeaderValue::from_str(bad).unwrap());
            assert_eq!(
                g.check(Access::Command, &h),
                Err(Refusal::NotJson(bad.into()))
            );
        }
        h.insert(
            "content-type",
            HeaderValue::from_static("application/json; charset=utf-8"),
        );
        assert!(g.check(Access::Command, &h).is_ok());
    }

    #[test]
    fn keys_are_fresh_and_long() {
        let (a, b) = (new_key().unwrap(), new_key().unwrap());
        assert_eq!(a.len(), 32);
        assert_ne!(a, b);
    }
}
