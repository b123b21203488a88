//! Confirmation by effect (issue 48 item 2) over UDP on loopback: a component that
//! acknowledges ends as `acknowledged` (`jaus send --confirm` against `jaus node`); one
//! that never acknowledges, as OpenJAUS 3.3's components do (a responder hand-rolled
//! here, answering only its read-back queries and control), ends as `confirmed by
//! read-back` with the value read; a value not stored and a Resume that leaves the
//! driver in Standby end as `not confirmed`, saying what is known.

mod common;

use std::io::{BufRead, BufReader};
use std::net::{SocketAddr, UdpSocket};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::*;
use jaus::net::Framing;
use jaus::{Address, CommandCode, Header, JausMessage, Packet};
use jaus_client::catalogue::Catalogue;
use jaus_client::confirm::Confirmation;
use jaus_client::{Carrier, Client, Mode, Script};

use common::jaus_bin;

/// The silent driver's address (a subsystem of its own).
const DRIVER: Address = Address::new(30, 1, 45, 1);

struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// What the hand-rolled driver does with the commands it gets.
#[derive(Clone, Copy)]
struct Habit {
    /// Set Travel Speed is stored (else the speed stays 1 m/s).
    stores: bool,
    /// Resume makes it Ready (else it stays in Standby).
    resumes: bool,
}

/// A component that never sends ACK/NAK, like OpenJAUS 3.3's: it grants control,
/// keeps a travel speed and a state, and answers Query Travel Speed and Query Component
/// Status (the speed as the wire carries it: 1 m/s reads 1.07 m/s). Everything else
/// is ignored. Stops when the flag is set.
fn silent_driver(habit: Habit, me: Address, stop: Arc<AtomicBool>) -> (SocketAddr, JoinHandle<()>) {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    socket
        .set_read_timeout(Some(Duration::from_millis(50)))
        .unwrap();
    let local = socket.local_addr().unwrap();
    let thread = std::thread::spawn(move || {
        let mut speed = 1.0f64;
        let mut state = ComponentState::Standby;
        let mut introduced = false;
        let mut buf = [0u8; 9000];
        while !stop.load(Ordering::Relaxed) {
            let Ok((n, from)) = socket.recv_from(&mut buf) else {
                continue;
            };
            let Ok((h, body)) = Framing::Judp.packet(&buf[..n]) else {
                continue;
            };
            let reply = |code: CommandCode, body: Vec<u8>, to: Address| {
                let p = Packet::new(Header::new(code, to, DRIVER), body);
                if let Ok(bytes) = p.to_bytes() {
                    let _ = socket.send_to(&Framing::Judp.encode(&bytes), from);
                }
            };
            if !introduced {
                // As a node manager would: ask who the commander is, so that it sends
                // its commands at once.
                introduced = true;
                let q = QueryIdentification {
                    query_field: QueryLevel::Component,
                };
                reply(QueryIdentification::CODE, q.to_bytes().unwrap(), me);
            }
            if h.destination != DRIVER {
                continue;
            }
            let Ok(m) = Message::decode(h.command_code, body) else {
                continue;
            };
            let src = h.source;
            match m {
                Message::RequestComponentControl(_) => {
                    let c = ConfirmComponentControl {
                        response_code: ControlResponse::ControlAccepted,
                    };
                    reply(ConfirmComponentControl::CODE, c.to_bytes().unwrap(), src);
                }
                Message::SetTravelSpeed(s) if habit.stores => speed = s.speed,
                Message::Resume(_) if habit.resumes => state = ComponentState::Ready,
                Message::Standby(_) => state = ComponentState::Standby,
                Message::QueryTravelSpeed(_) => {
                    let r = ReportTravelSpeed { speed };
                    reply(ReportTravelSpeed::CODE, r.to_bytes().unwrap(), src);
                }
                Message::QueryComponentStatus(_) => {
                    let r = ReportComponentStatus {
                        primary_status_code: state,
                        secondary_status_code: 0,
                    };
                    reply(ReportComponentStatus::CODE, r.to_bytes().unwrap(), src);
                }
                _ => {}
            }
        }
    });
    (local, thread)
}

/// A session of the CLI's client (a node of its own at `me`) sending `messages` to
/// `to` with `--confirm`: its outcome and what it wrote to stderr.
fn confirm_session(
    me: Address,
    peer: SocketAddr,
    to: Address,
    messages: &[&str],
) -> (jaus_client::Outcome, String) {
    let client = Client {
        me,
        bind: Some("127.0.0.1:0".parse().unwrap()),
        peers: vec![peer],
        carrier: Carrier::Udp,
        framing: Framing::Judp,
        wait: Duration::from_millis(1200),
        mode: Mode::Node,
        name: "confirm test".into(),
        confirm: true,
    };
    let script = Script {
        messages: messages
            .iter()
            .map(|m| (to, jaus_client::parse_message(m).unwrap().1))
            .collect(),
        until_answered: true,
        catalogue: Arc::new(Catalogue::sdk()),
        ..Script::default()
    };
    let stop = AtomicBool::new(false);
    let (mut out, mut err) = (Vec::new(), Vec::new());
    let o = client.session(&script, &stop, &mut out, &mut err).unwrap();
    (o, String::from_utf8_lossy(&err).into_owned())
}

fn names_and_ends(o: &jaus_client::Outcome) -> Vec<(&str, &Confirmation)> {
    o.confirmations
        .iter()
        .map(|(_, n, c)| (n.as_str(), c))
        .collect()
}

#[test]
fn a_component_that_never_acknowledges_is_confirmed_by_read_back() {
    let stop = Arc::new(AtomicBool::new(false));
    let me = Address::new(31, 1, 40, 1);
    let habit = Habit {
        stores: true,
        resumes: true,
    };
    let (peer, driver) = silent_driver(habit, me, stop.clone());
    let (o, err) = confirm_session(
        me,
        peer,
        DRIVER,
        &[
            r#"{"message":"RequestComponentControl","fields":{"authority_code":10}}"#,
            r#"{"message":"Resume"}"#,
            r#"{"message":"SetTravelSpeed","fields":{"speed":2.5}}"#,
        ],
    );
    stop.store(true, Ordering::Relaxed);
    driver.join().unwrap();
    let ends = names_and_ends(&o);
    assert_eq!(ends.len(), 3, "{ends:?}\n{err}");
    assert_eq!(
        ends[0],
        (
            "RequestComponentControl",
            &Confirmation::ReadBack("Confirm Component Control ControlAccepted".into())
        )
    );
    assert_eq!(
        ends[1],
        (
            "Resume",
            &Confirmation::ReadBack("Report Component Status Ready".into())
        )
    );
    // 2.5 m/s travels as 16 counts of 10000/65535 m/s: 2.44 m/s.
    assert_eq!(
        ends[2],
        (
            "SetTravelSpeed",
            &Confirmation::ReadBack("Report Travel Speed 2.44 m/s".into())
        )
    );
    assert!(o.unacknowledged.is_empty(), "{:?}", o.unacknowledged);
    assert!(
        err.contains(
            "SetTravelSpeed to 30.1.45.1: confirmed by read-back: Report Travel Speed 2.44 m/s"
        ),
        "{err}"
    );
}

#[test]
fn a_value_not_stored_and_a_resume_without_effect_are_not_confirmed() {
    let stop = Arc::new(AtomicBool::new(false));
    let me = Address::new(32, 1, 40, 1);
    let habit = Habit {
        stores: false,
        resumes: false,
    };
    let (peer, driver) = silent_driver(habit, me, stop.clone());
    let (o, err) = confirm_session(
        me,
        peer,
        DRIVER,
        &[
            r#"{"message":"RequestComponentControl","fields":{"authority_code":10}}"#,
            r#"{"message":"Resume"}"#,
            r#"{"message":"SetTravelSpeed","fields":{"speed":2.5}}"#,
        ],
    );
    stop.store(true, Ordering::Relaxed);
    driver.join().unwrap();
    let ends = names_and_ends(&o);
    assert_eq!(ends.len(), 3, "{ends:?}\n{err}");
    assert!(matches!(ends[0].1, Confirmation::ReadBack(_)), "{ends:?}");
    let Confirmation::NotConfirmed(resume) = ends[1].1 else {
        panic!("Resume: {:?}", ends[1])
    };
    assert!(
        resume.contains("still Standby after Resume (Ready expected)"),
        "{resume}"
    );
    // Learnt from the control request: this component never acknowledges.
    assert!(
        resume.contains("30.1.45.1 never acknowledges (OpenJAUS 3.3 components send no ACK/NAK)"),
        "{resume}"
    );
    let Confirmation::NotConfirmed(speed) = ends[2].1 else {
        panic!("SetTravelSpeed: {:?}", ends[2])
    };
    assert!(
        speed.contains(
            "the read-back (Query Travel Speed) shows Report Travel Speed 1.07 m/s, not the 2.44 m/s sent"
        ),
        "{speed}"
    );
    assert_eq!(o.unacknowledged.len(), 2, "{:?}", o.unacknowledged);
    assert!(
        err.contains("Resume to 30.1.45.1: not confirmed: "),
        "{err}"
    );
}

/// Starts `jaus node` hosting the demo vehicle at subsystem 20 on a free port.
fn vehicle(dir: &std::path::Path) -> (Running, u16) {
    let port = common::free_port();
    let cfg = dir.join("vehicle.yaml");
    std::fs::write(
        &cfg,
        format!(
            "subsystem: 20\nnode: 1\nnode_name: vehicle\nbind: 127.0.0.1:{port}\nhost: [vehicle]\n"
        ),
    )
    .unwrap();
    let mut child = Command::new(jaus_bin())
        .args(["node", "--config"])
        .arg(&cfg)
        .args(["--seconds", "30"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start jaus node");
    let out = child.stdout.take().unwrap();
    let running = Running(child);
    let end = Instant::now() + Duration::from_secs(15);
    for line in BufReader::new(out).lines().map_while(Result::ok) {
        if line.contains("20.1.45.1 'GlobalWaypointDriver'") || Instant::now() > end {
            break;
        }
    }
    (running, port)
}

#[test]
fn jaus_send_confirm_prints_acknowledged_and_refused_per_command() {
    let dir = std::env::temp_dir().join(format!("jaus-confirm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (_node, port) = vehicle(&dir);
    let out = Command::new(jaus_bin())
        .args(["send", "--confirm", "--me", "21.1.40.1", "--mode", "node"])
        .args(["--to", "20.1.45.1", "--wait", "1.5"])
        .arg("--peer")
        .arg(format!("127.0.0.1:{port}"))
        .arg("--bind")
        .arg("127.0.0.1:0")
        .arg(r#"{"message":"RequestComponentControl","fields":{"authority_code":200}}"#)
        .arg(r#"{"message":"SetTravelSpeed","fields":{"speed":1.5}}"#)
        .arg(r#"{"message":"SetTravelSpeed","fields":{"speed":50}}"#)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let ends: Vec<serde_json::Value> = stdout
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter(|v| v.get("confirm").is_some())
        .collect();
    let outcomes: Vec<(&str, &str)> = ends
        .iter()
        .map(|v| {
            (
                v["confirm"].as_str().unwrap_or(""),
                v["outcome"].as_str().unwrap_or(""),
            )
        })
        .collect();
    assert_eq!(
        outcomes,
        [
            ("RequestComponentControl", "acknowledged"),
            ("SetTravelSpeed", "acknowledged"),
            ("SetTravelSpeed", "refused"),
        ],
        "{stdout}\n{stderr}"
    );
    assert!(
        ends[2]["detail"]
            .as_str()
            .is_some_and(|d| d.contains("from 20.1.45.1") && d.contains("[0, 2] m/s")),
        "{}",
        ends[2]
    );
    assert!(
        stderr.contains("SetTravelSpeed to 20.1.45.1: acknowledged"),
        "{stderr}"
    );
    assert!(!out.status.success(), "a refused command fails the run");
    let _ = std::fs::remove_dir_all(dir);
}
