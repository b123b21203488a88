//! `jaus`: the command-line tool of the SDK.

mod conform;

use clap::{Parser, Subcommand};
use jaus_cli::{commands, report};
use std::io::{BufRead, Write};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

#[derive(Parser)]
#[command(
    name = "jaus",
    version,
    about = "JAUS RA 3.3 toolkit: message catalogue, packet decoder and encoder, nodes, the simulated-vehicle demo"
)]
struct Cli {
    /// More log output on stderr (-v info, -vv debug, -vvv trace: one line per message
    /// sent and received); default: warnings. `RUST_LOG` (e.g. `jaus::net=trace`)
    /// overrides it when set.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    /// A vendor's YAML overlay (on the SDK's definitions, as its build loads it), for
    /// `messages`, `decode`, `encode`, `send`, `query` and `watch`: its messages are
    /// encoded from and printed as JSON by name. Repeatable.
    #[arg(long, value_name = "FILE", global = true)]
    spec: Vec<std::path::PathBuf>,
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// List the message set: code, name, group, and the report answering each query.
    Messages {
        /// Only this group (e.g. `platform`).
        #[arg(long)]
        group: Option<String>,
        /// One message: its fields with types, units, ranges, presence bits, and an
        /// example JSON line.
        name: Option<String>,
        /// The catalogue as JSON lines, one per message: code (number), name, title,
        /// group, class, report (name or null), experimental.
        #[arg(long)]
        json: bool,
    },
    /// Decode packets given as hex (arguments, or stdin one per line) to JSON lines.
    Decode {
        /// Packets as hex: 16-byte header followed by the body.
        hex: Vec<String>,
        /// Decode the JAUS messages of a capture (pcap or pcapng) instead, multi-packet
        /// messages reassembled; each line also has `t` (s), `src` and `dst`.
        #[arg(long, value_name = "FILE", conflicts_with = "hex")]
        pcap: Option<std::path::PathBuf>,
    },
    /// Send the datagrams of a capture (pcap or pcapng) to a node again, with their
    /// captured timing.
    Replay {
        /// The capture.
        file: std::path::PathBuf,
        /// Where to send them (a node's socket).
        #[arg(long)]
        to: std::net::SocketAddr,
        /// Only the datagrams originally sent to this socket (e.g. what one node received).
        #[arg(long, value_name = "ADDR")]
        only_to: Option<std::net::SocketAddrV4>,
        /// Time scale (2: twice as fast; 0: as fast as possible).
        #[arg(long, default_value_t = 1.0)]
        speed: f64,
        /// Local socket.
        #[arg(long, default_value = "127.0.0.1:0")]
        bind: std::net::SocketAddr,
    },
    /// Encode JSON lines from stdin (the form `decode` prints) to hex packets.
    Encode,
    /// Walk through the SDK: build messages, encode packets, decode them back.
    Tour,
    /// The operator console in the browser: a System Commander on a node of its own
    /// serving a local page (system tree, map with trails, control, emergency stop,
    /// waypoints, missions, message log). `--vehicle` also runs the demo's simulated
    /// vehicle on loopback: `jaus ocu --vehicle`, then open the address it prints.
    Ocu {
        /// A node file (as `jaus node` reads, without `host:`) for the console's node.
        #[arg(long)]
        config: Option<std::path::PathBuf>,
        /// The web server's address (keep it on 127.0.0.1 unless the network is trusted:
        /// the page commands vehicles). Open the address printed at start-up: it carries
        /// the run's key, without which the server refuses everything but its static
        /// files; on any address other than loopback that key is all that keeps others
        /// out, and plain HTTP carries it unencrypted.
        #[arg(long, default_value = "127.0.0.1:8700")]
        http: std::net::SocketAddr,
        /// A DNS name the page may be opened under besides IP addresses and `localhost`
        /// (every other name is refused, against DNS rebinding); repeatable.
        #[arg(long = "allow-host", value_name = "NAME")]
        allow_hosts: Vec<String>,
        /// The console's JAUS socket (without --config).
        #[arg(long, default_value = "127.0.0.1:0")]
        bind: std::net::SocketAddr,
        /// Nodes to talk to (without --config); repeatable.
        #[arg(long = "peer", value_name = "ADDR")]
        peers: Vec<std::net::SocketAddr>,
        /// The console's subsystem id (without --config).
        #[arg(long, default_value_t = 200)]
        subsystem: u8,
        /// The console's node id (without --config).
        #[arg(long, default_value_t = 1)]
        node: u8,
        /// Also run the demo's simulated vehicle (subsystem 1) on loopback.
        #[arg(long)]
        vehicle: bool,
        /// The map's origin in degrees: the point whose metres east and north the map
        /// counts (default: the first position received). Give it with --background so
        /// the image's metres mean the same place on every run; --tiles needs an origin
        /// (this, or the first position) to place tiles.
        #[arg(long, value_name = "LAT,LON", value_parser = jaus_cli::ocu::parse_origin, allow_hyphen_values = true)]
        origin: Option<(f64, f64)>,
        /// A background image under the map (PNG or JPEG; read once at start-up, never
        /// fetched). Placed in the map's frame (metres east, north of the origin) by
        /// --background-bounds, else by its world file beside it (map.png -> map.pgw,
        /// map.jpg -> map.jgw, or .wld: six lines: metres per pixel east, rotation,
        /// rotation, metres per pixel north (negative), then x and y of the centre of the
        /// upper-left pixel).
        #[arg(long, value_name = "PATH")]
        background: Option<std::path::PathBuf>,
        /// Where the background image's outer edges lie: west, south, east, north, in
        /// metres east and north of the map's origin (e.g. -100,-50,100,50).
        #[arg(long, value_name = "X0,Y0,X1,Y1", requires = "background", value_parser = jaus_cli::ocu::parse_bounds, allow_hyphen_values = true)]
        background_bounds: Option<[f64; 4]>,
        /// A local directory of map tiles in the usual z/x/y.png layout (as tile
        /// downloaders and tile servers' caches write; .jpg and .webp too), drawn under
        /// the map by latitude and longitude; nothing is fetched from the network.
        #[arg(long, value_name = "DIR")]
        tiles: Option<std::path::PathBuf>,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// Run a node from a configuration file (YAML: subsystem, node, bind, framing,
    /// peers, host); prints the system tree whenever it changes.
    Node {
        /// The configuration file.
        #[arg(long)]
        config: std::path::PathBuf,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
        /// Write every datagram the node receives and sends to this pcapng file
        /// (Wireshark: load the dissector of `jaus-gen wireshark`).
        #[arg(long, value_name = "FILE")]
        capture: Option<std::path::PathBuf>,
    },
    /// Make a node's key and certificate for authenticated QUIC data links: writes
    /// NAME.crt (for the far end's `peer_cert`) and NAME.key (mode 0600; stays on this
    /// node), prints both paths and the certificate's SHA-256 fingerprint. Never
    /// overwrites existing files.
    Keygen {
        /// The node's name (letters, digits, `-`, `_`, `.`): the files' names and the
        /// certificate's subject.
        name: String,
        /// Where to write the files (created if missing).
        #[arg(long, default_value = ".")]
        dir: std::path::PathBuf,
    },
    /// Run stock components as OpenJAUS component processes under an OpenJAUS node
    /// manager (or a `jaus node` with `openjaus_components`): each checks in for its
    /// address on the control socket, then talks raw JAUS on the data socket.
    Attach {
        /// Stock components to run (names as in a node file's `host:`).
        #[arg(long = "host", value_name = "NAME", required = true)]
        host: Vec<String>,
        /// The node manager's control socket.
        #[arg(long, default_value = "127.0.0.1:24627")]
        control: std::net::SocketAddr,
        /// The node manager's data socket.
        #[arg(long, default_value = "127.0.0.1:24629")]
        data: std::net::SocketAddr,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// Test components on the network against Part 1 and the core rules (checks read
    /// from the definitions, --spec overlays included); exits 1 when a required check fails.
    Conform {
        #[command(flatten)]
        net: NetArgs,
        #[command(flatten)]
        args: conform::ConformArgs,
    },
    /// Listen for a while and print the system tree seen on the network.
    Discover {
        #[command(flatten)]
        net: NetArgs,
        /// The tree as one JSON document: {"subsystems": [{"id", "name", "nodes": [{"id",
        /// "name", "components": [{"address", "name", "services"}]}]}]}.
        #[arg(long)]
        json: bool,
    },
    /// Send messages in one session (arguments, or JSON lines on stdin as they come),
    /// each after the previous one was answered; prints every message addressed to this
    /// tool as a timestamped JSON line as it arrives. Control taken in the session is
    /// held (heartbeats keep this tool in the system) and given back at the end.
    Send {
        #[command(flatten)]
        net: NetArgs,
        /// Destination (subsystem.node.component.instance) of messages without a header.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// Stay this many seconds after the last message (holding control, printing
        /// what arrives); default: until every message is answered or --wait passed.
        #[arg(long)]
        hold: Option<f64>,
        /// Messages: {"message": "SetTravelSpeed", "fields": {"speed": 2.0}}; `fields` may
        /// be left out for a message without fields. None: JSON lines from stdin.
        messages: Vec<String>,
    },
    /// Send queries and print their reports; returns as soon as every query is answered
    /// and exits 1 if one was not within --wait.
    Query {
        #[command(flatten)]
        net: NetArgs,
        /// Destination address.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// The queries (as for `send`).
        messages: Vec<String>,
    },
    /// Print every message addressed to this tool as it arrives (timestamped JSON
    /// lines) until interrupted: service connections (--sc), events, replies to the
    /// messages given.
    Watch {
        #[command(flatten)]
        net: NetArgs,
        /// Provider of the service connections, and destination of the messages.
        #[arg(long)]
        to: Option<jaus::Address>,
        /// A service connection to open: REPORT@HZ[:PRESENCE], e.g. ReportGlobalPose@2:0x1ff.
        #[arg(long)]
        sc: Vec<String>,
        /// Stop after this many seconds (default: until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
        /// Also print queries and heartbeats sent to this tool.
        #[arg(long)]
        all: bool,
        /// Messages to send first (as for `send`).
        messages: Vec<String>,
    },
    /// Run a simulated subsystem: an operator takes control, drives a waypoint mission
    /// and the path segments of Part 1 Figures 5-12/5-14; prints arrival times and
    /// cross-track errors per leg and plots the run.
    Demo {
        /// Seed of the sensor noise.
        #[arg(long, default_value_t = 7)]
        seed: u64,
        /// Position noise of the pose sensors (standard deviation, m).
        #[arg(long, default_value_t = 0.02)]
        noise: f64,
        /// Run at wall-clock speed (default: as fast as possible).
        #[arg(long)]
        realtime: bool,
        /// Directory for demo.svg.
        #[arg(long, default_value = "target/demo")]
        out: std::path::PathBuf,
        /// Progress line every this many simulated seconds (0: none).
        #[arg(long, default_value_t = 5.0)]
        progress: f64,
        /// Run only the operator (node 1.2), driving a vehicle hosted by `jaus node`
        /// (`host: [vehicle]`) over UDP.
        #[arg(long)]
        ocu_only: bool,
        /// With --ocu-only: the local socket.
        #[arg(long, default_value = "127.0.0.1:3795")]
        bind: std::net::SocketAddr,
        /// With --ocu-only: the vehicle node's socket.
        #[arg(long, default_value = "127.0.0.1:3794")]
        peer: Vec<std::net::SocketAddr>,
        /// Run the arm instead: the ten manipulator components over a simulated 6-axis
        /// arm and an operator's pick-and-place sequence (pose, joint move, velocity
        /// jog, timed poses); prints each move's time and error and plots arm.svg.
        #[arg(long, conflicts_with = "ocu_only")]
        arm: bool,
    },
}

/// Network options of the commands that act as a component.
#[derive(clap::Args)]
struct NetArgs {
    /// This tool's own address (a System Commander). On the node of a peer, the tool
    /// joins that node as one of its components; else it runs a node of its own.
    /// Default: S.1.40.1 with S in 200-253 taken from the process id, so that two
    /// sessions at once are two subsystems (OpenJAUS keeps one address per subsystem).
    #[arg(long)]
    me: Option<jaus::Address>,
    /// Local socket (default: port 3794 on an address of its own, e.g. 127.0.0.2:3794,
    /// because JUDP peers answer port 3794 of the sender's address).
    #[arg(long)]
    bind: Option<std::net::SocketAddr>,
    /// auto (join the peer's node when --me is on it), join, or node.
    #[arg(long, default_value = "auto")]
    mode: jaus_cli::net::Mode,
    /// Peer node sockets.
    #[arg(long, default_value = "127.0.0.1:3794")]
    peer: Vec<std::net::SocketAddr>,
    /// Framing: judp or opc.
    #[arg(long, default_value = "judp")]
    framing: String,
    /// Seconds to wait for answers (discover: to listen).
    #[arg(long, default_value_t = 2.0)]
    wait: f64,
}

impl NetArgs {
    fn client(&self) -> Result<jaus_cli::net::Client, String> {
        let framing = match self.framing.as_str() {
            "judp" => jaus::net::Framing::Judp,
            "opc" => jaus::net::Framing::Opc,
            other => return Err(format!("unknown framing `{other}` (judp or opc)")),
        };
        Ok(jaus_cli::net::Client {
            me: self.me.unwrap_or_else(jaus_cli::net::default_me),
            bind: self.bind,
            peers: self.peer.clone(),
            framing,
            wait: std::time::Duration::from_secs_f64(self.wait.max(0.0)),
            mode: self.mode,
        })
    }
}

/// Lines of standard input. A line that is not UTF-8 is kept (lossily converted) so
/// that it is reported as a bad line instead of ending the input.
fn stdin_lines() -> impl Iterator<Item = String> {
    std::io::stdin()
        .lock()
        .split(b'\n')
        .map_while(Result::ok)
        .map(|l| {
            let l = l.strip_suffix(b"\r").unwrap_or(&l).to_vec();
            String::from_utf8(l)
                .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
        })
}

/// Prints an error line; true on success.
/// `--seconds` as a duration (negative: none at all).
fn duration(seconds: Option<f64>) -> Option<std::time::Duration> {
    seconds.map(|s| std::time::Duration::from_secs_f64(s.max(0.0)))
}

fn report(err: &mut impl Write, r: Result<(), String>) -> bool {
    match r {
        Ok(()) => true,
        Err(e) => {
            let _ = writeln!(err, "error: {e}");
            false
        }
    }
}

/// Set on Ctrl-C: sessions end cleanly (service connections ended, control released).
static STOP: AtomicBool = AtomicBool::new(false);

/// `REPORT@HZ[:PRESENCE]` of `watch --sc`.
fn parse_sc(
    catalogue: &jaus_cli::catalogue::Catalogue,
    s: &str,
    to: Option<jaus::Address>,
) -> Result<(jaus::Address, jaus::CommandCode, f64, u32), String> {
    let to = to.ok_or("--sc needs --to: the component that provides the report")?;
    let (name, rest) = s.split_once('@').ok_or_else(|| {
        format!("--sc {s}: expected REPORT@HZ[:PRESENCE], e.g. ReportGlobalPose@2:0x1ff")
    })?;
    let (hz, pv) = match rest.split_once(':') {
        Some((hz, pv)) => (hz, Some(pv)),
        None => (rest, None),
    };
    let code = catalogue
        .code_of(name)
        .ok_or_else(|| {
            jaus_cli::catalogue::with_overlay_hint(
                format!("no message named `{name}` (see `jaus messages`)"),
                catalogue.schema().is_some(),
            )
        })
        .map_err(|e| format!("--sc {s}: {e}"))?;
    let hz: f64 = hz
        .parse()
        .map_err(|_| format!("--sc {s}: `{hz}` is not a rate in Hz"))?;
    if !(hz.is_finite() && hz > 0.0) {
        return Err(format!("--sc {s}: the rate must be above 0 Hz"));
    }
    let pv = match pv {
        None => 0,
        Some(p) => {
            let r = match p.strip_prefix("0x").or_else(|| p.strip_prefix("0X")) {
                Some(h) => u32::from_str_radix(h, 16),
                None => p.parse(),
            };
            r.map_err(|_| format!("--sc {s}: `{p}` is not a presence vector (decimal or 0x hex)"))?
        }
    };
    Ok((to, code, hz, pv))
}

/// Runs one operator session; an error when a command was refused, input was bad, or
/// nothing came back at all.
#[allow(clippy::too_many_arguments)]
fn session(
    catalogue: &std::sync::Arc<jaus_cli::catalogue::Catalogue>,
    net: &NetArgs,
    to: Option<jaus::Address>,
    messages: &[String],
    hold: Option<f64>,
    until_answered: bool,
    scs: &[(jaus::Address, jaus::CommandCode, f64, u32)],
    all: bool,
    out: &mut impl Write,
) -> Result<jaus_cli::net::Outcome, String> {
    let c = net.client()?;
    let mut parsed = Vec::new();
    for m in messages {
        let (dest, msg) = catalogue.parse_message(m)?;
        let dest = dest
            .or(to)
            .ok_or_else(|| format!("{}: no destination: give --to ADDRESS", msg.name()))?;
        parsed.push((dest, msg));
    }
    let script = jaus_cli::net::Script {
        messages: parsed,
        stdin: messages.is_empty() && scs.is_empty() && hold.is_none_or(f64::is_finite),
        service_connections: scs.to_vec(),
        all,
        until_answered,
        hold: hold
            .filter(|h| h.is_finite())
            .map(std::time::Duration::from_secs_f64),
        to,
        catalogue: catalogue.clone(),
    };
    // Not locked for the session: its threads (and the log) write to stderr too.
    let o = c.session(&script, &STOP, out, &mut std::io::stderr())?;
    if let Some(conflict) = o.conflict {
        return Err(conflict);
    }
    if !o.heard {
        return Err(jaus_cli::net::silence_hint(
            &o.local
                .or(c.bind)
                .unwrap_or_else(|| std::net::SocketAddr::from(([0, 0, 0, 0], 3794))),
            &c.peers,
            c.wait,
        ));
    }
    // Every way a command failed to have its effect, in one line (each was printed
    // with its reason as it happened).
    let mut failed = Vec::new();
    if o.rejected > 0 {
        failed.push(format!("{} control request(s) rejected", o.rejected));
    }
    if o.naks > 0 {
        failed.push(format!("{} command(s) refused (NAK)", o.naks));
    }
    if !o.unacknowledged.is_empty() {
        failed.push(format!(
            "{} command(s) not acknowledged",
            o.unacknowledged.len()
        ));
    }
    if o.bad_lines > 0 {
        failed.push(format!("{} bad input line(s)", o.bad_lines));
    }
    if failed.is_empty() {
        Ok(o)
    } else {
        Err(failed.join(", "))
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let _ = ctrlc::set_handler(|| STOP.store(true, Ordering::Relaxed));
    // RUST_LOG (e.g. `jaus=debug,jaus::net=trace`) when set; else -v/-vv/-vvv.
    let filter = match std::env::var("RUST_LOG") {
        Ok(spec) if !spec.trim().is_empty() => tracing_subscriber::EnvFilter::try_new(&spec)
            .unwrap_or_else(|e| {
                eprintln!("warning: RUST_LOG `{spec}`: {e}; using warnings only");
                tracing_subscriber::EnvFilter::new("warn")
            }),
        _ => tracing_subscriber::EnvFilter::new(match cli.verbose {
            0 => "warn",
            1 => "info",
            2 => "debug",
            _ => "trace",
        }),
    };
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .init();
    // Standard output and error are locked per write, never for a whole command:
    // commands run threads (a simulated vehicle, the console's web server, socket
    // receivers) that log to stderr, and a lock held here would block them forever.
    let mut out = std::io::stdout();
    let mut err = std::io::stderr();
    let catalogue = match jaus_cli::catalogue::Catalogue::load(&cli.spec) {
        Ok(c) => std::sync::Arc::new(c),
        Err(e) => {
            let _ = writeln!(err, "error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let ok = match cli.cmd {
        Cmd::Messages {
            group,
            name: None,
            json,
        } => report(
            &mut err,
            commands::check_group(group.as_deref()).map(|()| {
                if json {
                    commands::print_messages_json(&mut out, group.as_deref(), &catalogue);
                } else {
                    commands::print_messages(&mut out, group.as_deref(), &catalogue);
                }
            }),
        ),
        Cmd::Messages {
            name: Some(name), ..
        } => report(
            &mut err,
            jaus_cli::describe::spec_with(&cli.spec)
                .and_then(|spec| {
                    jaus_cli::describe::describe(&spec, &name).map_err(|e| {
                        jaus_cli::catalogue::with_overlay_hint(e, !cli.spec.is_empty())
                    })
                })
                .map(|text| {
                    let _ = write!(out, "{text}");
                }),
        ),
        Cmd::Decode {
            pcap: Some(file), ..
        } => match jaus_cli::traffic::decode_capture(&file, &catalogue, &mut out, &mut err) {
            Ok((_, 0)) => true,
            Ok((_, _)) => false,
            Err(e) => {
                let _ = writeln!(err, "error: {e}");
                false
            }
        },
        Cmd::Replay {
            file,
            to,
            only_to,
            speed,
            bind,
        } => report(
            &mut err,
            jaus_cli::traffic::replay(
                &file,
                &jaus_cli::traffic::Replay {
                    to,
                    only_to,
                    speed: speed.max(0.0),
                    bind,
                },
                &STOP,
            )
            .map(|n| {
                let _ = writeln!(out, "sent {n} datagrams to {to}");
            }),
        ),
        Cmd::Decode { hex, .. } => {
            let lines: Box<dyn Iterator<Item = String>> = if hex.is_empty() {
                Box::new(stdin_lines())
            } else {
                Box::new(hex.into_iter())
            };
            commands::run_lines(lines, &mut out, &mut err, |l| catalogue.decode_line(l))
        }
        Cmd::Encode => commands::run_lines(stdin_lines(), &mut out, &mut err, |l| {
            catalogue.encode_line(l)
        }),
        Cmd::Tour => commands::tour(&mut out),
        Cmd::Ocu {
            config,
            http,
            allow_hosts,
            bind,
            peers,
            subsystem,
            node,
            vehicle,
            origin,
            background,
            background_bounds,
            tiles,
            seconds,
        } => report(
            &mut err,
            jaus_cli::ocu::ocu(
                &jaus_cli::ocu::OcuArgs {
                    config,
                    http,
                    allow_hosts,
                    bind,
                    peers,
                    subsystem,
                    node,
                    vehicle,
                    origin,
                    background,
                    background_bounds,
                    tiles,
                    duration: duration(seconds),
                },
                &STOP,
                &mut out,
            ),
        ),
        Cmd::Node {
            config,
            seconds,
            capture,
        } => {
            let d = duration(seconds);
            report(
                &mut err,
                jaus_cli::net::node(&config, d, capture.as_deref(), &STOP, &mut out),
            )
        }
        Cmd::Keygen { name, dir } => {
            report(&mut err, jaus_cli::keygen::keygen(&name, &dir, &mut out))
        }
        Cmd::Attach {
            host,
            control,
            data,
            seconds,
        } => report(
            &mut err,
            jaus_cli::net::attach_openjaus(
                jaus_cli::net::OjNodeManager { control, data },
                &host,
                duration(seconds),
                &STOP,
                &mut out,
            ),
        ),
        Cmd::Conform { net, args } => {
            report(&mut err, conform::conform(&net, &args, &cli.spec, &mut out))
        }
        Cmd::Discover { net, json } => report(
            &mut err,
            net.client().and_then(|c| {
                let (tree, heard) = c.discover(&STOP)?;
                if json {
                    let _ = writeln!(out, "{}", jaus_cli::net::tree_json(&tree));
                } else {
                    let _ = write!(out, "{}", tree.render());
                }
                if heard {
                    Ok(())
                } else {
                    Err(jaus_cli::net::silence_hint(
                        &c.bind
                            .unwrap_or_else(|| std::net::SocketAddr::from(([0, 0, 0, 0], 3794))),
                        &c.peers,
                        c.wait,
                    ))
                }
            }),
        ),
        Cmd::Send {
            net,
            to,
            hold,
            messages,
        } => report(
            &mut err,
            session(
                &catalogue,
                &net,
                to,
                &messages,
                hold.map(|h| h.max(0.0)),
                hold.is_none(),
                &[],
                false,
                &mut out,
            )
            .map(|_| ()),
        ),
        Cmd::Query { net, to, messages } => report(
            &mut err,
            session(
                &catalogue,
                &net,
                to,
                &messages,
                None,
                true,
                &[],
                false,
                &mut out,
            )
            .and_then(|o| {
                if o.answered < o.sent {
                    Err(format!(
                        "{} of {} queries unanswered within {} s",
                        o.sent - o.answered,
                        o.sent,
                        net.wait
                    ))
                } else {
                    Ok(())
                }
            }),
        ),
        Cmd::Watch {
            net,
            to,
            sc,
            seconds,
            all,
            messages,
        } => report(
            &mut err,
            sc.iter()
                .map(|s| parse_sc(&catalogue, s, to))
                .collect::<Result<Vec<_>, String>>()
                .and_then(|scs| {
                    session(
                        &catalogue,
                        &net,
                        to,
                        &messages,
                        Some(seconds.unwrap_or(f64::INFINITY)),
                        false,
                        &scs,
                        all,
                        &mut out,
                    )
                    .map(|_| ())
                }),
        ),
        Cmd::Demo {
            ocu_only: true,
            bind,
            peer,
            out: dir,
            ..
        } => {
            let run = jaus_cli::net::demo_operator(
                bind,
                peer,
                jaus::net::Framing::Judp,
                std::time::Duration::from_secs(180),
                &mut out,
            );
            // Measured on the positions the operator received over the network.
            report(
                &mut err,
                run.and_then(|run| {
                    let _ = writeln!(out, "{}", report::summary(&run));
                    let path = report::write_svg(&run, &dir)
                        .map_err(|e| format!("{}: {e}", dir.display()))?;
                    let _ = writeln!(out, "plot: {}", path.display());
                    if let Some((path, what)) = report::write_image(&run, &dir)
                        .map_err(|e| format!("{}: {e}", dir.display()))?
                    {
                        let _ = writeln!(out, "camera image: {} ({what})", path.display());
                    }
                    Ok(())
                }),
            )
        }
        Cmd::Demo {
            arm: true,
            seed,
            out: dir,
            progress,
            ..
        } => {
            let opts = jaus_sim::arm_demo::ArmOptions {
                seed,
                progress: (progress > 0.0)
                    .then(|| std::time::Duration::from_secs_f64(progress.min(2.0))),
                ..Default::default()
            };
            let _ = writeln!(
                out,
                "JAUS arm demo: subsystem 1 node 3 (primitive manipulator, joint position/velocity/force-torque sensors, joint positions, end-effector pose, joint velocities, end-effector velocity state, joint move and end-effector discrete pose drivers, over a simulated 6-axis arm), operator 1.2.40.1"
            );
            match jaus_sim::arm_demo::run(&opts, |line| {
                let _ = writeln!(std::io::stdout(), "{line}");
            }) {
                Ok(run) => {
                    let _ = writeln!(out, "{}", jaus_cli::arm_report::summary(&run));
                    match jaus_cli::arm_report::write_svg(&run, &dir) {
                        Ok(path) => {
                            let _ = writeln!(out, "plot: {}", path.display());
                            true
                        }
                        Err(e) => {
                            let _ = writeln!(err, "error: {}: {e}", dir.display());
                            false
                        }
                    }
                }
                Err(e) => {
                    let _ = writeln!(err, "arm demo failed: {e}");
                    false
                }
            }
        }
        Cmd::Demo {
            seed,
            noise,
            realtime,
            out: dir,
            progress,
            ..
        } => {
            let opts = jaus_sim::demo::Options {
                seed,
                position_noise: noise.max(0.0),
                realtime,
                progress: (progress > 0.0).then(|| std::time::Duration::from_secs_f64(progress)),
                ..Default::default()
            };
            let _ = writeln!(
                out,
                "JAUS demo: subsystem 1 node 1 (primitive and reflexive drivers, pose and velocity sensors, range and visual sensors, global waypoint and local path-segment drivers, mission spooler, world model, over a simulated skid-steer vehicle), operator 1.2.40.1"
            );
            match jaus_sim::demo::run(&opts, |line| {
                let _ = writeln!(std::io::stdout(), "{line}");
            }) {
                Ok(run) => {
                    let _ = writeln!(out, "{}", report::summary(&run));
                    match report::write_svg(&run, &dir).and_then(|path| {
                        let _ = writeln!(out, "plot: {}", path.display());
                        report::write_image(&run, &dir)
                    }) {
                        Ok(image) => {
                            if let Some((path, what)) = image {
                                let _ = writeln!(out, "camera image: {} ({what})", path.display());
                            }
                            true
                        }
                        Err(e) => {
                            let _ = writeln!(err, "error: {}: {e}", dir.display());
                            false
                        }
                    }
                }
                Err(e) => {
                    let _ = writeln!(err, "demo failed: {e}");
                    false
                }
            }
        }
    };
    let _ = out.flush();
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
