//! `jaus`: the command-line tool of the SDK.

mod args;
mod conform;

use args::{Cli, Cmd, NetArgs};
use clap::Parser;
use jaus_cli::{commands, report};
use std::io::{BufRead, Write};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

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
    catalogue: &jaus_client::catalogue::Catalogue,
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
            jaus_client::catalogue::with_overlay_hint(
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
    catalogue: &std::sync::Arc<jaus_client::catalogue::Catalogue>,
    net: &NetArgs,
    to: Option<jaus::Address>,
    messages: &[String],
    hold: Option<f64>,
    until_answered: bool,
    scs: &[(jaus::Address, jaus::CommandCode, f64, u32)],
    all: bool,
    out: &mut impl Write,
) -> Result<jaus_client::Outcome, String> {
    let c = net.client()?;
    let mut parsed = Vec::new();
    for m in messages {
        let (dest, msg) = catalogue.parse_message(m)?;
        let dest = dest
            .or(to)
            .ok_or_else(|| format!("{}: no destination: give --to ADDRESS", msg.name()))?;
        parsed.push((dest, msg));
    }
    let script = jaus_client::Script {
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
        return Err(jaus_client::silence_hint(
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
    let catalogue = match jaus_client::catalogue::Catalogue::load(&cli.spec) {
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
            jaus_client::describe::spec_with(&cli.spec)
                .and_then(|spec| {
                    jaus_client::describe::describe(&spec, &name).map_err(|e| {
                        jaus_client::catalogue::with_overlay_hint(e, !cli.spec.is_empty())
                    })
                })
                .map(|text| {
                    let _ = write!(out, "{text}");
                }),
        ),
        Cmd::Decode {
            pcap: Some(file), ..
        } => match jaus_client::traffic::decode_capture(&file, &catalogue, &mut out, &mut err) {
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
            jaus_client::traffic::replay(
                &file,
                &jaus_client::traffic::Replay {
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
                jaus_node::node(&config, d, capture.as_deref(), &STOP, &mut out),
            )
        }
        Cmd::Wireshark {
            out: path,
            as4_spec,
        } => report(
            &mut err,
            jaus_client::describe::spec_with(&cli.spec).and_then(|ra33| {
                let as4 = jaus_client::as4_link::as4_spec(&as4_spec, &[])
                    .map_err(|e| format!("--as4-spec: {e}"))?;
                let lua = jaus_gen::wireshark::dissector_for(&ra33, Some(&as4));
                std::fs::write(&path, lua).map_err(|e| format!("{}: {e}", path.display()))?;
                writeln!(
                    out,
                    "wrote {}: RA 3.3 {} messages, AS-4 {} messages",
                    path.display(),
                    ra33.messages.len(),
                    as4.messages.len()
                )
                .map_err(|e| e.to_string())
            }),
        ),
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
            jaus_node::attach_openjaus(
                jaus_node::OjNodeManager { control, data },
                &host,
                duration(seconds),
                &STOP,
                &mut out,
            ),
        ),
        Cmd::Conform { net, args } => {
            report(&mut err, conform::conform(&net, &args, &cli.spec, &mut out))
        }
        Cmd::Ros2 { args } => report(&mut err, jaus_cli::ros2::run(&args, &STOP, &mut out)),
        Cmd::As4Drive { args } => report(&mut err, jaus_cli::as4_drive::as4_drive(&args, &mut out)),
        Cmd::As4Query { args } => report(
            &mut err,
            jaus_cli::as4_talk::as4_talk(&args, true, &mut out),
        ),
        Cmd::As4Send { args } => report(
            &mut err,
            jaus_cli::as4_talk::as4_talk(&args, false, &mut out),
        ),
        Cmd::Discover { net, json } => report(
            &mut err,
            net.client().and_then(|c| {
                let (tree, heard) = c.discover(&STOP)?;
                if json {
                    let _ = writeln!(out, "{}", jaus_client::tree_json(&tree));
                } else {
                    let _ = write!(out, "{}", tree.render());
                }
                if heard {
                    Ok(())
                } else {
                    Err(jaus_client::silence_hint(
                        &c.bind
                            .unwrap_or_else(|| std::net::SocketAddr::from(([0, 0, 0, 0], 3794))),
                        &c.peers,
                        c.wait,
                    ))
                }
            }),
        ),
        Cmd::Send {
            mut net,
            to,
            hold,
            confirm,
            messages,
        } => report(&mut err, {
            net.confirm = confirm;
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
            .map(|_| ())
        }),
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
            let run = jaus_cli::demo_operator(
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
            loss,
            no_retry,
            ..
        } => {
            let network = loss.map(|pct| jaus_sim::demo::Impairment {
                loss: pct / 100.0,
                seed,
                reliable: !no_retry,
            });
            let opts = jaus_sim::demo::Options {
                seed,
                position_noise: noise.max(0.0),
                realtime,
                progress: (progress > 0.0).then(|| std::time::Duration::from_secs_f64(progress)),
                network,
                ..Default::default()
            };
            let _ = writeln!(
                out,
                "JAUS demo: subsystem 1 node 1 (primitive and reflexive drivers, pose and velocity sensors, range and visual sensors, global waypoint and local path-segment drivers, mission spooler, world model, over a simulated skid-steer vehicle), operator 1.2.40.1"
            );
            if let Some(n) = &network {
                let _ = writeln!(
                    out,
                    "over a simulated radio: {:.1} % of datagrams lost, 0.2-50 ms delays (reordering), 5 % duplicated, seed {}; commands {}",
                    n.loss * 100.0,
                    n.seed,
                    if n.reliable {
                        "acknowledged and resent until they arrive"
                    } else {
                        "sent once"
                    }
                );
            }
            let print = |line: &str| {
                let _ = writeln!(std::io::stdout(), "{line}");
            };
            let result = if network.is_some() {
                jaus_sim::demo::run_over_network(&opts, print).map(|(run, net)| {
                    let _ = writeln!(out, "{}", jaus_sim::demo::network_summary(&net));
                    run
                })
            } else {
                jaus_sim::demo::run(&opts, print)
            };
            match result {
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
