//! `jaus`: the command-line tool of the SDK.

use clap::{Parser, Subcommand};
use jaus::cli;
use std::io::{BufRead, Write};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "jaus",
    version,
    about = "JAUS RA 3.3 toolkit: message catalogue, packet decoder and encoder"
)]
struct Cli {
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
    },
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let stderr = std::io::stderr();
    let mut err = stderr.lock();
    let ok = match cli.cmd {
        Cmd::Messages { group } => {
            cli::print_messages(&mut out, group.as_deref());
            true
        }
        Cmd::Decode { hex } => {
            let lines: Box<dyn Iterator<Item = String>> = if hex.is_empty() {
                Box::new(stdin_lines())
            } else {
                Box::new(hex.into_iter())
            };
            cli::run_lines(lines, &mut out, &mut err, cli::decode_line)
        }
        Cmd::Encode => cli::run_lines(stdin_lines(), &mut out, &mut err, cli::encode_line),
        Cmd::Tour => cli::tour(&mut out),
        Cmd::Demo {
            seed,
            noise,
            realtime,
            out: dir,
            progress,
        } => {
            let opts = jaus::demo::Options {
                seed,
                position_noise: noise.max(0.0),
                realtime,
                out: Some(dir),
                progress: (progress > 0.0).then(|| std::time::Duration::from_secs_f64(progress)),
                ..Default::default()
            };
            let _ = writeln!(
                out,
                "JAUS demo: subsystem 1 node 1 (primitive and reflexive drivers, pose and velocity sensors, global waypoint and local path-segment drivers over a simulated skid-steer vehicle), operator 1.2.40.1"
            );
            match jaus::demo::run(&opts, |line| {
                let _ = writeln!(std::io::stdout(), "{line}");
            }) {
                Ok(report) => {
                    let _ = writeln!(out, "{}", jaus::demo::summary(&report));
                    true
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
