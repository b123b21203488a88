//! `jaus conform`: the conformance tester (crate `jaus-conform`) on UDP, with its
//! reports written where asked.

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use jaus_conform::profile::{self, Profile, Selection};
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
    /// Judge this capture (pcap or pcapng: `jaus node --capture`, `--pcap`, tshark)
    /// instead of testing components on the network: nothing is sent; queries
    /// answered, acknowledgements given, malformed packets and state commands from
    /// clients not in control carried out, each finding naming its packet numbers
    /// (`--answer-wait` is the window an answer may take).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["target", "subsystem", "as4", "pcap", "list", "peer"])]
    from_pcap: Option<PathBuf>,
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
    /// Run (or with --list, list) only the checks of a profile: a built-in one (`all`,
    /// the default; `ra33-core`, the checks every RA 3.3 component gets; `iop`, the AS-4
    /// judge's, as --as4) or a YAML file (name, description, checks: a list of
    /// `{ id: ID or PREFIX*, level: required|advisory }`).
    #[arg(long, value_name = "NAME|FILE")]
    profile: Option<String>,
    /// With --as4: seconds to wait for the waypoint list to be driven to its end.
    #[arg(long, default_value_t = 60.0)]
    mission_timeout: f64,
    /// With --as4: instead of the IOP scenario, plan the checks from the AS-4 service
    /// definitions of every service the component lists in Report Services: each query
    /// answered with its report, each command that needs control refused without it
    /// (and read back from the controller), each query subscribed with Create Event.
    /// The definitions are jaus-as4's (Core v1.1, Mobility), with --as4-spec or --jsidl.
    #[arg(long, requires = "as4")]
    plan: bool,
    /// With --as4 --plan: directories of YAML definitions loaded on jaus-as4's (a
    /// vendor's messages and services, `extends: as4`), as `jaus as4-query --as4-spec`.
    #[arg(
        id = "as4_spec",
        long = "as4-spec",
        visible_alias = "defs",
        value_name = "DIR",
        requires = "plan"
    )]
    as4_spec: Vec<PathBuf>,
    /// With --as4 --plan: directories of JSIDL to import and plan from instead of
    /// jaus-as4's definitions (give every set the component's services need).
    #[arg(
        long,
        value_name = "DIR",
        requires = "plan",
        conflicts_with = "as4_spec"
    )]
    jsidl: Vec<PathBuf>,
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
    let fail =
        |e: jaus_client::capture::CaptureError| format!("cannot write {}: {e}", path.display());
    let mut w = jaus_client::capture::CaptureWriter::create(path).map_err(fail)?;
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
    sel: Option<&Selection>,
    out: &mut impl Write,
) -> Result<(), String> {
    use jaus_conform::as4::{self, planned, udp::UdpAs4Session, As4Options, As4Session};
    let defs = if args.plan {
        if sel.is_some() {
            return Err("--profile selects the IOP scenario's checks: not with --plan".into());
        }
        Some(planned::Definitions::load(&args.as4_spec, &args.jsidl)?)
    } else {
        None
    };
    let me = match &net.me {
        Some(m) => m
            .parse::<jaus::net::as5669a::As4Id>()
            .map_err(|e| format!("--me {e}"))?,
        None => As4Options::default().me,
    };
    let target = args
        .as4_target
        .as_deref()
        .map(|t| {
            t.parse::<jaus::net::as5669a::As4Id>()
                .map_err(|e| e.to_string())
        })
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
    let socket = jaus_client::bind_socket(net.bind, &[peer])?;
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
    let run = match (&defs, sel) {
        (Some(defs), sel) => planned::run_planned_selected(&mut session, defs, &opts, sel),
        (None, Some(sel)) => profile::run_as4(&mut session, &opts, sel),
        (None, None) => as4::run_as4(&mut session, &opts),
    };
    let _ = write!(out, "{}", report::summary(&run));
    write_reports(&run, args)?;
    if let Some(p) = &args.pcap {
        write_pcap(p, session.take_recording(), out)?;
    }
    if !session.heard() {
        let wait = opts.wait;
        return Err(jaus_client::silence_hint(
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

/// The definitions: the SDK's, with the overlays of `spec_paths`.
fn load_spec(spec_paths: &[PathBuf]) -> Result<jaus_spec::Spec, String> {
    if spec_paths.is_empty() {
        jaus_spec::load_sdk()
    } else {
        jaus_spec::load_overlays(spec_paths)
    }
    .map_err(|e| e.to_string())
}

/// The checks `--profile` selects among those of `spec`, if given.
fn selection(args: &ConformArgs, spec: &jaus_spec::Spec) -> Result<Option<Selection>, String> {
    let Some(name) = &args.profile else {
        return Ok(None);
    };
    let catalogue = jaus_conform::catalogue::catalogue(spec);
    Profile::named(name)
        .and_then(|p| p.select(&catalogue))
        .map(Some)
        .map_err(|e| e.to_string())
}

/// `jaus conform --list`: the catalogue of checks of `spec_paths` (or the SDK's), those
/// of `--profile` when given.
fn list(
    format: ListFormat,
    args: &ConformArgs,
    spec_paths: &[PathBuf],
    out: &mut impl Write,
) -> Result<(), String> {
    let spec = load_spec(spec_paths)?;
    let mut all = jaus_conform::catalogue::catalogue(&spec);
    if let Some(sel) = selection(args, &spec)? {
        all = jaus_conform::catalogue::selected(&all, &sel);
    }
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
        return list(format, args, spec_paths, out);
    }
    if let Some(path) = &args.from_pcap {
        return from_pcap(path, args, out);
    }
    let spec = load_spec(spec_paths)?;
    let sel = selection(args, &spec)?;
    if let Some(sel) = &sel {
        let _ = writeln!(
            out,
            "profile {}: {} checks ({})",
            sel.name,
            sel.ids.len(),
            sel.description
        );
    }
    let as4_only = sel.as_ref().is_some_and(|s| !s.has_ra33());
    if args.as4 || as4_only {
        if let Some(s) = sel.as_ref().filter(|s| !s.has_as4()) {
            return Err(format!(
                "profile {} selects no check of the AS-4 judge (--as4)",
                s.name
            ));
        }
        if !args.target.is_empty() || args.subsystem.is_some() {
            return Err("--target and --subsystem go with RA 3.3 checks: the profile selects the AS-4 judge's only (its vehicle is the first --peer, or --as4-target)".into());
        }
        return conform_as4(net, args, sel.as_ref(), out);
    }
    if args.allow_motion || args.as4_target.is_some() {
        return Err("--allow-motion and --as4-target go with --as4 (the IOP scenario)".into());
    }
    net.udp_peers("conform")?;
    let client = net.client()?;
    let socket = jaus_client::bind_socket(client.bind, &client.peers)?;
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
                    jaus_client::silence_hint(&local, &client.peers, client.wait)
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
    let mut run = match &sel {
        Some(sel) => profile::run(&mut session, &spec, voices, &targets, opts, sel),
        None => jaus_conform::run(&mut session, &spec, voices, &targets, opts),
    };
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
        return Err(jaus_client::silence_hint(
            &local,
            &client.peers,
            client.wait,
        ));
    }
    verdict(&run)
}

/// The record of datagram `d` (frame `number`) for the offline judge; `None` for one
/// that is no JAUS traffic: OpenJAUS's local control datagrams, and datagrams of no
/// JAUS framing (first byte not 1, 2 or "JAUS01.0") off the JAUS ports (3794, and
/// OpenJAUS's data socket 24629, whose raw packets have no framing).
fn offline_record(
    number: u64,
    d: &jaus_client::capture::Datagram,
) -> Option<jaus_conform::offline::Record> {
    use jaus::net::as5669a::Generation;
    use jaus_conform::offline::{Carrier, Record};
    if d.is_openjaus_control() {
        return None;
    }
    let ports = [d.src.port(), d.dst.port()];
    let jaus_port = ports.contains(&3794) || ports.contains(&jaus::net::oj::DATA_PORT);
    if Generation::of(&d.payload) == Generation::Unknown && !jaus_port {
        return None;
    }
    let (carrier, payload) = if d.is_as5669a() {
        (Carrier::As5669a, d.payload.clone())
    } else {
        match d.jaus_packet() {
            Ok(p) => (Carrier::Ra33, p.to_vec()),
            Err(e) => (Carrier::Unframed(e), d.payload.clone()),
        }
    };
    Some(Record {
        number,
        time: d.time,
        src: d.src.into(),
        dst: d.dst.into(),
        carrier,
        payload,
    })
}

/// `jaus conform --from-pcap FILE`: judges the capture, sending nothing; the same
/// reports as a live run, `Err` when a required check failed.
fn from_pcap(
    path: &std::path::Path,
    args: &ConformArgs,
    out: &mut impl Write,
) -> Result<(), String> {
    if args.allow_motion || args.allow_shutdown || args.as4_target.is_some() {
        return Err("--allow-motion, --allow-shutdown and --as4-target test a vehicle on the network: not with --from-pcap".into());
    }
    let (frames, stats) = jaus_client::capture::read_frames(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let opts = jaus_conform::offline::Options {
        window: Duration::from_secs_f64(args.answer_wait.clamp(0.001, 3600.0)),
        ..jaus_conform::offline::Options::default()
    };
    let mut judge = jaus_conform::offline::Judge::new(opts);
    let (mut judged, mut other) = (0u64, 0u64);
    for (number, d) in &frames {
        match offline_record(*number, d) {
            Some(r) => {
                judged += 1;
                judge.push(&r);
            }
            None => other += 1,
        }
    }
    let dropped = judge.dropped();
    let run = judge.finish(&path.display().to_string());
    let _ = writeln!(
        out,
        "{}: {judged} JAUS datagrams judged{}{}{}",
        path.display(),
        if other > 0 {
            format!(", {other} other UDP datagrams left aside")
        } else {
            String::new()
        },
        if stats.skipped > 0 {
            format!(", {} frames not IPv4/UDP skipped", stats.skipped)
        } else {
            String::new()
        },
        if stats.truncated {
            " (the file ends inside a packet: read up to it)"
        } else {
            ""
        },
    );
    if dropped > 0 {
        let _ = writeln!(
            out,
            "{dropped} requests not judged: {} of their kind were waiting at once",
            opts.max_outstanding
        );
    }
    let _ = write!(out, "{}", report::summary(&run));
    write_reports(&run, args)?;
    verdict(&run)
}
