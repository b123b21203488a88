//! `jaus`: the command-line tool of the SDK.

use clap::{Parser, Subcommand};
use jaus_cli::{commands, report};
use std::io::{BufRead, Write};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "jaus",
    version,
    about = "JAUS RA 3.3 toolkit: message catalogue, packet decoder and encoder, nodes, the simulated-vehicle demo"
)]
struct Cli {
    /// More log output on stderr (-v info, -vv debug, -vvv trace); default: warnings.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
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
    },
    /// Decode packets given as hex (arguments, or stdin one per line) to JSON lines.
    Decode {
        /// Packets as hex: 16-byte header followed by the body.
        hex: Vec<String>,
    },
    /// Encode JSON lines from stdin (the form `decode` prints) to hex packets.
    Encode,
    /// Walk through the SDK: build messages, encode packets, decode them back.
    Tour,
    /// Run a node from a configuration file (YAML: subsystem, node, bind, framing,
    /// peers, host); prints the system tree whenever it changes.
    Node {
        /// The configuration file.
        #[arg(long)]
        config: std::path::PathBuf,
        /// Stop after this many seconds (default: run until interrupted).
        #[arg(long)]
        seconds: Option<f64>,
    },
    /// Listen for a while and print the system tree seen on the network.
    Discover {
        #[command(flatten)]
        net: NetArgs,
    },
    /// Send one message (JSON as `jaus decode` prints it) and print what comes back.
    Send {
        #[command(flatten)]
        net: NetArgs,
        /// Destination address (subsystem.node.component.instance).
        #[arg(long)]
        to: jaus::Address,
        /// The message: {"message": "QueryGlobalPose", "fields": {"presence_vector": 3}}.
        message: String,
    },
    /// Like `send`, and exit 1 if no reply arrived.
    Query {
        #[command(flatten)]
        net: NetArgs,
        /// Destination address.
        #[arg(long)]
        to: jaus::Address,
        /// The query.
        message: String,
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
    },
}

/// Network options of the one-shot commands.
#[derive(clap::Args)]
struct NetArgs {
    /// This tool's own address (its node manager is SS.NODE.1.1).
    #[arg(long, default_value = "1.250.40.1")]
    me: jaus::Address,
    /// Local socket.
    #[arg(long, default_value = "127.0.0.1:0")]
    bind: std::net::SocketAddr,
    /// Peer node sockets.
    #[arg(long, default_value = "127.0.0.1:3794")]
    peer: Vec<std::net::SocketAddr>,
    /// Framing: judp or opc.
    #[arg(long, default_value = "judp")]
    framing: String,
    /// Seconds to listen.
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
            me: self.me,
            bind: self.bind,
            peers: self.peer.clone(),
            framing,
            wait: std::time::Duration::from_secs_f64(self.wait.max(0.0)),
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
fn report(err: &mut impl Write, r: Result<(), String>) -> bool {
    match r {
        Ok(()) => true,
        Err(e) => {
            let _ = writeln!(err, "error: {e}");
            false
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let level = match cli.verbose {
        0 => tracing::Level::WARN,
        1 => tracing::Level::INFO,
        2 => tracing::Level::DEBUG,
        _ => tracing::Level::TRACE,
    };
    tracing_subscriber::fmt()
        .with_max_level(level)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .init();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let stderr = std::io::stderr();
    let mut err = stderr.lock();
    let ok = match cli.cmd {
        Cmd::Messages { group } => {
            commands::print_messages(&mut out, group.as_deref());
            true
        }
        Cmd::Decode { hex } => {
            let lines: Box<dyn Iterator<Item = String>> = if hex.is_empty() {
                Box::new(stdin_lines())
            } else {
                Box::new(hex.into_iter())
            };
            commands::run_lines(lines, &mut out, &mut err, jaus::json::decode_line)
        }
        Cmd::Encode => {
            commands::run_lines(stdin_lines(), &mut out, &mut err, jaus::json::encode_line)
        }
        Cmd::Tour => commands::tour(&mut out),
        Cmd::Node { config, seconds } => {
            let d = seconds.map(|s| std::time::Duration::from_secs_f64(s.max(0.0)));
            report(&mut err, jaus_cli::net::node(&config, d, &mut out))
        }
        Cmd::Discover { net } => report(
            &mut err,
            net.client()
                .and_then(|c| jaus_cli::net::discover(&c, &mut out)),
        ),
        Cmd::Send { net, to, message } => report(
            &mut err,
            net.client()
                .and_then(|c| jaus_cli::net::send(&c, to, &message, &mut out))
                .map(|_| ()),
        ),
        Cmd::Query { net, to, message } => report(
            &mut err,
            net.client()
                .and_then(|c| jaus_cli::net::send(&c, to, &message, &mut out))
                .and_then(|n| {
                    if n == 0 {
                        Err(format!("no reply from {to}"))
                    } else {
                        Ok(())
                    }
                }),
        ),
        Cmd::Demo {
            ocu_only: true,
            bind,
            peer,
            ..
        } => report(
            &mut err,
            jaus_cli::net::demo_operator(
                bind,
                peer,
                jaus::net::Framing::Judp,
                std::time::Duration::from_secs(180),
                &mut out,
            ),
        ),
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
                "JAUS demo: subsystem 1 node 1 (primitive and reflexive drivers, pose and velocity sensors, global waypoint and local path-segment drivers, mission spooler, world model, over a simulated skid-steer vehicle), operator 1.2.40.1"
            );
            match jaus_sim::demo::run(&opts, |line| {
                let _ = writeln!(std::io::stdout(), "{line}");
            }) {
                Ok(run) => {
                    let _ = writeln!(out, "{}", report::summary(&run));
                    match report::write_svg(&run, &dir) {
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
