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
    };
    let _ = out.flush();
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
