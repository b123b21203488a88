//! The stream transport of AS-4 Digital Video (`as4: { video: … }` of a node file):
//! MJPEG over HTTP. `GET /video/<sensor id>` answers the frames the Digital Video
//! service publishes to the node's [`VideoHub`] as `multipart/x-mixed-replace` JPEG
//! parts (what browsers, VLC, ffplay and OpenCV play), while the stream plays; it waits
//! while the stream is paused and ends when it is stopped. The AS-4 client controlling
//! the component decides, with Set Digital Video Sensor Configuration and Control Digital
//! Video Sensor Stream, whether and how fast frames come; a viewer only watches.
//!
//! Read as an attacker would: one request per connection (`Connection: close`), its head
//! [`MAX_REQUEST`] bytes at most and read within [`IO_TIMEOUT`]; connections served at
//! once bounded ([`VideoFile::max_viewers`] watching, as many again being read: more are
//! closed unanswered, counted); only `GET` of the one path; an optional token
//! (`?token=…`, compared in constant time); a `Host` header naming anything but an IP
//! address or `localhost` refused (no web page of another site reaches the stream by DNS
//! rebinding; a page may still show it in an `<img>`, which gives it no pixels to read);
//! a write that stalls for [`IO_TIMEOUT`] ends the viewer. The listener is the node file's `listen` (default loopback only): the
//! HTTP side has no authentication but the token, so expose it only on a trusted link.

use std::io::{self, Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus_as4::environment::video::{Next, StreamState, WatchError};
use jaus_as4::environment::VideoHub;

/// A request's head is this long at most, bytes.
pub const MAX_REQUEST: usize = 4096;
/// A request's head must arrive, and each write go out, within this.
pub const IO_TIMEOUT: Duration = Duration::from_secs(5);
/// The multipart boundary.
const BOUNDARY: &str = "jausframe";

/// `as4: { video: … }` of a node file: Digital Video over the RA 3.3 Visual Sensor,
/// its frames served as MJPEG over HTTP.
///
/// ```yaml
/// as4:
///   video:
///     listen: 127.0.0.1:8090   # the HTTP listener (default 127.0.0.1:8090; port 0: any)
///     max_frame_rate: 10       # frames/s a client may ask for at most (default 10)
///     max_frame_bytes: 1048576 # a larger frame is dropped (default 1 MiB)
///     max_viewers: 4           # viewers at once, all streams (default 4)
///     token: s3cret            # if set, viewers must give ?token=s3cret
/// ```
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VideoFile {
    /// The HTTP listener.
    #[serde(default = "default_listen")]
    pub listen: SocketAddr,
    /// The highest frame rate a client may ask for, frames/s.
    #[serde(default = "default_rate")]
    pub max_frame_rate: u8,
    /// A frame larger than this is dropped, bytes.
    #[serde(default = "default_frame_bytes")]
    pub max_frame_bytes: usize,
    /// Viewers at once (all streams).
    #[serde(default = "default_viewers")]
    pub max_viewers: usize,
    /// A token viewers must give (`?token=`).
    #[serde(default)]
    pub token: Option<String>,
}

fn default_listen() -> SocketAddr {
    SocketAddr::from(([127, 0, 0, 1], 8090))
}
fn default_rate() -> u8 {
    10
}
fn default_frame_bytes() -> usize {
    1 << 20
}
fn default_viewers() -> usize {
    4
}

impl Default for VideoFile {
    fn default() -> Self {
        Self {
            listen: default_listen(),
            max_frame_rate: default_rate(),
            max_frame_bytes: default_frame_bytes(),
            max_viewers: default_viewers(),
            token: None,
        }
    }
}

impl VideoFile {
    /// The hub of these settings and the service's bounds (for the gateway's
    /// `GatewayConfig::video`).
    pub fn hub(&self) -> (VideoHub, jaus_as4::environment::VideoLimits) {
        (
            VideoHub::new(self.max_viewers),
            jaus_as4::environment::VideoLimits {
                max_frame_rate: self.max_frame_rate.max(1),
                max_frame_bytes: self.max_frame_bytes,
            },
        )
    }
}

/// What the MJPEG server counted.
#[derive(Debug, Default)]
pub struct MjpegStats {
    /// Connections accepted.
    pub accepted: AtomicU64,
    /// Connections closed unanswered (too many at once).
    pub busy: AtomicU64,
    /// Requests refused: malformed, too long, too slow, not GET (400, 405, 408, 431).
    pub bad_requests: AtomicU64,
    /// Requests for no stream (404).
    pub not_found: AtomicU64,
    /// Requests without the token (403).
    pub forbidden: AtomicU64,
    /// Requests refused: the stream stopped or the viewers at their limit (503).
    pub unavailable: AtomicU64,
    /// Frames written.
    pub frames: AtomicU64,
    /// Viewers ended by a failed or stalled write.
    pub write_errors: AtomicU64,
}

/// The MJPEG server of a node (runs on threads of its own until dropped).
#[derive(Debug)]
pub struct MjpegServer {
    addr: SocketAddr,
    stop: Arc<AtomicBool>,
    stats: Arc<MjpegStats>,
    accept: Option<JoinHandle<()>>,
}

#[derive(Debug)]
struct Ctx {
    hub: VideoHub,
    token: Option<String>,
    stop: Arc<AtomicBool>,
    stats: Arc<MjpegStats>,
    open: AtomicUsize,
    max_open: usize,
}

impl MjpegServer {
    /// Listens on `file.listen`, serving `hub`'s streams.
    pub fn start(file: &VideoFile, hub: VideoHub) -> io::Result<Self> {
        let listener = TcpListener::bind(file.listen)?;
        let addr = listener.local_addr()?;
        let stop = Arc::new(AtomicBool::new(false));
        let stats = Arc::new(MjpegStats::default());
        let ctx = Arc::new(Ctx {
            hub,
            token: file.token.clone(),
            stop: stop.clone(),
            stats: stats.clone(),
            open: AtomicUsize::new(0),
            max_open: file.max_viewers.saturating_mul(2).max(2),
        });
        let accept = std::thread::Builder::new()
            .name("jaus-mjpeg".into())
            .spawn(move || accept_loop(&listener, &ctx))?;
        Ok(Self {
            addr,
            stop,
            stats,
            accept: Some(accept),
        })
    }

    /// The address it listens on.
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// What it counted.
    pub fn stats(&self) -> &MjpegStats {
        &self.stats
    }

    /// One line of `key value` pairs of [`stats`](Self::stats).
    pub fn stats_line(&self) -> String {
        let s = &self.stats;
        let g = |a: &AtomicU64| a.load(Ordering::Relaxed);
        format!(
            "video stats: accepted {} busy {} bad_requests {} not_found {} forbidden {} unavailable {} frames {} write_errors {}",
            g(&s.accepted), g(&s.busy), g(&s.bad_requests), g(&s.not_found), g(&s.forbidden),
            g(&s.unavailable), g(&s.frames), g(&s.write_errors)
        )
    }
}

impl Drop for MjpegServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        // Wake the accept loop; viewers notice the flag within a second.
        let _ = TcpStream::connect_timeout(&self.addr, Duration::from_millis(200));
        if let Some(t) = self.accept.take() {
            let _ = t.join();
        }
    }
}

fn accept_loop(listener: &TcpListener, ctx: &Arc<Ctx>) {
    for conn in listener.incoming() {
        if ctx.stop.load(Ordering::SeqCst) {
            return;
        }
        let Ok(stream) = conn else { continue };
        ctx.stats.accepted.fetch_add(1, Ordering::Relaxed);
        if ctx.open.fetch_add(1, Ordering::SeqCst) >= ctx.max_open {
            ctx.open.fetch_sub(1, Ordering::SeqCst);
            ctx.stats.busy.fetch_add(1, Ordering::Relaxed);
            continue;
        }
        let c = ctx.clone();
        let spawned = std::thread::Builder::new()
            .name("jaus-mjpeg-viewer".into())
            .spawn(move || {
                serve(stream, &c);
                c.open.fetch_sub(1, Ordering::SeqCst);
            });
        if spawned.is_err() {
            ctx.open.fetch_sub(1, Ordering::SeqCst);
            ctx.stats.busy.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// Reads a request's head: up to the blank line, within the bounds.
fn read_head(stream: &mut TcpStream) -> Result<String, (u16, &'static str)> {
    let deadline = Instant::now() + IO_TIMEOUT;
    let mut head = Vec::with_capacity(512);
    let mut buf = [0u8; 512];
    while !head.windows(4).any(|w| w == b"\r\n\r\n") {
        if head.len() > MAX_REQUEST {
            return Err((431, "request head over 4096 bytes"));
        }
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return Err((408, "request head not received in time"));
        }
        match stream.read(&mut buf) {
            Ok(0) => return Err((400, "connection closed inside the request head")),
            Ok(n) => head.extend_from_slice(&buf[..n]),
            Err(_) => return Err((408, "request head not received in time")),
        }
    }
    String::from_utf8(head).map_err(|_| (400, "request head not UTF-8"))
}

/// Byte strings equal, in a time that does not depend on where they differ.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

/// Whether a request's `Host` header may reach the server: absent (HTTP/1.0), an IP
/// address or `localhost`, with or without a port. A web page whose own name an attacker
/// made resolve to this address (DNS rebinding) sends its name: refused, so no page of
/// another site can read the stream through a visitor's browser.
fn host_allowed(head: &str) -> bool {
    let Some(host) = head.lines().skip(1).find_map(|l| {
        let (name, value) = l.split_once(':')?;
        name.trim()
            .eq_ignore_ascii_case("host")
            .then(|| value.trim())
    }) else {
        return true;
    };
    let name = match host.strip_prefix('[') {
        // [v6]:port
        Some(v6) => {
            return v6
                .split(']')
                .next()
                .is_some_and(|a| a.parse::<std::net::Ipv6Addr>().is_ok())
        }
        None => host.rsplit_once(':').map_or(host, |(n, _)| n),
    };
    name.eq_ignore_ascii_case("localhost") || name.parse::<std::net::Ipv4Addr>().is_ok()
}

/// The sensor id a request line asks for, or the status refusing it.
fn route(head: &str, token: Option<&str>) -> Result<u16, (u16, &'static str)> {
    if !host_allowed(head) {
        return Err((
            403,
            "Host must be this server's address (an IP or localhost)",
        ));
    }
    let line = head.lines().next().unwrap_or_default();
    let mut parts = line.split(' ');
    let (Some(method), Some(target), Some(version), None) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        return Err((400, "malformed request line"));
    };
    if !version.starts_with("HTTP/1.") {
        return Err((400, "HTTP/1.x only"));
    }
    if method != "GET" {
        return Err((405, "GET only"));
    }
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let Some(id) = path.strip_prefix("/video/") else {
        return Err((404, "no such path: /video/<sensor id>"));
    };
    let Ok(sensor) = id.parse::<u16>() else {
        return Err((404, "the sensor id is a number"));
    };
    if let Some(t) = token {
        let given = query
            .split('&')
            .find_map(|kv| kv.strip_prefix("token="))
            .unwrap_or_default();
        if !same(given.as_bytes(), t.as_bytes()) {
            return Err((403, "a token is required (?token=)"));
        }
    }
    Ok(sensor)
}

fn refuse(stream: &mut TcpStream, ctx: &Ctx, (status, why): (u16, &str)) {
    let counter = match status {
        403 => &ctx.stats.forbidden,
        404 => &ctx.stats.not_found,
        503 => &ctx.stats.unavailable,
        _ => &ctx.stats.bad_requests,
    };
    counter.fetch_add(1, Ordering::Relaxed);
    let reason = match status {
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        408 => "Request Timeout",
        431 => "Request Header Fields Too Large",
        _ => "Service Unavailable",
    };
    let _ = write!(
        stream,
        "HTTP/1.1 {status} {reason}\r\nContent-Type: text/plain; charset=utf-8\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{why}\n",
        why.len() + 1
    );
}

fn serve(mut stream: TcpStream, ctx: &Ctx) {
    let sensor = match read_head(&mut stream).and_then(|h| route(&h, ctx.token.as_deref())) {
        Ok(s) => s,
        Err(e) => return refuse(&mut stream, ctx, e),
    };
    let mut viewer = match ctx.hub.watch(sensor) {
        Ok(v) => v,
        Err(WatchError::Unknown(_)) => {
            return refuse(&mut stream, ctx, (404, "no video stream of that sensor"))
        }
        Err(WatchError::Full(_)) => {
            return refuse(&mut stream, ctx, (503, "the viewers are at their limit"))
        }
    };
    if ctx.hub.state(sensor) == Some(StreamState::Stopped) {
        return refuse(
            &mut stream,
            ctx,
            (503, "the stream is stopped: its AS-4 controlling client plays it (Control Digital Video Sensor Stream)"),
        );
    }
    if stream.set_write_timeout(Some(IO_TIMEOUT)).is_err() {
        return;
    }
    let head = format!(
        "HTTP/1.1 200 OK\r\nContent-Type: multipart/x-mixed-replace; boundary={BOUNDARY}\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n"
    );
    if stream.write_all(head.as_bytes()).is_err() {
        ctx.stats.write_errors.fetch_add(1, Ordering::Relaxed);
        return;
    }
    while !ctx.stop.load(Ordering::SeqCst) {
        match viewer.next(Duration::from_secs(1)) {
            Next::Frame(f) => {
                let part = format!(
                    "--{BOUNDARY}\r\nContent-Type: image/jpeg\r\nContent-Length: {}\r\n\r\n",
                    f.jpeg.len()
                );
                let written = stream
                    .write_all(part.as_bytes())
                    .and_then(|()| stream.write_all(&f.jpeg))
                    .and_then(|()| stream.write_all(b"\r\n"));
                if written.is_err() {
                    ctx.stats.write_errors.fetch_add(1, Ordering::Relaxed);
                    return;
                }
                ctx.stats.frames.fetch_add(1, Ordering::Relaxed);
            }
            Next::TimedOut => {}
            Next::Stopped => break,
        }
    }
    let _ = write!(stream, "--{BOUNDARY}--\r\n");
}

#[cfg(test)]
#[path = "video_tests.rs"]
mod tests;
