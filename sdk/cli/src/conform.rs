//! `jaus conform`: the conformance tester (crate `jaus-conform`) on UDP, with its
//! reports written where asked.

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use jaus_conform::session::{Session, Voices};
use jaus_conform::udp::UdpSession;
use jaus_conform::{report, Options};

/// `jaus conform`'s own options (the network ones are [`super::NetArgs`]).
#[derive(clap::Args)]
pub struct ConformArgs {
    /// The component to test (subsystem.node.component.instance); repeat it to test
    /// several, in the order given.
    #[arg(long, conflicts_with = "subsystem")]
    target: Vec<jaus::Address>,
    /// Test every component discovery finds in this subsystem (node managers aside).
    #[arg(long)]
    subsystem: Option<u8>,
    /// Write the run as JSON to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the run as JUnit XML to this file (failed required checks are failures).
    #[arg(long, value_name = "FILE")]
    junit: Option<PathBuf>,
    /// Write the run as one HTML page to this file.
    #[arg(long, value_name = "FILE")]
    html: Option<PathBuf>,
    /// Keep every datagram the tester sent and received in this pcapng file (the
    /// evidence, for Wireshark or `jaus decode --pcap`).
    #[arg(long, value_name = "FILE")]
    pcap: Option<PathBuf>,
    /// Seconds to wait for each answer during the checks.
    #[arg(long, default_value_t = 1.0)]
    answer_wait: f64,
    /// Milliseconds to wait after a command before reading back what it did.
    #[arg(long, default_value_t = 200)]
    settle_ms: u64,
    /// Run the IOP challenge scenario on an AS-4 vehicle over AS5669A instead (the
    /// judge's client at --me, default 42.1.1; the vehicle at the first --peer, found by
    /// Query Identification unless --as4-target gives its id).
    #[arg(long, conflicts_with_all = ["target", "subsystem"])]
    as4: bool,
    /// With --as4: the vehicle's component (S.N.C) instead of whichever answers Query
    /// Identification.
    #[arg(long, value_name = "ID")]
    as4_target: Option<String>,
    /// With --as4: run Execute List (the vehicle drives its waypoints, a few metres) and
    /// the checks that need the list running; without it they are reported as not run.
    #[arg(long)]
    allow_motion: bool,
    /// With --as4: end with the scenario's Shutdown (`as4.management.shutdown`), which
    /// leaves the component shut down; without it the judge gives the component back
    /// as it found it (`as4.control.release`).
    #[arg(long)]
    allow_shutdown: bool,
    /// Print every check this tester can run (RA 3.3 per component type of the
    /// definitions, a vendor's overlay included, and the AS-4 judge's) and exit: id,
    /// level, rule and its source, what it tests, what it applies to; `--list json`
    /// prints them as one JSON array.
    #[arg(long, value_name = "FORMAT", num_args = 0..=1, default_missing_value = "text")]
    list: Option<ListFormat>,
    /// With --as4: seconds to wait for the waypoint list to be driven to its end.
    #[arg(long, default_value_t = 60.0)]
    mission_timeout: f64,
}

fn write_file(path: &PathBuf, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Writes the datagrams of the run as pcapng; says what could not be kept.
fn write_pcap(
    path: &std::path::Path,
    rec: jaus_conform::capture::Recording,
    out: &mut impl Write,
) -> Result<(), String> {
    let fail = |e: jaus_cli::capture::CaptureError| format!("cannot write {}: {e}", path.display());
    let mut w = jaus_cli::capture::CaptureWriter::create(path).map_err(fail)?;
    for d in &rec.datagrams {
        w.write(d.time, d.from, d.to, &d.bytes).map_err(fail)?;
    }
    w.flush().map_err(fail)?;
    let _ = writeln!(
        out,
        "pcap: {} datagrams in {}{}{}",
        rec.datagrams.len() as u64 - w.skipped,
        path.display(),
        if rec.dropped > 0 {
            format!(
                "; {} not kept (the capture's bound was reached)",
                rec.dropped
            )
        } else {
            String::new()
        },
        if w.skipped > 0 {
            format!("; {} not written (IPv6 addresses)", w.skipped)
        } else {
            String::new()
        },
    );
    Ok(())
}

/// Writes the reports asked for.
fn write_reports(run: &jaus_conform::RunReport, args: &ConformArgs) -> Result<(), String> {
    if let Some(p) = &args.json {
        write_file(p, &report::json(run))?;
    }
    if let Some(p) = &args.junit {
        write_file(p, &report::junit(run))?;
    }
    if let Some(p) = &args.html {
        write_file(p, &report::html(run))?;
    }
    Ok(())
}

/// `Err` naming how many required checks failed, if any did.
fn verdict(run: &jaus_conform::RunReport) -> Result<(), String> {
    let failed: usize = run.components.iter().map(|c| c.required_failures()).sum();
    if failed > 0 {
        Err(format!("{failed} required checks failed"))
    } else {
        Ok(())
    }
}

/// `jaus conform --as4`: the IOP scenario on the vehicle at the first peer.
fn conform_as4(
    net: &super::NetArgs,
    args: &ConformArgs,
    out: &mut impl Write,
) -> Result<(), String> {
    use jaus_conform::as4::{self, udp::UdpAs4Session, As4Options, As4Session};
    let me = match &net.me {
        Some(m) => as4::parse_id(m).map_err(|e| format!("--me {e}"))?,
        None => As4Options::default().me,
    };
    let target = args
        .as4_target
        .as_deref()
        .map(as4::parse_id)
        .transpose()
        .map_err(|e| format!("--as4-target {e}"))?;
    let peers = net.udp_peers("conform --as4")?;
    let peer = *peers
        .first()
        .ok_or("give the vehicle's socket with --peer ADDR")?;
    if peers.len() > 1 {
        let _ = writeln!(
            out,
            "--as4 tests one vehicle: {peer} (the other peers are not used)"
        );
    }
    let socket = jaus_cli::net::bind_socket(net.bind, &[peer])?;
    let mut session = UdpAs4Session::new(socket, peer)?;
    if args.pcap.is_some() {
        session.record();
    }
    let opts = As4Options {
        me,
        target,
        vehicle: Some(peer),
        wait: Duration::from_secs_f64(args.answer_wait.max(0.01)),
        settle: Duration::from_millis(args.settle_ms),
        allow_motion: args.allow_motion,
        shutdown: args.allow_shutdown,
        mission_timeout: Duration::from_secs_f64(args.mission_timeout.max(0.0)),
        ..As4Options::default()
    };
    let run = as4::run_as4(&mut session, &opts);
    let _ = write!(out, "{}", report::summary(&run));
    write_reports(&run, args)?;
    if let Some(p) = &args.pcap {
        write_pcap(p, session.take_recording(), out)?;
    }
    if !session.heard() {
        let wait = opts.wait;
        return Err(jaus_cli::net::silence_hint(
            &session.local_addr(),
            &[peer],
            wait,
        ));
    }
    verdict(&run)
}

/// How `--list` prints the checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ListFormat {
    /// Lines for a reader.
    Text,
    /// One JSON array.
    Json,
}

/// `jaus conform --list`: the catalogue of checks of `spec_paths` (or the SDK's).
fn list(format: ListFormat, spec_paths: &[PathBuf], out: &mut impl Write) -> Result<(), String> {
    let spec = if spec_paths.is_empty() {
        jaus_spec::load_sdk()
    } else {
        jaus_spec::load_overlays(spec_paths)
    }
    .map_err(|e| e.to_string())?;
    let all = jaus_conform::catalogue::catalogue(&spec);
    let text = match format {
        ListFormat::Text => jaus_conform::catalogue::text(&all),
        ListFormat::Json => serde_json::to_string_pretty(&all).map_err(|e| e.to_string())? + "\n",
    };
    write!(out, "{text}").map_err(|e| e.to_string())
}

/// Runs the checks and writes the reports; `Err` when a required check failed (exit
/// status 1) or the run could not start.
pub fn conform(
    net: &super::NetArgs,
    args: &ConformArgs,
    spec_paths: &[PathBuf],
    out: &mut impl Write,
) -> Result<(), String> {
    if let Some(format) = args.list {
        return list(format, spec_paths, out);
    }
    if args.as4 {
        return conform_as4(net, args, out);
    }
    if args.allow_motion || args.as4_target.is_some() {
        return Err("--allow-motion and --as4-target go with --as4 (the IOP scenario)".into());
    }
    net.udp_peers("conform")?;
    let client = net.client()?;
    let spec = if spec_paths.is_empty() {
        jaus_spec::load_sdk()
    } else {
        jaus_spec::load_overlays(spec_paths)
    }
    .map_err(|e| e.to_string())?;
    let socket = jaus_cli::net::bind_socket(client.bind, &client.peers)?;
    let voices = Voices::on(client.me.subsystem, client.me.node);
    let mut session = UdpSession::new(socket, client.peers.clone(), client.framing, &voices)?;
    if args.pcap.is_some() {
        session.record();
    }
    let targets = match (args.target.as_slice(), args.subsystem) {
        (given @ [_, ..], _) => {
            if let Some(t) = given
                .iter()
                .find(|t| (t.subsystem, t.node) == (client.me.subsystem, client.me.node))
            {
                return Err(format!(
                    "--target {t} is on the tester's own node ({}.{}, from --me): give --me a node of its own (the tester runs one)",
                    t.subsystem, t.node
                ));
            }
            // A moment for the nodes to meet.
            session.discover(client.wait.min(Duration::from_millis(500)));
            given.to_vec()
        }
        ([], Some(s)) => {
            let found = session.discover(client.wait);
            let t = jaus_conform::targets_in(&found, s, &voices);
            if t.is_empty() {
                let local = session
                    .local_addr()
                    .unwrap_or_else(|| std::net::SocketAddr::from(([0, 0, 0, 0], 0)));
                return Err(if session.heard() {
                    format!(
                        "no component of subsystem {s} found within {:.1} s (found: {found:?})",
                        client.wait.as_secs_f64()
                    )
                } else {
                    jaus_cli::net::silence_hint(&local, &client.peers, client.wait)
                });
            }
            t
        }
        ([], None) => return Err("give --target S.N.C.I or --subsystem S".into()),
    };
    let opts = Options {
        wait: Duration::from_secs_f64(args.answer_wait.max(0.01)),
        settle: Duration::from_millis(args.settle_ms),
    };
    let mut run = jaus_conform::run(&mut session, &spec, voices, &targets, opts);
    run.peer = client
        .peers
        .iter()
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let _ = write!(out, "{}", report::summary(&run));
    write_reports(&run, args)?;
    if let Some(p) = &args.pcap {
        write_pcap(p, session.take_recording(), out)?;
    }
    if !session.heard() {
        let local = session
            .local_addr()
            .unwrap_or_else(|| std::net::SocketAddr::from(([0, 0, 0, 0], 0)));
        return Err(jaus_cli::net::silence_hint(
            &local,
            &client.peers,
            client.wait,
        ));
    }
    verdict(&run)
}
