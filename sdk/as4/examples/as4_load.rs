//! An AS5669A (AS-4 JUDP) load generator: keeps `--window` Query Status messages
//! outstanding to one AS-4 component and measures Report Status replies per second,
//! round-trip percentiles and the server processes' CPU, the same method as
//! `../shared/perf/loadgen` uses for RA 3.3 (requests matched to replies in order, a
//! warm-up before measuring, a request unanswered for `--loss-ms` counted lost). It
//! times any AS-4 node the same way: `jaus node` with `as4:` or the JAUS Tool Set's
//! node manager with its Management example (docs/performance.md, "The AS-4 path").
//!
//! ```sh
//! cargo run --release -p jaus-as4 --example as4_load -- --server 10.77.0.2:3794 \
//!     --bind 10.77.0.1:3794 --target 126.1.11 --window 32 --count 30000 --pids <pid>,<pid>
//! ```
//!
//! Every request is a datagram of its own with a sequence number of its own (a peer
//! that drops duplicates by sequence number sees none). Our id is `--me` (default
//! 42.1.1, the IOP judge's).

use std::collections::{HashMap, VecDeque};
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use jaus::net::as5669a::{parse_datagram, write_datagrams, As4Header, As4Id, As4Packet};

/// Query Status and Report Status (Core Management).
const QUERY_STATUS: u16 = 0x2002;
const REPORT_STATUS: u16 = 0x4002;

struct Args {
    server: SocketAddr,
    bind: SocketAddr,
    target: As4Id,
    me: As4Id,
    window: usize,
    count: u64,
    warmup: u64,
    seconds: f64,
    loss: Duration,
    pids: Vec<u32>,
    label: String,
}

fn id(s: &str) -> Result<As4Id, String> {
    let parts: Vec<&str> = s.split('.').collect();
    match parts.as_slice() {
        [a, b, c] => Ok(As4Id::new(
            a.parse().map_err(|e| format!("{s}: subsystem: {e}"))?,
            b.parse().map_err(|e| format!("{s}: node: {e}"))?,
            c.parse().map_err(|e| format!("{s}: component: {e}"))?,
        )),
        _ => Err(format!("{s}: an AS-4 id is subsystem.node.component")),
    }
}

fn args() -> Result<Args, String> {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    let mut a: HashMap<&str, &str> = HashMap::new();
    for kv in raw.chunks(2) {
        let key = kv[0]
            .strip_prefix("--")
            .ok_or_else(|| format!("{}: options are --name value", kv[0]))?;
        a.insert(key, kv.get(1).map_or("", String::as_str));
    }
    let get = |k: &str, d: &'static str| a.get(k).copied().unwrap_or(d);
    let num = |k: &str, d: &'static str| -> Result<f64, String> {
        get(k, d).parse().map_err(|e| format!("--{k}: {e}"))
    };
    Ok(Args {
        server: get("server", "127.0.0.1:3794")
            .parse()
            .map_err(|e| format!("--server: {e}"))?,
        bind: get("bind", "127.0.0.2:3794")
            .parse()
            .map_err(|e| format!("--bind: {e}"))?,
        target: id(get("target", "126.1.11"))?,
        me: id(get("me", "42.1.1"))?,
        window: num("window", "1")?.max(1.0) as usize,
        count: num("count", "30000")? as u64,
        warmup: num("warmup", "2000")? as u64,
        seconds: num("seconds", "30")?,
        loss: Duration::from_millis(num("loss-ms", "200")? as u64),
        pids: get("pids", "")
            .split(',')
            .filter(|p| !p.is_empty())
            .map(|p| p.parse().map_err(|e| format!("--pids {p}: {e}")))
            .collect::<Result<_, String>>()?,
        label: get("label", "").to_string(),
    })
}

/// User and system CPU ticks of a process (`/proc/PID/stat`).
fn cpu_ticks(pid: u32) -> Option<u64> {
    let s = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    let after = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = after.split(' ').collect();
    Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
}

fn pct(v: &[f64], p: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v[((v.len() - 1) as f64 * p).round() as usize]
}

/// The Query Status datagram with sequence number `seq`.
fn request(a: &Args, seq: u16) -> Vec<u8> {
    let p = As4Packet {
        header: As4Header::new(a.target, a.me),
        payload: QUERY_STATUS.to_le_bytes().to_vec(),
        sequence: seq,
    };
    write_datagrams(&[p], 4096)
        .expect("a Query Status fits a datagram")
        .remove(0)
}

fn main() {
    let a = match args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("as4_load: {e}");
            std::process::exit(2);
        }
    };
    let sock = UdpSocket::bind(a.bind).unwrap_or_else(|e| {
        eprintln!("as4_load: bind {}: {e}", a.bind);
        std::process::exit(1)
    });
    sock.set_read_timeout(Some(a.loss)).expect("a read timeout");
    let mut buf = vec![0u8; 65_536];
    let mut other: HashMap<u16, u64> = HashMap::new();
    let mut outstanding: VecDeque<Instant> = VecDeque::with_capacity(a.window);
    let mut rtts: Vec<f64> = Vec::with_capacity(a.count as usize);
    let (mut sent, mut got, mut lost, mut stalls) = (0u64, 0u64, 0u64, 0u64);
    let total = a.count + a.warmup;
    let mut seq: u16 = 0;
    let mut t_start = Instant::now();
    let mut cpu0: Vec<Option<u64>> = a.pids.iter().map(|p| cpu_ticks(*p)).collect();
    let mut self0 = cpu_ticks(std::process::id());
    let mut deadline = t_start + Duration::from_secs_f64(a.seconds + 60.0);
    let mut measuring = a.warmup == 0;
    let (mut m_sent0, mut m_lost0) = (0u64, 0u64);
    loop {
        let now = Instant::now();
        if now >= deadline || (got + lost >= total && outstanding.is_empty()) {
            break;
        }
        while outstanding.len() < a.window && sent < total && now < deadline {
            seq = seq.wrapping_add(1);
            let _ = sock.send_to(&request(&a, seq), a.server);
            outstanding.push_back(Instant::now());
            sent += 1;
        }
        match sock.recv_from(&mut buf) {
            Ok((n, _)) => {
                let t = Instant::now();
                let Ok(packets) = parse_datagram(&buf[..n]) else {
                    *other.entry(0xFFFF).or_default() += 1;
                    continue;
                };
                for p in packets {
                    let mine = p.header.source == a.target && p.header.destination == a.me;
                    if !(mine && p.message_id() == Some(REPORT_STATUS)) {
                        *other.entry(p.message_id().unwrap_or(0)).or_default() += 1;
                        continue;
                    }
                    let Some(s) = outstanding.pop_front() else {
                        *other.entry(0xFFFE).or_default() += 1; // unmatched reply
                        continue;
                    };
                    got += 1;
                    if measuring {
                        rtts.push((t - s).as_secs_f64() * 1e6);
                    } else if got + lost >= a.warmup {
                        measuring = true;
                        t_start = Instant::now();
                        deadline = t_start + Duration::from_secs_f64(a.seconds);
                        cpu0 = a.pids.iter().map(|p| cpu_ticks(*p)).collect();
                        self0 = cpu_ticks(std::process::id());
                        m_sent0 = sent;
                        m_lost0 = lost;
                    }
                }
            }
            Err(_) => {
                // Nothing for the loss time: every outstanding request is lost.
                stalls += 1;
                lost += outstanding.len() as u64;
                outstanding.clear();
            }
        }
    }
    let el = t_start.elapsed().as_secs_f64();
    lost += outstanding.len() as u64;
    let hz = 100.0; // USER_HZ
    let cpu: Vec<String> = a
        .pids
        .iter()
        .zip(cpu0.iter())
        .map(|(p, before)| match (before, cpu_ticks(*p)) {
            (Some(x), Some(y)) => format!("{p}:{:.0}%", (y - x) as f64 / hz / el * 100.0),
            _ => format!("{p}:?"),
        })
        .collect();
    let selfcpu = match (self0, cpu_ticks(std::process::id())) {
        (Some(x), Some(y)) => (y - x) as f64 / hz / el * 100.0,
        _ => f64::NAN,
    };
    let n = rtts.len();
    rtts.sort_by(f64::total_cmp);
    let t = a.target;
    println!(
        "{} query=status target={}.{}.{} window={} replies={n} sent={} lost={} stalls={stalls} secs={el:.2} rate={:.0}/s p50={:.1}us p90={:.1}us p99={:.1}us max={:.1}us cpu_server=[{}] cpu_loadgen={selfcpu:.0}% other={other:?}",
        a.label,
        t.subsystem,
        t.node,
        t.component,
        a.window,
        sent - m_sent0,
        lost - m_lost0,
        n as f64 / el,
        pct(&rtts, 0.5),
        pct(&rtts, 0.9),
        pct(&rtts, 0.99),
        rtts.last().copied().unwrap_or(f64::NAN),
        cpu.join(","),
    );
    if n == 0 {
        eprintln!(
            "as4_load: no Report Status from {}.{}.{} at {}",
            t.subsystem, t.node, t.component, a.server
        );
        std::process::exit(1);
    }
}
