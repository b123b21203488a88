//! Runs the Vendor Lamp lamp on UDP: `cargo run -- --bind 127.0.0.1:3794 --id 30.1.5`.
//! Drive it with the SDK's command line, e.g.
//! `jaus as4-send --peer 127.0.0.1:3794 --to 30.1.5 --as4-spec defs --control 10 '{"message": "SetLampLevel", "fields": {"level": 40}}' '{"message": "QueryLampLevel"}'`.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::AtomicBool;

use jaus::net::as5669a::As4Id;

fn main() -> Result<(), String> {
    // What the node does (`RUST_LOG` overrides; `jaus::hsm=trace` shows each transition).
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .init();
    let mut bind: SocketAddr = "127.0.0.1:3794".parse().map_err(|e| format!("{e}"))?;
    let mut id = As4Id::new(30, 1, 5);
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--bind" => bind = value.parse().map_err(|e| format!("--bind {value}: {e}"))?,
            "--id" => {
                let parts: Vec<&str> = value.split('.').collect();
                let [s, n, c] = parts.as_slice() else {
                    return Err(format!("--id {value}: SUBSYSTEM.NODE.COMPONENT"));
                };
                let bad = |e: std::num::ParseIntError| format!("--id {value}: {e}");
                id = As4Id::new(
                    s.parse().map_err(bad)?,
                    n.parse().map_err(bad)?,
                    c.parse().map_err(bad)?,
                );
            }
            other => return Err(format!("unknown option {other} (--bind, --id)")),
        }
    }
    let socket = UdpSocket::bind(bind).map_err(|e| format!("{bind}: {e}"))?;
    println!("{id} on {bind}");
    let stop = AtomicBool::new(false);
    vendor_lamp::serve(&socket, id, &stop).map_err(|e| format!("{bind}: {e}"))
}
