//! `jaus attach`: stock components as OpenJAUS component processes, under an OpenJAUS
//! node manager (or a `jaus node` serving `openjaus_components`): each checks in on the
//! control socket for its address, then all of them exchange raw JAUS packets with the
//! node manager's data socket (docs/wire.md §8.5).

use std::io::Write;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use crate::host::{Host, Stock};
use jaus::net::oj::Control;
use jaus::net::{udp, Attached, AttachedConfig, Framing, ReassemblyLimits};

/// Where the node manager's two sockets are.
#[derive(Debug, Clone, Copy)]
pub struct OjNodeManager {
    /// Control socket (OpenJAUS: 127.0.0.1:24627).
    pub control: SocketAddr,
    /// Data socket (OpenJAUS: 127.0.0.1:24629).
    pub data: SocketAddr,
}

/// Checks in a stock component per name of `host`, runs them until `stop` or
/// `duration`, then checks them out.
pub fn attach_openjaus(
    nm: OjNodeManager,
    host: &[String],
    duration: Option<Duration>,
    stop: &AtomicBool,
    out: &mut impl Write,
) -> Result<(), String> {
    if host.is_empty() {
        return Err("nothing to attach: give --host NAME (a stock component)".into());
    }
    let local = |a: SocketAddr| SocketAddr::new(a.ip(), 0);
    let control = UdpSocket::bind(local(nm.control)).map_err(|e| e.to_string())?;
    let data = UdpSocket::bind(local(nm.data)).map_err(|e| e.to_string())?;
    let data_port = data.local_addr().map_err(|e| e.to_string())?.port();
    let mut assigned = Vec::new();
    for name in host {
        let stock = Stock::by_name(name).ok_or_else(|| {
            let known: Vec<&str> = Stock::names().collect();
            format!("unknown component `{name}` (known: {})", known.join(", "))
        })?;
        let a = udp::oj_check_in(
            &control,
            nm.control,
            stock.id(),
            data_port,
            Duration::from_secs(2),
        )
        .map_err(|e| format!("check-in of {name}: {e}"))?;
        let _ = writeln!(
            out,
            "checked in {name} as {a} at the node manager {}",
            nm.control
        );
        assigned.push((stock, a));
    }
    let (ss, node) = (assigned[0].1.subsystem, assigned[0].1.node);
    let t0 = Instant::now();
    let mut attached = Attached::new(
        AttachedConfig {
            subsystem: ss,
            node,
            node_socket: nm.data,
            framing: Framing::Raw,
            reassembly: ReassemblyLimits::default(),
            max_outbox: 8192,
        },
        t0,
    );
    let mut builder = Host::new(ss, node, t0);
    for (stock, a) in &assigned {
        let entry = Host::entry(*stock).instance(a.instance);
        let c = builder.build(&entry).map_err(|e| e.to_string())?;
        attached.add_boxed(c).map_err(|e| e.to_string())?;
    }
    let _ = out.flush();
    let result = udp::run_on(&mut attached, &data, stop, duration.map(|d| t0 + d), |_| {})
        .map_err(|e| format!("{}: {e}", nm.data));
    for (_, a) in &assigned {
        let _ = control.send_to(&Control::CheckOut(*a).encode(), nm.control);
    }
    result
}
