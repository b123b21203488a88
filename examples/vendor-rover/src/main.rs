//! Runs the Vendor Rover node on UDP:
//! `cargo run -- --subsystem 1 --node 1 --bind 127.0.0.1:3794 --peer 127.0.0.1:3795 --seconds 60`.

use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::{udp, NodeConfig};

fn main() -> Result<(), String> {
    // Warnings and what the node does (`RUST_LOG` overrides): a refused command is
    // logged with its reason.
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .init();
    let mut config = NodeConfig::default();
    let mut bind: SocketAddr = "127.0.0.1:3794".parse().map_err(|e| format!("{e}"))?;
    let mut seconds = None;
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        let bad = |e: &dyn std::fmt::Display| format!("{flag} {value}: {e}");
        match flag.as_str() {
            "--subsystem" => config.subsystem = value.parse().map_err(|e| bad(&e))?,
            "--node" => config.node = value.parse().map_err(|e| bad(&e))?,
            "--bind" => bind = value.parse().map_err(|e| bad(&e))?,
            "--peer" => config.peers.push(value.parse().map_err(|e| bad(&e))?),
            "--seconds" => seconds = Some(Duration::from_secs(value.parse().map_err(|e| bad(&e))?)),
            other => {
                return Err(format!(
                    "unknown option {other} (--subsystem, --node, --bind, --peer, --seconds)"
                ))
            }
        }
    }
    let t0 = Instant::now();
    let mut node = vendor_rover::node(config, t0).map_err(|e| e.to_string())?;
    println!("{} on {bind}", node.address());
    let stop = AtomicBool::new(false);
    udp::run(&mut node, bind, &stop, seconds.map(|d| t0 + d), |_| {})
        .map_err(|e| format!("{bind}: {e}"))
}
