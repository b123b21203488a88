//! `jaus demo --ocu-only`: the demo's operator over UDP.

use std::io::Write;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use jaus::net::{udp, Framing, Node, NodeConfig};

/// `jaus demo --ocu-only`: the demo's operator on its own node (1.2), driving a vehicle
/// hosted by `jaus node` (`host: [vehicle]`) over UDP. Prints progress and the times
/// the two phases finished.
pub fn demo_operator(
    bind: SocketAddr,
    peers: Vec<SocketAddr>,
    framing: Framing,
    timeout: Duration,
    out: &mut impl Write,
) -> Result<jaus_sim::demo::Report, String> {
    let t0 = Instant::now();
    let mut c = NodeConfig {
        subsystem: 1,
        node: 2,
        framing,
        peers,
        ..NodeConfig::default()
    };
    c.manager.node_name = "operator".into();
    let mut node = Node::new(c, t0);
    let opts = jaus_sim::demo::Options::default();
    node.add(jaus_sim::demo::operator(t0, &opts))
        .map_err(|e| e.to_string())?;
    let stop = AtomicBool::new(false);
    let mut last = "";
    let mut done = None;
    let mut report = None;
    udp::run(&mut node, bind, &stop, Some(t0 + timeout), |n| {
        if done.is_some() {
            return;
        }
        if let Some(o) = n.get::<jaus_sim::demo::Ocu>(jaus_sim::demo::addr::OCU) {
            let (phase, wp, path, mission) = jaus_sim::demo::progress(o);
            if phase != last {
                let _ = writeln!(out, "t = {:6.1} s  {phase}", t0.elapsed().as_secs_f64());
                let _ = out.flush();
                last = phase;
            }
            if phase == "done" {
                done = Some((wp, path, mission));
                report = jaus_sim::demo::operator_report(t0, o);
                stop.store(true, Ordering::Relaxed);
            }
        }
    })
    .map_err(|e| format!("{bind}: {e}"))?;
    match done {
        Some((wp, path, mission)) => {
            let s = |t: Option<Instant>| t.map_or("—".into(), |t| format!("{:.1} s", (t - t0).as_secs_f64()));
            let _ = writeln!(
                out,
                "waypoints: Standby at {}; path segments: Standby at {}; spooled mission finished at {}",
                s(wp),
                s(path),
                s(mission)
            );
            report.ok_or_else(|| "the operator finished without a report".to_string())
        }
        None => Err(format!("the mission did not finish within {timeout:?} (is `jaus node` with host: [vehicle] running and reachable?)")),
    }
}
