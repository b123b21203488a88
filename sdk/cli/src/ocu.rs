//! `jaus ocu`: the operator console in the browser (crate `jaus-ocu`), on a node of its
//! own, optionally beside a simulated vehicle on loopback (`--vehicle`).

use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::net::{udp, NodeConfig};
use jaus_ocu::{BackgroundSource, ConsoleOptions, MapOptions};

/// What `jaus ocu` was asked for.
#[derive(Debug, Clone)]
pub struct OcuArgs {
    /// A node file (`jaus node`'s format) for the console's node: subsystem, node,
    /// bind, framing, peers, multicast (it hosts no components).
    pub config: Option<PathBuf>,
    /// The web server's socket.
    pub http: SocketAddr,
    /// DNS names the page may be opened under besides IP addresses and `localhost`.
    pub allow_hosts: Vec<String>,
    /// The console's JAUS socket (without a config).
    pub bind: SocketAddr,
    /// Peers (without a config).
    pub peers: Vec<SocketAddr>,
    /// The console's subsystem and node (without a config).
    pub subsystem: u8,
    /// The console's node id.
    pub node: u8,
    /// Also run the demo's simulated vehicle (subsystem 1) on loopback.
    pub vehicle: bool,
    /// The map's origin (latitude, longitude, degrees); default the first position.
    pub origin: Option<(f64, f64)>,
    /// A background image under the map.
    pub background: Option<PathBuf>,
    /// Its outer edges (west, south, east, north, metres in the map's frame); without
    /// them, its world file.
    pub background_bounds: Option<[f64; 4]>,
    /// A directory of z/x/y map tiles.
    pub tiles: Option<PathBuf>,
    /// Stop after this long.
    pub duration: Option<Duration>,
}

/// Runs the console until `stop` is set or `duration` passes.
pub fn ocu(args: &OcuArgs, stop: &AtomicBool, out: &mut impl Write) -> Result<(), String> {
    let mut options = ConsoleOptions {
        http: args.http,
        allowed_hosts: args.allow_hosts.clone(),
        bind: args.bind,
        origin: args.origin,
        map: MapOptions {
            background: args
                .background
                .clone()
                .map(|image| BackgroundSource::new(image, args.background_bounds))
                .transpose()
                .map_err(|e| e.to_string())?,
            tiles: args.tiles.clone(),
        },
        ..ConsoleOptions::default()
    };
    match &args.config {
        Some(path) => {
            let file = jaus_node::NodeFile::load(path)?;
            if !file.host.is_empty() {
                return Err(format!(
                    "{}: `host:` — the console's node hosts only the console (run the components with `jaus node`)",
                    path.display()
                ));
            }
            options.node = file.node_config();
            options.bind = file.bind;
        }
        None => {
            options.node = NodeConfig {
                subsystem: args.subsystem,
                node: args.node,
                peers: args.peers.clone(),
                // As ConsoleOptions::default: the Station's commands arrive.
                reliable: Some(jaus::net::reliable::RetryPolicy::cautious()),
                ..NodeConfig::default()
            };
        }
    }
    let local_stop = Arc::new(AtomicBool::new(false));
    let deadline = args.duration.map(|d| Instant::now() + d);
    // Owned threads, each waited for within a bound at the end: one that is stuck is
    // named and the command fails instead of hanging.
    let vehicle = if args.vehicle {
        let socket = std::net::UdpSocket::bind("127.0.0.1:0")
            .map_err(|e| format!("simulated vehicle: 127.0.0.1:0: {e}"))?;
        let at = socket.local_addr().map_err(|e| e.to_string())?;
        options.node.peers.push(at);
        let vehicle_stop = local_stop.clone();
        Some(
            std::thread::Builder::new()
                .name("simulated-vehicle".into())
                .spawn(move || run_vehicle(&socket, &vehicle_stop))
                .map_err(|e| format!("simulated vehicle: {e}"))?,
        )
    } else {
        None
    };
    let result = std::thread::scope(|scope| {
        // Turns Ctrl-C and --seconds into the console's stop (it only sleeps and reads
        // flags, so the scope's wait for it is short).
        scope.spawn(|| {
            while !local_stop.load(Ordering::Relaxed) {
                if stop.load(Ordering::Relaxed) || deadline.is_some_and(|d| Instant::now() >= d) {
                    local_stop.store(true, Ordering::Relaxed);
                }
                std::thread::sleep(Duration::from_millis(50));
            }
        });
        let result = jaus_ocu::run(&options, &local_stop, |b| {
            let _ = writeln!(
                out,
                "operator console: open {}  (System Commander {} on {}, peers {:?}{})",
                b.url(),
                b.me,
                b.udp,
                options.node.peers,
                if args.vehicle {
                    "; simulated vehicle: subsystem 1"
                } else {
                    ""
                }
            );
            if b.is_public() {
                let _ = writeln!(
                    out,
                    "warning: the console answers on {} beyond this machine: anyone who can reach it and has the address above (its key) can command vehicles, and plain HTTP carries the key unencrypted",
                    b.http
                );
            }
            let _ = out.flush();
        })
        .map_err(|e| e.to_string());
        local_stop.store(true, Ordering::Relaxed);
        result
    });
    let vehicle = vehicle.map(|v| match udp::join_within(v, udp::SHUTDOWN_BOUND) {
        Ok(r) => r,
        Err(e) => Err(e.to_string()),
    });
    result?;
    vehicle.unwrap_or(Ok(()))
}

/// The demo's simulated vehicle (subsystem 1, node 1), as `jaus node` with `host:
/// [vehicle]` runs it, on `socket`.
fn run_vehicle(socket: &std::net::UdpSocket, stop: &AtomicBool) -> Result<(), String> {
    let mut node = jaus_sim::demo::vehicle_node(Instant::now(), NodeConfig::default(), 1, 1)
        .map_err(|e| format!("simulated vehicle: {e}"))?;
    udp::run_on(&mut node, socket, stop, None, |_| {})
        .map_err(|e| format!("simulated vehicle: {e}"))
}

/// `--origin LAT,LON`: degrees, latitude within ±90 and longitude within ±180.
pub fn parse_origin(text: &str) -> Result<(f64, f64), String> {
    let v = numbers(text, 2, "LAT,LON")?;
    if v[0].abs() > 90.0 || v[1].abs() > 180.0 {
        return Err(format!(
            "`{text}`: latitude within ±90 and longitude within ±180 degrees"
        ));
    }
    Ok((v[0], v[1]))
}

/// `--background-bounds X0,Y0,X1,Y1`: west, south, east, north, metres, with x0 < x1
/// and y0 < y1.
pub fn parse_bounds(text: &str) -> Result<[f64; 4], String> {
    let v = numbers(text, 4, "X0,Y0,X1,Y1")?;
    if v[0] >= v[2] || v[1] >= v[3] {
        return Err(format!(
            "`{text}`: west, south, east, north (metres), with west < east and south < north"
        ));
    }
    Ok([v[0], v[1], v[2], v[3]])
}

/// `n` finite numbers separated by commas.
fn numbers(text: &str, n: usize, form: &str) -> Result<Vec<f64>, String> {
    let v: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("`{text}`: expected {form} (numbers separated by commas)"))?;
    if v.len() != n {
        return Err(format!(
            "`{text}`: expected {form} ({n} numbers, got {})",
            v.len()
        ));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origins_and_bounds_are_checked() {
        assert_eq!(parse_origin("29.6436,-82.3549"), Ok((29.6436, -82.3549)));
        assert!(parse_origin("91,0").is_err());
        assert!(parse_origin("1").unwrap_err().contains("2 numbers"));
        assert_eq!(parse_bounds("-10, -5, 10, 5"), Ok([-10.0, -5.0, 10.0, 5.0]));
        assert!(parse_bounds("10,-5,-10,5")
            .unwrap_err()
            .contains("west < east"));
        assert!(parse_bounds("a,b,c,d").unwrap_err().contains("X0,Y0,X1,Y1"));
        assert!(parse_bounds("0,0,1,nan").is_err());
    }
}
