//! The QUIC link's cost against the plain UDP link, side by side on loopback, the two
//! alternated round after round in one run:
//!
//! * round trips of a 64-byte and of a 4096-byte frame (one link echoes what the other
//!   sends; median and 99th percentile): the latency each link adds, from `send` on one
//!   node's thread to `recv` on the other's and back (both threads poll the links
//!   without sleeping, so the node's 10 ms poll period is not in the figures);
//! * a one-way burst of 64-byte and of 4096-byte frames, sent as fast as the link takes
//!   them (`Busy` offered again) and read as fast as they come: frames and Mbit/s
//!   delivered, and how many were lost (UDP: what the receiving socket could not hold,
//!   dropped by the kernel; QUIC: congestion-controlled, its 4096-byte frames on
//!   reliable streams, but what the reader does not take in time is dropped by the
//!   receiving link's bounded queue, shown apart as `queue`).
//!
//! The threads of both ends share the machine's cores with quinn's two threads: on a
//! small machine, and with anything else running, the figures move from round to round;
//! the medians over the rounds are printed last.
//!
//! ```text
//! cargo run --release -p jaus-quic --example link_figures [-- ROUNDS]
//! ```

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::net::udp::link::{UdpLink, UdpLinkConfig};
use jaus::stock::communicator::{DataLink, LinkError};
use jaus_quic::{Identity, QuicLink, QuicLinkConfig};

/// A link of either kind, and what it dropped on the way in by itself.
trait Link: DataLink {
    /// Frames received and dropped by the link (its queue full, over the MTU); what the
    /// operating system dropped is not counted here.
    fn dropped(&self) -> u64;
}

impl Link for UdpLink {
    fn dropped(&self) -> u64 {
        self.stats().dropped_oversize_received
    }
}

impl Link for QuicLink {
    fn dropped(&self) -> u64 {
        let s = self.stats();
        s.dropped_queue_full + s.dropped_oversize_received
    }
}

fn local(port: u16) -> SocketAddr {
    SocketAddr::from(([127, 0, 0, 1], port))
}

fn free_port() -> u16 {
    UdpSocket::bind(local(0))
        .and_then(|s| s.local_addr())
        .map(|a| a.port())
        .unwrap_or(0)
}

/// Two UDP links, each the other's far end.
fn udp_pair() -> (UdpLink, UdpLink) {
    let (pa, pb) = (free_port(), free_port());
    let a = UdpLink::bind(UdpLinkConfig::new(1, local(pa), local(pb))).expect("udp link");
    let b = UdpLink::bind(UdpLinkConfig::new(1, local(pb), local(pa))).expect("udp link");
    (a, b)
}

/// Two QUIC links, each the other's far end, connected.
fn quic_pair() -> (QuicLink, QuicLink) {
    let (pa, pb) = (free_port(), free_port());
    let (ia, ib) = (
        Identity::generate("a").expect("key"),
        Identity::generate("b").expect("key"),
    );
    let ca = QuicLinkConfig::new(1, local(pa), local(pb), ia.clone(), ib.cert.clone());
    let cb = QuicLinkConfig::new(1, local(pb), local(pa), ib, ia.cert);
    let a = QuicLink::bind(ca).expect("quic link");
    let b = QuicLink::bind(cb).expect("quic link");
    let end = Instant::now() + Duration::from_secs(10);
    while !(a.is_connected() && b.is_connected()) {
        assert!(Instant::now() < end, "QUIC link not up");
        std::thread::sleep(Duration::from_millis(1));
    }
    (a, b)
}

/// Offers `frame` until the link takes it.
fn send(link: &mut impl DataLink, frame: &[u8]) {
    loop {
        match link.send(Instant::now(), frame) {
            Ok(()) => return,
            Err(LinkError::Busy) => std::thread::yield_now(),
            Err(e) => panic!("send: {e}"),
        }
    }
}

/// Echoes every frame `b` receives until `stop`; gives `b` back.
fn echo<L: Link>(mut b: L, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<L> {
    std::thread::spawn(move || {
        let mut buf = Vec::new();
        while !stop.load(Ordering::Relaxed) {
            if b.recv(Instant::now(), &mut buf) {
                send(&mut b, &buf);
            } else {
                std::thread::yield_now();
            }
        }
        b
    })
}

/// `n` round trips of a `len`-byte frame from `a` through the echo; the times of those
/// answered within 1 s (a UDP frame may be lost).
fn round_trips(a: &mut impl Link, len: usize, n: usize) -> (Vec<Duration>, usize) {
    let mut rtts = Vec::with_capacity(n);
    let mut lost = 0;
    let mut buf = Vec::new();
    for i in 0..n {
        let mut frame = vec![0u8; len];
        frame[..8].copy_from_slice(&(i as u64).to_le_bytes());
        let t = Instant::now();
        send(a, &frame);
        loop {
            if a.recv(Instant::now(), &mut buf) {
                if buf.get(..8) == Some(&frame[..8]) {
                    rtts.push(t.elapsed());
                    break;
                }
            } else if t.elapsed() > Duration::from_secs(1) {
                lost += 1;
                break;
            } else {
                std::thread::yield_now();
            }
        }
    }
    rtts.sort();
    (rtts, lost)
}

/// A burst of `n` `len`-byte frames from `a` to `b`: frames delivered and the time from
/// the first send to the last frame read.
fn burst<L: Link>(a: &mut L, b: L, len: usize, n: usize) -> (usize, Duration, L) {
    let reader = std::thread::spawn(move || {
        let mut b = b;
        let mut buf = Vec::new();
        let mut got = 0;
        let mut last = Instant::now();
        let start = Instant::now();
        while got < n && last.elapsed() < Duration::from_millis(500) {
            if b.recv(Instant::now(), &mut buf) {
                got += 1;
                last = Instant::now();
            } else {
                std::thread::yield_now();
            }
        }
        (got, last.duration_since(start), b)
    });
    let frame = vec![0x5A; len];
    for _ in 0..n {
        send(a, &frame);
    }
    reader.join().expect("reader")
}

fn pct(sorted: &[Duration], p: f64) -> Duration {
    if sorted.is_empty() {
        return Duration::ZERO;
    }
    let i = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

fn us(d: Duration) -> f64 {
    d.as_secs_f64() * 1e6
}

/// One round's figures of one link.
#[derive(Debug, Clone, Copy, Default)]
struct Figures {
    /// Round trips, µs: 64-byte median and p99, 4096-byte median and p99.
    rtt: [f64; 4],
    /// Bursts of 64-byte and of 4096-byte frames: frames/s, Mbit/s, frames lost, of
    /// which dropped by the receiving link itself (its queue full).
    burst: [(f64, f64, usize, u64); 2],
    /// Round trips lost (no echo within 1 s).
    rtt_lost: usize,
}

fn measure<L: Link>((mut a, b): (L, L)) -> Figures {
    let stop = Arc::new(AtomicBool::new(false));
    let echoer = echo(b, stop.clone());
    let (small, lost_s) = round_trips(&mut a, 64, 2000);
    let (large, lost_l) = round_trips(&mut a, 4096, 1000);
    stop.store(true, Ordering::Relaxed);
    let mut b = echoer.join().expect("echo");
    let mut f = Figures {
        rtt: [
            us(pct(&small, 0.5)),
            us(pct(&small, 0.99)),
            us(pct(&large, 0.5)),
            us(pct(&large, 0.99)),
        ],
        rtt_lost: lost_s + lost_l,
        ..Figures::default()
    };
    for (i, (len, n)) in [(64usize, 50_000usize), (4096, 10_000)]
        .into_iter()
        .enumerate()
    {
        let before = b.dropped();
        let (got, took, back) = burst(&mut a, b, len, n);
        b = back;
        let secs = took.as_secs_f64().max(1e-9);
        f.burst[i] = (
            got as f64 / secs,
            (got * len * 8) as f64 / secs / 1e6,
            n - got,
            b.dropped() - before,
        );
        // Let what is still in flight land before the next burst.
        std::thread::sleep(Duration::from_millis(200));
        let mut buf = Vec::new();
        while b.recv(Instant::now(), &mut buf) {}
    }
    f
}

fn row(kind: &str, round: &str, f: &Figures) -> String {
    let [b64, b4k] = f.burst;
    format!(
        "{:<5} {:>6} | {:>9.1} {:>9.1} | {:>9.1} {:>9.1} | {:>10.0} {:>8.1} {:>6} {:>6} | {:>10.0} {:>8.1} {:>6} {:>6}{}",
        kind,
        round,
        f.rtt[0],
        f.rtt[1],
        f.rtt[2],
        f.rtt[3],
        b64.0,
        b64.1,
        b64.2,
        b64.3,
        b4k.0,
        b4k.1,
        b4k.2,
        b4k.3,
        if f.rtt_lost > 0 {
            format!("  (round trips lost: {})", f.rtt_lost)
        } else {
            String::new()
        }
    )
}

/// The median of each figure over the rounds.
fn median(all: &[Figures]) -> Figures {
    let mid = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    };
    let mut m = Figures::default();
    for i in 0..4 {
        m.rtt[i] = mid(all.iter().map(|f| f.rtt[i]).collect());
    }
    for i in 0..2 {
        m.burst[i] = (
            mid(all.iter().map(|f| f.burst[i].0).collect()),
            mid(all.iter().map(|f| f.burst[i].1).collect()),
            mid(all.iter().map(|f| f.burst[i].2 as f64).collect()) as usize,
            mid(all.iter().map(|f| f.burst[i].3 as f64).collect()) as u64,
        );
    }
    m.rtt_lost = all.iter().map(|f| f.rtt_lost).sum();
    m
}

fn main() {
    let rounds: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(3);
    println!(
        "{:<5} {:>6} | {:>9} {:>9} | {:>9} {:>9} | {:>10} {:>8} {:>6} {:>6} | {:>10} {:>8} {:>6} {:>6}",
        "link",
        "round",
        "rtt64 p50",
        "p99 µs",
        "rtt4k p50",
        "p99 µs",
        "64 B fr/s",
        "Mbit/s",
        "lost",
        "queue",
        "4 KiB fr/s",
        "Mbit/s",
        "lost",
        "queue"
    );
    let mut results: [Vec<Figures>; 2] = [Vec::new(), Vec::new()];
    for round in 1..=rounds {
        let u = measure(udp_pair());
        println!("{}", row("udp", &round.to_string(), &u));
        results[0].push(u);
        let q = measure(quic_pair());
        println!("{}", row("quic", &round.to_string(), &q));
        results[1].push(q);
    }
    println!(
        "median of the {rounds} rounds (lost: of the 50,000 and 10,000 frames of a burst; queue: of those, dropped by the receiving link's own queue)"
    );
    for (k, kind) in ["udp", "quic"].into_iter().enumerate() {
        println!("{}", row(kind, "median", &median(&results[k])));
    }
}
